"""`rapidgen spy` against hostile network data (issue 19), on real Cyclone over loopback: a
healthy K10Red bridge plus a rogue participant (tests/hostile/rogue_spy.py), DDS domains
10-19 (one per test). Each spy run is a child measured by tests.hostile.measure: it ends
with its normal verdict (exit 0), its output has no control byte from the wire, JSON parses
with a strict parser, and its peak memory stays under the caps docs/spy.md documents
(generous margins; never time)."""
from __future__ import annotations

import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager

import pytest

from tests.conformance.harness import DESCRIPTORS
from tests.runtime.live import ROOT, SEEDS, BridgeProcess, env_for, python_dir
from tests.hostile.measure import RAPIDGEN, Measured, assert_clean, run_measured, strict_json

pytest.importorskip("cyclonedds")

BAD, FLOOD, PARTITIONS = 10, 11, 12  # DDS domains
FLOOD_CAP_MIB = 512  # docs/spy.md: spy --once --json beside a 4.6 MB CommandConfig at 10 Hz
PARTITIONS_CAP_MIB = 256  # docs/spy.md: spy --once --json beside one participant in 4000 partitions
ENV = env_for(python_dir("k10"), SEEDS["k10"])
K10 = ["--asset", str(DESCRIPTORS["k10"])]


