"""Hostile recordings (issue 34, items 4 and 6) given to `rapidgen record --info` and
`rapidgen replay` as subprocesses: decompression bombs (a 29 KB file whose zstd chunk
inflates to 900 MiB, its declared size honest or a lie; the same with lz4), 3 million
empty messages (as states: read through; as configs, which replay holds: refused), and a
schema that #includes a local file. Each refusal is exit 1 with a message naming the file
and the limit, no traceback; each tool's peak RSS (its own, tests/record/bombs.py) stays
far below what the file inflates to. `replay` joins DDS only for the schema case (domain
16, loopback)."""
from __future__ import annotations

import builtins
import sys
from pathlib import Path

import pytest

from tests.record import bombs
from tests.runtime.live import ROOT, SEEDS, env_for, python_dir

RAPIDGEN = [sys.executable, "-m", "rapidgen"]
ENV = env_for(python_dir("k10"), SEEDS["k10"])
BOUND = 400  # MiB: each tool's peak RSS; the bombs inflate to 900 MiB (and took 1.8-1.9 GiB before)

pytest.importorskip("mcap")


def run(*args: str) -> tuple[int, str, str, float]:
    code, out, err, rss = bombs.run_measured([*RAPIDGEN, *args], timeout=600, cwd=ROOT, env=ENV)
    assert "Traceback" not in err and "internal error" not in err, err[-3000:]
    return code, out, err, rss


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("hostile")
    out = {name: tmp / f"{name}.mcap" for name in ("bomb", "bomb_complete", "bomb_lie", "lz4", "lz4_lie",
                                                   "empty", "configs")}
    assert bombs.zstd_bomb(out["bomb"]) < 64 * 1024  # 900 MiB inflated
    bombs.zstd_bomb(out["bomb_complete"], complete=True)
    bombs.zstd_bomb(out["bomb_lie"], declared=4096)
    bombs.zstd_bomb(out["lz4"], inflated=600 * bombs.MiB, compression="lz4")
    bombs.zstd_bomb(out["lz4_lie"], inflated=600 * bombs.MiB, declared=1 << 20, compression="lz4")
    assert bombs.empty_messages(out["empty"]) < 64 * 1024  # 3 million messages
    bombs.empty_messages(out["configs"], 400_000, type_name="rapid::AgentConfig", role="config", numbered=True)
    out["tmp"] = tmp
    return out


@pytest.mark.parametrize("name", ["bomb", "bomb_complete", "lz4"])
def test_a_chunk_declared_past_the_ceiling_is_refused(files, name):
    path = files[name]
    inflated = 600 if name == "lz4" else 900
    tools = [["replay", str(path), "--domain", "16", "--linger", "0"]]
    if name != "bomb_complete":  # a complete file is summarised from its statistics: --info reads no chunk
        tools.append(["record", "--info", str(path)])
    for args in tools:
        code, _out, err, rss = run(*args)
        assert code == 1, err
        assert f"{path}: the chunk at byte 297 declares {(inflated << 20) + 31} bytes uncompressed, over the 64 MiB " \
            "limit on a chunk: refused (a small file that inflates to that much is a decompression bomb" in err, err
        assert rss < BOUND, (args, rss)


@pytest.mark.parametrize("name", ["bomb_lie", "lz4_lie"])
def test_a_chunk_that_inflates_past_its_declared_size_is_refused(files, name):
    path = files[name]
    for args in (["record", "--info", str(path)], ["replay", str(path), "--domain", "16", "--linger", "0"]):
        code, _out, err, rss = run(*args)
        assert code == 1, err
        assert f"{path}: the chunk at byte 297 inflates past the " in err and "it declares (uncompressed_size)" in err
        assert rss < BOUND, (args, rss)


def test_info_reads_three_million_empty_messages_in_bounded_memory(files):
    code, out, err, rss = run("record", "--info", str(files["empty"]))
    assert code == 0, err
    assert "messages: 3000000 " in out and "3000000 messages" in out, out
    assert rss < BOUND, rss  # 495 MiB before (the library's list of a chunk's records)


def test_replay_refuses_more_configs_than_it_holds(files):
    path = files["configs"]
    code, _out, err, rss = run("replay", str(path), "--domain", "16", "--linger", "0")
    assert code == 1, err
    assert f"{path}: its config messages take more than 64 MiB (counting 1024 bytes for each)" in err, err
    assert "this file holds over 65536" in err, err
    assert rss < BOUND, rss


def test_definitions_past_their_cap_are_refused(tmp_path):
    """65 536 channels of 1 KiB metadata each (a 200 KB file): over the 64 MiB of schemas,
    channels and metadata a reader holds."""
    path = tmp_path / "channels.mcap"
    bombs.many_channels(path)
    code, _out, err, rss = run("record", "--info", str(path))
    assert code == 1, err
    assert f"{path}: its schemas, channels and metadata take more than 64 MiB (counting 512 bytes for each)" in err
    assert rss < BOUND, rss


def test_a_length_field_past_the_end_of_the_file_is_damage_not_a_read(tmp_path):
    """A record claiming 3 GiB (under the library's own 4 GiB limit: the read would be allocated
    first, and the library checks no length inside a record); now the file is cut
    there (read up to it, as a killed recorder's), in bounded memory."""
    import struct
    path = tmp_path / "long.mcap"
    bombs.empty_messages(path, 10, per_chunk=10)
    path.write_bytes(path.read_bytes() + struct.pack("<BQ", 0x80, 3 << 30) + b"x" * 100)
    code, out, err, rss = run("record", "--info", str(path))
    assert code == 0, err
    assert "cut: read up to its last whole chunk" in out and "runs past the end of the file" in out, out
    assert "messages: 10 " in out and rss < BOUND, out


