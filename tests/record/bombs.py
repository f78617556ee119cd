"""Hostile MCAP files for the memory tests (tests/record/test_bombs.py,
tests/monitor/test_monitor_replay.py) and bench/record.py --bombs: small files that cost a
naive reader a lot of memory. Written record by record with the `mcap` library's record
classes (its Writer would compress the bomb itself, in memory), the chunk compressed as a
stream so that crafting one costs no more memory than the file.

- `zstd_bomb`: one zstd chunk holding one message of `inflated` zero bytes (900 MiB by
  default: a file of about 29 KB), its declared `uncompressed_size` honest or a lie.
- `empty_messages`: `count` messages of zero bytes (3 million by default), in chunks of
  `per_chunk`; every message at the same log time and sequence (or numbered, for configs:
  a reader that keeps configs per sequence keeps each one).
Both are cut files (no summary, as a killed recorder leaves them, so every tool reads them
whole) unless `complete` (a summary with chunk indexes and statistics, and a footer).
"""
from __future__ import annotations

import struct
from pathlib import Path

MAGIC = b"\x89MCAP0\r\n"
T0 = 1_700_000_000_000_000_000
MiB = 1 << 20


def _record(record) -> bytes:
    from mcap.data_stream import RecordBuilder
    b = RecordBuilder()
    record.write(b)
    return b.end()


def _message_header(length: int, channel: int = 1, sequence: int = 0, t: int = T0) -> bytes:
    """A Message record's opcode, length and fixed fields, for `length` bytes of data."""
    return struct.pack("<BQHIQQ", 0x05, 22 + length, channel, sequence, t, t)


class _File:
    def __init__(self, path: Path, type_name: str, role: str, complete: bool) -> None:
        from mcap.records import Channel, Header, Schema
        self.path, self.complete = path, complete
        self.parts: list[bytes] = [MAGIC]
        self.size = len(MAGIC)
        self.schema = Schema(id=1, name=type_name, encoding="omgidl", data=b"module acme { struct Nothing { long x; }; };")
        meta = {"dds_type": type_name, "partition": "K10Red", "role": role, "reliability": "Reliable",
                "durability": "TransientLocal" if role == "config" else "Volatile"}
        self.channel = Channel(id=1, topic="rapid_bomb", message_encoding="cdr", schema_id=1, metadata=meta)
        for r in (Header(profile="", library="tests/record/bombs"), self.schema, self.channel):
            self._add(_record(r))
        self.chunks: list = []
        self.messages = 0

    def _add(self, data: bytes) -> None:
        self.parts.append(data)
        self.size += len(data)

    def chunk(self, pieces, declared: int | None = None, compression: str = "zstd") -> None:
        """A zstd (or lz4) chunk of the byte pieces (an iterable), compressed as a stream;
        `declared`: the uncompressed_size written (default: the true one)."""
        from mcap.records import Chunk, ChunkIndex
        out, size = [], 0
        if compression == "zstd":
            import zstandard
            cobj = zstandard.ZstdCompressor(level=3).compressobj()
            for piece in pieces:
                size += len(piece)
                out.append(cobj.compress(piece))
            out.append(cobj.flush())
        else:
            import lz4.frame
            lz = lz4.frame.LZ4FrameCompressor()
            out.append(lz.begin())
            for piece in pieces:
                size += len(piece)
                out.append(lz.compress(piece))
            out.append(lz.flush())
        data = b"".join(out)
        start = self.size
        rec = _record(Chunk(compression=compression, data=data, message_start_time=T0, message_end_time=T0,
                            uncompressed_crc=0, uncompressed_size=size if declared is None else declared))
        self._add(rec)
        self.chunks.append(ChunkIndex(message_start_time=T0, message_end_time=T0, chunk_start_offset=start,
                                      chunk_length=len(rec), message_index_offsets={}, message_index_length=0,
                                      compression=compression, compressed_size=len(data),
                                      uncompressed_size=size if declared is None else declared))

    def close(self) -> int:
        from mcap.records import DataEnd, Footer, Statistics
        if self.complete:
            self._add(_record(DataEnd(data_section_crc=0)))
            summary_start = self.size
            stats = Statistics(message_count=self.messages, schema_count=1, channel_count=1, attachment_count=0,
                               metadata_count=0, chunk_count=len(self.chunks), message_start_time=T0,
                               message_end_time=T0, channel_message_counts={1: self.messages})
            for r in (self.schema, self.channel, *self.chunks, stats):
                self._add(_record(r))
            self._add(_record(Footer(summary_start=summary_start, summary_offset_start=0, summary_crc=0)))
            self._add(MAGIC)
        data = b"".join(self.parts)
        self.path.write_bytes(data)
        return len(data)


