"""The DDS side (Cyclone): one participant in the asset's domain, publisher and subscriber
in its partition, writers and readers with each topic's generated QoS, a command-reading
thread. Nothing here decides anything: manager.py does."""
from __future__ import annotations

import importlib
import os
import threading
import time

from cyclonedds.core import GuardCondition, InstanceState, ReadCondition, SampleState, ViewState, WaitSet
from cyclonedds.domain import DomainParticipant
from cyclonedds.pub import DataWriter, Publisher
from cyclonedds.qos import Policy, Qos
from cyclonedds.sub import DataReader, Subscriber
from cyclonedds.topic import Topic
from cyclonedds.util import duration

from rapid_runtime.teardown import delete_participant
from rapid_runtime.untrusted import GuardedReader


def use_transport(qos, transport: str | None) -> str | None:
    """Point CYCLONEDDS_URI at the package's transport file (default: the loopback-only
    "local") unless the environment already chose one. Must run before DDS starts."""
    if os.environ.get("CYCLONEDDS_URI") and transport is None:
        return None
    path = qos.cyclonedds_config(transport or "local")
    os.environ["CYCLONEDDS_URI"] = "file://" + os.path.abspath(path)
    return path


def type_class(rapid, scoped: str):
    """rapid::ext::arc::GpsConfig -> the generated class (rapid is the package's `rapid` module)."""
    parts = scoped.split("::")
    if parts[0] != "rapid":
        raise KeyError(scoped)
    mod = rapid
    for name in parts[1:-1]:
        mod = getattr(mod, name, None) or importlib.import_module(f"{mod.__name__}.{name}")
    return getattr(mod, parts[-1])


class Node:
    def __init__(self, rapid, qos, domain: int) -> None:
        self.rapid, self.qos = rapid, qos
        self.participant = DomainParticipant(domain)
        try:
            self.publisher = Publisher(self.participant, qos=qos.publisher())
            self.subscriber = Subscriber(self.participant, qos=qos.subscriber())
        except BaseException:  # no half-made participant left running (close())
            self.close()
            raise
        self._topics: dict[str, Topic] = {}
        self._writers: dict[str, DataWriter] = {}
        self._lock = threading.Lock()

    def topic(self, name: str, cls) -> Topic:
        with self._lock:
            if name not in self._topics:
                self._topics[name] = Topic(self.participant, name, cls)
            return self._topics[name]

    def writer(self, topic: str, cls, keep_last: int | None = None, blocking: float | None = None) -> DataWriter:
        """The topic's shared writer. keep_last: history depth per instance instead of the
        profile's; blocking: how long (s) a reliable write may wait for room in the writer's
        history instead of the profile's max_blocking_time (neither is request/offered, so
        matching is unchanged)."""
        with self._lock:
            w = self._writers.get(topic)
        if w is None:
            w = DataWriter(self.publisher, self.topic(topic, cls), qos=self._writer_qos(topic, keep_last, blocking))
            with self._lock:
                self._writers[topic] = w
        return w

    def new_writer(self, topic: str, cls, keep_last: int | None = None, blocking: float | None = None) -> DataWriter:
        """A writer of its own (not the topic's shared one), for the caller to delete()."""
        return DataWriter(self.publisher, self.topic(topic, cls), qos=self._writer_qos(topic, keep_last, blocking))

    def _writer_qos(self, topic: str, keep_last: int | None, blocking: float | None) -> Qos:
        q = self.qos.writer(topic)
        if keep_last is not None:
            # Cyclone keeps for a late-joining reader what durability_service.history says
            # (default: the last sample per instance), not the writer's history: both, or a
            # late commander gets COMPLETED without the EXECUTING before it
            q = q + Qos(Policy.History.KeepLast(keep_last),
                        Policy.DurabilityService(cleanup_delay=0, history=Policy.History.KeepLast(keep_last),
                                                 max_samples=-1, max_instances=-1, max_samples_per_instance=-1))
        if blocking is not None:
            q = q + Qos(Policy.Reliability.Reliable(max_blocking_time=duration(seconds=blocking)))
        return q

    def deliver(self, seconds: float, first=()) -> None:
        """Wait, at most `seconds` in all, until every reliable reader has acknowledged what the
        writers in `first` (a bridge's ack writers), then the shared writers, wrote: a sample
        lost on the way is resent only while its writer lives, so a bridge that exits right
        after its last acks or telemetry would leave some readers without them."""
        end = time.monotonic() + seconds
        with self._lock:
            writers = [*first, *self._writers.values()]
        for w in writers:
            left = end - time.monotonic()
            if left <= 0:
                return
            try:
                w.wait_for_acks(duration(seconds=left))
            except Exception:  # a reader that left without acknowledging; cyclonedds 11 raises oddly here
                pass

    def close(self) -> None:
        """Delete the participant and everything in it now (teardown.py: left to the garbage
        collector, its domain's threads outlive the interpreter; under DDS Security that
        crashed the process at exit). Stop the reader threads first; nothing is used after.
        Idempotent; a Node whose creation failed has closed itself."""
        delete_participant(self.participant)

    @staticmethod
    def delete(entity) -> None:
        """Delete a DDS entity now (cyclonedds deletes on __del__, guarded against a second call;
        waiting for the garbage collector would keep its memory for an unknown while)."""
        entity.__del__()

    def reader(self, topic: str, cls, keep_all: bool = False, max_samples: int | None = None) -> DataReader:
        """keep_all: every sample, not the last per instance (a commander must see each ack).
        max_samples: what the reader's cache holds at most (not request/offered either); a
        reliable writer past it is held back by DDS until the reader takes."""
        q = self.qos.reader(topic)
        if keep_all:
            q = q + Qos(Policy.History.KeepAll)
        if max_samples is not None:
            q = q + Qos(Policy.ResourceLimits(max_samples=max_samples, max_instances=-1,
                                              max_samples_per_instance=max_samples))
        return DataReader(self.subscriber, self.topic(topic, cls), qos=q)


