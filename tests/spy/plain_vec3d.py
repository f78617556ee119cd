"""A ground tool whose RAPID types were written by hand, one detail off: its
ParameterUnion.vec3d is a plain `double[3]` where RAPID has the Vec3d typedef. Cyclone
does not match its command writer with the asset's reader (a typedef and the type it
names differ inside a nested type), and `rapidgen spy` must say where (SPY-TYPE-01).

    python -m tests.spy.plain_vec3d GENERATED_PYTHON_DIR PACKAGE DOMAIN SECONDS

Prints "plain-vec3d ready" once its writer exists."""
import importlib
import sys
import time
from dataclasses import dataclass, field

from cyclonedds.idl import IdlStruct, IdlUnion, annotations as annotate, types


def hand_written_command(rapid, base):
    """rapid::Command as the hand-written tool has it: RAPID's but for ParameterUnion.vec3d."""
    DataType = rapid.DataType

    class ParameterUnion(IdlUnion, discriminator=DataType, typename="rapid.ParameterUnion"):
        b: types.case[[DataType.RAPID_BOOL], bool]
        d: types.case[[DataType.RAPID_DOUBLE], types.float64]
        f: types.case[[DataType.RAPID_FLOAT], types.float32]
        i: types.case[[DataType.RAPID_INT], types.int32]
        ll: types.case[[DataType.RAPID_LONGLONG], types.int64]
        s: types.case[[DataType.RAPID_STRING], base.String128]
        vec3d: types.case[[DataType.RAPID_VEC3d], types.array[types.float64, 3]]  # RAPID: Vec3d
        mat33f: types.case[[DataType.RAPID_MAT33f], base.Mat33f]

    @dataclass
    @annotate.final
    class Command(IdlStruct, typename="rapid.Command"):
        hdr: rapid.Header = field(default_factory=rapid.Header)
        annotate.key("hdr")
        cmdName: base.String64 = ""
        cmdId: base.String64 = ""
        cmdSrc: base.String32 = ""
        subsysName: base.String32 = ""
        arguments: types.typedef["rapid.ParameterSequence16", types.sequence[ParameterUnion, 16]] = \
            field(default_factory=list)
        cmdAction: rapid.QueueAction = rapid.QueueAction.QUEUE_BYPASS
        targetCmdId: base.String64 = ""

    return Command


def main() -> int:
    pydir, package, domain, seconds = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
    sys.path.insert(0, pydir)
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.pub import DataWriter, Publisher
    from cyclonedds.qos import Policy, Qos
    from cyclonedds.topic import Topic

    rapid = importlib.import_module(f"{package}.rapid")
    qos = importlib.import_module(f"{package}.qos").RapidQos()
    Command = hand_written_command(rapid, importlib.import_module(f"{package}._idl.BaseTypes"))

    dp = DomainParticipant(domain)
    pub = Publisher(dp, qos=Qos(Policy.Partition(["K10Red"])))
    writer = DataWriter(pub, Topic(dp, "rapid_command", Command), qos=qos.writer("rapid_command"))
    print("plain-vec3d ready", flush=True)
    end, n = time.monotonic() + seconds, 0
    while time.monotonic() < end:
        n += 1
        writer.write(Command(hdr=rapid.Header(srcName="HandTool", assetName="K10Red"), cmdName="noOp",
                             cmdId=f"hand-{n}", cmdSrc="HandTool", subsysName="Admin"))
        time.sleep(0.3)
    return 0


if __name__ == "__main__":
    sys.exit(main())
