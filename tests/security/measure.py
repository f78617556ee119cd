"""Running a live tool (spy, conform, cmd) as a child and measuring its peak memory, for the
hostile-data tier: the caps docs/security.md documents are asserted with generous margins
(memory, never time)."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
from dataclasses import dataclass

RAPIDGEN = [sys.executable, "-m", "rapidgen"]
# No byte of these may reach a terminal or a report from the wire: C0 controls but tab and
# newline (ESC and BEL among them), DEL and the C1 controls.
FORBIDDEN = {chr(c) for c in range(0x20) if c not in (0x09, 0x0A)} | {chr(0x7F)} | {chr(c) for c in range(0x80, 0xA0)}


@dataclass
class Measured:
    code: int  # negative: killed by that signal
    out: str
    err: str
    peak_mib: float  # the child's peak resident set (ru_maxrss)


def run_measured(argv: list[str], env: dict, cwd: str | os.PathLike, timeout: float = 240) -> Measured:
    """Run argv to completion; its own peak RSS from wait4 (not the other children's)."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        proc = subprocess.Popen(argv, cwd=cwd, env=env, stdout=out, stderr=err, stdin=subprocess.DEVNULL)
        _, status, usage = _wait4(proc, timeout)
        out.seek(0)
        err.seek(0)
        code = os.waitstatus_to_exitcode(status)
        return Measured(code, out.read().decode("utf-8", "replace"), err.read().decode("utf-8", "replace"),
                        usage.ru_maxrss / 1024)


def _wait4(proc: subprocess.Popen, timeout: float):
    import signal
    import threading
    timer = threading.Timer(timeout, lambda: os.kill(proc.pid, signal.SIGKILL))
    timer.start()
    try:
        got = os.wait4(proc.pid, 0)
    finally:
        timer.cancel()
    proc.returncode = os.waitstatus_to_exitcode(got[1])  # Popen must not wait for it again
    return got


def assert_clean(text: str, where: str) -> None:
    """No control byte from the wire in `text` (a terminal's output or a report)."""
    bad = sorted({f"{ord(c):#04x}" for c in text if c in FORBIDDEN})
    assert not bad, f"{where}: control characters {bad} in {text[-1500:]!r}"


def strict_json(text: str):
    """json.loads that refuses NaN/Infinity (not JSON)."""
    def refuse(name):
        raise ValueError(f"not JSON: {name}")
    return json.loads(text, parse_constant=refuse)


def strict_xml(path: str | os.PathLike):
    """Parse a file with a strict XML 1.0 parser (expat refuses control characters)."""
    return ET.parse(path)
