"""Run a script of tests/node under Node with Foxglove's npm libraries (tests/node/package.json,
installed by scripts/setup.sh with `npm ci`). No skip: a machine without them fails the test
with what to run."""
from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path
from typing import Any

NODE_DIR = Path(__file__).resolve().parent
PACKAGES = ("@mcap/core", "@mcap/support", "@foxglove/omgidl-parser", "@foxglove/omgidl-serialization",
            "@foxglove/ws-protocol", "@foxglove/schemas", "ajv", "ws")


def node() -> str:
    """The node binary, once the packages resolve from tests/node; else an AssertionError
    saying how to install them."""
    exe = shutil.which("node")
    assert exe, "node is not on PATH: install Node.js (scripts/setup.sh then installs tests/node)"
    probe = subprocess.run([exe, "-e", f"for (const m of {json.dumps(list(PACKAGES))}) require.resolve(m)"],
                           cwd=NODE_DIR, capture_output=True, text=True)
    assert probe.returncode == 0, ("Foxglove's npm libraries are not installed in tests/node/node_modules: "
                                   "run `bash scripts/setup.sh` (or `npm ci` in tests/node)\n" + probe.stderr[-800:])
    return exe


def run_json(script: str, *args: str, timeout: float = 180) -> Any:
    """Run tests/node/SCRIPT with ARGS; its stdout's last line parsed as JSON."""
    res = subprocess.run([node(), str(NODE_DIR / script), *args], cwd=NODE_DIR, capture_output=True, text=True,
                         timeout=timeout)
    assert res.returncode == 0, f"{script} exited {res.returncode}: {res.stderr[-3000:]}"
    return json.loads(res.stdout.strip().splitlines()[-1])
