"""A running RAPID asset: the manager on DDS, configs published, telemetry helpers.

    python -m <package>.bridge [--simulate] [--domain N] [--transport local|lan|wan]

`<package>.bridge` calls main() with the package's tables, its `rapid` types and its
handlers. Prints "bridge ready" once every config is published and commands are read.
"""
from __future__ import annotations

import argparse
import copy
import os
import signal
import struct
import sys
import threading
import time
from typing import Any

from cyclonedds._clayer import ddspy_write
from cyclonedds.core import DDSException

from rapid_runtime import messages as M
from rapid_runtime import texts
from rapid_runtime.ack_wire import AckWire
from rapid_runtime.ack_writers import AckWriters
from rapid_runtime.acks import COMPLETED, NOT, clip, valid
from rapid_runtime.dds import Node, ReaderThread, type_class, use_transport
from rapid_runtime.identity import Identities, IdentitiesError
from rapid_runtime.images import describe as describe_image
from rapid_runtime.intake import Intake
from rapid_runtime.journal import Journal, Recovered, default_dir, start_serials
from rapid_runtime.manager import COMMAND_WINDOW, SHUTDOWN_TIMEOUT_MS, STOP_TIMEOUT_MS, CommandManager
from rapid_runtime.security import SecurityUnavailable, enclave_from_environment, use_enclave
from rapid_runtime.tables import Tables
from rapid_runtime.telemetry import STALE_KEY, Freshness, TelemetryError, ordered_values, stale_after_ms, typed_values
from rapid_runtime.untrusted import visible

COMMAND_TOPIC = "rapid_command"
ACK_TOPIC = "rapid_ack"
QUEUE_STATE_TOPIC = "rapid_queue_state"
ACCESS_STATE_TOPIC = "rapid_accesscontrol_state"
# Acks are transient-local, keyed by cmdId: a commander whose reader this writer has not
# discovered yet when EXECUTING goes out still gets the whole sequence (QUEUED, EXECUTING,
# REQUEUED, EXECUTING, COMPLETED and a few progress acks), not only the last one.
ACK_HISTORY = 8
# How long an ack write may wait for room in the writer's history: a burst across a slow
# link fills it for a round trip or more, and the profile's 100 ms would then lose the ack
# (DDS_RETCODE_TIMEOUT). As the commander's writer (commander.WRITE_BLOCKING).
ACK_BLOCKING = 10.0
# Ack writer generations (ack_writers.py): a new writer every window/4 commands (at least
# every 256: each new writer is discovered anew by every ack reader), an old one deleted once
# all its commands' acks are retired.
ACK_GENERATIONS = 4
ACK_GENERATION_MIN = 256
# Commands the DDS reader holds before the intake thread takes them: past this, DDS holds a
# reliable writer back (the flood waits in the flooder's own history, not in the bridge).
COMMAND_CACHE = 4096
# How long a second stop() waits for the first to finish (its acks delivered, journal closed),
# beyond the shutdown bound: the first waits at most that bound for the handlers, then at most
# ACK_DELIVERY in all for the last acks, telemetry and states to be acknowledged by their readers.
STOP_WAIT = 5.0
ACK_DELIVERY = 2.0
# Log lines per second; past that they are counted and the count logged (a flood of bad
# commands would otherwise become a flood of log lines).
LOG_RATE = 50


class Log:
    """The bridge's log: one visible line per call (wire text escaped), at most LOG_RATE lines
    a second, then how many were left out."""

    def __init__(self, write, rate: int = LOG_RATE, clock=time.monotonic) -> None:
        self.write, self.rate, self.clock = write, rate, clock
        self.window, self.lines, self.left_out = clock(), 0, 0
        self.lock = threading.Lock()

    def __call__(self, text: str) -> None:
        with self.lock:
            now = self.clock()
            if now - self.window >= 1.0:
                if self.left_out:
                    self.write(f"({self.left_out} log lines left out in the last second)")
                self.window, self.lines, self.left_out = now, 0, 0
            self.lines += 1
            if self.lines > self.rate:
                self.left_out += 1
                return
        self.write(visible(text, 1000))