class ReaderThread:
    """Calls on_sample(sample) for every valid sample the reader takes, in a thread (with
    .sample_info); or, with on_batch, on_batch(samples) once per take with what it decoded. Samples that do not decode are dropped alone and logged once per writer
    (untrusted.py); an exception in on_sample is logged and the thread goes on."""

    def __init__(self, node: Node, reader: DataReader, cls, on_sample, name: str, log=None, wanted=None,
                 batch: int = 32, on_batch=None) -> None:
        self.reader, self.cls, self.on_sample, self.on_batch = reader, cls, on_sample, on_batch
        self.log = log or (lambda text: None)
        self.guard = GuardedReader(reader, self.log, batch=batch, wanted=wanted)
        self.waitset = WaitSet(node.participant)
        self.waitset.attach(ReadCondition(reader, SampleState.Any | ViewState.Any | InstanceState.Any))
        self.wake = GuardCondition(node.participant)
        self.waitset.attach(self.wake)
        self.stopping = threading.Event()
        self.thread = threading.Thread(target=self._run, daemon=True, name=name)

    def start(self) -> "ReaderThread":
        self.thread.start()
        return self

    def _run(self) -> None:
        while not self.stopping.is_set():
            self.waitset.wait(duration(seconds=1))
            while not self.stopping.is_set():
                samples = self.guard.take()
                if self.on_batch is not None and samples:
                    try:
                        self.on_batch(samples)
                    except Exception as exc:  # (on_batch handles its samples' own trouble)
                        self.log(f"samples on {self.reader.topic.name} not handled: {type(exc).__name__}: {exc}")
                    samples = []
                for sample in samples:
                    try:
                        self.on_sample(sample)
                    except Exception as exc:  # one sample's trouble must not end the thread
                        self.log(f"sample on {self.reader.topic.name} not handled: {type(exc).__name__}: {exc}")
                if self.guard.last_taken < self.guard.batch:  # the reader is empty
                    break

    def stop(self) -> None:
        self.stopping.set()
        self.wake.set(True)
        self.thread.join(timeout=5)
