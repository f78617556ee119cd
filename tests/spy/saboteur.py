"""A deliberately broken participant beside a healthy K10Red bridge, for `rapidgen spy`:

    python -m tests.spy.saboteur GENERATED_PYTHON_DIR PACKAGE DOMAIN SECONDS

- a best-effort command writer (the bridge's command reader is reliable): SPY-QOS-01
- a command writer in partition K10Blue sending commands for K10Red: SPY-PART-01
- a writer of rapid_ack whose type is named rapid::Ack but has another layout: SPY-TYPE-01
- acks for a cmdId no command carried: SPY-ACK-01
Prints "saboteur ready" once its writers exist."""
import importlib
import sys
import time
from dataclasses import dataclass

from cyclonedds.idl import IdlStruct, types


@dataclass
class WrongAck(IdlStruct, typename="rapid.Ack"):  # the right name, another layout (no hdr first)
    cmdId: str
    status: types.int32


def main() -> int:
    pydir, package, domain, seconds = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
    sys.path.insert(0, pydir)
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.pub import DataWriter, Publisher
    from cyclonedds.qos import Policy, Qos
    from cyclonedds.topic import Topic

    rapid = importlib.import_module(f"{package}.rapid")
    qos = importlib.import_module(f"{package}.qos").RapidQos()

    dp = DomainParticipant(domain)
    home = Publisher(dp, qos=Qos(Policy.Partition(["K10Red"])))
    away = Publisher(dp, qos=Qos(Policy.Partition(["K10Blue"])))
    cmd_topic = Topic(dp, "rapid_command", rapid.Command)
    lossy = DataWriter(home, cmd_topic, qos=qos.writer("rapid_command") + Qos(Policy.Reliability.BestEffort))
    lost = DataWriter(away, cmd_topic, qos=qos.writer("rapid_command"))
    wrong_ack = DataWriter(home, Topic(dp, "rapid_ack", WrongAck), qos=qos.writer("rapid_ack"))
    dp2 = DomainParticipant(domain)  # one participant cannot hold rapid_ack with two types
    ghost = DataWriter(Publisher(dp2, qos=Qos(Policy.Partition(["K10Red"]))), Topic(dp2, "rapid_ack", rapid.Ack),
                       qos=qos.writer("rapid_ack"))
    print("saboteur ready", flush=True)
    end, n = time.monotonic() + seconds, 0
    while time.monotonic() < end:
        n += 1
        now = time.time_ns() // 1000
        hdr = rapid.Header(srcName="Saboteur", assetName="K10Red", timeStamp=now, statusCode=0, serial=0)
        cmd = rapid.Command(hdr=hdr, cmdName="noOp", cmdId=f"sab-{n}", cmdSrc="Saboteur", subsysName="Admin",
                            arguments=[], cmdAction=rapid.QueueAction.QUEUE_BYPASS, targetCmdId="")
        lost.write(cmd)
        wrong_ack.write(WrongAck(cmdId=f"sab-{n}", status=1))
        ghost.write(rapid.Ack(hdr=rapid.Header(srcName="K10Red", assetName="K10Red", timeStamp=now, statusCode=0,
                                               serial=0),
                              cmdId=f"ghost-{n}", status=rapid.AckStatus.ACK_COMPLETED,
                              completedStatus=rapid.AckCompletedStatus.ACK_COMPLETED_OK, message=""))
        if n % 3 == 0:
            lossy.write(cmd)
        time.sleep(0.3)
    return 0


if __name__ == "__main__":
    sys.exit(main())