def test_the_limits_leave_a_real_recording_alone(files, tmp_path):
    """A recording of messages as large as a chunk may be (60 MiB, one per chunk) reads back."""
    from mcap.writer import CompressionType, Writer
    path = tmp_path / "large.mcap"
    with open(path, "wb") as fh:
        w = Writer(fh, chunk_size=1 << 20, compression=CompressionType.ZSTD)
        w.start(library="test")
        sid = w.register_schema("rapid::ImageSensorSample", "omgidl", b"module rapid { struct X { long x; }; };")
        cid = w.register_channel("rapid_image_sensor_sample", "cdr", sid,
                                 {"dds_type": "rapid::ImageSensorSample", "partition": "K10Red"})
        for i in range(3):
            w.add_message(cid, log_time=bombs.T0 + i, publish_time=bombs.T0 + i, data=bytes([i]) * (60 << 20))
        w.finish()
    code, out, err, rss = run("record", "--info", str(path))
    assert code == 0 and "messages: 3 " in out, err
    from rapidgen.record.mcapfile import open_recording
    rec, messages = open_recording(str(path))
    assert [m.data[:1] + m.data[-1:] for _s, _c, m in messages] == [bytes([i, i]) for i in range(3)]
    assert rec.complete and not rec.cut_reason


# ---- item 6: a schema's #include ---------------------------------------------------------------
SECRET = "RAPIDGEN_TEST_SECRET_7f3a"


def _schema_recording(path: Path, schema: bytes) -> None:
    from mcap.writer import CompressionType, Writer
    with open(path, "wb") as fh:
        w = Writer(fh, compression=CompressionType.ZSTD)
        w.start(library="test")
        w.add_metadata("rapidgen", {"domain": "16"})
        sid = w.register_schema("acme::Secret", "omgidl", schema)
        cid = w.register_channel("acme_secret", "cdr", sid, {"dds_type": "acme::Secret", "partition": "K10Red",
                                                             "role": "sample"})
        for i in range(3):
            w.add_message(cid, log_time=bombs.T0 + i * 1000, publish_time=bombs.T0, data=b"\0\1\0\0\1\0\0\0")
        w.finish()


@pytest.fixture
def secret(tmp_path):
    path = tmp_path / "secret-file"
    path.write_text(f"{SECRET} struct\n")  # what the include showed: its first token
    return path


def test_replay_refuses_a_schema_that_includes_a_local_file(tmp_path, secret):
    pytest.importorskip("cyclonedds")
    rec = tmp_path / "include.mcap"
    _schema_recording(rec, f'#include "{secret}"\nmodule acme {{ struct Secret {{ long x; }}; }};\n'.encode())
    code, out, err, _rss = run("replay", str(rec), "--domain", "16", "--linger", "0", "--rate", "100")
    assert SECRET not in out + err
    assert "no bindings for acme::Secret: its schema holds a preprocessor directive (#include on its line 1): " \
        "refused" in err, err
    assert "not replayed: [K10Red] acme_secret: no bindings for acme::Secret" in err, err
    assert code == 0, err  # the other channels (none here) would be replayed


@pytest.mark.parametrize("schema", [
    '#include "{secret}"\n',
    '  #  include "{secret}"\n',
    '/* a comment */ #include "{secret}"\n',
    'module acme {{ struct Secret {{ long x; }}; }};\n\f#include "{secret}"\n',
    '#define X\n#include "{secret}"\n',
    'module acme {{ struct Secret {{ long x; }}; }}; // \\\n#include "{secret}"\n',
    '%:include "{secret}"\n',
    '#if 1\n#endif\n',
    '#pragma keylist Secret x\n',
])
def test_a_schema_with_a_directive_is_never_compiled(schema, secret, monkeypatch):
    """Whatever the directive, however it is hidden: refused, and the secret never opened."""
    from rapidgen.record.schema_types import classes_from_schemas
    text = schema.format(secret=secret) + "module acme { struct Secret { long x; }; };\n"
    opened: list[str] = []
    real_open = builtins.open

    def spy(file, *a, **kw):
        opened.append(str(file))
        return real_open(file, *a, **kw)
    monkeypatch.setattr(builtins, "open", spy)
    found, why, keep = classes_from_schemas({"acme::Secret": text.encode()})
    monkeypatch.setattr(builtins, "open", real_open)
    keep.cleanup()
    assert found == {} and "preprocessor directive" in why["acme::Secret"], why
    assert str(secret) not in opened
    assert SECRET not in why["acme::Secret"]


def test_a_schema_without_directives_still_compiles():
    """The refusal is of directives only: '#' inside a comment or a string is no directive."""
    from rapidgen.record.schema_types import classes_from_schemas
    text = b'module acme { const string TAG = "#include"; /* #include "x" */ struct Secret { long x; }; };\n'
    found, why, keep = classes_from_schemas({"acme::Secret": text})
    try:
        assert set(found) == {"acme::Secret"}, why
    finally:
        keep.cleanup()
