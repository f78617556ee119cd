"""Starting a seed asset's simulated bridge for the live tests: loopback only (the
package's own qos_files/cyclonedds/local.xml), its own DDS domain, ready when it says so."""
from __future__ import annotations

import os
import queue
import subprocess
import sys
import tempfile
import threading
from pathlib import Path

ROOT = Path(__file__).parents[2]
SEEDS = {"athlete": "rapid_athlete", "chariot": "rapid_chariot", "eva-suit": "rapid_evasuita", "k10": "rapid_k10red",
         "robonaut2": "rapid_robonaut2", "xarm2": "rapid_xarm2"}


def python_dir(asset: str) -> Path:
    return ROOT / "generated" / asset / "python"


def env_for(pydir: Path, package: str) -> dict:
    """Loopback only; the bridge's restart journal in a folder of this test run's own (a
    journal left by an earlier run would answer its commands again)."""
    local = pydir / package / "qos_files" / "cyclonedds" / "local.xml"
    return dict(os.environ, CYCLONEDDS_URI=f"file://{local}", PYTHONPATH=f"{pydir}{os.pathsep}{ROOT}",
                PYTHONDONTWRITEBYTECODE="1", RAPID_STATE_DIR=_STATE)


_STATE = tempfile.mkdtemp(prefix="rapid-state-")


class BridgeProcess:
    def __init__(self, pydir: Path, package: str, domain: int, *extra: str, python: str = sys.executable) -> None:
        self._spawn([python, "-m", f"{package}.bridge", "--simulate", "--domain", str(domain), "--sim-speed", "20",
                     *extra], pydir, env_for(pydir, package))

    @classmethod
    def of_command(cls, argv: list[str], cwd: Path, env: dict) -> "BridgeProcess":
        """Another program in the bridge's place (e.g. a deliberately broken asset)."""
        bp = cls.__new__(cls)
        bp._spawn(argv, cwd, env)
        return bp

    def _spawn(self, argv: list[str], cwd: Path, env: dict) -> None:
        self.proc = subprocess.Popen(argv, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.lines: queue.Queue = queue.Queue()
        self.err: list[str] = []
        # One reader thread per pipe: stop() must not read stdout too (it would close the
        # pipe under the pump), and stderr must be drained so a chatty bridge never blocks.
        self._threads = [threading.Thread(target=self._pump, daemon=True),
                         threading.Thread(target=lambda: self.err.extend(self.proc.stderr), daemon=True)]
        for t in self._threads:
            t.start()

    def _pump(self) -> None:
        for line in self.proc.stdout:
            self.lines.put(line)
        self.lines.put(None)

    def wait_ready(self, timeout: float = 30) -> str:
        line = self.lines.get(timeout=timeout)
        if line is None or not line.startswith("bridge ready"):
            self.proc.kill()
            self.proc.wait()
            self._threads[1].join(timeout=5)
            raise AssertionError(f"bridge did not start: {line!r} {''.join(self.err)[-2000:]}")
        return line

    def stop(self) -> str:
        if self.proc.poll() is None:
            self.proc.terminate()
        try:
            self.proc.wait(timeout=20)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        for t in self._threads:
            t.join(timeout=5)
        return "".join(self.err)


def ground(check: str, pydir: Path, package: str, domain: int, python: str = sys.executable) -> dict:
    import json
    res = subprocess.run([python, "-m", "tests.runtime.ground", check, str(pydir), package, str(domain)],
                         cwd=ROOT, env=env_for(pydir, package), capture_output=True, text=True, timeout=240)
    assert res.returncode == 0, res.stdout[-2000:] + res.stderr[-4000:]
    return json.loads(res.stdout.splitlines()[-1])
