"""`--write | --check` of a module the package ships precomputed from another of its files
(rapidgen/idl/packaged_tables.py from the IDL grammar): a stale one still works (it is not
used), only slower."""
from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Callable, Sequence


def refresh_command(prog: str, description: str, path: Path, text: Callable[[], str],
                    argv: Sequence[str] | None = None) -> int:
    """`prog --write` rewrites `path` with `text()` when it differs; `prog --check` exits 1
    when it differs (and says how to refresh it)."""
    parser = argparse.ArgumentParser(prog=prog, description=description)
    what = parser.add_mutually_exclusive_group(required=True)
    what.add_argument("--write", action="store_true", help=f"rewrite {path.name} when it is stale")
    what.add_argument("--check", action="store_true", help="exit 1 if it is stale")
    args = parser.parse_args(argv)
    want = text()
    have = path.read_text(encoding="utf-8") if path.is_file() else None
    if args.write:
        if have != want:
            path.write_text(want, encoding="utf-8")
            print(f"wrote {path}")
        return 0
    if have != want:
        print(f"stale: {path} ({prog} --write)", file=sys.stderr)
        return 1
    return 0
