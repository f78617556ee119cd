"""The live half of the demo: an asset announces itself over DDS, a ground tool reads it.

    python scripts/demo_live.py asset  ASSET.yaml GENERATED_DIR [--seconds N]
    python scripts/demo_live.py ground ASSET.yaml GENERATED_DIR [--seconds N]
    python scripts/demo_live.py watch  ASSET.yaml GENERATED_DIR [--seconds N]

`watch` prints the position and agent telemetry a running bridge publishes
(`python -m <package>.bridge --simulate`), read with the generated bindings.

GENERATED_DIR is `rapidgen generate ASSET.yaml --lang python,qos -o GENERATED_DIR`. The
asset publishes every config its descriptor computes (CommandConfig, AgentConfig,
JointConfig, PositionConfig...) with the generated Python bindings, each with the QoS its
topic maps to (qos/topics.json; RapidConfigQos: reliable, transient-local, keep-last 1)
loaded from the generated DDS-XML by Cyclone's QoS provider through the generated package's
QoS runtime (`<package>.qos.RapidQos`), in the asset's partition; the
ground side joins late, receives them all, and checks each against the descriptor. Values
are built with the reference codec (rapidgen.cdr) and handed to the generated classes
as bytes, so this also shows the two agree. Run with CYCLONEDDS_URI pointing at the
generated loopback transport, GENERATED_DIR/qos/cyclonedds/local.xml: anything else
(unset, inline XML, not a file, multicast allowed, an interface or peer other than
127.0.0.1) is refused before DDS starts.
"""
from __future__ import annotations

import argparse
import importlib
import os
import sys
import time
import xml.etree.ElementTree as ET


def _load(asset_path: str):
    from rapidgen.asset import load_asset
    from rapidgen.reporting import report
    from rapidgen.diagnostics import DiagnosticSink

    sink = DiagnosticSink()
    loaded = load_asset(asset_path, sink)
    if loaded is None or sink.has_errors:
        report(sink)
        raise SystemExit(1)
    return loaded, loaded.configs


def _class_of(package: str, scoped: str):
    *modules, name = scoped.split("::")
    return getattr(importlib.import_module(".".join([package, *modules])), name)


def _qos(package: str, generated: str):
    """The generated package's QoS runtime (<package>/qos.py) on GENERATED_DIR/qos."""
    try:
        runtime = importlib.import_module(f"{package}.qos")
    except ModuleNotFoundError as exc:
        raise SystemExit(f"demo_live: {generated} has no {package}.qos ({exc}); regenerate it with this rapidgen")
    try:
        return runtime.RapidQos(os.path.join(generated, "qos"))
    except runtime.RapidQosError as exc:
        raise SystemExit(f"demo_live: {exc}")


