"""`rapidgen record` and `rapidgen replay` on loopback (domains 56-57): the README's main job
(K10's simulated bridge driven by `rapidgen cmd`) recorded while an independent raw reader
(tests/record/tap.py) listens too; read back with the `mcap` library: every topic, every
message's bytes equal to the tap's and to the generated codec's re-encoding, schemas that
rapidgen's own IDL front end parses into the recorded type; the recorder rotates files by
size and each one is complete. A second recorder is killed with SIGKILL: its file is
readable up to its last chunk. The recording replayed into another domain is seen by `rapidgen spy` with
the recorded per-topic rates (within 20%), its extension types built from the recording's own
schemas."""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

import pytest

from tests.runtime.live import ROOT, SEEDS, BridgeProcess, env_for, python_dir

DOMAIN, REPLAY_DOMAIN = 56, 57
MIN_SECONDS = 9  # the bridge runs at least this long: ~8 intervals of its 1 Hz topics after SKIP
SKIP = 1.0  # replayed --from: a bridge's first samples come in pairs
RAPIDGEN = [sys.executable, "-m", "rapidgen"]
K10 = str(ROOT / "specs" / "assets" / "k10.yaml")
PYDIR, PKG = python_dir("k10"), SEEDS["k10"]
ENV = env_for(PYDIR, PKG)
CMD = [*RAPIDGEN, "cmd", K10, "--domain", str(DOMAIN), "--source", "RapidWorkbench", "--timeout", "20"]
# The README's main job (scripts/demo, step 5): (arguments, expected exit status)
JOB = [(["AccessControl", "requestControl"], 0),
       (["Mobility", "simpleMove", "frame=site", "xyt=2,1,0"], 0),
       (["PanCam", "pointCamera", "pan=4", "--no-check"], 1),  # answered BAD_SYNTAX
       (["Mobility", "simpleMove", "frame=site", "xyt=200,0,0", "--action", "APPEND", "--id", "rec-long-drive",
         "--no-wait"], 0),
       (["Admin", "noOp", "--action", "DELETE", "--target", "rec-long-drive"], 0)]


