"""The `rapidgen` program: the command line, run with the dataclass code cache.

The cache (rapidgen.codecache) is installed before any of rapidgen's classes is made, so
only a rapidgen process of its own has it; `rapidgen.cli.main(argv)` called as a library
runs without.
"""
from __future__ import annotations

from rapidgen import codecache
from rapidgen.speed_devices import without


def main() -> int:
    if not without("codecache"):
        codecache.install()
    from rapidgen.cli import main as cli_main

    code = cli_main()
    codecache.save()
    return code
