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
  domain: 99  # (a default: each test names its own)
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


RESTARTED = ("asset restarted before it ran", "asset restarted while it ran; outcome unknown")


def check_kill_run(got: dict, kills: int, why: str) -> int:
    """The verdict on a kill campaign (restart_ground.py's JSON, either runtime's bridge):
    every command a final ack, the late joiner's the same, nothing run twice, each outcome
    as its command and the restarts say; the damaged journal reported once and set aside.
    Returns how many commands were answered "restarted"."""
    finals, late, runs = got["finals"], got["late"], got["runs"]
    assert [cid for cid, f in finals.items() if f is None] == [], why  # every command: a final ack
    assert {cid: late[cid] for cid in finals if late[cid] != finals[cid]} == {}, why  # the late joiner: the same
    assert {cid: n for cid, n in runs.items() if n > 1} == {}, why  # nothing ran twice
    assert set(runs) <= set(finals), why
    restarted = 0
    for cid, (sub, _name, _action) in got["plan"].items():
        _status, completion, message = finals[cid]
        if message == RESTARTED[0]:
            assert completion == "ACK_COMPLETED_CANCELED" and cid not in runs, f"{cid} {finals[cid]} {why}"
        elif message == RESTARTED[1]:
            assert completion == "ACK_COMPLETED_EXEC_FAILED", f"{cid} {finals[cid]} {why}"
        elif sub != "Admin":
            assert (completion, message, runs.get(cid)) == ("ACK_COMPLETED_OK", "worked", 1), f"{cid} {why}"
        restarted += message in RESTARTED
    # the damaged journal: one line, set aside, the bridge went on
    damaged = [ln for ln in got["journal_logs"] if "damaged line" in ln]
    assert len(damaged) == 1 and len(got["aside"]) == 1 and got["aside"][0] in damaged[0], why
    assert sum(1 for ln in got["journal_logs"] if "restarted after a crash" in ln) == kills, why
    return restarted