class Bridge:
    def __init__(self, tables: Tables, rapid, handlers, qos, domain: int | None = None,
                 log=None, serial: int | None = None, command_window: int = COMMAND_WINDOW,
                 journal: str | None = None, stop_timeout_ms: int = STOP_TIMEOUT_MS,
                 shutdown_timeout_ms: int = SHUTDOWN_TIMEOUT_MS, identities: Identities | None = None) -> None:
        """journal: the restart journal's folder (journal.py; None: no journal, nothing in
        flight survives a crash). stop_timeout_ms: a told-to-stop handler's bound when its
        command declares none; shutdown_timeout_ms: how long stop() waits for the handlers
        (docs/runtime.md, "Handler faults"). identities: a secured bridge's ground sources
        (identity.py): a command runs only when its cmdSrc is the certificate that wrote it."""
        self.shutdown_timeout = shutdown_timeout_ms / 1000.0
        self.tables, self.rapid, self.handlers = tables, rapid, handlers
        self.name = tables.name
        domain = tables.domain if domain is None else domain
        self._log = Log(log or (lambda text: print(f"[{visible(self.name)}] {text}", file=sys.stderr, flush=True)))
        self.journal: Journal | None = None
        self.recovered = Recovered()
        if journal is not None:
            self.journal, self.recovered = Journal.open(journal, self.name, domain, command_window, self.log)
        self.serials = start_serials(serial, self.recovered, self.journal)  # after a crash: a new serial
        self.node = Node(rapid, qos, domain)
        self.stopped = threading.Event()
        self._stop_done = threading.Event()
        self.manager = CommandManager(tables, handlers, self, on_shutdown=self.stop, window=command_window,
                                      journal=self.journal, stop_timeout_ms=stop_timeout_ms)
        self.telemetry = TelemetryPublisher(self)
        self._reader: ReaderThread | None = None
        self.identities = identities
        self._writers: dict[int, bytes] = {}  # publication handle -> the writer's GUID prefix (secured)
        self._command_reader: Any = None  # the command DataReader, made at start()
        # inline: a command arriving at an empty door is handled on the reader thread (intake.py)
        self.intake = Intake(self.manager, self.log, inline=True)
        self.ack_writers: AckWriters | None = None  # made at start(): commanders wait to match it
        self._ack_wire: AckWire | None = None  # an Ack's bytes made by hand (ack_wire.py), with the first writer

    # ---- Outbox (manager.py) ---------------------------------------------------------------
    def _acks(self) -> AckWriters:
        if self.ack_writers is None:
            self.ack_writers = AckWriters(lambda: self.node.new_writer(ACK_TOPIC, self.rapid.Ack, ACK_HISTORY,
                                                                       ACK_BLOCKING),
                                          max(ACK_GENERATION_MIN, self.manager.window // ACK_GENERATIONS),
                                          self._delete_writer)
            self._ack_wire = AckWire(self.rapid, self.ack_writers.current.writer)
        return self.ack_writers

    def _delete_writer(self, writer) -> None:
        """Delete an old generation's writer in a thread of its own: Cyclone lingers in the
        delete until readers have acknowledged its last unregisters (100-200 ms seen on
        loopback, round trips over a real link), and the caller holds the manager's lock."""
        def delete() -> None:
            try:
                self.node.delete(writer)
            except Exception as exc:  # a writer kept is memory, not a failure
                self.log(f"an old ack writer not deleted: {type(exc).__name__}: {exc}")
        threading.Thread(target=delete, daemon=True, name="rapid-ack-writer-delete").start()

    def ack(self, cmd, status, completed, message) -> None:
        writer = self._acks().writer_for(_ack_key(cmd))
        assert self._ack_wire is not None  # (made with the first ack writer, by _acks())
        data = self._ack_wire.encode(cmd.src_name, cmd.asset_name, cmd.serial, M.now_us(), cmd.cmd_id, status,
                                     completed, message)
        if data is None:  # what ack_wire does not encode exactly: cyclonedds' own serializer, its errors
            writer.write(M.ack(self.rapid, cmd, status, completed, message))
            return
        ret = ddspy_write(writer._ref, data)  # what DataWriter.write does after serializing
        if ret < 0:
            raise DDSException(ret, f"Occurred while writing an ack of {cmd.cmd_id!r}")

    def queue_state(self, code, pending, active, completed) -> None:
        hdr = M.header(self.rapid, self.name, self.name, self.serials.start, status=code)
        self.node.writer(QUEUE_STATE_TOPIC, self.rapid.QueueState).write(
            M.queue_state(self.rapid, hdr, pending, active, completed))

    def access_state(self, controller, requestors) -> None:
        hdr = M.header(self.rapid, self.name, self.name, self.serials.start)
        self.node.writer(ACCESS_STATE_TOPIC, self.rapid.AccessControlState).write(
            M.access_state(self.rapid, hdr, controller, requestors))

    def retire(self, cmd) -> None:
        """Unregister the command's ack instance (its key: the command's header and cmdId):
        the writer drops its history once readers have acknowledged, so a late joiner no
        longer gets these acks and memory stays bounded (manager.py, COMMAND_WINDOW)."""
        key = _ack_key(cmd)
        writer = self._acks().retire(key)
        try:
            if writer is not None:
                writer.unregister_instance(M.ack(self.rapid, cmd, COMPLETED, NOT, ""))
        except Exception as exc:  # cyclonedds raises DDSException; a kept instance must not stop intake
            self.log(f"acks of {cmd.cmd_id!r} not unregistered: {type(exc).__name__}: {exc}")
        finally:
            self._acks().drop(key)  # its generation's writer goes once all of its commands are retired

    def log(self, text: str) -> None:
        self._log(text)

    # ---- configs -----------------------------------------------------------------------------
    def publish_config(self, topic: str, value: dict | None = None) -> int:
        """Publish a config (the computed one by default); a changed content gets a new
        serial. Returns the serial."""
        type_name, computed = self.tables.configs[topic]
        value = computed if value is None else _valid_strings(value)
        serial, changed = self.serials.update(topic, value)
        if changed:
            hdr = M.header(self.rapid, self.name, self.name, serial)
            self.node.writer(topic, type_class(self.rapid, type_name)).write(
                M.config(self.rapid, type_name, value, hdr))
        return serial

    # ---- life --------------------------------------------------------------------------------
    def start(self) -> "Bridge":
        for topic in self.tables.configs:
            self.publish_config(topic)
        self.manager.publish_states()
        if self.tables.subsystems:
            self._acks()  # now: commanders wait to match the ack writer
            if self.recovered.crashed:  # before any new command: a retried cmdId is known
                answered, again = self.manager.restore(self.recovered)
                self.log(f"journal: restarted after a crash; {answered} unfinished command(s) answered, "
                         f"{again} final ack(s) written again")
            reader = self.node.reader(COMMAND_TOPIC, self.rapid.Command, max_samples=COMMAND_CACHE)
            self._command_reader = reader
            self.intake.start()
            self._reader = ReaderThread(self.node, reader, self.rapid.Command, self._on_command, "rapid-commands",
                                        log=self.log, on_batch=self._on_commands)
            self._reader.start()
        self.handlers.on_start(self)
        return self

    def _on_commands(self, samples: list) -> None:
        """The reader thread: what one take read, to the intake (intake.py decides the order);
        a command read alone may be handled on this thread at once."""
        alone = len(samples) == 1
        for sample in samples:
            self._on_command(sample, alone)

    def _on_command(self, sample, alone: bool = True) -> None:
        try:
            cmd = M.command_in(sample)
        except Exception as exc:  # a bad sample must not stop command intake
            self.log(f"command {getattr(sample, 'cmdId', '?')!r} not read: {type(exc).__name__}: {exc}")
            return
        writer = sample.sample_info.publication_handle
        if self.identities is not None:
            why = self.identities.refusal(cmd.cmd_src, self._writer_prefix(writer))
            if why is not None:  # before the door, as the C++ bridge (docs/secure.md)
                self.log(f"refused {visible(cmd.cmd_id)!r} from writer {self._writer_prefix(writer).hex()}: {why}")
                self.manager.refuse(cmd, why)
                return
        self.intake.offer(cmd, writer, alone)

    def _writer_prefix(self, handle: int) -> bytes:
        """The GUID prefix of the writer a command came from (discovery data; kept per handle)."""
        prefix = self._writers.get(handle)
        if prefix is None:
            try:
                found = self._command_reader.get_matched_publication_data(handle)
            except Exception:  # cyclonedds raises DDSException for a writer no longer matched
                found = None
            if found is None:
                return b""  # (not kept: refused now, looked up again next time)
            prefix = found.key.bytes[:12]
            if len(self._writers) >= 4096:  # writers come and go: forget them all now and then
                self._writers.clear()
            self._writers[handle] = prefix
        return prefix

    def stop(self) -> None:
        """Stop taking commands, tell the running handlers to stop and wait for them at most the
        shutdown bound, answer every command still in flight, deliver the last acks, close the
        journal. A second caller (main() after Admin/shutdown's thread began, a signal) waits for
        the first, at most as long as the first may take."""
        if self.stopped.is_set():
            self._stop_done.wait(self.shutdown_timeout + ACK_DELIVERY + STOP_WAIT)
            return
        self.stopped.set()
        end = time.monotonic() + self.shutdown_timeout
        try:
            self._on_stop(end)
            if self.tables.subsystems:  # no new command; the unfinished answered, then their acks delivered
                if self._reader is not None and threading.current_thread() is not self._reader.thread:
                    self._reader.stop()
                self.intake.stop()
                in_flight, stuck = self.manager.shutdown(max(0.0, end - time.monotonic()))
                if in_flight:
                    self.log(f"stopping: {in_flight} unfinished command(s) answered"
                             + (f", {stuck} of them \"handler did not stop\"" if stuck else ""))
                acks = self._acks()
                self.node.deliver(ACK_DELIVERY, acks.writers())  # the last acks, then telemetry and states
                acks.close()
            else:
                self.node.deliver(ACK_DELIVERY)  # the last telemetry and states
        finally:
            if self._reader is not None and threading.current_thread() is not self._reader.thread:
                self._reader.stop()
            self.intake.stop()
            self._close_journal()
            self._stop_done.set()

    def _on_stop(self, end: float) -> None:
        """handlers.on_stop() on a thread of its own, waited for until `end` at most (user code:
        it may hang; the stop goes on without it)."""
        def call() -> None:
            try:
                self.handlers.on_stop()
            except BaseException as exc:
                self.log(f"handlers' on_stop raised {type(exc).__name__}: {exc}")
        t = threading.Thread(target=call, daemon=True, name="rapid-on-stop")
        t.start()
        t.join(max(0.0, end - time.monotonic()))
        if t.is_alive():
            self.log("handlers' on_stop did not return within the shutdown bound; stopping without it")

    def _close_journal(self) -> None:
        """A clean stop: every command answered, the next start begins afresh."""
        with self.manager.lock:
            j, self.manager.journal = self.journal, None
        if j is None:
            return
        try:
            j.close(clean=True)
        except OSError as exc:
            self.log(f"journal {j.path}: not closed ({exc.strerror or exc}); the next start answers again")

    def wait(self, seconds: float | None = None) -> None:
        self.stopped.wait(seconds)


def _ack_key(cmd) -> tuple:
    """The Ack instance's key: the command's header names and cmdId."""
    return cmd.src_name, cmd.asset_name, cmd.cmd_id


class TelemetryPublisher:
    """Samples of the declared telemetry, headers filled (serial of the paired config,
    timeStamp in microseconds), values in declaration order and checked against their
    DataTypes. `index` picks among entries of the same kind.

    Stale telemetry (docs/runtime.md): a sample's stamp is its source's time (the caller's
    `stamp`, else now). A position, joint, agent or image entry with a bound
    (telemetry.stale_after_ms) refuses samples older than it (the call returns False), and once
    its newest sample is older than it the entry is silent: logged, one TextMessage (first text
    entry), the agent entry's stale_telemetry key; a current sample again says it is back."""

    WATCHED = ("position", "joint", "agent", "image")

    def __init__(self, bridge: Bridge) -> None:
        self.b = bridge
        self.entries = bridge.tables.telemetry
        self.freshness = Freshness()
        for e in self.entries:
            bound = stale_after_ms(e) if e["kind"] in self.WATCHED else None
            if bound is not None:
                self.freshness.watch(self._name(e), bound)
        self._agent_values: dict[int, dict] = {}
        self._watcher: threading.Thread | None = None
        self._watcher_lock = threading.Lock()
        self._stopped: threading.Event | None = getattr(bridge, "stopped", None)  # the watcher's end

    @staticmethod
    def _name(entry: dict) -> str:
        """An entry as the stale messages name it: its sample topic (an agent's state topic)."""
        topics = entry["topics"]
        return topics.get("sample") or topics.get("state") or next(iter(topics.values()))

    def _current(self, e: dict, stamp: int | None) -> int | None:
        """The sample's stamp (now when not given), or None when it is older than its entry's bound."""
        stamp = M.now_us() if stamp is None else int(stamp)
        name = self._name(e)
        if name not in self.freshness.bounds:
            return stamp
        ok, back = self.freshness.offer(name, stamp / 1e6)
        self._watch()
        if back:
            self._announce(texts.source_back(name), "MSG_INFO")
        return stamp if ok else None

    def _watch(self) -> None:
        with self._watcher_lock:
            if self._watcher is None and self._stopped is not None:
                tick = min(0.5, max(0.05, min(self.freshness.bounds.values()) / 4))
                self._watcher = threading.Thread(target=self._watch_loop, args=(tick,), daemon=True,
                                                 name="rapid-stale-telemetry")
                self._watcher.start()

    def _watch_loop(self, tick: float) -> None:
        assert self._stopped is not None
        while not self._stopped.wait(tick):
            self.check()

    def check(self) -> None:
        """Say which watched sources went silent since the last check (the watcher's tick)."""
        for name, age in self.freshness.check():
            self._announce(texts.source_silent(name, age), "MSG_WARN")

    def _announce(self, text: str, level: str) -> None:
        """A source gone silent or back: the log, one TextMessage, the agent entries' stale key."""
        self.b.log(text)
        try:
            texts = [t for t in self.entries if t["kind"] == "text"]
            if texts:
                categories = texts[0].get("categories") or []
                self.text(text, level=level, category="system" if "system" in categories else (categories or [""])[0])
            for index, e in enumerate(t for t in self.entries if t["kind"] == "agent"):
                if self._stale_key(e):
                    self._agent(e, self._agent_values.get(index, {}), None)
        except Exception as exc:  # a writer gone at shutdown: the log line is what is left
            self.b.log(f"stale telemetry not published: {type(exc).__name__}: {exc}")

    @staticmethod
    def _stale_key(entry: dict) -> bool:
        return any(k["name"] == STALE_KEY and k["type"] == "RAPID_STRING" for k in entry["values"])

    def of(self, kind: str, index: int = 0) -> dict:
        found = [t for t in self.entries if t["kind"] == kind]
        if index >= len(found):
            raise LookupError(f"asset {self.b.name} declares {len(found)} {kind} telemetry entries")
        return found[index]

    def _hdr(self, entry: dict, stamp: int | None = None):
        config = entry["topics"].get("config")
        serial = self.b.serials.of(config) if config else self.b.serials.start
        return M.header(self.b.rapid, self.b.name, self.b.name, serial, stamp=stamp)

    def _values(self, entry: dict, values: dict | None) -> list:
        return [M.union(self.b.rapid, t, v) for t, v in ordered_values(entry["values"], values or {})]

    def _write(self, entry: dict, role: str, type_name: str, sample) -> None:
        self.b.node.writer(entry["topics"][role], type_class(self.b.rapid, type_name)).write(sample)

    def agent_state(self, values: dict | None = None, index: int = 0, stamp: int | None = None) -> bool:
        """False: not published (older than the entry's stale bound)."""
        e = self.of("agent", index)
        stamp = self._current(e, stamp)
        if stamp is None:
            return False
        self._agent_values[index] = dict(values or {})
        self._agent(e, values, stamp)
        return True

    def _agent(self, e: dict, values: dict | None, stamp: int | None) -> None:
        values = dict(values or {})
        if self._stale_key(e):
            values[STALE_KEY] = ", ".join(self.freshness.silent_names())
        r = self.b.rapid
        self._write(e, "state", "rapid::AgentState", r.AgentState(hdr=self._hdr(e, stamp), values=self._values(e, values)))

    def position(self, xyz, rot=None, velocity_xyz=None, velocity_rot=None, values: dict | None = None,
                 index: int = 0, stamp: int | None = None) -> bool:
        """rot and velocity_rot as the config's encodings say (9 floats; unused ones 0).
        False: not published (older than the entry's stale bound)."""
        e = self.of("position", index)
        stamp = self._current(e, stamp)
        if stamp is None:
            return False
        r = self.b.rapid

        def t3(a, b):
            return r.Transform3D(xyz=[float(x) for x in a], rot=[float(x) for x in (list(b or []) + [0.0] * 9)[:9]])
        self._write(e, "sample", "rapid::PositionSample", r.PositionSample(
            hdr=self._hdr(e, stamp), pose=t3(xyz, rot), velocity=t3(velocity_xyz or [0, 0, 0], velocity_rot),
            values=self._values(e, values)))
        return True

    def joints(self, positions, velocities=None, torques=None, status=None, index: int = 0,
               stamp: int | None = None) -> bool:
        """False: not published (older than the entry's stale bound)."""
        e = self.of("joint", index)
        n = len(e["joints"])
        for name, seq in (("positions", positions), ("velocities", velocities), ("torques", torques)):
            if seq is not None and len(seq) != n:
                raise ValueError(f"{name}: {len(seq)} values for {n} joints")
        stamp = self._current(e, stamp)
        if stamp is None:
            return False
        r = self.b.rapid
        f = [float(x) for x in positions]
        self._write(e, "sample", "rapid::JointSample", r.JointSample(
            hdr=self._hdr(e, stamp), anglePos=f, angleVel=[float(x) for x in velocities or []],
            torque=[float(x) for x in torques or []], status=[int(x) for x in status or []]))
        return True

    def text(self, message: str, level: str = "MSG_INFO", category: str = "", index: int = 0) -> None:
        e = self.of("text", index)
        r = self.b.rapid
        self._write(e, "sample", "rapid::TextMessage", r.TextMessage(
            hdr=self._hdr(e), level=r.MessageLevel[level], category=self._clip("rapid::TextMessage", "category", category),
            message=self._clip("rapid::TextMessage", "message", message)))

    def _clip(self, type_name: str, member: str, text: object) -> str:
        """text made valid for the member's string type (acks.clip): U+FFFD for a lone
        surrogate or NUL, cut to its bound (less the terminator) on a character boundary."""
        bound = self._bound(type_name, member)
        return clip(text, None if bound is None else max(0, bound - 1))

    # ---- images ------------------------------------------------------------------------------
    def _meta(self, e: dict, width: int | None, height: int | None, offset, extras: dict | None):
        w, h = width or e.get("width") or 0, height or e.get("height") or 0
        return M.image_meta(self.b.rapid, e.get("sensor") or "", e.get("sensor_type") or "", w, h, offset,
                            typed_values(extras))

    def image(self, data: bytes, mime: str | None = None, width: int | None = None, height: int | None = None,
              index: int = 0, stamp: int | None = None, offset=None, extras: dict | None = None,
              state: bool = False) -> bool:
        """One picture on the index-th image entry's sample topic (ImageSensorSample); False:
        not published (older than the entry's stale bound).
        ImageMetadata names the declared sensor and sensor type; width, height and mimeType
        are the picture's own when its header says them (PNG, JPEG, GIF, BMP, PNM), else the
        arguments', else the declared ones. A mime, width or height given that contradicts the
        header, or more bytes than the type holds, is a TelemetryError. offset: (xyz, rot9)
        of the sensor in the asset frame (default origin, identity); extras: ImageMetadata
        extras, key -> value or (DataType, value). state=True also publishes ImageSensorState
        with the same metadata."""
        e = self.of("image", index)
        data = bytes(data)
        info = describe_image(data)
        if info is not None:
            wrong = [f"{what} {given!r} (the picture's header says {real!r})"
                     for what, given, real in (("mime", mime, info.mime), ("width", width, info.width),
                                               ("height", height, info.height))
                     if given is not None and given != real]
            if wrong:
                raise TelemetryError(f"image {e.get('sensor')}: {'; '.join(wrong)}")
            mime, width, height = info.mime, info.width, info.height
        bound = self._bound("rapid::ImageSensorSample", "data")
        if bound is not None and len(data) > bound:
            raise TelemetryError(f"image {e.get('sensor')}: {len(data)} bytes, ImageSensorSample.data holds {bound}")
        meta = self._meta(e, width, height, offset, extras)
        stamp = self._current(e, stamp)
        if stamp is None:
            return False
        hdr = self._hdr(e, stamp)
        r = self.b.rapid
        if state:
            self._write(e, "state", "rapid::ImageSensorState", M.image_state(r, hdr, meta))
        self._write(e, "sample", "rapid::ImageSensorSample",
                    M.image_sample(r, hdr, meta, mime or e.get("mime") or "", data))
        return True

    def image_state(self, width: int | None = None, height: int | None = None, index: int = 0,
                    stamp: int | None = None, offset=None, extras: dict | None = None) -> None:
        """The index-th image entry's ImageSensorState (its sensor's metadata: declared size
        unless given; offset and extras as for image())."""
        e = self.of("image", index)
        self._write(e, "state", "rapid::ImageSensorState",
                    M.image_state(self.b.rapid, self._hdr(e, stamp), self._meta(e, width, height, offset, extras)))

    def _bound(self, type_name: str, member: str) -> int | None:
        return M.shape(M.members(type_class(self.b.rapid, type_name))[member]).bound

    # ---- extension types -----------------------------------------------------------------------
    def custom(self, values=None, role: str = "sample", index: int = 0, stamp: int | None = None) -> int:
        """A message of the index-th custom entry's role (config, sample or state), of the
        generated class its descriptor names. values: the class's members by name (nested
        structs as dicts, enums by enumerator name, unions as {case: value}; members not given
        keep their defaults), or an instance of the class. hdr (a rapid::Header member, when
        the type has one) is filled: a config gets a new, larger serial when its content
        changed and is written only then (as Bridge.publish_config); samples and states copy
        their config's serial. Returns the serial. A member the type lacks or a value that
        does not fit: TelemetryError."""
        e = self.of("custom", index)
        type_name = e.get("types", {}).get(role)
        if type_name is None or role not in e["topics"]:
            raise TelemetryError(f"custom telemetry entry {index} has no {role} (it has {', '.join(e['topics'])})")
        cls = type_class(self.b.rapid, type_name)
        try:
            msg = M.build(cls, dict(values or {}) if not isinstance(values, cls) else values)
        except (KeyError, TypeError, ValueError) as exc:
            raise TelemetryError(f"{type_name}: {exc.args[0] if exc.args else exc}") from None
        topic = e["topics"][role]
        has_hdr = "hdr" in M.members(cls)
        if role == "config":
            content = copy.deepcopy(msg)
            if has_hdr:
                content.hdr = None
            serial, changed = self.b.serials.update(topic, content)
            if not changed:
                return serial
        else:
            config = e["topics"].get("config")
            serial = self.b.serials.of(config) if config else self.b.serials.start
        if has_hdr:
            msg = copy.copy(msg)
            msg.hdr = M.header(self.b.rapid, self.b.name, self.b.name, serial, stamp=stamp)
        try:
            self.b.node.writer(topic, cls).write(msg)
        except (TypeError, ValueError, struct.error) as exc:  # cyclonedds serializes on write
            raise TelemetryError(f"{type_name}: not written: {type(exc).__name__}: {exc}") from None
        return serial


def _positive(text: str) -> int:
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"{text}: at least 1")
    return value


