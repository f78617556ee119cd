"""MCAP files through the `mcap` library: writing a recording (rotation, a chunk flushed
every second so a killed recorder leaves a file readable up to its last chunk), and reading
one back whole or cut (a file without its summary is read record by record up to the first
damaged or missing byte, as `mcap recover` does)."""
from __future__ import annotations

import io
import os
import struct
import time
import zlib
from dataclasses import dataclass, field
from typing import IO, TYPE_CHECKING, Generator

if TYPE_CHECKING:
    from mcap.records import Channel, Message, Schema, Statistics
    from mcap.writer import Writer

Item = tuple["Schema | None", "Channel", "Message"]  # what reading a recording yields

SCHEMA_ENCODING = "omgidl"
MESSAGE_ENCODING = "cdr"
PROFILE = ""  # no MCAP profile: RAPID over DDS is none of the registered ones (ros1, ros2)
FLUSH_SECONDS = 1.0  # a chunk is closed and written at least this often
CHUNK_BYTES = 1 << 20


class RecordingError(Exception):
    """A file that cannot be read as a recording (said to the user, no traceback)."""


@dataclass(frozen=True)
class ChannelInfo:
    topic: str
    type_name: str
    partition: str
    metadata: dict[str, str]
    # a derived channel of --foxglove (rapidgen.foxglove): ("jsonschema", "json"); RAPID's: omgidl, cdr
    encodings: tuple[str, str] = (SCHEMA_ENCODING, MESSAGE_ENCODING)


class Sink:
    """Messages into one MCAP file, or a numbered series when rotating (`NAME-000.mcap`,
    ...: each file is whole, with its own schemas, channels and metadata)."""

    def __init__(self, path: str, metadata: dict[str, dict[str, str]], library: str,
                 split_bytes: int | None = None, split_seconds: float | None = None,
                 attachments: tuple[tuple[str, str, bytes], ...] = ()) -> None:
        self.path, self.metadata, self.library = path, metadata, library
        self.attachments = attachments  # (name, media type, bytes): the descriptors, in every file
        self.split_bytes, self.split_seconds = split_bytes, split_seconds
        self.files: list[str] = []
        self._schemas: dict[str, bytes] = {}  # type name -> IDL text, registered per file
        self._ids: dict[str, int] = {}
        self._channels: dict[tuple[str, str, str], int] = {}
        self._known: dict[tuple[str, str, str], ChannelInfo] = {}
        self._configs: dict[tuple[str, str, str], tuple[int, bytes, int]] = {}  # the latest config per channel
        self._fh: IO[bytes] | None = None
        self._writer: Writer | None = None
        self._opened = 0.0
        self._flushed = 0.0
        self.messages = 0
        self.bytes = 0
        self._open()

    def _name(self) -> str:
        if self.split_bytes is None and self.split_seconds is None:
            return self.path
        stem, ext = os.path.splitext(self.path)
        return f"{stem}-{len(self.files):03d}{ext or '.mcap'}"

    def _open(self) -> None:
        from mcap.writer import CompressionType, Writer
        name = self._name()
        self._fh = open(name, "wb")
        self.files.append(name)
        writer = self._writer = Writer(self._fh, chunk_size=CHUNK_BYTES, compression=CompressionType.ZSTD)
        writer.start(profile=PROFILE, library=self.library)
        for key, values in self.metadata.items():
            writer.add_metadata(key, values)
        now = time.time_ns()
        for name, media_type, data in self.attachments:
            writer.add_attachment(create_time=now, log_time=now, name=name, media_type=media_type, data=data)
        self._ids.clear()
        self._channels.clear()
        self._opened = self._flushed = time.monotonic()
        writer.flush()

    def schema(self, type_name: str, idl: str) -> None:
        self._schemas.setdefault(type_name, idl.encode("utf-8"))

    def channel(self, ch: ChannelInfo) -> int:
        key = (ch.topic, ch.partition, ch.type_name)
        got = self._channels.get(key)
        if got is None:
            assert self._writer is not None
            sid = self._ids.get(ch.type_name)
            if sid is None:
                data = self._schemas.get(ch.type_name, b"")
                sid = self._ids[ch.type_name] = self._writer.register_schema(
                    ch.type_name, ch.encodings[0] if data else "", data)
            meta = dict(ch.metadata)
            if ch.encodings[1] == MESSAGE_ENCODING:
                meta["dds_type"] = ch.type_name
            meta["partition"] = ch.partition
            got = self._channels[key] = self._writer.register_channel(ch.topic, ch.encodings[1], sid, meta)
            self._known[key] = ch
        return got

    def write(self, ch: ChannelInfo, log_time: int, publish_time: int, data: bytes, sequence: int = 0) -> None:
        assert self._writer is not None
        self._writer.add_message(self.channel(ch), log_time=log_time, data=data,
                                 publish_time=publish_time, sequence=sequence)
        self.messages += 1
        self.bytes += len(data)
        if ch.metadata.get("role") == "config":
            self._configs[(ch.topic, ch.partition, ch.type_name)] = (publish_time, data, sequence)

    def tick(self) -> None:
        """Called often: flush a chunk each FLUSH_SECONDS, rotate when a limit is reached."""
        now = time.monotonic()
        if now - self._flushed >= FLUSH_SECONDS:
            assert self._writer is not None and self._fh is not None
            self._writer.flush()
            self._flushed = now
            if (self.split_bytes is not None and self._fh.tell() >= self.split_bytes) or \
                    (self.split_seconds is not None and now - self._opened >= self.split_seconds):
                self._close_file()
                self._open()
                self._carry_over()

    def _carry_over(self) -> None:
        """A new file of a series gets every channel and each channel's latest config (logged
        again now, published when it was): a durable config came only once, and each file
        must replay and open alone."""
        for key, ch in list(self._known.items()):
            self.channel(ch)
            if key in self._configs:
                publish_time, data, sequence = self._configs[key]
                assert self._writer is not None  # the same sequence number: a reader of the series can tell
                self._writer.add_message(self.channel(ch), log_time=time.time_ns(), data=data,
                                         publish_time=publish_time, sequence=sequence)

    def _close_file(self) -> None:
        if self._writer is not None and self._fh is not None:
            self._writer.finish()
            self._fh.close()
        self._writer, self._fh = None, None

    def metadata_at_end(self, values: dict[str, str]) -> None:
        """What is known only at the end (partitions seen, counts), into the current file."""
        if self._writer is not None:
            self._writer.add_metadata("recorded", values)

    def close(self) -> None:
        """Summary and index written: the file is complete."""
        self._close_file()


