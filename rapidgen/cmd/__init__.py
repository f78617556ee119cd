"""`rapidgen cmd ASSET SUBSYSTEM COMMAND key=value ...`: a command to a live asset.

ASSET is a descriptor (the asset's package is generated into a temporary folder for its
types, QoS and tables: rapidgen.live.bindings, the loader `conform` and `spy` use too) or
an importable generated package (`rapid_k10red`). The dictionary is the asset's live
CommandConfig, merged with the descriptor's units, ranges, allowed values and defaults;
`--from-descriptor`, or no config within `--discover` seconds, uses the descriptor's
alone. Arguments are checked before anything is sent; a bad one is a located error on the
command line (exit 1). The acks are printed as they come; exit 0 on COMPLETED/OK, 1
otherwise. The protocol side is rapid_runtime.commander; cyclonedds and rapid_runtime are
imported lazily, so the compiler runs without them.

    command.py     the subcommand: arguments, the run
    line.py        the command line as a located line (diagnostics point at its words)
    arguments.py   key=value words parsed, checked and completed against a command's parameters
    dictionary.py  the live CommandConfig, merged with the descriptor's tables
"""
