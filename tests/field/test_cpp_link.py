"""Field conditions (issue 23), the other stack: K10's generated C++ bridge (Fast DDS 2.9,
its `wan` participant from a site library with the link's rtt and lease: docs/qos.md "Slow
links") in the asset namespace, driven across the lunar link (1.3 s each way, 20 ms
jitter, 5% loss each way) by Python/Cyclone ground tools: `rapidgen cmd --rtt 2.6` and a
script (tests/field/ground.py), then a late-joining ground tool.

Short by default (one round of every queue action from the script, one from rapidgen cmd);
RAPIDGEN_FIELD_FULL=1 runs 4 rounds of each and `rapidgen conform --rtt 2.6`.
RAPIDGEN_CPP_SEEDS must include k10 (the default builds every seed's bridge), or
RAPIDGEN_FIELD_CPP_BRIDGE name a K10 bridge built already."""
from __future__ import annotations

import json
import os
import subprocess
from collections import Counter
from pathlib import Path

import pytest

from tests.cpp_runtime import build as B
from tests.field.link import LUNAR, Link, rtt
from tests.field.site import K10, RAPIDGEN, ROOT, site_env, site_fastdds, site_library
from tests.field.test_link import _answer, _cli, _cli_results, _final, _ground
from tests.runtime.live import BridgeProcess

pytestmark = pytest.mark.skipif(os.geteuid() != 0 or not Path("/dev/net/tun").exists(),
                                reason="needs root and /dev/net/tun (network namespaces, TUN devices)")

FULL = os.environ.get("RAPIDGEN_FIELD_FULL") == "1"
ROUNDS = 4 if FULL else 1  # script rounds, and rapidgen cmd rounds (5 processes each)
RTT = rtt(LUNAR)
LEASE = 120.0
PARTICIPANTS = 24
SPEED = 20.0
DOMAIN = 7  # inside the namespaces: any (the same value test_link's helpers use)


class _CppSite:
    """A lunar link with K10's C++ bridge in the asset namespace; Cyclone ground files."""

    def __init__(self, bridge: Path, tmp: Path, seed: int) -> None:
        self.link = Link(LUNAR, seed=seed)
        self.link.start()
        try:
            self.config = site_library(tmp, rtt=RTT, lease=LEASE, participants=PARTICIPANTS)
            self.fastdds = site_fastdds(tmp, rtt=RTT, lease=LEASE, participants=PARTICIPANTS)
            self.bridge = BridgeProcess.of_command(self.link.argv("asset", [
                str(bridge), "--simulate", "--sim-speed", str(SPEED), "--domain", str(DOMAIN), "--transport", "wan",
                "--qos", str(self.fastdds), "--journal", str(tmp / "journal")]), ROOT, B.dds_env())
            self.link.children.append(self.bridge.proc)
            self.bridge.wait_ready(60)
        except BaseException:
            self.link.close()
            raise

    def close(self) -> str:
        try:
            return self.bridge.stop()
        finally:
            self.link.close()


@pytest.fixture(scope="module")
def cpp_bridge(tmp_path_factory) -> Path:
    prebuilt = os.environ.get("RAPIDGEN_FIELD_CPP_BRIDGE")  # a K10 bridge built already (iterating)
    if prebuilt:
        return Path(prebuilt)
    if "k10" not in B.chosen_seeds():
        pytest.skip("RAPIDGEN_CPP_SEEDS leaves out k10")
    return B.seed_bridges(tmp_path_factory)["k10"]


def _executing(acks: list) -> int:
    return sum(1 for a in acks if a[0] == "ACK_EXECUTING")


