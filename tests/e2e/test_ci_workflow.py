"""docs/ci.md's GitHub Actions workflow, run here (issue 26): the test reads the workflow
from the page and runs its `run:` steps with bash, in order, in a scratch repository laid
out like a team's (a descriptor, rapidgen.yaml, committed generated/, an origin/main), with
the workflow's env. The install step is skipped (rapidgen is this checkout's) and `uses:`
steps are GitHub's own. DDS stays on loopback (the package's local transport), on the
domain the workflow names."""
from __future__ import annotations

import os
import re
import shutil
import signal
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "ci.md"


def workflow() -> dict:
    text = DOC.read_text(encoding="utf-8")
    block = next(b for b in re.findall(r"```yaml\n(.*?)```", text, re.S) if "jobs:" in b)
    return yaml.safe_load(block)


def git(repo: Path, *args: str) -> None:
    subprocess.run(["git", *args], cwd=repo, check=True, capture_output=True, text=True)


def team_repository(tmp_path: Path) -> Path:
    """A clone of a team's repository: K10's descriptor and the RAPID IDL, a project file
    with its python and qos targets, generated/ committed, main pushed to origin."""
    origin, repo = tmp_path / "origin.git", tmp_path / "work"
    git(tmp_path, "init", "-q", "--bare", str(origin))
    repo.mkdir()
    shutil.copytree(ROOT / "specs", repo / "specs")
    (repo / "rapidgen.yaml").write_text("targets:\n  - name: k10\n    asset: specs/assets/k10.yaml\n"
                                        "    lang: [python, qos]\n    out: generated/k10\n", encoding="utf-8")
    fixed = subprocess.run([sys.executable, "-m", "rapidgen", "check", "--fix"], cwd=repo, capture_output=True,
                           text=True)
    assert fixed.returncode == 0, fixed.stderr
    git(repo, "init", "-q", "-b", "main")
    git(repo, "config", "user.email", "ci@example.invalid")
    git(repo, "config", "user.name", "ci")
    git(repo, "add", "-A")
    git(repo, "commit", "-q", "-m", "k10")
    git(repo, "remote", "add", "origin", str(origin))
    git(repo, "push", "-q", "origin", "main")
    git(repo, "fetch", "-q", "origin")
    return repo


def test_the_workflow_steps_pass_in_a_team_repository(tmp_path):
    pytest.importorskip("cyclonedds")
    flow = workflow()
    job = next(iter(flow["jobs"].values()))
    steps = [s for s in job["steps"] if "run" in s and not s.get("name", "").startswith("Install")]
    assert [s["name"] for s in steps] == ["Generated code is up to date", "No wire or protocol break against main",
                                          "Conformance of the simulated bridge"]
    assert any(s.get("uses", "").startswith("actions/upload-artifact") for s in job["steps"])
    repo = team_repository(tmp_path)
    bindir = str(Path(sys.executable).parent)  # rapidgen and python as installed in this environment
    env = {k: v for k, v in os.environ.items() if k not in ("CYCLONEDDS_URI", "PYTHONPATH")}
    env.update({k: str(v) for k, v in flow["env"].items()}, PATH=bindir + os.pathsep + env.get("PATH", ""),
               GITHUB_ACTIONS="true")
    for step in steps:
        proc = subprocess.Popen(["bash", "-eo", "pipefail", "-c", step["run"]], cwd=repo, env=env,
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True)
        try:
            out, _ = proc.communicate(timeout=300)
        finally:
            try:  # the step's own children (a bridge left behind when a step fails)
                os.killpg(proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        assert proc.returncode == 0, f"{step['name']}:\n{out[-4000:]}"
    report = ET.parse(repo / "build" / "conformance.xml").getroot()
    suites = [report] if report.tag == "testsuite" else list(report)
    cases = [c for s in suites for c in s.iter("testcase")]
    assert len(cases) > 30 and not [c for c in cases if c.find("failure") is not None or c.find("error") is not None]
