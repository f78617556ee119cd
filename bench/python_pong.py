"""The Python bridge's floor: bare cyclonedds-python answering every command with the
bridge's own ack sequence (EXECUTING, then COMPLETED/OK), nothing else.

    python bench/python_pong.py --domain D      # run by bench/command_latency.py

The same generated types (K10's `rapid.Command`, `rapid.Ack`), the same partition, topics
and QoS as the bridge (the package's profiles; the command reader's cache and the ack
writer's KEEP_LAST 8 and 10 s blocking as bridge.py sets them), the same loopback transport
(CYCLONEDDS_URI from the caller). One thread: a waitset on the command reader, take, two
writes. No intake, door, checks, journal or handler thread: what the bridge adds over this
is the bridge's own cost. Prints "pong ready" once its endpoints exist.
"""
from __future__ import annotations

import argparse
import importlib
import signal
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PYDIR = ROOT / "generated" / "k10" / "python"
PACKAGE = "rapid_k10red"
ACK_HISTORY, ACK_BLOCKING, COMMAND_CACHE = 8, 10.0, 4096  # as runtime/rapid_runtime/bridge.py


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--domain", type=int, required=True)
    args = p.parse_args()
    sys.path[:0] = [str(PYDIR)]
    from cyclonedds.core import InstanceState, ReadCondition, SampleState, ViewState, WaitSet
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.pub import DataWriter, Publisher
    from cyclonedds.qos import Policy, Qos
    from cyclonedds.sub import DataReader, Subscriber
    from cyclonedds.topic import Topic
    from cyclonedds.util import duration

    rapid = importlib.import_module(f"{PACKAGE}.rapid")
    qos = importlib.import_module(f"{PACKAGE}.qos").RapidQos()
    dp = DomainParticipant(args.domain)
    pub, sub = Publisher(dp, qos=qos.publisher()), Subscriber(dp, qos=qos.subscriber())
    reader = DataReader(sub, Topic(dp, "rapid_command", rapid.Command), qos=qos.reader("rapid_command") + Qos(
        Policy.ResourceLimits(max_samples=COMMAND_CACHE, max_instances=-1, max_samples_per_instance=COMMAND_CACHE)))
    writer = DataWriter(pub, Topic(dp, "rapid_ack", rapid.Ack), qos=qos.writer("rapid_ack") + Qos(
        Policy.History.KeepLast(ACK_HISTORY), Policy.Reliability.Reliable(max_blocking_time=duration(seconds=ACK_BLOCKING))))
    ws = WaitSet(dp)
    ws.attach(ReadCondition(reader, SampleState.Any | ViewState.Any | InstanceState.Any))
    executing, completed = rapid.AckStatus.ACK_EXECUTING, rapid.AckStatus.ACK_COMPLETED
    not_, ok = rapid.AckCompletedStatus.ACK_COMPLETED_NOT, rapid.AckCompletedStatus.ACK_COMPLETED_OK
    stop = []
    signal.signal(signal.SIGTERM, lambda *_: stop.append(1))
    print("pong ready", flush=True)
    while not stop:
        ws.wait(duration(milliseconds=200))
        for c in reader.take(32):
            h = c.hdr
            for status, done in ((executing, not_), (completed, ok)):
                hdr = rapid.Header(srcName=h.srcName, assetName=h.assetName, timeStamp=time.time_ns() // 1000,
                                   statusCode=0, serial=h.serial)
                writer.write(rapid.Ack(hdr=hdr, cmdId=c.cmdId, status=status, completedStatus=done, message=""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
