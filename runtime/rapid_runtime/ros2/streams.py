"""A mapped RAPID input stream read on the ROS 2 bridge's Cyclone participant: each sample
goes to ROS 2, a missed deadline or a departed writer is a loss (the handlers act on it)."""
from __future__ import annotations

import queue
import sys
import threading
from typing import Any


class StreamReader:
    """One mapped input stream: a Cyclone reader in the writer's partition (best effort, keep
    last 1, DEADLINE) and a thread that publishes each sample to ROS 2 and acts on losses.
    The deadline listener only queues the event: everything else happens in the thread.

    `handlers` gives publish_stream_sample(spec, sample), stream_state(spec, state, missed,
    text, level) and _log_once(key, text) (rapid_runtime.ros2.handlers.Ros2Handlers)."""

    def __init__(self, handlers: Any, spec: dict, bridge: Any) -> None:
        from cyclonedds.core import (GuardCondition, InstanceState, Listener, ReadCondition, SampleState, ViewState,
                                     WaitSet)
        from cyclonedds.qos import Policy, Qos
        from cyclonedds.sub import DataReader, Subscriber
        from cyclonedds.util import duration

        from rapid_runtime.dds import type_class

        self.handlers, self.spec, self.bridge = handlers, spec, bridge
        self.duration, self.alive = duration, InstanceState.Alive
        self.state, self.missed = "waiting", 0
        self.events: queue.Queue[tuple[str, int]] = queue.Queue()
        node = bridge.node
        self.subscriber = Subscriber(node.participant, qos=Qos(Policy.Partition(partitions=[spec["partition"]])))
        qos = Qos(Policy.Reliability.BestEffort, Policy.Durability.Volatile, Policy.History.KeepLast(1),
                  Policy.Deadline(duration(microseconds=int(round(spec["deadline_ms"] * 1000)))))
        self.reader = DataReader(self.subscriber, node.topic(spec["topic"], type_class(bridge.rapid, spec["type"])),
                                 qos=qos, listener=Listener(on_requested_deadline_missed=self._on_missed))
        self.waitset = WaitSet(node.participant)
        self.waitset.attach(ReadCondition(self.reader, SampleState.Any | ViewState.Any | InstanceState.Any))
        self.wake = GuardCondition(node.participant)
        self.waitset.attach(self.wake)
        self.stopping = threading.Event()
        self.thread = threading.Thread(target=self._run, name=f"stream-{spec['stream']}", daemon=True)

    def start(self) -> "StreamReader":
        self.thread.start()
        return self

    def stop(self) -> None:
        self.stopping.set()
        self.wake.set(True)
        self.thread.join(timeout=5)

    def _on_missed(self, reader: Any, status: Any) -> None:  # Cyclone's listener thread: hand over, nothing more
        self.events.put(("missed", status.total_count))
        self.wake.set(True)

    def _run(self) -> None:
        name, spec = self.spec["stream"], self.spec
        while not self.stopping.is_set():
            self.waitset.wait(self.duration(seconds=1))
            self.wake.set(False)
            while True:
                try:
                    _kind, count = self.events.get_nowait()
                except queue.Empty:
                    break
                self.missed = max(self.missed, count)
                if self.state == "active":
                    self._change("lost", f"no sample within {spec['deadline_ms']:g} ms")
            try:
                samples = self.reader.take(N=32)
            except Exception as exc:  # a sample that does not decode: say so, go on
                self.handlers._log_once(("stream", name), f"ros2: stream {name}: {exc!r}")
                continue
            last = None
            for s in samples:
                info = s.sample_info
                if not info.valid_data:  # a dispose/unregister notice: the writer left
                    if info.instance_state != self.alive and self.state == "active":
                        self._change("lost", "its writer left")
                    continue
                last = s
            if last is not None:
                if self.state != "active":
                    self._change("active", None)
                try:
                    self.handlers.publish_stream_sample(spec, last)
                except Exception as exc:
                    self.handlers._log_once(("stream", name), f"ros2: stream {name} -> {spec['ros2']['topic']}: "
                                                               f"{exc!r}")

    def _change(self, state: str, why: str | None) -> None:
        spec, old = self.spec, self.state
        self.state = state
        if state == "lost":
            action = {"stop": "stopped" + (f" (published on {spec['stop']['topic']})" if spec["stop"] else ""),
                      "hold": "holding the last setpoint", "none": "reported"}[spec["on_loss"]]
            text, level = f"stream {spec['stream']} lost: {why}; {action}", "MSG_WARN"
        elif old == "lost":
            text, level = f"stream {spec['stream']} recovered", "MSG_INFO"
        else:
            text, level = f"stream {spec['stream']} active: publishing on {spec['ros2']['topic']}", "MSG_INFO"
        try:
            self.handlers.stream_state(spec, state, self.missed, text, level)
        except Exception as exc:
            print(f"ros2: stream {spec['stream']}: {exc!r}", file=sys.stderr, flush=True)
