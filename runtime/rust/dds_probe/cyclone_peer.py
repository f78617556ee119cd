"""The Cyclone (Python) side of the DDS stack probes (docs/rust-backend.md, "Choosing the stack"):
  acks D PARTITION SECONDS      a late-joining transient-local reader of rapid_ack: prints each Ack
  cmds D PARTITION N            writes N Commands (cmdId c0..) in PARTITION
  ping D N                      N Command -> Ack round trips against a pong peer, prints p50/p99
Loopback only: CYCLONEDDS_URI is K10's local.xml."""
import statistics
import sys
import time

from cyclonedds.core import Policy, Qos
from cyclonedds.domain import DomainParticipant
from cyclonedds.pub import DataWriter, Publisher
from cyclonedds.sub import DataReader, Subscriber
from cyclonedds.topic import Topic
from cyclonedds.util import duration
from rapid_k10red._idl.Ack import Ack
from rapid_k10red._idl.Command import Command

mode, domain = sys.argv[1], int(sys.argv[2])
part = sys.argv[3] if len(sys.argv) > 3 else "K10Red"
dp = DomainParticipant(domain)
pq = Qos(Policy.Partition([part]))
rel = Policy.Reliability.Reliable(duration(milliseconds=100))
acks = Topic(dp, "rapid_ack", Ack)
cmds = Topic(dp, "rapid_command", Command)
if mode == "acks":
    r = DataReader(Subscriber(dp, qos=pq), acks, qos=Qos(rel, Policy.Durability.TransientLocal, Policy.History.KeepLast(10)))
    end = time.time() + float(sys.argv[4])
    while time.time() < end:
        for a in r.take(100):
            print("ACK", a.cmdId, a.hdr.serial, a.message, flush=True)
        time.sleep(0.02)
elif mode == "cmds":
    w = DataWriter(Publisher(dp, qos=pq), cmds, qos=Qos(rel, Policy.Durability.Volatile, Policy.History.KeepLast(100)))
    time.sleep(3)  # discovery
    for i in range(int(sys.argv[4])):
        c = Command(); c.hdr.srcName = "probe"; c.hdr.assetName = "K10Red"
        c.cmdId, c.cmdName, c.cmdSrc, c.subsysName = f"c{i}", "moveTo", "probe", "Mobility"
        w.write(c)
    time.sleep(2)
elif mode == "ping":
    pq = Qos(Policy.Partition(["K10Red"]))
    q = Qos(rel, Policy.Durability.Volatile, Policy.History.KeepLast(100))
    w = DataWriter(Publisher(dp, qos=pq), cmds, qos=q)
    r = DataReader(Subscriber(dp, qos=pq), acks, qos=q)
    time.sleep(3)
    rtts = []
    for i in range(int(sys.argv[3])):
        c = Command(); c.hdr.srcName = "probe"; c.hdr.assetName = "K10Red"; c.cmdId = f"p{i}"
        t = time.perf_counter(); w.write(c)
        got = False
        while not got and time.perf_counter() - t < 2:
            got = any(a.cmdId == c.cmdId for a in r.take(10))
        if got:
            rtts.append((time.perf_counter() - t) * 1e6)
    rtts.sort()
    print(f"RTT n={len(rtts)} p50={statistics.median(rtts):.0f}us p99={rtts[int(len(rtts)*0.99)-1]:.0f}us" if rtts else "RTT none")
