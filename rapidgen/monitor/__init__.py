"""`rapidgen monitor`: a local web page showing every asset on a DDS domain (docs/monitor.md)."""