class Proc:
    """A child whose stderr lines are collected (read by a thread: it never blocks)."""

    def __init__(self, argv: list[str]) -> None:
        import threading
        self.proc = subprocess.Popen(argv, cwd=ROOT, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.err: list[str] = []
        self.out: list[str] = []
        self._threads = [threading.Thread(target=lambda: self.err.extend(self.proc.stderr), daemon=True),
                         threading.Thread(target=lambda: self.out.extend(self.proc.stdout), daemon=True)]
        for t in self._threads:
            t.start()

    def wait_for(self, text: str, where: str = "err", timeout: float = 60) -> None:
        end = time.monotonic() + timeout
        while not any(text in line for line in (self.err if where == "err" else self.out)):
            assert self.proc.poll() is None, "".join(self.err)[-3000:]
            assert time.monotonic() < end, f"no {text!r}: " + "".join(self.err)[-3000:]
            time.sleep(0.05)

    def end(self, sig: int = signal.SIGTERM, timeout: float = 60) -> int:
        if self.proc.poll() is None:
            self.proc.send_signal(sig)
        code = self.proc.wait(timeout=timeout)
        for t in self._threads:
            t.join(timeout=5)
        return code


@pytest.fixture(scope="module")
def job(tmp_path_factory):
    pytest.importorskip("cyclonedds")
    pytest.importorskip("mcap")
    tmp = tmp_path_factory.mktemp("record")
    main, killed = tmp / "main.mcap", tmp / "killed.mcap"
    tap = Proc([sys.executable, "-m", "tests.record.tap", str(PYDIR), PKG, str(DOMAIN), str(tmp / "tap.json")])
    rec = Proc([*RAPIDGEN, "record", "--asset", K10, "--domain", str(DOMAIN), "-o", str(main), "--split-size", "16K"])
    rot = Proc([*RAPIDGEN, "record", "--asset", K10, "--domain", str(DOMAIN), "-o", str(killed), "--quiet"])
    bridge = None
    try:
        tap.wait_for("tap ready", where="out")
        for r in (rec, rot):
            r.wait_for("rapidgen record: recording domain")
        bridge = BridgeProcess(PYDIR, PKG, DOMAIN, "--sim-speed", "4")
        bridge.wait_ready()
        up = time.monotonic()
        results = [subprocess.run(CMD + argv, cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=120)
                   for argv, _ in JOB]
        # the second recorder has written chunks (its file grew twice after the header): kill it
        sizes = {killed.stat().st_size}
        end = time.monotonic() + 60
        while len(sizes) < 3 and time.monotonic() < end:
            sizes.add(killed.stat().st_size)
            time.sleep(0.05)
        rot_killed = rot.end(signal.SIGKILL)
        time.sleep(max(0.0, MIN_SECONDS - (time.monotonic() - up)))  # enough 1 Hz samples to measure a rate
        bridge.stop()
        bridge = None
        time.sleep(0.5)  # the last samples reach both readers
        rec_code, tap_code = rec.end(), tap.end()
    finally:
        if bridge is not None:
            bridge.stop()
        for p in (tap, rec, rot):
            if p.proc.poll() is None:
                p.proc.kill()
                p.proc.wait()
    assert tap_code == 0 and rec_code == 0, "".join(rec.err)[-3000:]
    with open(tmp / "tap.json", encoding="utf-8") as fh:
        tapped = {t: [bytes.fromhex(h) for h in hs] for t, hs in json.load(fh).items()}
    return {"tmp": tmp, "main": sorted(tmp.glob("main-*.mcap")), "killed": killed, "rot_killed": rot_killed,
            "results": results, "tap": tapped, "rec_err": "".join(rec.err)}


def _read(path: Path):
    """(summary, [(schema, channel, message)]) through the mcap library alone."""
    from mcap.reader import make_reader
    with open(path, "rb") as fh:
        reader = make_reader(fh, validate_crcs=True)
        return reader.get_summary(), list(reader.iter_messages(log_time_order=True))


def _read_all(paths: list[Path]):
    """Every file of a rotated recording: ([summaries], [(schema, channel, message)]); a config
    carried into a later file (the same sequence number) is counted once."""
    got = [_read(p) for p in paths]
    seen: set[int] = set()
    out = []
    for _, ms in got:
        for item in ms:
            if item[2].sequence not in seen:
                seen.add(item[2].sequence)
                out.append(item)
    return [s for s, _ in got], out


def _topics_json() -> list[dict]:
    with open(PYDIR / PKG / "qos_files" / "topics.json", encoding="utf-8") as fh:
        return json.load(fh)["topics"]


def _every_sample_promised() -> set[str]:
    """The topics whose writers promise every sample to every matched reader: reliable, with
    a history of more than one sample per instance (commands, acks; configs are written once).
    On the others (best-effort samples; reliable states keeping the last one) a reader that
    lost a packet gets the next sample instead, and two readers may differ by it."""
    from rapidgen.live.discovery import QosSummary
    sys.path.insert(0, str(PYDIR))
    try:
        import importlib
        qos = importlib.import_module(f"{PKG}.qos").RapidQos()
    finally:
        sys.path.remove(str(PYDIR))
    promised = {"rapid_ack"}  # (the profile keeps one; the bridge's ack writers keep each command's 8)
    for entry in _topics_json():
        w = QosSummary.of(qos.writer(entry["topic"]))
        if w.reliability == "Reliable" and (w.history == "KeepAll" or (w.depth or 0) > 1 or "config" in entry["topic"]):
            promised.add(entry["topic"])
    return promised


def test_main_job_ran_as_the_readme_says(job):
    for (argv, want), res in zip(JOB, job["results"]):
        assert res.returncode == want, (argv, res.stdout[-1500:], res.stderr[-1500:])
    assert "BAD_SYNTAX" in job["results"][2].stdout


def test_every_topic_recorded_with_the_bytes_sent(job):
    summaries, messages = _read_all(job["main"])
    assert len(summaries) >= 2, job["main"]  # rotated by size, each file complete (summary, statistics)
    assert all(s is not None for s in summaries)
    assert len(messages) > 0 and len({m.sequence for _s, _c, m in messages}) == len(messages)
    for later in job["main"][1:]:  # each later file opens with the configs (replayable alone)
        assert {c.topic for _s, c, _m in _read(later)[1]} >= {"rapid_command_config", "rapid_agent_config"}
    by_topic: dict[str, list[bytes]] = {}
    for _s, ch, msg in messages:
        assert ch.message_encoding == "cdr" and ch.metadata["partition"] == "K10Red"
        by_topic.setdefault(ch.topic, []).append(msg.data)
    for summary in summaries:
        channels = {ch.topic: ch for ch in summary.channels.values()}
        for entry in _topics_json():  # every topic K10 declares has its channel and DDS type, in each file
            assert channels[entry["topic"]].metadata["dds_type"] == entry["type"], entry["topic"]
    promised = _every_sample_promised()
    assert {"rapid_command", "rapid_ack", "rapid_command_config"} <= promised
    lossy, differ = 0, 0
    for topic, sent in job["tap"].items():  # what the independent reader got, byte for byte
        got = Counter(by_topic.get(topic, []))
        if topic in promised:
            assert got == Counter(sent), topic
        else:  # a sample a reader lost and the writer no longer holds: each of the two readers may
            # lose one under load (two were seen with five workers on two cores); a recorder that
            # altered bytes would differ on every sample
            odd = (got - Counter(sent)) + (Counter(sent) - got)
            assert sum(odd.values()) <= max(2, len(sent) // 50), (topic, len(sent), sum(got.values()))
            lossy, differ = lossy + len(sent), differ + sum(odd.values())
    assert differ <= max(2, lossy // 50), (differ, lossy)  # and 2% of them in all
    for topic in ("rapid_command", "rapid_ack", "rapid_command_config", "rapid_agent_state", "rapid_position_sample",
                  "rapid_queue_state", "rapid_accesscontrol_state", "rapid_ext_arc_gps_sample"):
        assert by_topic.get(topic), f"nothing recorded on {topic}"
    assert len(by_topic["rapid_command"]) == len(JOB)  # each command the job sent


def test_recorded_bytes_are_the_generated_codecs_encoding(job):
    sys.path.insert(0, str(PYDIR))
    try:
        import importlib
        _summaries, messages = _read_all(job["main"])
        for schema, _ch, msg in messages:
            module, _, name = schema.name.replace("::", ".").rpartition(".")
            cls = getattr(importlib.import_module(f"{PKG}.{module}"), name)
            again = cls.deserialize(msg.data).serialize()
            assert again.ljust(len(again) + (-len(again)) % 4, b"\0") == msg.data, schema.name
    finally:
        sys.path.remove(str(PYDIR))


def test_schemas_parse_as_idl_into_the_recorded_type(job):
    from rapidgen.diagnostics import DiagnosticSink
    from rapidgen.idl.load import load_idl
    from rapidgen.model import ir
    summary, _ = _read(job["main"][0])
    assert len(summary.schemas) >= 10
    with tempfile.TemporaryDirectory() as tmp:
        for schema in summary.schemas.values():
            assert schema.encoding == "omgidl"
            path = os.path.join(tmp, "schema.idl")
            Path(path).write_bytes(schema.data)
            sink = DiagnosticSink()
            model, _ = load_idl([path], [], sink)
            assert model is not None and not sink.has_errors, (schema.name, [str(d) for d in sink.diagnostics])
            top = model.get(schema.name)
            assert isinstance(top, ir.Struct) and top.base is None, schema.name  # valuetypes flattened
            if schema.name != "rapid::Header" and any(m.name == "hdr" for m in top.members):
                assert top.keys[:2] == ("hdr.srcName", "hdr.assetName"), schema.name


def test_metadata_and_info(job):
    from mcap.reader import make_reader
    with open(job["main"][0], "rb") as fh:
        meta = {m.name: m.metadata for m in make_reader(fh).iter_metadata()}
    import hashlib
    assert meta["descriptors"]["k10.yaml"] == hashlib.sha256(Path(K10).read_bytes()).hexdigest()
    assert meta["assets"] == {"K10Red": "K10Red"} and meta["rapidgen"]["domain"] == str(DOMAIN)
    assert meta["rapidgen"]["version"]
    res = subprocess.run([*RAPIDGEN, "record", "--info", str(job["main"][0])], cwd=ROOT, capture_output=True, text=True)
    assert res.returncode == 0 and "complete" in res.stdout and "[K10Red] rapid_agent_state" in res.stdout, res.stderr
    size = len(Path(K10).read_bytes())
    assert f"attachment k10.yaml (application/yaml, {size} bytes)" in res.stdout, res.stdout


def test_every_file_of_a_series_carries_the_descriptor(job):
    """The descriptor itself is attached (not only its hash), to each file of a rotated
    series: a file names the asset it was recorded against, alone."""
    from mcap.reader import make_reader
    assert len(job["main"]) > 1, job["main"]  # --split-size 16K: a series
    for path in job["main"]:
        with open(path, "rb") as fh:
            got = [(a.name, a.media_type, a.data) for a in make_reader(fh).iter_attachments()]
        assert got == [("k10.yaml", "application/yaml", Path(K10).read_bytes())], path


def test_killed_recorder_leaves_a_readable_file(job):
    from mcap.records import Channel, Footer, Message
    from mcap.stream_reader import StreamReader
    assert job["rot_killed"] == -signal.SIGKILL
    main_messages = _read_all(job["main"])[1]
    main = {m.data for _s, _c, m in main_messages}
    first: dict[str, int] = {}  # topic -> the main recording's first publish time on it
    for _s, ch, m in main_messages:
        first[ch.topic] = min(first.get(ch.topic, m.publish_time), m.publish_time)
    got, cut, topics = [], None, {}
    with open(job["killed"], "rb") as fh:  # no footer, no summary: read record by record
        try:
            for r in StreamReader(fh, validate_crcs=True).records:
                assert not isinstance(r, Footer)
                if isinstance(r, Channel):
                    topics[r.id] = r.topic
                if isinstance(r, Message):
                    got.append((topics[r.channel_id], r.publish_time, r.data))
        except Exception as exc:  # where the kill cut it (a record not written whole), if anywhere
            cut = exc
    assert got, cut
    # each message is one the main recording has too; but a telemetry topic is volatile: a
    # sample its writer sent before the main recorder's reader matched (the bridge's first
    # ones, as discovery orders the readers) is the killed recorder's alone, never a later one
    for topic, stamp, data in got:
        assert data in main or stamp < first.get(topic, 0), (topic, stamp, first.get(topic), cut)
    res = subprocess.run([*RAPIDGEN, "record", "--info", str(job["killed"])], cwd=ROOT, capture_output=True, text=True)
    assert res.returncode == 0 and "cut" in res.stdout and f"messages: {len(got)} " in res.stdout, res.stdout


def _rates(paths: list[Path], skip: float) -> dict[str, float]:
    """Messages per second of each periodic topic at about 1 Hz or more, as spy measures a rate
    ((n - 1) intervals over their span of publish times), leaving out the first `skip`
    seconds (a bridge's first two samples come together). Periodic: two thirds of its
    intervals within 30% of their median; event topics (acks, queue state) are not."""
    import statistics
    msgs = _read_all(paths)[1]
    start = min(m.log_time for _s, _c, m in msgs) + int(skip * 1e9)
    times: dict[str, list[int]] = {}
    for _s, ch, msg in msgs:
        if msg.log_time >= start:
            times.setdefault(ch.topic, []).append(msg.publish_time)
    out = {}
    for topic, ts in times.items():
        ts.sort()
        gaps = [b - a for a, b in zip(ts, ts[1:])]
        if len(gaps) < 4:
            continue
        median = statistics.median(gaps)
        rate = len(gaps) / ((ts[-1] - ts[0]) / 1e9)
        if sum(abs(g - median) <= 0.3 * median for g in gaps) >= 2 / 3 * len(gaps) and rate >= 0.9:
            out[topic] = rate
    return out


def _gaps(paths: list[Path]) -> dict[str, list[int]]:
    """Milliseconds between publish times, per topic (for a failure's message)."""
    times: dict[str, list[int]] = {}
    for _s, ch, msg in _read_all(paths)[1]:
        times.setdefault(ch.topic, []).append(msg.publish_time)
    return {t: [(b - a) // 1_000_000 for a, b in zip(sorted(ts), sorted(ts)[1:])] for t, ts in times.items()}


def test_replay_seen_by_spy_with_the_recorded_rates(job):
    rates = _rates(job["main"], SKIP)
    assert {"rapid_agent_state", "rapid_ext_arc_gps_sample"} <= set(rates), f"{rates} {_gaps(job['main'])}"
    # no --asset: K10's extension types (rapid::ext::arc::Gps*) come from the recording's schemas
    replay = Proc([*RAPIDGEN, "replay", *map(str, job["main"]), "--domain", str(REPLAY_DOMAIN),
                   "--from", str(SKIP)])
    try:
        spy = subprocess.run([*RAPIDGEN, "spy", "--once", "--json", "--domain", str(REPLAY_DOMAIN), "--seconds", "6",
                              "--asset", K10], cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=120)
        code = replay.end(signal.SIGINT)
    finally:
        if replay.proc.poll() is None:
            replay.proc.kill()
    assert spy.returncode == 0, spy.stderr[-2000:]
    assert code == 0, "".join(replay.err)[-2000:]
    snap = json.loads(spy.stdout)
    assert not [f for f in snap["findings"] if f["code"] == "SPY-TYPE-01"], snap["findings"]  # the same types
    view = next(a for a in snap["assets"] if a["partition"] == "K10Red")
    seen = {t["topic"]: t for t in view["topics"]}
    for topic, rate in rates.items():
        assert seen[topic]["rate"] is not None and abs(seen[topic]["rate"] - rate) <= 0.2 * rate, \
            (topic, rate, seen[topic]["rate"])
    for config in ("rapid_command_config", "rapid_agent_config", "rapid_position_config",
                   "rapid_ext_arc_gps_config"):  # configs first, decoded by spy's own bindings
        assert seen[config]["latest"]["hdr"]["assetName"] == "K10Red", config


def test_foxglove_libraries_read_the_recording(job):
    """Foxglove's own libraries under Node (tests/node: @mcap/core with @mcap/support's zstd
    handlers, @foxglove/omgidl-parser, @foxglove/omgidl-serialization) read the main recording's
    files as written, zstd chunks and all: every schema parsed, every message decoded."""
    from mcap.reader import make_reader

    from tests.node.runner import run_json
    total, compressions = 0, set()
    for path in job["main"]:
        with open(path, "rb") as fh:
            summary = make_reader(fh).get_summary()
        assert summary is not None
        compressions |= {c.compression for c in summary.chunk_indexes}
        total += sum(summary.statistics.channel_message_counts.values()) if summary.statistics else 0
    assert compressions == {"zstd"}, compressions  # the files as rapidgen writes them
    got = run_json("read_mcap.js", *map(str, job["main"]))
    assert got["failed"] == [] and got["decoded"] == total > 0, got["failed"][:3]
    assert got["compression"] == ["zstd"]
    assert got["derived"] == {}  # no --foxglove: RAPID channels only
    assert got["sample"]["rapid_command"]["subsysName"] == "AccessControl"
    assert got["sample"]["rapid_agent_state"]["hdr"]["assetName"] == "K10Red"