def _valid_strings(value):
    """A config's value from a handler with every string made valid (acks.valid)."""
    if isinstance(value, str):
        return valid(value)
    if isinstance(value, dict):
        return {k: _valid_strings(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return type(value)(_valid_strings(v) for v in value)
    return value


def main(asset_tables, rapid, make_handlers, package: str, argv=None, module: str = "bridge",
         description: str | None = None, simulate: bool = True) -> int:
    """The bridge's command line. `module`, `description`: what --help names (the ROS 2 bridge's
    own); `simulate`: whether --simulate and --sim-speed are offered (not where handlers must be real)."""
    tables = Tables(asset_tables)
    p = argparse.ArgumentParser(prog=f"python -m {package}.{module}",
                                description=description or f"RAPID bridge of asset {tables.name} (rapid_runtime)")
    if simulate:
        p.add_argument("--simulate", action="store_true", help="a simulated robot behind the handlers")
    p.add_argument("--domain", type=int, default=None, help=f"DDS domain (default {tables.domain})")
    p.add_argument("--transport", default=None,
                   help="Cyclone transport from the package's QoS files: local (loopback, the default when "
                        "CYCLONEDDS_URI is unset), lan, wan")
    p.add_argument("--seconds", type=float, default=None, help="stop after this long (default: run until stopped)")
    if simulate:
        p.add_argument("--sim-speed", type=float, default=1.0, help="simulated time runs this many times faster")
    p.add_argument("--command-window", type=_positive, default=COMMAND_WINDOW, metavar="N",
                   help=f"commands remembered: repeated cmdIds detected among the last N, acks of the last N "
                        f"completed kept for late joiners (default {COMMAND_WINDOW})")
    p.add_argument("--journal", metavar="DIR", default=None,
                   help=f"the restart journal's folder: commands accepted and not finished are answered after a "
                        f"crash (default {default_dir()}, or $RAPID_STATE_DIR)")
    p.add_argument("--no-journal", action="store_true", help="no restart journal (a crash leaves commands unanswered)")
    p.add_argument("--stop-timeout", type=_positive, default=STOP_TIMEOUT_MS, metavar="MS",
                   help=f"how long a handler told to stop may run on before its command is answered "
                        f"EXEC_FAILED 'handler did not stop', when the command declares no stop_timeout_ms "
                        f"(default {STOP_TIMEOUT_MS})")
    p.add_argument("--shutdown-timeout", type=_positive, default=SHUTDOWN_TIMEOUT_MS, metavar="MS",
                   help=f"how long a shutdown (Admin/shutdown, SIGTERM, SIGINT) waits for the running handlers "
                        f"(default {SHUTDOWN_TIMEOUT_MS})")
    args = p.parse_args(argv)
    if not simulate:
        args.simulate, args.sim_speed = False, 1.0
    qos_mod = __import__(f"{package}.qos", fromlist=["RapidQos"])
    try:
        qos = qos_mod.RapidQos()
        use_transport(qos, args.transport)
    except qos_mod.RapidQosError as exc:
        print(f"bridge: {exc}", file=sys.stderr)
        return 2
    identities = None
    enclave = enclave_from_environment(tables.partition or tables.name)
    if enclave is not None:  # secured (RAPID_SECURITY_KEYSTORE): never started unsecured
        try:
            use_enclave(enclave)
            identities = Identities.load(enclave)
        except (SecurityUnavailable, IdentitiesError) as exc:
            print(f"bridge: DDS Security: {exc}", file=sys.stderr)
            return 1
        print(f"[{visible(tables.name)}] DDS Security: cmdSrc bound to the writer's certificate "
              f"({len(identities.sources)} ground source(s) in {enclave}/identities.txt)", file=sys.stderr, flush=True)
    if args.simulate:
        from rapid_runtime.simulate import Simulator
        handlers = Simulator(tables, speed=args.sim_speed)
    else:
        handlers = make_handlers()
    journal = None if args.no_journal else (args.journal or str(default_dir()))
    bridge = None
    try:
        bridge = Bridge(tables, rapid, handlers, qos, domain=args.domain, command_window=args.command_window,
                        journal=journal, stop_timeout_ms=args.stop_timeout,
                        shutdown_timeout_ms=args.shutdown_timeout, identities=identities)
        bridge.start()
    except DDSException as exc:  # with an enclave: the security plugins refused it
        if bridge is not None:  # its participant deleted now, not left to exit (teardown.py)
            bridge.node.close()
        if enclave is None:
            raise
        print(f"bridge: DDS Security refused this participant's keystore ({enclave}): {exc}; Cyclone's own "
              "log line above says which file and why", file=sys.stderr)
        return 1
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda *_: bridge.stop())
    print(f"bridge ready: asset {tables.name}, domain {tables.domain if args.domain is None else args.domain}, "
          f"partition {tables.partition}{', simulated' if args.simulate else ''}", flush=True)
    end = None if args.seconds is None else time.monotonic() + args.seconds
    while not bridge.stopped.is_set():
        left = None if end is None else end - time.monotonic()
        if left is not None and left <= 0:
            break
        bridge.wait(0.5 if left is None else min(0.5, left))
    bridge.stop()
    print("bridge stopped", flush=True)
    left = bridge.manager.handlers_running()
    if left:  # handler threads that never returned: answered and journaled, not waited for
        print(f"bridge: {left} handler thread(s) still running; exiting without them", file=sys.stderr, flush=True)
        sys.stderr.flush()
        os._exit(0)
    bridge.node.close()  # before the interpreter ends: its threads outlived OpenSSL's exit handler (teardown.py)
    return 0
