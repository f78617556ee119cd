"""The live half of the demo: an asset announces itself over DDS, a ground tool reads it.

    python scripts/demo_live.py asset  ASSET.yaml GENERATED_DIR [--seconds N]
    python scripts/demo_live.py ground ASSET.yaml GENERATED_DIR [--seconds N]

GENERATED_DIR is `rapidgen generate ASSET.yaml --lang python,qos -o GENERATED_DIR`. The
asset publishes every config its descriptor computes (CommandConfig, AgentConfig,
JointConfig, PositionConfig...) with the generated Python bindings, each with the QoS its
topic maps to (qos/topics.json; RapidConfigQos: reliable, transient-local, keep-last 1)
loaded from the generated DDS-XML by Cyclone's QoS provider, in the asset's partition; the
ground side joins late, receives them all, and checks each against the descriptor. Values
are built with the reference codec (rapidgen.model.cdr) and handed to the generated classes
as bytes, so this also shows the two agree. Run with CYCLONEDDS_URI pointing at the
generated loopback transport, GENERATED_DIR/qos/cyclonedds/local.xml.
"""
from __future__ import annotations

import argparse
import importlib
import os
import sys
import time


def _load(asset_path: str):
    from rapidgen.asset import load_asset
    from rapidgen.asset.publish import configs
    from rapidgen.cli import report
    from rapidgen.diagnostics import DiagnosticSink

    sink = DiagnosticSink()
    loaded = load_asset(asset_path, sink)
    if loaded is None or sink.has_errors:
        report(sink)
        raise SystemExit(1)
    return loaded, configs(loaded)


def _class_of(package: str, scoped: str):
    *modules, name = scoped.split("::")
    return getattr(importlib.import_module(".".join([package, *modules])), name)


class _QosMap:
    """QoS per topic: the generated topic map names a profile, the DDS-XML defines it."""

    def __init__(self, qos_dir: str) -> None:
        import json

        from cyclonedds.qos_provider import QosProvider

        with open(os.path.join(qos_dir, "topics.json"), encoding="utf-8") as fh:
            self.map = json.load(fh)
        self.provider = QosProvider(os.path.join(qos_dir, self.map["files"]["dds_xml"]))
        self.keys = {t["topic"]: t["key"] for t in self.map["topics"]}

    def writer(self, topic: str):
        return self.provider.get_datawriter_qos(self.keys[topic])

    def reader(self, topic: str):
        return self.provider.get_datareader_qos(self.keys[topic])

    def publisher(self):
        return self.provider.get_publisher_qos(next(iter(self.keys.values())))

    def subscriber(self):
        return self.provider.get_subscriber_qos(next(iter(self.keys.values())))


def run_asset(args, loaded, configs, package: str) -> int:
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.pub import DataWriter, Publisher
    from cyclonedds.topic import Topic

    from rapidgen.model.cdr import Codec

    name = loaded.spec.name
    qos = _QosMap(os.path.join(args.generated, "qos"))
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

    from rapidgen.model.cdr import Codec

    qos = _QosMap(os.path.join(args.generated, "qos"))
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


def _print_dictionary(config: dict) -> None:
    types = {t["name"]: t for t in config["availableSubsystemTypes"]}
    for sub in config["availableSubsystems"]:
        for cmd in types[sub["subsystemTypeName"]]["commands"]:
            params = ", ".join(f"{p['key']}:{p['type'].removeprefix('RAPID_')}" for p in cmd["parameters"])
            print(f"          {sub['name']:>10} / {cmd['name']}({params})")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("role", choices=("asset", "ground"))
    parser.add_argument("asset_file")
    parser.add_argument("generated", help="output of `rapidgen generate ASSET --lang python,qos`")
    parser.add_argument("--domain", type=int, default=30)
    parser.add_argument("--seconds", type=float, default=10.0)
    args = parser.parse_args()
    if "127.0.0.1" not in open(os.environ.get("CYCLONEDDS_URI", "").removeprefix("file://") or os.devnull).read():
        print("demo_live: set CYCLONEDDS_URI to a loopback-only Cyclone config first", file=sys.stderr)
        return 2
    loaded, configs = _load(args.asset_file)
    python_dir = os.path.join(args.generated, "python")
    package = next(p for p in sorted(os.listdir(python_dir)) if os.path.isfile(os.path.join(python_dir, p, "__init__.py")))
    sys.path.insert(0, os.path.abspath(python_dir))
    run = run_asset if args.role == "asset" else run_ground
    return run(args, loaded, configs, package)


if __name__ == "__main__":
    raise SystemExit(main())
