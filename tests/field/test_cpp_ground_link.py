"""Field conditions (issue 23), the C++ ground side: K10's generated `rapid_k10red_cmd`
(Fast DDS 2.9, the site library's Fast DDS file: `wan` participant, `@wan` profiles with
rtt 2.6 / lease 120) in the ground namespace drives K10's Python (Cyclone) bridge
(tests/field/counting_bridge.py: a line per handler start) in the asset namespace across
the lunar link (1.3 s each way, 20 ms jitter, 5% loss each way); then a late-joining
ground tool (tests/field/ground.py, Python/Cyclone). The reverse pairing is
test_cpp_link.py.

Every command is a `rapid_k10red_cmd --rtt 2.6` process: requestControl; a long drive
APPENDed (it holds the queue); per round 3 pending targets APPENDed behind it, then at once
an APPEND, an INSERT after one target, a REPLACE of another, a DELETE of the third and a
BYPASS; then a DELETE of the drive lets the queue run. Beside them one process sends
sequential BYPASS commands (`--repeat`, its latency). One round by default; 4 with
RAPIDGEN_FIELD_FULL=1. RAPIDGEN_CPP_SEEDS must include k10 (the default builds every seed's
bridge), or RAPIDGEN_FIELD_CPP_CMD name a rapid_k10red_cmd built already."""
from __future__ import annotations

import json
import os
import re
import time
from collections import Counter
from pathlib import Path

import pytest

from tests.cpp_client.drive import Running
from tests.cpp_runtime import build as B
from tests.field.site import site_fastdds
from tests.field.test_link import DISCOVER, LEASE, PACKAGE, RTT, SPEED, _answer, _ground, _runs, _Site

pytestmark = pytest.mark.skipif(os.geteuid() != 0 or not Path("/dev/net/tun").exists(),
                                reason="needs root and /dev/net/tun (network namespaces, TUN devices)")

FULL = os.environ.get("RAPIDGEN_FIELD_FULL") == "1"
ROUNDS = 4 if FULL else 1  # each: 3 targets, then APPEND, INSERT, REPLACE, DELETE, BYPASS at once
REPEAT = 40 if FULL else 6  # sequential BYPASS commands from one process, beside the queue
PARTICIPANTS = 40 if FULL else 24  # Fast DDS ids probed per host: ground processes alive at once
DOMAIN = 7  # inside the namespaces: any (test_link's _Site starts its bridge on it)
SOURCE = "RapidWorkbench"  # K10's allow-list lets it send everything
STAGE = 300.0  # s: a bound for one step of a broken run (discovery over the link, a loaded machine)


@pytest.fixture(scope="module")
def cpp_cmd(tmp_path_factory) -> Path:
    prebuilt = os.environ.get("RAPIDGEN_FIELD_CPP_CMD")  # a rapid_k10red_cmd built already (iterating)
    return Path(prebuilt) if prebuilt else B.k10_cmd(tmp_path_factory)


class _Ground:
    """rapid_k10red_cmd processes in the ground namespace, the site's Fast DDS file."""

    def __init__(self, site: _Site, program: Path, fastdds: Path) -> None:
        self.site, self.program, self.fastdds = site, program, fastdds
        self.stamp = f"{os.getpid()}-{time.time_ns() % 10**9}"

    def start(self, name: str, *words: str, action: str = "BYPASS", target: str = "",
              extra: tuple[str, ...] = ()) -> tuple[str, Running]:
        cmd_id = f"cpp-{name}-{self.stamp}"
        argv = [str(self.program), *words, "--source", SOURCE, "--domain", str(DOMAIN), "--transport", "wan",
                "--qos", str(self.fastdds), "--rtt", f"{RTT:g}", "--timeout", str(STAGE), "--discover", f"{DISCOVER:g}",
                "--action", action,
                *(["--target", target] if target else []), *(["--id", cmd_id] if not extra else []), *extra]
        run = Running(self.site.link.argv("ground", argv), B.dds_env())  # no FASTDDS_* of ours: --qos only
        self.site.link.children.append(run.proc)
        return cmd_id, run