# ---- reading ------------------------------------------------------------------------------
# A recording is a file from anywhere: what reading one may hold is capped (docs/record.md,
# "Hostile recordings"). The mcap library reads the file's records and the summary; a
# chunk's records are read here instead, because the library inflates a chunk whole
# (zstandard or lz4 up to whatever the data says, not the chunk's declared size) and makes
# a list of every record in it (3 million empty messages: hundreds of MiB).
MAX_CHUNK = 64 << 20  # a chunk's declared uncompressed_size, and what it may inflate to
MAX_RECORD = MAX_CHUNK + (1 << 20)  # one read: a record outside chunks, a chunk's compressed bytes
MAX_DEFINITIONS = 64 << 20  # schemas, channels and metadata held, bytes plus PER_DEFINITION each
PER_DEFINITION = 512


class LimitError(RecordingError):
    """A recording past one of the reading caps: refused (exit 1), never taken for a cut."""


class _Bounded:
    """The file, for the mcap library: a read past the file's end is damage (EOFError: a cut
    file, read up to there), and no single read may be larger than MAX_RECORD (LimitError).
    Record lengths are the file's word: 2**63 bytes asked would be allocated before the short
    read; the library's own record_size_limit is not used, it cannot tell the two apart."""

    def __init__(self, fh: IO[bytes], path: str) -> None:
        self.fh, self.path = fh, path
        self.size = os.fstat(fh.fileno()).st_size

    def read(self, n: int = -1) -> bytes:
        at = self.fh.tell()
        if n is None or n < 0:
            n = self.size - at
        if n > self.size - at:
            raise EOFError(f"a record at byte {at} runs past the end of the file ({n} bytes asked, "
                           f"{self.size - at} left)")
        if n > MAX_RECORD:
            raise LimitError(f"{self.path}: a record at byte {at} is {n} bytes long, over the {MAX_RECORD >> 20} "
                             "MiB a record may have: refused (a recording of larger records must be rewritten "
                             "with smaller ones)")
        return self.fh.read(n)

    def seek(self, offset: int, whence: int = 0) -> int:
        target = offset + (0 if whence == 0 else self.fh.tell() if whence == 1 else self.size)
        if not 0 <= target <= self.size:  # an offset from the summary or footer that is damaged
            raise EOFError(f"an offset ({target}) outside the file (of {self.size} bytes)")
        return self.fh.seek(target)

    def tell(self) -> int:
        return self.fh.tell()

    def seekable(self) -> bool:
        return True


