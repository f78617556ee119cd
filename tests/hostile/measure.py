"""Running a live tool (spy, conform, cmd) as a child and measuring its peak memory, for the
hostile-data tier: the caps docs/security.md documents are asserted with generous margins
(memory, never time)."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
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
    """Run argv to completion; its own peak resident set, VmHWM of its address space read
    every 20 ms while it runs. (wait4's ru_maxrss will not do: Linux carries the parent's
    high-water mark into a forked child across exec, so under a large pytest process every
    child would seem to peak at pytest's size.)"""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        proc = subprocess.Popen(argv, cwd=cwd, env=env, stdout=out, stderr=err, stdin=subprocess.DEVNULL)
        peak_kb = 0
        end = time.monotonic() + timeout
        while proc.poll() is None:
            peak_kb = max(peak_kb, _hwm_kb(proc.pid))
            if time.monotonic() > end:
                proc.kill()
            time.sleep(0.02)
        out.seek(0)
        err.seek(0)
        return Measured(proc.returncode, out.read().decode("utf-8", "replace"), err.read().decode("utf-8", "replace"),
                        peak_kb / 1024)


def _hwm_kb(pid: int) -> int:
    """VmHWM of a running process in kB (0 once it is gone)."""
    try:
        with open(f"/proc/{pid}/status") as fh:
            for line in fh:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1])
    except OSError:
        pass
    return 0


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
