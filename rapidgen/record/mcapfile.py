"""MCAP files through the `mcap` library: writing a recording (rotation, a chunk flushed
every second so a killed recorder leaves a file readable up to its last chunk), and reading
one back whole or cut (a file without its summary is read record by record up to the first
damaged or missing byte, as `mcap recover` does)."""
from __future__ import annotations

import os
import time
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
                    ch.type_name, SCHEMA_ENCODING if data else "", data)
            got = self._channels[key] = self._writer.register_channel(
                ch.topic, MESSAGE_ENCODING, sid, dict(ch.metadata, dds_type=ch.type_name, partition=ch.partition))
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


def _check_magic(fh: IO[bytes], path: str) -> None:
    head = fh.read(8)
    fh.seek(0)
    if head != b"\x89MCAP0\r\n":
        raise RecordingError(f"{path} is not an MCAP file (it does not start with the MCAP magic bytes)")


def open_recording(path: str) -> tuple[Recording, Generator[Item, None, None]]:
    """(what the file holds, an iterator of (schema, channel, message) in log-time order for
    a complete file, file order for a cut one). Raises RecordingError."""
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
    if rec is not None:
        return rec, _complete_messages(fh, rec)
    fh.seek(0)
    rec = Recording(path, complete=False)
    return rec, _stream_messages(fh, rec)


def _summary(fh: IO[bytes], path: str) -> Recording | None:
    """The complete file's schemas, channels and metadata; None when it has no summary."""
    from mcap.exceptions import McapError
    from mcap.reader import SeekingReader
    try:
        fh.seek(0)
        reader = SeekingReader(fh, validate_crcs=True)
        summary = reader.get_summary()
        if summary is None:
            return None
        header = reader.get_header()
        rec = Recording(path, True, dict(summary.schemas), dict(summary.channels), library=header.library,
                        statistics=summary.statistics)
        for m in reader.iter_metadata():
            rec.metadata[m.name] = dict(m.metadata)
        rec.attachments = [(a.name, a.media_type, a.data_size) for a in summary.attachment_indexes]
        return rec
    except (McapError, ValueError, EOFError, OSError, KeyError, IndexError) as exc:
        if isinstance(exc, OSError):
            raise RecordingError(f"cannot read {path}: {exc}") from None
        return None  # no usable summary: read it as a cut file


def _complete_messages(fh: IO[bytes], rec: Recording) -> Generator[Item, None, None]:
    from mcap.reader import SeekingReader
    try:
        fh.seek(0)
        reader = SeekingReader(fh, validate_crcs=True)
        yield from reader.iter_messages(log_time_order=True)
    except Exception as exc:  # a damaged chunk inside a file with a summary
        rec.cut_reason = f"{type(exc).__name__}: {exc}"[:200]
    finally:
        fh.close()


def _stream_messages(fh: IO[bytes], rec: Recording) -> Generator[Item, None, None]:
    from mcap.records import Channel, Footer, Header, Message, Metadata, Schema
    from mcap.stream_reader import StreamReader
    try:
        for r in StreamReader(fh, validate_crcs=True).records:
            if isinstance(r, Header):
                rec.library = r.library
            elif isinstance(r, Schema):
                rec.schemas[r.id] = r
            elif isinstance(r, Channel):
                rec.channels[r.id] = r
            elif isinstance(r, Metadata):
                rec.metadata[r.name] = dict(r.metadata)
            elif isinstance(r, Message):
                ch = rec.channels.get(r.channel_id)
                if ch is not None:
                    yield rec.schemas.get(ch.schema_id), ch, r
            elif isinstance(r, Footer):
                return
    except Exception as exc:  # the end of what a killed recorder wrote (or damage)
        rec.cut_reason = f"{type(exc).__name__}: {exc}"[:200] or type(exc).__name__
    finally:
        fh.close()