@dataclass
class Recording:
    """What a file holds, read through the mcap library."""
    path: str
    complete: bool  # False: no summary (a killed recorder); read up to the first bad byte
    schemas: dict[int, Schema] = field(default_factory=dict)
    channels: dict[int, Channel] = field(default_factory=dict)
    metadata: dict[str, dict[str, str]] = field(default_factory=dict)
    attachments: list[tuple[str, str, int]] = field(default_factory=list)  # (name, media type, size): a complete file's
    library: str = ""
    cut_reason: str = ""  # why reading stopped early (a cut file)
    statistics: Statistics | None = None  # a complete file's
    held: dict[tuple[str, object], int] = field(default_factory=dict, repr=False)  # definition -> bytes counted
    held_bytes: int = 0

    def hold(self, kind: str, key: object, size: int) -> None:
        """Count a schema, channel or metadata record kept (replacing one of the same key)."""
        self.held_bytes += size + PER_DEFINITION - self.held.get((kind, key), 0)
        self.held[(kind, key)] = size + PER_DEFINITION
        if self.held_bytes > MAX_DEFINITIONS:
            raise LimitError(f"{self.path}: its schemas, channels and metadata take more than "
                             f"{MAX_DEFINITIONS >> 20} MiB (counting {PER_DEFINITION} bytes for each), the most "
                             "a reader holds: refused (a recording's definitions are a few KiB each)")


def _check_magic(fh: IO[bytes], path: str) -> None:
    head = fh.read(8)
    fh.seek(0)
    if head != b"\x89MCAP0\r\n":
        raise RecordingError(f"{path} is not an MCAP file (it does not start with the MCAP magic bytes)")


def open_recording(path: str) -> tuple[Recording, Generator[Item, None, None]]:
    """(what the file holds, an iterator of (schema, channel, message) in file order: a
    complete file's schemas and channels are known from its summary, a cut one's are filled
    as it is read). Raises RecordingError; iterating raises LimitError past a cap (a damaged
    or cut file ends the iteration, with rec.cut_reason)."""
    try:
        fh = open(path, "rb")
    except OSError as exc:
        raise RecordingError(f"cannot open {path}: {exc.strerror or exc}") from None
    try:
        _check_magic(fh, path)
        rec = _summary(fh, path)
    except RecordingError:
        fh.close()
        raise
    fh.seek(0)
    if rec is None:
        rec = Recording(path, complete=False)
    return rec, _messages(fh, rec)


def _summary(fh: IO[bytes], path: str) -> Recording | None:
    """The complete file's schemas, channels and metadata; None when it has no summary."""
    from mcap.exceptions import McapError
    from mcap.reader import SeekingReader
    try:
        if os.fstat(fh.fileno()).st_size < 8 + 29 + 8:  # magic, footer, magic: too short for a summary
            return None
        fh.seek(0)
        reader = SeekingReader(_Bounded(fh, path), validate_crcs=True)  # type: ignore[arg-type]
        summary = reader.get_summary()
        if summary is None:
            return None
        header = reader.get_header()
        rec = Recording(path, True, library=header.library, statistics=summary.statistics)
        for sid, schema in summary.schemas.items():
            rec.hold("schema", sid, len(schema.data) + len(schema.name))
            rec.schemas[sid] = schema
        for cid, ch in summary.channels.items():
            rec.hold("channel", cid, _channel_size(ch))
            rec.channels[cid] = ch
        for m in reader.iter_metadata():
            rec.hold("metadata", m.name, sum(len(k) + len(v) for k, v in m.metadata.items()))
            rec.metadata[m.name] = dict(m.metadata)
        rec.attachments = [(a.name, a.media_type, a.data_size) for a in summary.attachment_indexes]
        return rec
    except LimitError:
        raise
    except (McapError, ValueError, EOFError, OSError, KeyError, IndexError, struct.error) as exc:
        if isinstance(exc, OSError):
            raise RecordingError(f"cannot read {path}: {exc}") from None
        return None  # no usable summary: read it as a cut file


def _channel_size(ch: Channel) -> int:
    return len(ch.topic) + sum(len(k) + len(v) for k, v in ch.metadata.items())


def _messages(fh: IO[bytes], rec: Recording) -> Generator[Item, None, None]:
    """Every message, record by record (chunks through _chunk_records), up to the footer or
    to the first damaged or missing byte (rec.cut_reason). LimitError goes through."""
    from mcap.records import Channel, Chunk, Footer, Header, Message, Metadata, Schema
    from mcap.stream_reader import StreamReader
    bounded = _Bounded(fh, rec.path)
    try:
        reader = StreamReader(bounded, emit_chunks=True, validate_crcs=True,  # type: ignore[arg-type]
                              record_size_limit=None)  # (every read is bounded by _Bounded)
        end = fh.tell()  # where the next record starts (after the magic)
        for record in reader.records:
            at, end = end, fh.tell()
            for r in _chunk_records(record, rec.path, at) if isinstance(record, Chunk) else (record,):
                if isinstance(r, Message):
                    ch = rec.channels.get(r.channel_id)
                    if ch is not None:
                        yield rec.schemas.get(ch.schema_id), ch, r
                elif isinstance(r, Schema):
                    rec.hold("schema", r.id, len(r.data) + len(r.name))
                    rec.schemas[r.id] = r
                elif isinstance(r, Channel):
                    rec.hold("channel", r.id, _channel_size(r))
                    rec.channels[r.id] = r
                elif isinstance(r, Header):
                    rec.library = r.library
                elif isinstance(r, Metadata):
                    rec.hold("metadata", r.name, sum(len(k) + len(v) for k, v in r.metadata.items()))
                    rec.metadata[r.name] = dict(r.metadata)
                elif isinstance(r, Footer):
                    return
    except LimitError:
        raise
    except Exception as exc:  # the end of what a killed recorder wrote (or damage)
        rec.cut_reason = f"{type(exc).__name__}: {exc}"[:200] or type(exc).__name__
    finally:
        fh.close()