def zstd_bomb(path: Path, inflated: int = 900 * MiB, declared: int | None = None, complete: bool = False,
              type_name: str = "rapid::AgentState", role: str = "state", compression: str = "zstd") -> int:
    """One chunk, one message of `inflated` zero bytes; the file's size."""
    f = _File(path, type_name, role, complete)

    def pieces():
        yield _message_header(inflated)
        zeros = bytes(MiB)
        left = inflated
        while left > 0:
            yield zeros[:min(left, MiB)]
            left -= MiB
    f.chunk(pieces(), declared, compression)
    f.messages = 1
    return f.close()


def empty_messages(path: Path, count: int = 3_000_000, per_chunk: int = 1_000_000, complete: bool = False,
                   type_name: str = "acme::Nothing", role: str = "state", numbered: bool = False) -> int:
    """`count` messages of no bytes; the file's size."""
    f = _File(path, type_name, role, complete)
    done = 0
    while done < count:
        n = min(per_chunk, count - done)
        if numbered:
            first = done
            f.chunk(_message_header(0, sequence=first + i) for i in range(n))
        else:
            f.chunk([_message_header(0) * n])
        done += n
    f.messages = count
    return f.close()


def many_channels(path: Path, count: int = 65536, meta_bytes: int = 1024) -> int:
    """`count` channel records (every id of the u16 space), each with `meta_bytes` of
    metadata, in zstd chunks of at most 32 MiB; the file's size."""
    from mcap.records import Channel
    f = _File(path, "acme::Nothing", "state", False)
    value = "v" * meta_bytes
    per_chunk = (32 << 20) // (meta_bytes + 64)
    for first in range(0, count, per_chunk):
        f.chunk(_record(Channel(id=i % 65536, topic=f"t{i}", message_encoding="cdr", schema_id=1,
                                metadata={"m": value})) for i in range(first, min(count, first + per_chunk)))
    return f.close()


def peak_rss_mib(pid: int) -> float:
    """A running process's peak resident set (VmHWM), in MiB; 0 when it is gone."""
    try:
        with open(f"/proc/{pid}/status") as fh:
            for line in fh:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024
    except OSError:
        pass
    return 0.0


# The measuring parent: Linux carries the resident high-water mark of the process that
# spawns a child into the child's ru_maxrss (at exec), so a large test process would be
# counted as the tool's peak; this small one spawns the tool and writes its rusage.
_MEASURE = ("import resource, subprocess, sys; code = subprocess.run(sys.argv[2:]).returncode; "
            "open(sys.argv[1], 'w').write(str(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)); "
            "sys.exit(code)")


def run_measured(args: list[str], timeout: float = 300, **kw) -> tuple[int, str, str, float]:
    """Run a command to its end: (exit status, stdout, stderr, its own peak RSS in MiB)."""
    import subprocess
    import sys
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        rss = Path(tmp) / "rss"
        res = subprocess.run([sys.executable, "-c", _MEASURE, str(rss), *args], capture_output=True, text=True,
                             timeout=timeout, **kw)
        return res.returncode, res.stdout, res.stderr, int(rss.read_text()) / 1024
