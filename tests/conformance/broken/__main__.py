"""python -m tests.conformance.broken KIND GENERATED_PYTHON_DIR PACKAGE DOMAIN"""
from __future__ import annotations

import os
import signal
import sys


def main() -> int:
    name, pydir, package, domain = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
    sys.path.insert(0, pydir)
    from tests.conformance.broken import PATCHES
    from tests.conformance.broken.asset import Asset

    asset = Asset(package, domain)
    PATCHES[name](asset)
    asset.start()
    for sig in (signal.SIGINT, signal.SIGTERM):  # leave the domain cleanly: the next run may reuse it
        signal.signal(sig, lambda *_: asset.bridge.stop())
    print(f"bridge ready: broken asset ({name}) {asset.tables.name}, domain {domain}", flush=True)
    try:
        asset.bridge.wait(float(os.environ.get("BROKEN_SECONDS", "120")))
    finally:
        asset.bridge.stop()
    return 0


if __name__ == "__main__":
    sys.exit(main())
