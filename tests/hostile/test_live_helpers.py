"""The wire rules: visible() has two copies (rapid_runtime.untrusted for the robot,
rapidgen.textsafe for the compiler, which must run without the runtime) that escape alike;
the one GuardedReader (rapid_runtime.untrusted, the bridge's and the live tools') keeps and
drops the same samples whether it logs (the bridge) or dedupes (the tools), from a real
reader (Cyclone on loopback, domain 34)."""
from __future__ import annotations

import json
import subprocess
import sys

from hypothesis import given, settings
from hypothesis import strategies as st

from rapid_runtime.untrusted import visible as runtime_visible
from rapidgen.textsafe import visible as tool_visible
from tests.runtime.live import ROOT, SEEDS, env_for, python_dir
from tests.hostile.measure import FORBIDDEN


@settings(max_examples=500)
@given(st.text(alphabet=st.characters(codec=None), max_size=120))
def test_both_visible_escape_alike_and_leave_no_control_byte(text):
    shown = runtime_visible(text, limit=1000)
    assert shown == tool_visible(text)
    assert not FORBIDDEN & set(shown)


def test_runtime_visible_bounds_a_line():
    assert runtime_visible("x" * 5000, limit=10) == "x" * 10 + "..."


def test_the_guarded_reader_keeps_the_good_and_drops_the_bad_as_the_bridge_and_the_tools_use_it():
    pydir, package = python_dir("k10"), SEEDS["k10"]
    res = subprocess.run([sys.executable, "-m", "tests.hostile.guard_probe", str(pydir), package, "34"], cwd=ROOT,
                         env=env_for(pydir, package), capture_output=True, text=True, timeout=60)
    assert res.returncode == 0, res.stderr[-3000:]
    out = json.loads(res.stdout.splitlines()[-1])
    good = [f"good-{i}" for i in range(10) if i % 3 != 1]
    for side in ("runtime", "tool"):
        assert out[side]["got"] == good, out  # every good sample, in order, bad neighbours or not
        assert out[side]["dropped"] == 3 and out[side]["counts"] == [3]
    assert out["runtime"]["writers"] == out["tool"]["writers"]
    assert len(out["logs"]) == 1 and out["runtime"]["writers"][0] in out["logs"][0]  # said once, naming the writer