def loopback_refusal(uri: str | None) -> str | None:
    """Why CYCLONEDDS_URI does not keep Cyclone on loopback, or None when it does.

    It must name exactly one configuration file (`file://PATH` or `PATH`; not inline XML,
    not a list, no ${VAR}) whose every <Domain> sets <AllowMulticast>false</AllowMulticast>,
    pins every network interface to 127.0.0.1 and has no peer but 127.0.0.1.
    """
    uri = (uri or "").strip()
    if not uri:
        return "CYCLONEDDS_URI is not set (Cyclone's default uses every interface and multicast)"
    if uri.startswith("<"):
        return "CYCLONEDDS_URI holds inline XML; point it at a configuration file (file://PATH)"
    if "," in uri or "$" in uri:
        return f"CYCLONEDDS_URI={uri!r} is a list or uses ${{VAR}}; give exactly one file (file://PATH)"
    path = uri[len("file://"):] if uri.startswith("file://") else uri
    if "://" in path:
        return f"CYCLONEDDS_URI={uri!r} is not a file URI (file://PATH)"
    try:
        root = ET.parse(path).getroot()  # XML comments are dropped: only live settings count
    except (OSError, ValueError, ET.ParseError) as exc:
        return f"cannot read {path!r} as a Cyclone DDS configuration: {exc}"

    def tag(e) -> str:
        return e.tag.rsplit("}", 1)[-1] if isinstance(e.tag, str) else ""

    domains = [e for e in root.iter() if tag(e) == "Domain"]
    if tag(root) != "CycloneDDS" or not domains:
        return f"{path} is not a Cyclone DDS configuration with a <Domain> section"
    for d in domains:
        where = f"{path} <Domain Id={d.get('Id', 'any')!r}>"
        multicast = [(e.text or "").strip().lower() for e in d.iter() if tag(e) == "AllowMulticast"]
        nics = [e.get("address") if tag(e) == "NetworkInterface" else (e.text or "").strip()
                for e in d.iter() if tag(e) in ("NetworkInterface", "NetworkInterfaceAddress")]
        peers = [e.get("Address") or e.get("address") for e in d.iter() if tag(e) == "Peer"]
        if multicast != ["false"]:
            return f"{where}: needs <AllowMulticast>false</AllowMulticast> (once), has {multicast}"
        if not nics or any(n != "127.0.0.1" for n in nics):
            return f'{where}: must pin every interface to 127.0.0.1 (<NetworkInterface address="127.0.0.1"/>)'
        if any(p != "127.0.0.1" for p in peers):
            return f"{where}: every <Peer> must be 127.0.0.1, has {peers}"
    return None


def run_asset(args, loaded, configs, package: str) -> int:
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.pub import DataWriter, Publisher
    from cyclonedds.topic import Topic

    from rapidgen.cdr import Codec

    name = loaded.spec.name
    qos = _qos(package, args.generated)
    participant = DomainParticipant(args.domain)
    publisher = Publisher(participant, qos=qos.publisher())
    codec = Codec(loaded.model)
    header = {"srcName": name, "assetName": name, "timeStamp": int(time.time() * 1e6), "statusCode": 0,
              "serial": int(time.time())}
    writers = []
    for topic_name, (type_name, value) in configs.items():
        cls = _class_of(package, type_name)
        sample = cls.deserialize(codec.encode(type_name, dict(hdr=header, **value)))
        writer = DataWriter(publisher, Topic(participant, topic_name, cls), qos=qos.writer(topic_name))
        writer.write(sample)
        writers.append(writer)
        print(f"asset {name}: published {type_name} on {topic_name}", flush=True)
    time.sleep(args.seconds)  # stay up so a late-joining ground tool gets the transient-local configs
    return 0


def run_ground(args, loaded, configs, package: str) -> int:
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.sub import DataReader, Subscriber
    from cyclonedds.topic import Topic

    from rapidgen.cdr import Codec

    qos = _qos(package, args.generated)
    participant = DomainParticipant(args.domain)
    subscriber = Subscriber(participant, qos=qos.subscriber())
    codec = Codec(loaded.model)
    readers = {t: (ty, DataReader(subscriber, Topic(participant, t, _class_of(package, ty)), qos=qos.reader(t)))
               for t, (ty, _v) in configs.items()}
    pending = dict(readers)
    deadline = time.monotonic() + args.seconds
    failures = 0
    while pending and time.monotonic() < deadline:
        for topic_name, (type_name, reader) in list(pending.items()):
            samples = reader.take(N=1)
            if not samples:
                continue
            got = codec.decode(type_name, samples[0].serialize())
            # Round the descriptor's values through the codec (float32 etc.) before comparing.
            want = codec.decode(type_name, codec.encode(type_name, dict(hdr=got["hdr"], **configs[topic_name][1])))
            same = got == want
            print(f"ground: {topic_name:32} {type_name:22} from {got['hdr']['srcName']}: "
                  f"{'matches the descriptor' if same else 'DIFFERS from the descriptor'}", flush=True)
            failures += not same
            if type_name == "rapid::CommandConfig":
                _print_dictionary(got)
            del pending[topic_name]
        time.sleep(0.05)
    for topic_name in pending:
        print(f"ground: {topic_name}: nothing received within {args.seconds} s", flush=True)
    return 1 if pending or failures else 0


