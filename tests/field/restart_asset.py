"""The asset of the restart tests: a queue, and one command that works for `ms` milliseconds
on two subsystems (Belt through the queue, Side beside it: different subsystems, so a BYPASS
command never preempts a queued one and nothing is requeued, i.e. run a second time by
design). No access control: control would not survive a restart (docs/runtime.md)."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).parents[2]
PACKAGE = "rapid_restarter"
ASSET = "Restarter"
DESCRIPTOR = """\
version: 1
asset:
  name: Restarter
  kind: rover
  description: a test asset for kill -9 and restart
dds:
  domain: 193
idl:
  rapid: {rapid}
subsystem_types:
  - name: Worker
    description: does slow work
    commands:
      - name: work
        description: work for ms milliseconds
        parameters:
          - {{name: ms, type: RAPID_INT, unit: ms, range: [0, 10000], default: 100}}
subsystems:
  - {{name: Admin}}
  - {{name: Queue}}
  - {{name: Belt, type: Worker, description: queued work}}
  - {{name: Side, type: Worker, description: work beside the queue}}
"""


def generate(folder: Path) -> Path:
    """Generate the asset's Python package into folder; its python dir."""
    folder.mkdir(parents=True, exist_ok=True)
    desc = folder / "restarter.yaml"
    desc.write_text(DESCRIPTOR.format(rapid=ROOT / "specs" / "rapid"))
    res = subprocess.run([sys.executable, "-m", "rapidgen", "generate", str(desc), "--lang", "python", "-o",
                          str(folder / "out")], cwd=ROOT, capture_output=True, text=True, timeout=120)
    if res.returncode != 0:
        raise RuntimeError(f"rapidgen generate failed: {res.stdout[-1000:]} {res.stderr[-2000:]}")
    return folder / "out" / "python"


def env_for(pydir: Path) -> dict:
    local = pydir / PACKAGE / "qos_files" / "cyclonedds" / "local.xml"  # loopback only
    return dict(os.environ, CYCLONEDDS_URI=f"file://{local}", PYTHONDONTWRITEBYTECODE="1",
                PYTHONPATH=os.pathsep.join([str(pydir), str(ROOT / "runtime"), str(ROOT)]))
