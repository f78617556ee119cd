"""`rapidgen monitor --replay FILE` in headless chromium: an MCAP file written with
rapidgen.record's writer (K10Red driving 20 m north while its battery drains past both
thresholds, a text message with markup) plays on the page; the time slider seeks (the end:
the whole traverse, the battery critical; the first quarter: a shorter traverse, the
battery ok) and no command is sent from a replay."""
from __future__ import annotations

import importlib
import subprocess
import sys
import time

import pytest

from tests.monitor import browser
from tests.monitor import harness as H

PYDIR = H.ROOT / "generated" / "k10" / "python"
TEXT = "<b id='pwn'>replayed</b>"
CRITICAL = "rgb(210, 30, 30)"


def _record(path, t0: int) -> None:
    """20 s of K10Red: 1 Hz position, 4 Hz agent state, one text message."""
    from rapidgen.record.mcapfile import ChannelInfo, Sink
    sys.path.insert(0, str(PYDIR))
    try:
        rapid = importlib.import_module("rapid_k10red.rapid")
    finally:
        sys.path.remove(str(PYDIR))

    def hdr(t):
        return rapid.Header(srcName="K10Red", assetName="K10Red", timeStamp=t // 1000, statusCode=0, serial=7)

    def f(v):
        return rapid.ParameterUnion(discriminator=rapid.DataType.RAPID_FLOAT, value=v)

    def ch(topic, type_name, role):
        return ChannelInfo(topic, type_name, "K10Red", {"role": role, "reliability": "Reliable",
                                                        "durability": "TransientLocal" if role == "config" else "Volatile"})
    sink = Sink(str(path), {"rapidgen": {"version": "test"}}, "tests/monitor")
    agent_cfg = rapid.AgentConfig(hdr=hdr(t0), agentTags=[], topics=[], valueKeys=[
        rapid.KeyTypeValueTriple(key="batteryCharge", padding=0, value=f(0.0))])
    pos_cfg = rapid.PositionConfig(hdr=hdr(t0), frameName="site", poseEncoding=rapid.RotationEncoding.RAPID_ROT_QUAT,
                                   velocityEncoding=rapid.RotationEncoding.RAPID_ROT_NONE, valueKeys=[])
    sink.write(ch("rapid_agent_config", "rapid::AgentConfig", "config"), t0, t0, agent_cfg.serialize())
    sink.write(ch("rapid_position_config", "rapid::PositionConfig", "config"), t0, t0, pos_cfg.serialize())
    for i in range(81):  # 0.25 s apart
        t = t0 + i * 250_000_000
        state = rapid.AgentState(hdr=hdr(t), values=[f(100.0 - i * 1.125)])  # 100 -> 10
        sink.write(ch("rapid_agent_state", "rapid::AgentState", "state"), t, t, state.serialize())
        if i % 4 == 0:
            pose = rapid.Transform3D(xyz=[i / 4, 0.0, 0.0], rot=[0.0, 0.0, 0.0, 1.0, 0, 0, 0, 0, 0])
            sample = rapid.PositionSample(hdr=hdr(t), pose=pose, velocity=rapid.Transform3D(), values=[])
            sink.write(ch("rapid_position_sample", "rapid::PositionSample", "sample"), t, t, sample.serialize())
        if i == 20:
            text = rapid.TextMessage(hdr=hdr(t), level=rapid.MessageLevel.MSG_INFO, category="system", message=TEXT)
            sink.write(ch("rapid_textmessage", "rapid::TextMessage", "sample"), t, t, text.serialize())
    sink.close()


@pytest.fixture(scope="module")
def replay(tmp_path_factory):
    pytest.importorskip("cyclonedds")
    pytest.importorskip("aiohttp")
    pytest.importorskip("mcap")
    why = browser.available()
    if why:
        pytest.skip(why)
    path = tmp_path_factory.mktemp("monitor-replay") / "k10.mcap"
    _record(path, time.time_ns() - 3600 * 10**9)
    env = H.env({"k10": PYDIR})
    proc = subprocess.Popen([sys.executable, "-m", "rapidgen", "monitor", "--replay", str(path), "--port", "0",
                             "--asset", "specs/assets/k10.yaml"], cwd=H.ROOT, env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    driver = None
    try:
        first = proc.stdout.readline()
        m = H.URL.search(first)
        assert m, first + proc.stderr.read()[-2000:]
        driver = browser.chromium()
        driver.get(m.group(1))
        yield driver
    finally:
        H.quietly(lambda: driver.quit() if driver is not None else None)
        proc.terminate()
        H.quietly(lambda: proc.communicate(timeout=20))
        H.kill(proc)


def _seek(driver, fraction: float) -> None:
    driver.execute_script("""
        const s = document.getElementById('replay-slider'); s.value = String(arguments[0]);
        s.dispatchEvent(new Event('change'));""", int(fraction * 1000))


def _points(driver) -> int:
    return int(driver.execute_script("const c = document.getElementById('map'); return c ? +c.dataset.points : 0"))


def test_replay_plays_and_seeks(replay):
    d = replay
    H.until(lambda: "replay of" in d.find_element("id", "mode").text, 20, what="replay mode")
    assert d.find_element("id", "replay").is_displayed()
    assert not d.find_element("id", "source-form").is_displayed()
    _seek(d, 1.0)
    H.select(d, "K10Red", "map")
    H.until(lambda: _points(d) >= 21, 20, what="the whole traverse")
    assert _points(d) == 21, d.execute_script("return document.getElementById('replay-time').textContent")
    assert H.traverse_pixels(d) > 100
    H.select(d, "K10Red", "telemetry")
    cell = H.until(lambda: (lambda c: c if c and c["level"] == "critical" else None)(
        H.value_cell(d, "agent/batteryCharge")), 20, what="battery critical at the end")
    assert float(cell["text"]) == 10 and cell["background"] == CRITICAL
    H.select(d, "K10Red", "log")
    H.until(lambda: TEXT in H.texts(d, "#log .text"), 20, what="the replayed text, as text")
    assert H.texts(d, "#pwn") == []
    _seek(d, 0.25)  # 5 s in: 6 positions, battery 77.5 %
    H.select(d, "K10Red", "telemetry")
    cell = H.until(lambda: (lambda c: c if c and c["level"] == "ok" else None)(
        H.value_cell(d, "agent/batteryCharge")), 20, what="battery ok a quarter in")
    assert 70 < float(cell["text"]) < 80
    H.select(d, "K10Red", "map")
    assert H.until(lambda: _points(d), 10, what="traverse") <= 7


def test_replay_sends_no_command(replay):
    from selenium.webdriver.common.by import By
    d = replay
    H.select(d, "K10Red", "commands")
    assert all(not b.is_enabled() for b in d.find_elements(By.CSS_SELECTOR, "button.send"))


def test_a_file_that_is_not_mcap_is_an_input_error(tmp_path):
    bad = tmp_path / "bad.mcap"
    bad.write_bytes(b"<html>not a recording</html>")
    res = subprocess.run([sys.executable, "-m", "rapidgen", "monitor", "--replay", str(bad), "--port", "0"],
                         cwd=H.ROOT, capture_output=True, text=True, timeout=120, env=H.env({"k10": PYDIR}))
    assert res.returncode == 1 and "not an MCAP file" in res.stderr and "Traceback" not in res.stderr, res.stderr


# ---- hostile recordings (issue 34, item 4): bounded memory, no traceback --------------------
BOUND = 400  # MiB: the monitor's peak RSS (the bomb inflates to 900 MiB; 1.85 GiB before)


def test_a_decompression_bomb_is_refused_in_bounded_memory(tmp_path):
    pytest.importorskip("aiohttp")
    pytest.importorskip("mcap")
    from tests.record import bombs
    path = tmp_path / "bomb.mcap"
    assert bombs.zstd_bomb(path) < 64 * 1024  # one zstd chunk of 900 MiB
    code, _out, err, rss = bombs.run_measured([sys.executable, "-m", "rapidgen", "monitor", "--replay", str(path),
                                               "--port", "0"], timeout=300, cwd=H.ROOT, env=H.env({"k10": PYDIR}))
    assert code == 1 and "Traceback" not in err, err
    assert f"rapidgen monitor: {path}: the chunk at byte 297 declares 943718431 bytes uncompressed, over the 64 MiB " \
        "limit on a chunk: refused" in err, err
    assert rss < BOUND, rss


def test_three_million_empty_messages_are_served_in_bounded_memory(tmp_path):
    """781 MiB before (a list of tuples, a bytes object per message); now 24 bytes each."""
    pytest.importorskip("aiohttp")
    pytest.importorskip("mcap")
    from tests.record import bombs
    path = tmp_path / "empty.mcap"
    assert bombs.empty_messages(path) < 64 * 1024
    proc = subprocess.Popen([sys.executable, "-m", "rapidgen", "monitor", "--replay", str(path), "--port", "0"],
                            cwd=H.ROOT, env=H.env({"k10": PYDIR}), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    try:
        first = proc.stdout.readline()  # once the recording is loaded and the page serves
        rss = bombs.peak_rss_mib(proc.pid)
        assert H.URL.search(first), first + proc.stderr.read()[-2000:]
        assert 0 < rss < BOUND, rss
    finally:
        proc.terminate()
        H.quietly(lambda: proc.communicate(timeout=20))
        H.kill(proc)


def test_each_message_counts_against_the_cap(tmp_path, monkeypatch):
    """Empty messages are not free: their count times PER_MESSAGE is held against MAX_BYTES."""
    pytest.importorskip("mcap")
    from rapidgen.monitor import replay
    from rapidgen.monitor.hints import Hints
    from tests.record import bombs
    monkeypatch.setattr(replay, "MAX_BYTES", 1 << 20)
    fits, past = (1 << 20) // replay.PER_MESSAGE, (1 << 20) // replay.PER_MESSAGE + 1
    for count in (fits, past):
        path = tmp_path / f"empty-{count}.mcap"
        bombs.empty_messages(path, count, complete=True)
        if count == past:
            with pytest.raises(replay.ReplayError) as err:
                replay.ReplaySource(str(path), [], Hints())
            assert str(err.value).startswith(f"{path}: its messages take more than 1 MiB (their bytes plus "
                                             f"{replay.PER_MESSAGE} for each), the most a replay holds: refused")
        else:
            source = replay.ReplaySource(str(path), [], Hints())
            try:
                assert len(source.times) == count
            finally:
                source.close()


def test_a_recording_out_of_time_order_is_sorted(tmp_path):
    """A cut file comes in file order: held sorted by time (stable), each message's bytes with it."""
    pytest.importorskip("mcap")
    from rapidgen.monitor import replay
    from rapidgen.monitor.hints import Hints
    from tests.record import bombs

    class Bytes:
        @staticmethod
        def deserialize(data):
            return data

    class Bindings:
        @staticmethod
        def type_class(name):
            return Bytes

    path = tmp_path / "unsorted.mcap"
    f = bombs._File(path, "acme::Nothing", "state", False)
    times = [5, 3, 3, 9, 1, 7, 3]
    f.chunk([bombs._message_header(1, sequence=i, t=bombs.T0 + t) + bytes([i]) for i, t in enumerate(times)])
    f.chunk([bombs._message_header(1 << 20, t=bombs.T0 + 2) + b"L" * (1 << 20)])  # a segment of its own
    f.close()
    source = replay.ReplaySource(str(path), [Bindings()], Hints())
    try:
        got = [(source.times[i] - bombs.T0, source._data(i)[:1]) for i in range(len(source.times))]
    finally:
        source.close()
    assert got == [(1, b"\4"), (2, b"L"), (3, b"\1"), (3, b"\2"), (3, b"\6"), (5, b"\0"), (7, b"\5"), (9, b"\3")]
