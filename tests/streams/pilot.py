"""A setpoint writer for tests/streams/rig.yaml's input streams (Cyclone DDS, loopback only):
writes `drive` and `mast` (PositionSample) and `arm` (JointSample) in partition RigPilot at
50 Hz, with the streams' QoS (best effort, keep last 1, DEADLINE 200 ms, AUTOMATIC
LIVELINESS 600 ms: what the rig's RapidStream_* reader profiles request).

    python -m tests.streams.pilot PACKAGE_DIR PACKAGE DOMAIN

Setpoints: drive to x = 2 m, mast to z = 1 m, arm joints to (2, -2, 0.5) rad, reached at the simulator's
speeds in a few seconds (the test stops the stream before). Commands on stdin, one a line:
`pause NAME..` (stop writing those streams, the writers stay alive: only DEADLINE passes),
`resume NAME..`, `nan NAME..` (those streams' samples carry NaN and Inf: for drive a new
target x = -1 m with a NaN rotation and an infinite velocity, for arm and mast NaN positions),
`finite NAME..` (back to the setpoints), `quit` (writers deleted, a clean exit). Prints
{"ready": true} once writing.

Run as its own process (CYCLONEDDS_URI is read when cyclonedds loads): the test sets it
to the package's qos_files/cyclonedds/local.xml."""
from __future__ import annotations

import importlib
import json
import sys
import threading
import time

STREAMS = {"drive": "rapid_position_sample-drive", "mast": "rapid_position_sample-mast",
           "arm": "rapid_joint_sample-arm"}
PERIOD = 0.02


def main() -> None:
    pydir, package, domain = sys.argv[1], sys.argv[2], int(sys.argv[3])
    sys.path.insert(0, pydir)
    from cyclonedds.core import Policy, Qos
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.pub import DataWriter, Publisher
    from cyclonedds.topic import Topic
    from cyclonedds.util import duration
    rapid = importlib.import_module(f"{package}.rapid")
    qos = Qos(Policy.Reliability.BestEffort, Policy.Durability.Volatile, Policy.History.KeepLast(1),
              Policy.Deadline(duration(milliseconds=200)), Policy.Liveliness.Automatic(duration(milliseconds=600)))
    dp = DomainParticipant(domain)
    pub = Publisher(dp, qos=Qos(Policy.Partition(["RigPilot"])))

    def header(serial: int):
        return rapid.Header(srcName="RigPilot", assetName="RigPilot", timeStamp=int(time.time() * 1e6),
                            serial=serial)

    def pose(x: float, y: float, z: float):
        return rapid.Transform3D(xyz=[x, y, z], rot=[1, 0, 0, 0, 1, 0, 0, 0, 1])

    writers = {name: DataWriter(pub, Topic(dp, topic, rapid.JointSample if name == "arm" else rapid.PositionSample),
                                qos=qos) for name, topic in STREAMS.items()}
    paused: set[str] = set()
    poisoned: set[str] = set()  # writing samples with NaN and Inf
    nan, inf = float("nan"), float("inf")
    stop = threading.Event()

    def commands() -> None:
        for line in sys.stdin:
            word, *names = line.split()
            if word == "pause":
                paused.update(names)
            elif word == "resume":
                paused.difference_update(names)
            elif word == "nan":
                poisoned.update(names)
            elif word == "finite":
                poisoned.difference_update(names)
            elif word == "quit":
                break
        stop.set()

    threading.Thread(target=commands, daemon=True).start()
    print(json.dumps({"ready": True}), flush=True)
    n = 0
    zero = pose(0, 0, 0)
    while not stop.is_set():
        n += 1
        for name, w in writers.items():
            if name in paused:
                continue
            bad = name in poisoned
            if name == "arm":
                w.write(rapid.JointSample(hdr=header(n), anglePos=[nan, -2.0, 0.5] if bad else [2.0, -2.0, 0.5],
                                          angleVel=[], angleAcc=[], current=[], torque=[], temperature=[], status=[],
                                          auxFloat=[]))
            elif bad and name == "drive":  # a target the simulator would follow, were it handed on
                w.write(rapid.PositionSample(hdr=header(n), pose=rapid.Transform3D(xyz=[-1.0, 0, 0], rot=[nan] * 9),
                                             velocity=pose(inf, 0, 0), values=[]))
            elif bad:
                w.write(rapid.PositionSample(hdr=header(n), pose=pose(0, 0, nan), velocity=zero, values=[]))
            else:
                w.write(rapid.PositionSample(hdr=header(n), pose=pose(2.0, 0, 0) if name == "drive" else pose(0, 0, 1.0),
                                             velocity=zero, values=[]))
        time.sleep(PERIOD)
    # (returning deletes the participant: its writers leave the domain)


if __name__ == "__main__":
    main()