_MESSAGE = struct.Struct("<BQHIQQ")  # opcode, record length, channel id, sequence, log time, publish time
_RECORD = struct.Struct("<BQ")


def _chunk_records(chunk, path: str, at: int):
    """A chunk's schemas, channels and messages, one at a time, from its data inflated to at
    most its declared uncompressed_size (itself at most MAX_CHUNK) and checked against its
    CRC before any record is given. A record that runs past the chunk is damage (ValueError)."""
    from mcap.data_stream import ReadDataStream
    from mcap.opcode import Opcode
    from mcap.records import Channel, Message, Schema
    from mcap.stream_reader import CRCValidationError
    size = chunk.uncompressed_size
    if size > MAX_CHUNK:
        raise LimitError(f"{path}: the chunk at byte {at} declares {size} bytes uncompressed, over the "
                         f"{MAX_CHUNK >> 20} MiB limit on a chunk: refused (a small file that inflates to that "
                         "much is a decompression bomb; a recording of larger chunks must be rewritten with "
                         "smaller ones)")
    data = _inflate(chunk.compression, chunk.data, size, path, at)
    if len(data) != size:
        raise ValueError(f"the chunk at byte {at} inflates to {len(data)} bytes, not the {size} it declares")
    if chunk.uncompressed_crc != 0 and zlib.crc32(data) != chunk.uncompressed_crc:
        raise CRCValidationError(expected=chunk.uncompressed_crc, actual=zlib.crc32(data), record=chunk)
    view = memoryview(data)
    pos, n = 0, len(data)
    while pos < n:
        if n - pos < 9:
            raise ValueError(f"a record cut short at the end of the chunk at byte {at}")
        opcode, length = _RECORD.unpack_from(data, pos)
        end = pos + 9 + length
        if end > n:
            raise ValueError(f"a record runs past the end of the chunk at byte {at}")
        if opcode == Opcode.MESSAGE:
            if length < 22:
                raise ValueError(f"a message record of {length} bytes in the chunk at byte {at}")
            _op, _len, channel_id, sequence, log_time, publish_time = _MESSAGE.unpack_from(data, pos)
            yield Message(channel_id=channel_id, log_time=log_time, data=bytes(view[pos + 31:end]),
                          publish_time=publish_time, sequence=sequence)
        elif opcode in (Opcode.SCHEMA, Opcode.CHANNEL):
            stream = ReadDataStream(io.BytesIO(view[pos + 9:end]))
            yield Schema.read(stream) if opcode == Opcode.SCHEMA else Channel.read(stream)
        pos = end  # other records inside a chunk: skipped, as the library does


def _inflate(compression: str, data: bytes, size: int, path: str, at: int) -> bytes | bytearray:
    """The chunk's data inflated, never past `size` bytes (LimitError when there is more)."""
    out: bytes | bytearray
    if compression == "":
        out = data
    elif compression == "zstd":
        import zstandard
        out = bytearray(size + 1)  # one byte more than declared: there must be none
        got = 0
        with zstandard.ZstdDecompressor().stream_reader(io.BytesIO(data), read_across_frames=True) as reader, \
                memoryview(out) as view:
            while got <= size:
                n = reader.readinto(view[got:])
                if not n:
                    break
                got += n
        del out[got:]
    elif compression == "lz4":
        import lz4.frame  # type: ignore[import-untyped]  # (mcap's dependency, no type information)
        out = lz4.frame.LZ4FrameDecompressor().decompress(data, max_length=size + 1)
    else:
        from mcap.exceptions import UnsupportedCompressionError
        raise UnsupportedCompressionError(compression)
    if len(out) > size:
        raise LimitError(f"{path}: the chunk at byte {at} inflates past the {size} bytes it declares "
                         "(uncompressed_size): refused (a decompression bomb, or damage)")
    return out
