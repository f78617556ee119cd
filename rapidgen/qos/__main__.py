"""python -m rapidgen.qos --write | --check: the packaged QoS library, precomputed
(rapidgen/qos/packaged.py, see rapidgen.qos.spec.default_library)."""
from __future__ import annotations

import sys
from pathlib import Path

from rapidgen.precomputed import refresh_command
from rapidgen.qos.spec import PACKAGED_MODULE, packaged_module_text


def main(argv: list[str] | None = None) -> int:
    return refresh_command("python -m rapidgen.qos", "the packaged QoS library, precomputed: refresh or check it",
                           Path(__file__).resolve().parent / PACKAGED_MODULE, packaged_module_text, argv)


if __name__ == "__main__":
    sys.exit(main())