def test_cpp_bridge_across_the_lunar_link_runs_every_queue_action_once_and_answers_all(cpp_bridge, tmp_path):
    site = _CppSite(cpp_bridge, tmp_path, seed=43)
    link, config = site.link, site.config
    try:
        script = _ground(link, config, "drive", "rapid_k10red", str(DOMAIN), str(ROUNDS), "--wave", str(ROUNDS),
                         "--speed", str(SPEED), "--targets", str(ROUNDS), stdin=subprocess.PIPE)
        line = script.stdout.readline()
        assert line.startswith("{"), script.stderr.read()[-3000:] if script.poll() is not None else line
        gated = json.loads(line)
        cli = _cli(link, config, gated["targets"])
        script.stdin.write("go\n")
        script.stdin.flush()
        res = _cli_results(cli)
        drive = _answer(script)
        ids = [*drive["acks"], *res]
        (tmp_path / "ids.json").write_text(json.dumps(ids))
        late = _answer(_ground(link, config, "late", "rapid_k10red", str(DOMAIN), str(tmp_path / "ids.json")))
        stats = link.stats()
    finally:
        out = site.close()
    acks = drive["acks"]
    # the script: each command's one final ack; run (one EXECUTING) or canceled (none) as its action says
    for r in drive["rounds"]:
        for k in "bceh":
            assert _final(acks[r[k]])[1] == "ACK_COMPLETED_OK" and _executing(acks[r[k]]) == 1, (k, acks[r[k]])
        for k, why in (("d", "replaced by"), ("f", "deleted by")):
            final = _final(acks[r[k]])
            assert final[1] == "ACK_COMPLETED_CANCELED" and final[2].startswith(why), final
            assert _executing(acks[r[k]]) == 0
        assert _final(acks[r["g"]])[1] == "ACK_COMPLETED_OK"  # the DELETE itself (it runs no handler)
    for hold in drive["holds"]:
        assert _final(acks[hold])[1] == "ACK_COMPLETED_CANCELED" and _executing(acks[hold]) == 1, acks[hold]
    # rapidgen cmd: every process its command's final ack, from the live dictionary
    for cid, (code, text, err) in res.items():
        assert "no CommandConfig" not in err, (cid, err)
        assert code == 0 and "COMPLETED OK" in text, (cid, code, text, err)
        assert text.count("EXECUTING") <= 1, (cid, text)
    for r, t in zip(cli["ids"], gated["targets"]):
        for k in ("append", "insert", "replace", "bypass"):
            assert res[r[k]][1].count("EXECUTING") == 1, (k, res[r[k]])
        for k, why in (("replace", "replaced by"), ("delete", "deleted by")):
            final = _final(acks[t[k]])
            assert final[1] == "ACK_COMPLETED_CANCELED" and final[2].startswith(why), final
        assert _final(acks[t["insert"]])[1] == "ACK_COMPLETED_OK" and _executing(acks[t["insert"]]) == 1
    # the late joiner: every final ack (the sender's), every config, an empty queue, each command once in it
    for cid in ids:
        assert cid in late["acks"] and late["acks"][cid][-1][0] == "ACK_COMPLETED", cid
        if cid in acks:
            assert late["acks"][cid][-1][:2] == _final(acks[cid])[:2], cid
    assert sorted(late["configs"]) == late["config_topics"] and late["configs"], late["configs"]
    queue = late["queue"]
    assert queue["pending"] == [] and queue["active"] == [], queue
    assert max(Counter(cid for cid, _status in queue["completed"]).values(), default=1) == 1, queue
    assert stats["up"]["lost"] > 0 and stats["down"]["lost"] > 0, stats  # the loss was real
    # the bridge's writers are the site's @wan profiles (docs/qos.md): blocking 2 round trips, not 100 ms
    assert late["ack_writers_blocking"] == [pytest.approx(2 * RTT)], (late["ack_writers_blocking"], out[-2000:])


@pytest.mark.skipif(not FULL, reason="RAPIDGEN_FIELD_FULL=1: conform against the C++ bridge across the link")
def test_cpp_bridge_passes_conform_across_the_lunar_link(cpp_bridge, tmp_path):
    site = _CppSite(cpp_bridge, tmp_path, seed=47)
    report = tmp_path / "conform.json"
    try:
        res = site.link.run("ground", [*RAPIDGEN, "conform", K10, "--domain", str(DOMAIN), "--rtt", f"{RTT:g}",
                                       "--json", str(report)], cwd=ROOT, env=site_env(site.config),
                            capture_output=True, text=True, timeout=1200)
    finally:
        site.close()
    data = json.loads(report.read_text())
    required = [c for c in data["checks"] if c["level"] == "required"]
    assert required and data["passed"] and res.returncode == 0, res.stdout[-4000:]