def run_watch(args, loaded, configs, package: str) -> int:
    """The last position and agent state the asset published within --seconds."""
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.sub import DataReader, Subscriber
    from cyclonedds.topic import Topic

    tables = importlib.import_module(f"{package}.asset_tables")
    qos = _qos(package, args.generated)
    participant = DomainParticipant(args.domain)
    subscriber = Subscriber(participant, qos=qos.subscriber())
    wanted = {"position": ("sample", "rapid::PositionSample"), "agent": ("state", "rapid::AgentState")}
    readers = {}
    for entry in tables.TELEMETRY:
        if entry["kind"] in wanted and entry["kind"] not in readers:
            role, type_name = wanted[entry["kind"]]
            topic = entry["topics"][role]
            keys = [v["name"] for v in entry["values"]]
            readers[entry["kind"]] = (keys, DataReader(subscriber, Topic(participant, topic, _class_of(package, type_name)),
                                                       qos=qos.reader(topic)))
    last: dict = {}
    deadline = time.monotonic() + args.seconds
    while time.monotonic() < deadline:
        for kind, (_keys, reader) in readers.items():
            for s in reader.take(N=16):
                last[kind] = s
        time.sleep(0.05)
    for kind, (keys, _reader) in readers.items():
        s = last.get(kind)
        if s is None:
            print(f"watch: no {kind} telemetry within {args.seconds:g} s", flush=True)
            continue
        values = ", ".join(f"{k}={_value(u.value)}" for k, u in zip(keys, s.values))
        where = ""
        if kind == "position":
            where = "pose xyz=(" + ", ".join(f"{x:.2f}" for x in s.pose.xyz) + ") "
        print(f"watch: {kind:8} from {s.hdr.srcName} at {s.hdr.timeStamp} us: {where}{values}", flush=True)
    return 0 if len(last) == len(readers) else 1


def _value(v) -> str:
    if isinstance(v, float):
        return f"{v:.2f}"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    return repr(v) if isinstance(v, str) else str(v)


def _print_dictionary(config: dict) -> None:
    types = {t["name"]: t for t in config["availableSubsystemTypes"]}
    for sub in config["availableSubsystems"]:
        for cmd in types[sub["subsystemTypeName"]]["commands"]:
            params = ", ".join(f"{p['key']}:{p['type'].removeprefix('RAPID_')}" for p in cmd["parameters"])
            print(f"          {sub['name']:>10} / {cmd['name']}({params})")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("role", choices=("asset", "ground", "watch"))
    parser.add_argument("asset_file")
    parser.add_argument("generated", help="output of `rapidgen generate ASSET --lang python,qos`")
    parser.add_argument("--domain", type=int, default=30)
    parser.add_argument("--seconds", type=float, default=10.0)
    args = parser.parse_args()
    refusal = loopback_refusal(os.environ.get("CYCLONEDDS_URI"))
    if refusal is not None:
        print(f"demo_live: {refusal}; refusing to start DDS. Set CYCLONEDDS_URI=file://<absolute path of "
              f"{os.path.join(args.generated, 'qos', 'cyclonedds', 'local.xml')}> (loopback only)", file=sys.stderr)
        return 2
    loaded, configs = _load(args.asset_file)
    python_dir = os.path.join(args.generated, "python")
    found = sorted(os.listdir(python_dir)) if os.path.isdir(python_dir) else []
    package = next((p for p in found if os.path.isfile(os.path.join(python_dir, p, "__init__.py"))), None)
    if package is None:
        print(f"demo_live: no generated Python package in {python_dir}; run "
              f"`rapidgen generate {args.asset_file} --lang python,qos -o {args.generated}`", file=sys.stderr)
        return 2
    sys.path.insert(0, os.path.abspath(python_dir))
    run = {"asset": run_asset, "ground": run_ground, "watch": run_watch}[args.role]
    return run(args, loaded, configs, package)


if __name__ == "__main__":
    raise SystemExit(main())
