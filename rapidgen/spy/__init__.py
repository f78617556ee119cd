"""`rapidgen spy`: watch a live RAPID network and say, in RAPID's terms, why something
does not talk.

`watch` joins the domain (the discovery layer of rapidgen.live, plus a reader per topic
and partition it sees), `model` turns what was seen into assets, topics and rates,
`diagnose` finds the known faults (stable codes, docs/spy.md), `render` prints text,
JSON or a live terminal view, `echo` prints one topic's samples, `command` is the CLI.
"""
