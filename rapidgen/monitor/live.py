"""The DDS side of the monitor: one thread owns the participant. It runs rapidgen spy's
Watcher (discovery, a reader per writer in its partition, guarded takes, caps) and hands
every decoded sample to the Hub; it also writes the commands the page asks for, one command
writer per asset partition, created when the asset shows up so that it is matched before
the operator's first command."""
from __future__ import annotations

import itertools
import os
import queue
import sys
import threading
import time

from rapidgen.monitor.commanding import Request
from rapidgen.monitor.state import Hub

STEP = 0.02  # seconds between two watcher steps (the page's latency floor, with the tick)
MATCH_WAIT = 3.0  # seconds a command waits for the asset's command reader to match
NOTES_EVERY = 1.0


class LiveFeed:
    def __init__(self, hub: Hub, domain: int, bindings: list, declared: list[str]) -> None:
        self.hub, self.domain, self.bindings, self.declared = hub, domain, bindings, declared
        self.base = bindings[-1]  # the RAPID base types (rapid::Command)
        self.requests: queue.Queue = queue.Queue()
        self._stop = threading.Event()
        self._ids = itertools.count(1)
        self._writers: dict[str, tuple] = {}
        self._pending: list[tuple[float, Request, str]] = []
        self.error: BaseException | None = None
        self.ready = threading.Event()
        self._thread = threading.Thread(target=self._run, name="monitor-dds", daemon=True)

    def start(self) -> "LiveFeed":
        self._thread.start()
        return self

    def stop(self) -> None:
        self._stop.set()
        self._thread.join(timeout=10)

    def send(self, req: Request) -> str:
        """Queue a checked command; returns its cmdId (acks come through the hub)."""
        cmd_id = f"{next(self._ids)}-{req.source}-{os.getpid()}-{time.time_ns() // 1_000_000}"
        self.hub.command_seen(req.partition, cmd_id, f"{req.subsystem}/{req.command}", req.source)
        self.requests.put((req, cmd_id))
        return cmd_id

    def _run(self) -> None:
        from rapidgen.spy.watch import Watcher
        try:
            w = Watcher(self.domain, self.bindings, None, declared=self.declared)
        except BaseException as exc:  # e.g. a domain Cyclone refuses: said by the command
            self.error = exc
            self.ready.set()
            return
        w.tap = self._tap
        self.ready.set()
        notes_at = 0.0
        failed: set[str] = set()
        try:
            while not self._stop.is_set():
                try:
                    w.step()
                    self._commands(w)
                    now = time.monotonic()
                    if now - notes_at >= NOTES_EVERY:
                        notes_at = now
                        self._notes(w)
                except Exception as exc:  # one bad step must not stop the page: said once, go on
                    what = f"{type(exc).__name__}: {exc}"[:300]
                    if what not in failed and len(failed) < 16:
                        failed.add(what)
                        print(f"monitor: error in the DDS thread (going on): {what}", file=sys.stderr, flush=True)
                time.sleep(STEP)
        finally:
            w.close()

    def _tap(self, st, rec) -> None:
        if rec.sample is not None:
            self.hub.sample(st.partition, st.topic, st.type_name, rec.sample, rec.stamp, writer=rec.writer)

    def _notes(self, w) -> None:
        from rapidgen.textsafe import visible
        lines = [f"{d['count']} undecodable {visible(d['topic'])} sample(s) in [{visible(d['partition'])}] from "
                 f"{d['writer']}: {d['error']}" for d in w.dropped()] + w.limits()
        writers = [e for e in w.discovery.endpoints.values() if e.kind == "writer"]
        self.hub.presence({p for e in writers for p in e.partitions}, {e.key for e in writers})
        with self.hub.lock:
            self.hub.notes = lines[:32]
            for part, a in self.hub.assets.items():  # a writer ready before the operator's first command
                commands = a.sections.get("commands", (0, None))[1]
                if isinstance(commands, dict) and commands.get("origin") == "live":
                    self._writer(w, part)

    def _writer(self, w, partition: str):
        """(the command writer in `partition`, the generated `rapid` module of its topic's type)."""
        if partition not in self._writers:
            from cyclonedds.pub import DataWriter, Publisher
            from cyclonedds.qos import Policy, Qos
            from cyclonedds.topic import Topic
            dp = w._participant()
            topic = w._topics.get("rapid_command")
            if topic is None:
                topic = w._topics["rapid_command"] = Topic(dp, "rapid_command", self.base.rapid.Command)
            # the watcher may have made the topic first, with an asset's own Command class
            rapid = next((b.rapid for b in self.bindings if b.rapid.Command is topic.data_type), self.base.rapid)
            pub = Publisher(dp, qos=Qos(Policy.Partition([partition])))
            self._writers[partition] = (DataWriter(pub, topic, qos=self.base.qos.writer("rapid_command")), rapid)
        return self._writers[partition]

    def _commands(self, w) -> None:
        from rapid_runtime import messages as M
        from rapid_runtime.command import Cmd
        while True:
            try:
                req, cmd_id = self.requests.get_nowait()
            except queue.Empty:
                break
            self._pending.append((time.monotonic() + MATCH_WAIT, req, cmd_id))
        keep = []
        for deadline, req, cmd_id in self._pending:
            writer, rapid = self._writer(w, req.partition)
            if not writer.get_matched_subscriptions() and time.monotonic() < deadline:
                keep.append((deadline, req, cmd_id))  # the asset's reader not matched yet
                continue
            cmd = Cmd(cmd_id=cmd_id, cmd_src=req.source, subsystem=req.subsystem, name=req.command, args=req.args,
                      action=req.action, target=req.target, src_name=req.source, asset_name=req.asset)
            writer.write(M.command_out(rapid, cmd))
        self._pending = keep
