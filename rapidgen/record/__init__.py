"""`rapidgen record` and `rapidgen replay`: RAPID traffic to and from MCAP files (docs/record.md).

`schema` (a type as one self-contained OMG IDL text), `mcapfile` (writing with rotation,
reading a complete or a cut file), `recorder` (the DDS side of recording), `info`,
`replay`, `schema_types` (classes from a recording's own schemas); `command` and
`replay_command` hold the command lines.
"""
