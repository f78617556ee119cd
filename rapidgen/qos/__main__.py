"""python -m rapidgen.qos --write | --check: the packaged QoS library, precomputed
(rapidgen/qos/packaged.py, see rapidgen.qos.spec.default_library)."""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from rapidgen.qos.spec import PACKAGED_MODULE, packaged_module_text


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m rapidgen.qos",
                                     description="the packaged QoS library, precomputed: refresh or check it")
    what = parser.add_mutually_exclusive_group(required=True)
    what.add_argument("--write", action="store_true", help=f"rewrite rapidgen/qos/{PACKAGED_MODULE}")
    what.add_argument("--check", action="store_true", help="exit 1 if it is stale")
    args = parser.parse_args(argv)
    path = Path(__file__).resolve().parent / PACKAGED_MODULE
    want = packaged_module_text()
    have = path.read_text(encoding="utf-8") if path.is_file() else None
    if args.write:
        if have != want:
            path.write_text(want, encoding="utf-8")
            print(f"wrote {path}")
        return 0
    if have != want:
        print(f"stale: {path} (python -m rapidgen.qos --write)", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
