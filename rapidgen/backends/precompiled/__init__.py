"""Templates compiled by Jinja2 (rapidgen/backends/templating.py); do not edit."""
