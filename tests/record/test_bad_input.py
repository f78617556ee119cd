"""Bad input to `rapidgen record --info` and `rapidgen replay`: files that are not MCAP, cut
or damaged ones, hostile names, messages that do not decode, channels of unknown types,
bad options. Each gets a clear message and an exit status, never a traceback; names from
a file reach the terminal escaped. Replay runs once, on loopback (domain 58)."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from tests.runtime.live import ROOT, SEEDS, env_for, python_dir

RAPIDGEN = [sys.executable, "-m", "rapidgen"]
PYDIR, PKG = python_dir("k10"), SEEDS["k10"]
ENV = env_for(PYDIR, PKG)
HOSTILE = "rapid_agent_state\x1b[31m\u202e"


def run(*args: str) -> subprocess.CompletedProcess:
    res = subprocess.run([*RAPIDGEN, *args], cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=120)
    assert "Traceback" not in res.stderr and "internal error" not in res.stderr, res.stderr
    assert "\x1b" not in res.stdout + res.stderr and "\u202e" not in res.stdout + res.stderr
    return res


def _agent_state_bytes() -> bytes:
    sys.path.insert(0, str(PYDIR))
    try:
        import importlib
        rapid = importlib.import_module(f"{PKG}.rapid")
        data = rapid.AgentState(hdr=rapid.Header(srcName="K10Red", assetName="K10Red", serial=7),
                                values=[rapid.ParameterUnion(d=1.5)]).serialize()
        return data + b"\0" * (-len(data) % 4)
    finally:
        sys.path.remove(str(PYDIR))


def write_recording(path: Path, per_chunk: int = 10, chunks: int = 4) -> None:
    """A recording as the mcap library writes it (chunks not compressed, so a test can damage
    a message's bytes): a good channel, one in a hostile partition whose messages do not
    decode, one with a hostile topic name, one of an unknown type, a json one."""
    from mcap.writer import CompressionType, Writer
    pytest.importorskip("cyclonedds")
    good = _agent_state_bytes()
    with open(path, "wb") as fh:
        w = Writer(fh, chunk_size=1 << 30, compression=CompressionType.NONE)
        w.start(library="test\x1b[2J")
        w.add_metadata("rapidgen", {"domain": "56", "version": "x\x1b]0;title\x07"})
        sid = w.register_schema("rapid::AgentState", "omgidl", b"module rapid { struct AgentState { long x; }; };")
        meta = {"dds_type": "rapid::AgentState", "partition": "K10Red", "role": "state",
                "reliability": "Reliable", "durability": "Volatile"}
        ok = w.register_channel("rapid_agent_state", "cdr", sid, meta)
        garbage = w.register_channel("rapid_agent_state", "cdr", sid, dict(meta, partition="P\x1b[1m"))
        hostile = w.register_channel(HOSTILE, "cdr", sid, meta)
        unknown = w.register_channel("acme_thing", "cdr", 0, dict(meta, dds_type="acme::Thing"))
        js = w.register_channel("json_thing", "json", 0, dict(meta))
        t = 1_000_000_000
        for c in range(chunks):
            for i in range(per_chunk):
                t += 10_000_000
                w.add_message(ok, log_time=t, publish_time=t, data=good, sequence=c * per_chunk + i + 1)
            w.add_message(garbage, log_time=t, publish_time=t, data=b"\x00\x01\x00\x00garbage!", sequence=0)
            w.add_message(hostile, log_time=t, publish_time=t, data=b"\x00\x01\x00\x00", sequence=0)
            w.add_message(unknown, log_time=t, publish_time=t, data=good)
            w.add_message(js, log_time=t, publish_time=t, data=b"{}")
            w.flush()  # one chunk each
        w.finish()


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("bad")
    whole = tmp / "whole.mcap"
    write_recording(whole)
    data = whole.read_bytes()
    not_mcap = tmp / "notes.mcap"
    not_mcap.write_text("hello\n")
    empty = tmp / "empty.mcap"
    empty.write_bytes(b"")
    cut = tmp / "cut.mcap"  # a killed writer: the file ends inside its third chunk
    from mcap.records import Chunk
    from mcap.stream_reader import StreamReader
    import io
    offsets, stream = [], io.BytesIO(data)
    reader = StreamReader(stream, emit_chunks=True)
    for r in reader.records:
        if isinstance(r, Chunk):
            offsets.append(stream.tell())
    cut.write_bytes(data[:offsets[2] - 20])
    damaged = tmp / "damaged.mcap"  # a message of the second chunk changed, the chunk's CRC not
    good, at = _agent_state_bytes(), []
    while len(at) < 13:
        at.append(data.index(good, at[-1] + 1 if at else 0))
    mid = at[12] + len(good) // 2  # chunks hold 11 copies each (10 good, 1 of the unknown type)
    damaged.write_bytes(data[:mid] + bytes([data[mid] ^ 0xFF]) + data[mid + 1:])
    return {"whole": whole, "not_mcap": not_mcap, "empty": empty, "cut": cut, "damaged": damaged, "tmp": tmp}


def test_info_of_a_file_that_is_not_mcap(files):
    for name in ("not_mcap", "empty"):
        res = run("record", "--info", str(files[name]))
        assert res.returncode == 1 and "is not an MCAP file" in res.stderr, res.stderr
    res = run("record", "--info", str(files["tmp"] / "missing.mcap"))
    assert res.returncode == 1 and "cannot open" in res.stderr


def test_info_escapes_names_from_the_file(files):
    res = run("record", "--info", str(files["whole"]))
    assert res.returncode == 0, res.stderr
    assert "rapid_agent_state\\x1b[31m\\u202e" in res.stdout and "complete" in res.stdout
    assert "messages: 56 " in res.stdout  # 4 chunks of 14


def test_info_of_a_cut_file_reads_its_whole_chunks(files):
    res = run("record", "--info", str(files["cut"]))
    assert res.returncode == 0, res.stderr
    assert "cut" in res.stdout and "messages: 28 " in res.stdout, res.stdout  # the first two chunks


def test_usage_errors():
    for args in (["record", "--split-size", "12X"], ["record", "--seconds", "-1"], ["record", "--domain", "999"],
                 ["replay", "x.mcap", "--rate", "0"], ["replay", "x.mcap", "--from", "5", "--to", "2"],
                 ["replay", "x.mcap", "--from", "-1"]):
        res = run(*args)
        assert res.returncode == 2, (args, res.stderr)


def test_replay_refuses_a_file_that_is_not_mcap(files):
    res = run("replay", str(files["not_mcap"]), "--domain", "58")
    assert res.returncode == 1 and "is not an MCAP file" in res.stderr


def test_replay_sends_what_decodes_and_says_what_it_did_not(files):
    res = run("replay", str(files["whole"]), str(files["cut"]), str(files["damaged"]), "--domain", "58",
              "--rate", "100", "--linger", "0", "--quiet")
    assert res.returncode == 0, res.stderr
    err = res.stderr
    assert "not replayed: [K10Red] acme_thing: no bindings for acme::Thing" in err
    assert "not replayed: [K10Red] json_thing: message encoding 'json', not cdr" in err
    assert "7 message(s) of [P\\x1b[1m] rapid_agent_state skipped" in err  # undecodable: 4 + 2 + 1
    assert "not replayed: [K10Red] rapid_agent_state\\x1b[31m\\u202e: DDS refused its topic or writer" in err
    assert "cut.mcap is cut" in err and "damaged.mcap is cut" in err and "CRC" in err
    # whole: 40 good; cut: its 2 whole chunks (20); damaged: the chunk before the damage (10)
    assert "rapidgen replay: 70 messages sent on 2 channel(s)" in err, err
