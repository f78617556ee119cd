"""Running the live interop peers (tests/cpp, tests/rust): each peer program reads
"topic type profile le_hex" lines on stdin; `pub` writes every sample for SECONDS, `sub`
prints "ok TOPIC" per topic received field-equal and exits 0 when all arrived."""
from __future__ import annotations

import subprocess
from pathlib import Path

# the Python/Cyclone peer (K10's generated bindings), for either interop test
PY_PEER = Path(__file__).resolve().parent / "py_peer.py"


def start(cmd: list[str], stdin: str, env: dict) -> subprocess.Popen:
    p = subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         env=env, start_new_session=True)
    assert p.stdin is not None
    p.stdin.write(stdin)
    p.stdin.close()
    p.stdin = None  # written and closed: communicate() must not flush it
    return p


def exchange(procs: dict[str, subprocess.Popen], lines: list[str], seconds: float) -> None:
    """Waits for the subscribers (names ending in "_sub") and asserts each received every
    line's topic field-equal; every process is stopped on the way out."""
    try:
        out = {}
        for name in (n for n in procs if n.endswith("_sub")):
            stdout, stderr = procs[name].communicate(timeout=seconds + 30)
            out[name] = (procs[name].returncode, stdout, stderr)
    finally:
        for p in procs.values():
            if p.poll() is None:
                p.kill()
            p.wait(timeout=30)
    want = sorted(f"ok {line.split()[0]}" for line in lines)
    for name, (code, stdout, stderr) in out.items():
        assert sorted(stdout.split("\n")[:-1]) == want, f"{name}: {stdout}\n{stderr[-3000:]}"
        assert code == 0, name
