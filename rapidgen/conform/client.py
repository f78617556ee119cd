"""The runner's own DDS endpoints in the asset's partition, each with its topic's
profile QoS (so an incompatibility the asset causes shows up as a status here):
a command writer, an ack reader, a reader per config and telemetry topic. One thread
takes every sample as it arrives and stamps it with its arrival time."""
from __future__ import annotations

import itertools
import math
import os
import threading
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from cyclonedds.sub import DataReader

COMMAND, ACK = "rapid_command", "rapid_ack"


@dataclass
class Received:
    at: float  # time.monotonic() at arrival
    sample: object


@dataclass
class AckSeen:
    index: int  # arrival order over all acks
    at: float
    cmd_id: str
    status: str
    completed: str
    message: str
    asset: str
    src: str


def enum_name(value) -> str:
    return getattr(value, "name", None) or str(value)


class Client:
    def __init__(self, bindings, participant, asset: str) -> None:
        from cyclonedds.core import Listener
        from cyclonedds.pub import DataWriter, Publisher
        from cyclonedds.qos import Policy, Qos
        from cyclonedds.sub import DataReader, Subscriber
        from cyclonedds.topic import Topic

        self.b, self.dp, self.asset = bindings, participant, asset
        self._Policy, self._Qos, self._DataReader, self._Topic = Policy, Qos, DataReader, Topic
        q = bindings.qos
        self.publisher = Publisher(participant, qos=q.publisher())
        self.subscriber = Subscriber(participant, qos=q.subscriber())
        self.incompatible: dict[str, list[tuple[str, int | None]]] = {}  # topic -> [("requested", policy id)]
        self._topics: dict[str, object] = {}
        self.lock = threading.Condition()
        self.readers: dict[str, DataReader[Any]] = {}
        self.received: dict[str, list[Received]] = {}
        self.acks: list[AckSeen] = []
        self.sent: dict[str, object] = {}  # cmdId -> Command we wrote
        self._ids = itertools.count(1)
        self.command_writer = None
        if COMMAND in q.topics:
            self.command_writer = DataWriter(self.publisher, self.topic(COMMAND, bindings.rapid.Command),
                                             qos=q.writer(COMMAND), listener=self._listener(COMMAND, Listener))
        self.stopping = threading.Event()
        self._thread = threading.Thread(target=self._pump, daemon=True, name="conform-readers")

    # ---- endpoints -----------------------------------------------------------------------
    def topic(self, name: str, cls):
        if name not in self._topics:
            self._topics[name] = self._Topic(self.dp, name, cls)
        return self._topics[name]

    def _listener(self, topic: str, Listener):
        def requested(_reader, status):
            self._incompatible(topic, "requested", status)

        def offered(_writer, status):
            self._incompatible(topic, "offered", status)
        return Listener(on_requested_incompatible_qos=requested, on_offered_incompatible_qos=offered)

    def _incompatible(self, topic: str, side: str, status) -> None:
        with self.lock:
            self.incompatible.setdefault(topic, []).append((side, getattr(status, "last_policy_id", None)))

    def profile_reader(self, topic: str, type_name: str, relaxed: bool = False):
        """A reader of topic with its profile's QoS and KEEP_ALL history (history is local:
        every sample is kept until taken). relaxed: VOLATILE, so it matches a writer whatever
        its durability (the ack reader: a broken ack durability must not hide every ack)."""
        from cyclonedds.core import Listener
        P, Q = self._Policy, self._Qos
        qos = self.b.qos.reader(topic) + Q(P.History.KeepAll)
        if relaxed:
            qos = qos + Q(P.Durability.Volatile)
        listener = None if relaxed else self._listener(topic, Listener)
        return self._DataReader(self.subscriber, self.topic(topic, self.b.type_class(type_name)), qos=qos,
                                listener=listener)

    def start(self, topics: dict[str, str]) -> "Client":
        """Read every topic (name -> type) and the acks; start taking samples."""
        for topic, type_name in topics.items():
            if topic != ACK:
                self.readers[topic] = self.profile_reader(topic, type_name)
                self.received[topic] = []
        if self.command_writer is not None:
            self.ack_reader = self.profile_reader(ACK, "rapid::Ack", relaxed=True)
        else:
            self.ack_reader = None
        self._thread.start()
        return self

    def _pump(self) -> None:
        while not self.stopping.is_set():
            now = time.monotonic()
            got = False
            for topic, r in list(self.readers.items()):
                for s in r.take(N=1024):
                    if s is not None and not type(s).__name__.startswith("Invalid"):
                        got = True
                        with self.lock:
                            self.received[topic].append(Received(now, s))
            if self.ack_reader is not None:
                for s in self.ack_reader.take(N=1024):
                    if hasattr(s, "cmdId"):
                        with self.lock:
                            self.acks.append(AckSeen(len(self.acks), now, s.cmdId, enum_name(s.status),
                                                     enum_name(s.completedStatus), s.message, s.hdr.assetName,
                                                     s.hdr.srcName))
                            self.lock.notify_all()
                        got = True
            if got:
                with self.lock:
                    self.lock.notify_all()
            time.sleep(0.005)

    def stop(self) -> None:
        self.stopping.set()
        self._thread.join(timeout=5)

    # ---- commands ------------------------------------------------------------------------
    def new_id(self, source: str) -> str:
        return f"{next(self._ids)}-{source}-{os.getpid()}-{time.time_ns() // 1_000_000}"

    def union(self, dtype: str, value):
        r = self.b.rapid
        if dtype in ("RAPID_FLOAT", "RAPID_DOUBLE"):
            value = float(value)
        elif dtype in ("RAPID_VEC3d", "RAPID_MAT33f"):
            value = [float(x) for x in value]
        return r.ParameterUnion(discriminator=r.DataType[dtype], value=value)

    def send(self, subsystem: str, name: str, args=(), source: str = "", action: str = "QUEUE_BYPASS",
             target: str = "", cmd_id: str | None = None, asset: str | None = None, serial: int = 0) -> str:
        r = self.b.rapid
        cmd_id = self.new_id(source) if cmd_id is None else cmd_id
        hdr = r.Header(srcName=source, assetName=self.asset if asset is None else asset,
                       timeStamp=time.time_ns() // 1000, statusCode=0, serial=serial)
        cmd = r.Command(hdr=hdr, cmdName=name, cmdId=cmd_id, cmdSrc=source, subsysName=subsystem,
                        arguments=[self.union(t, v) for t, v in args], cmdAction=r.QueueAction[action],
                        targetCmdId=target)
        with self.lock:
            self.sent.setdefault(cmd_id, cmd)
        if self.command_writer is None:  # callers check Session.needs_commands() first
            raise RuntimeError("the asset takes no commands: no command writer")
        self.command_writer.write(cmd)
        return cmd_id

    def acks_of(self, cmd_id: str) -> list[AckSeen]:
        with self.lock:
            return [a for a in self.acks if a.cmd_id == cmd_id]

    def wait_final(self, cmd_id: str, timeout: float = 10.0) -> list[AckSeen]:
        return self.wait_status(cmd_id, ("ACK_COMPLETED",), timeout)

    def wait_status(self, cmd_id: str, statuses: tuple[str, ...], timeout: float) -> list[AckSeen]:
        """The cmdId's acks once one has a status in statuses (or at the timeout)."""
        end = time.monotonic() + timeout
        with self.lock:
            while not any(a.cmd_id == cmd_id and a.status in statuses for a in self.acks):
                left = end - time.monotonic()
                if left <= 0:
                    break
                self.lock.wait(left)
        return self.acks_of(cmd_id)

    def samples(self, topic: str) -> list[Received]:
        with self.lock:
            return list(self.received.get(topic, ()))

    def wait_sample(self, topic: str, timeout: float) -> list[Received]:
        end = time.monotonic() + timeout
        with self.lock:
            while not self.received.get(topic) and time.monotonic() < end:
                self.lock.wait(max(0.0, end - time.monotonic()))
            return list(self.received.get(topic, ()))


def finite(x) -> bool:
    return isinstance(x, (int, float)) and math.isfinite(x)