def _own(lines: list[str]) -> list[str]:
    """A process's own ack lines (a DELETE then prints its target's after "target ID:")."""
    cut = next((i for i, ln in enumerate(lines) if ln.startswith("target ")), len(lines))
    return lines[:cut]


def _final(lines: list[str]) -> tuple[str, str]:
    """(completion word, message) of the one COMPLETED line, which nothing follows."""
    own = _own(lines)
    finals = [ln for ln in own if ln.strip().startswith("COMPLETED")]
    assert len(finals) == 1 and own[-1] == finals[0], lines
    word, _, message = finals[0].strip()[len("COMPLETED "):].partition("  ")
    return word, message


def _executing(lines: list[str]) -> int:
    return sum(1 for ln in _own(lines) if ln.strip() == "EXECUTING")


def test_cpp_ground_drives_the_python_bridge_across_the_lunar_link(cpp_cmd, tmp_path):
    site = _Site(tmp_path, seed=53)  # the counting bridge (Cyclone, the site library's wan file)
    fastdds = site_fastdds(tmp_path, rtt=RTT, lease=LEASE, participants=PARTICIPANTS)
    g = _Ground(site, cpp_cmd, fastdds)
    procs: dict[str, Running] = {}
    try:
        before = site.link.stats()
        control, p = g.start("control", "AccessControl", "requestControl")
        procs[control] = p
        p.wait_for("COMPLETED", STAGE)
        # sequential BYPASS commands beside the queue: one process, one participant
        _, rep = g.start("repeat", "K10Native", "nativeCommand", "text=seq", extra=("--repeat", str(REPEAT)))
        hold, p = g.start("hold", "Mobility", "simpleMove", "frame=site", f"xyt={300 * SPEED:g},0,0",
                          action="APPEND")
        procs[hold] = p
        p.wait_for("EXECUTING", STAGE)  # the queue is held: what follows stays pending
        targets = []
        for n in range(ROUNDS):
            t = {}
            for k in ("insert", "replace", "delete"):
                t[k], procs[t[k]] = g.start(f"t{k}{n}", "PanCam", "pointCamera", "pan=0.2", action="APPEND")
            targets.append(t)
        for t in targets:
            for k in t.values():
                procs[k].wait_for("QUEUED", STAGE)
        rounds = []
        for n, t in enumerate(targets):
            r = {}
            r["append"], procs[r["append"]] = g.start(f"append{n}", "PanCam", "pointCamera", "pan=0.3",
                                                      action="APPEND")
            r["insert"], procs[r["insert"]] = g.start(f"insert{n}", "PanCam", "pointCamera", "pan=-0.3",
                                                      action="INSERT", target=t["insert"])
            r["replace"], procs[r["replace"]] = g.start(f"replace{n}", "PanCam", "pointCamera", "pan=0.1",
                                                        action="REPLACE", target=t["replace"])
            r["delete"], procs[r["delete"]] = g.start(f"delete{n}", "Admin", "noOp", action="DELETE",
                                                      target=t["delete"])
            r["bypass"], procs[r["bypass"]] = g.start(f"bypass{n}", "K10Native", "nativeCommand", "text=cpp")
            rounds.append(r)
        for r in rounds:  # each queued (or, beside the queue, answered) before the drive goes
            for k in ("append", "insert", "replace"):
                procs[r[k]].wait_for("QUEUED", STAGE)
            for k in ("delete", "bypass"):
                procs[r[k]].wait_for("COMPLETED", STAGE)
        release, procs[release] = g.start("release", "Admin", "noOp", action="DELETE", target=hold)
        res = {cid: p.finish(STAGE) + ("".join(p.err),) for cid, p in procs.items()}
        rep_code, _ = rep.finish(STAGE)
        rep_out = rep.out
        log = site.log.read_text()
        seq_ids = sorted(set(re.findall(rf"^run (\S+-{SOURCE}-{rep.proc.pid}-\d+) ", log, re.M)))
        ids = [*res, *seq_ids]
        (tmp_path / "ids.json").write_text(json.dumps(ids))
        late = _answer(_ground(site.link, site.config, "late", PACKAGE, str(DOMAIN), str(tmp_path / "ids.json")))
        stats = site.link.stats()
    finally:
        site.close()
    runs = _runs(site.log)

    # every process: the live dictionary read (--rtt's discovery allowance), one final ack, at most one start
    for cid, (code, lines, err) in res.items():
        assert "no CommandConfig" not in err, (cid, err)
        _final(lines)
        assert _executing(lines) <= 1, (cid, lines)
    # control, then the held queue: the drive ran once and was canceled by the DELETE that released it
    assert res[control][0] == 0 and _final(res[control][1])[0] == "OK", res[control]
    assert _final(res[hold][1]) == ("CANCELED", "canceled") and runs[hold] == 1 and res[hold][0] == 1, res[hold]
    assert res[release][0] == 0 and _final(res[release][1])[0] == "OK" and runs[release] == 0, res[release]
    for r, t in zip(rounds, targets):
        for k in ("append", "insert", "replace", "bypass"):  # run once each, OK
            code, lines, _err = res[r[k]]
            assert code == 0 and _final(lines)[0] == "OK" and _executing(lines) == 1 and runs[r[k]] == 1, (k, lines)
        assert _final(res[t["insert"]][1])[0] == "OK" and runs[t["insert"]] == 1
        for k, why in (("replace", "replaced by"), ("delete", "deleted by")):  # canceled, never run
            code, lines, _err = res[t[k]]
            word, message = _final(lines)
            assert code == 1 and word == "CANCELED" and message.startswith(why), (k, lines)
            assert _executing(lines) == 0 and runs[t[k]] == 0, (k, lines)
        code, lines, _err = res[r["delete"]]  # a DELETE runs no handler; then its target's final ack, in order
        assert code == 0 and _final(lines)[0] == "OK" and runs[r["delete"]] == 0, lines
        after = lines[lines.index(f"target {t['delete']}:") + 1:]
        assert after[-1].startswith("  COMPLETED CANCELED  deleted by"), lines
    # INSERT puts its command right after its target (rapid-protocol.md): so they ran, in the queue's order
    queued = [line.split()[1] for line in site.log.read_text().splitlines()
              if line.split()[1] in {*(r[k] for r in rounds for k in ("append", "insert", "replace")),
                                     *(t["insert"] for t in targets)}]
    for r, t in zip(rounds, targets):
        assert queued[queued.index(t["insert"]) + 1] == r["insert"], queued
    # the sequential BYPASS commands: every one answered, each run once
    figures = json.loads(rep_out[-1])
    assert rep_code == 0 and figures["count"] == figures["answered"] == REPEAT, (rep_out, rep.err)
    assert len(seq_ids) == REPEAT and all(runs[s] == 1 for s in seq_ids), seq_ids
    print(f"rapid_k10red_cmd --repeat {REPEAT} across the lunar link: p50 {figures['p50_us'] / 1e6 / RTT:.2f}, "
          f"max {figures['max_us'] / 1e6 / RTT:.2f} round trips")
    # the late joiner: every final ack (the sender's), every config, an empty queue, each command once in it
    for cid in ids:
        assert cid in late["acks"] and late["acks"][cid][-1][0] == "ACK_COMPLETED", cid
        if cid in res:
            assert late["acks"][cid][-1][1] == "ACK_COMPLETED_" + _final(res[cid][1])[0], (cid, late["acks"][cid])
    assert sorted(late["configs"]) == late["config_topics"] and late["configs"], late["configs"]
    queue = late["queue"]
    assert queue["pending"] == [] and queue["active"] == [], queue
    assert max(Counter(cid for cid, _status in queue["completed"]).values(), default=1) == 1, queue
    # the loss was real, both ways
    assert stats["up"]["lost"] > before["up"]["lost"] and stats["down"]["lost"] > before["down"]["lost"], stats
