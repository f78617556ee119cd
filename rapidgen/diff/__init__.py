"""`rapidgen diff`: breaking-change detection between two versions of IDL sets or asset
descriptors (docs/diff.md).

    rules.py     the registry: stable ids, categories (WIRE, PROTOCOL, SOURCE), explanations
    types.py     how one type expression changed (assignable, bound shrunk, alias only)
    wire.py      wire rules over two models (XTypes 1.3 7.2.4, per extensibility)
    protocol.py  protocol rules over two asset descriptors
    sides.py     loading one side; gitread.py the old side from a git revision
    waivers.py   `--waivers FILE`; render.py text and JSON; command.py the command
"""