@contextmanager
def network(domain: int, mode: str, arg: str = ""):
    """A healthy K10Red bridge and a rogue in `mode`; yields the rogue's participant GUID
    once its first samples are written."""
    bridge = BridgeProcess(python_dir("k10"), SEEDS["k10"], domain)
    rogue = subprocess.Popen([sys.executable, "-m", "tests.hostile.rogue_spy", mode, str(python_dir("k10")),
                              SEEDS["k10"], str(domain), "120", arg], cwd=ROOT, env=ENV, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    try:
        bridge.wait_ready()
        assert rogue.stdout is not None
        first = rogue.stdout.readline()
        assert first.startswith("rogue ready "), first + rogue.communicate()[1][-2000:]
        while not (line := rogue.stdout.readline()).startswith("rogue written"):
            assert line, rogue.communicate()[1][-2000:]
        yield first.split()[2]
    finally:
        rogue.kill()
        rogue.communicate()
        bridge.stop()


def spy(domain: int, *argv: str) -> Measured:
    return run_measured([*RAPIDGEN, "spy", "--domain", str(domain), *argv], ENV, ROOT, timeout=180)


def spies(domain: int, *runs: list[str]) -> list[Measured]:
    """Several spy runs at once (each its own participant), in order."""
    with ThreadPoolExecutor(len(runs)) as pool:
        return list(pool.map(lambda argv: spy(domain, *argv), runs))


def ended_normally(m: Measured, what: str) -> None:
    assert m.code == 0, f"{what}: exit {m.code}\n{m.err[-3000:]}"
    assert "Traceback" not in m.err and "internal error" not in m.err, m.err[-3000:]
    assert_clean(m.out, f"{what} stdout")
    assert_clean(m.err, f"{what} stderr")


def test_bad_durable_config_once_json_and_echo_give_their_verdict(tmp_path):
    with network(BAD, "bad-config") as rogue:
        text, js, echo_cfg, echo_state = spies(
            BAD, ["--once", "--seconds", "3", *K10], ["--once", "--json", "--seconds", "3", *K10],
            ["echo", "rapid_command_config", "--seconds", "4"],
            ["echo", "rapid_agent_state", "--json", "--seconds", "4", "--partition", "K10Red"])
    prefix = rogue[:28]  # the GUID prefix every endpoint of the rogue's participant shares
    for m, what in ((text, "spy --once"), (js, "spy --once --json"), (echo_cfg, "spy echo"),
                    (echo_state, "spy echo --json")):
        ended_normally(m, what)

    # text: the finding names the topic and the rogue's writer; the bridge's configs are read
    data_lines = [x for x in text.out.splitlines() if "SPY-DATA-01" in x and "rapid_command_config" in x]
    assert len(data_lines) == 1 and prefix in data_lines[0] and "1 sample(s)" in data_lines[0], text.out[-3000:]
    assert "rapid_agent_config (serial" in text.out and "rapid_command_config (serial" in text.out, text.out

    # JSON: strict; "dropped" says what, from which writer of which participant; the rest is read
    snap = strict_json(js.out)
    dropped = {d["topic"]: d for d in snap["dropped"]}
    assert dropped["rapid_command_config"]["participant"] == rogue and dropped["rapid_command_config"]["count"] == 1
    assert dropped["rapid_command_config"]["writer"].startswith(prefix)
    assert "UnicodeDecodeError" in dropped["rapid_command_config"]["error"]
    assert [f["topic"] for f in snap["findings"] if f["code"] == "SPY-DATA-01"] == \
        ["rapid_agent_state", "rapid_command_config"], snap["findings"]
    k10 = next(a for a in snap["assets"] if a["partition"] == "K10Red")
    topics = {t["topic"]: t for t in k10["topics"]}
    assert topics["rapid_agent_config"]["latest"]["hdr"]["assetName"] == "K10Red"
    assert topics["rapid_command_config"]["samples"] >= 2  # the bridge's and the rogue's good one

    # echo (text): the bad config is said once, with its writer; the bridge's config is printed
    lines = echo_cfg.out.splitlines()
    said = [x for x in lines if "did not decode and were dropped" in x]
    assert len(said) == 1 and prefix in said[0], lines
    assert any('"srcName": "K10Red"' in x for x in lines), lines
    assert any('"srcName": "Rogue\\u001b]0;pw\\u0007' in x for x in lines), lines  # the rogue's, escaped

    # echo --json: every line strict JSON; +-Inf and NaN as strings; drops as their own lines
    objs = [strict_json(x) for x in echo_state.out.splitlines()]
    samples = [o["sample"] for o in objs if "sample" in o]
    odd = [s for s in samples if s["hdr"]["srcName"] == "RogueInf"]
    # (unions are {discriminator, value}: rapid_runtime.plain)
    assert odd and [v["value"] for v in odd[0]["values"]] == ["Infinity", "-Infinity", "NaN"]
    drops = [o for o in objs if "dropped" in o]
    assert drops and drops[-1]["writer"].startswith(prefix) and drops[-1]["dropped"] >= 5, objs[-5:]


def test_full_bounds_config_flood_keeps_spy_bounded():
    """JSON holds the newest config whole (the heavier output; the text view's cut is
    tests/spy/test_limits.py's). The flood's rate on loopback is bounded by Cyclone's 1100-byte
    fragments (4500 per sample): a few samples a second reach spy."""
    with network(FLOOD, "big-config") as rogue:
        js = spy(FLOOD, "--once", "--json", "--seconds", "3", *K10)
    ended_normally(js, "spy --once --json")
    assert js.peak_mib < FLOOD_CAP_MIB, js.peak_mib
    snap = strict_json(js.out)
    cfg = next(t for a in snap["assets"] if a["partition"] == "K10Red" for t in a["topics"]
               if t["topic"] == "rapid_command_config")
    assert cfg["samples"] >= 2  # the flood was read...
    assert any("republished config(s) with the same bytes decoded once" in x for x in snap["limits"])  # ...once
    assert len(cfg["latest"]["availableSubsystemTypes"]) == 64  # the newest config, whole, in JSON
    assert any(rogue == p["key"] for p in snap["participants"])


def test_one_participant_in_4000_partitions_keeps_spy_bounded():
    with network(PARTITIONS, "partitions", "4000") as rogue:
        js, text = spies(PARTITIONS, ["--once", "--json", "--seconds", "3", *K10], ["--once", "--seconds", "3", *K10])
    ended_normally(js, "spy --once --json")
    ended_normally(text, "spy --once")
    assert js.peak_mib < PARTITIONS_CAP_MIB and text.peak_mib < PARTITIONS_CAP_MIB, (js.peak_mib, text.peak_mib)
    snap = strict_json(js.out)
    parts = {a["partition"] for a in snap["assets"]}
    assert "K10Red" in parts and len(parts) <= 1 + 16  # the declared partition, and 16 of the rogue's
    k10 = next(a for a in snap["assets"] if a["partition"] == "K10Red")
    assert {t["topic"] for t in k10["topics"]} >= {"rapid_command_config", "rapid_agent_config", "rapid_agent_state"}
    who = next(p for p in snap["participants"] if p["key"] == rogue)
    assert len(who["partitions"]) <= 16 and len(who["partitions"]) + who["other_partitions"] >= 3999
    assert any("partition names of an endpoint left out" in x for x in snap["limits"]), snap["limits"]
    assert any("partition(s) not read" in x for x in snap["limits"]), snap["limits"]
    assert "Limits reached" in text.out and "'Evil\\x1b]0;pwned" in text.out  # the partition's name, escaped
