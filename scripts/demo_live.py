"""The live half of the demo: an asset announces itself over DDS, a ground tool reads it.

    python scripts/demo_live.py asset  ASSET.yaml GENERATED_PYTHON_DIR [--seconds N]
    python scripts/demo_live.py ground ASSET.yaml GENERATED_PYTHON_DIR [--seconds N]

The asset publishes every config its descriptor computes (CommandConfig, AgentConfig,
JointConfig, PositionConfig...) with the generated Python bindings, on RAPID's config QoS
(reliable, transient-local, keep-last 1) in its own partition; the ground side joins
late, receives them all, and checks each against the descriptor. Values are built with the
reference codec (rapidgen.model.cdr) and handed to the generated classes as bytes, so this
also shows the two agree. Run with CYCLONEDDS_URI pointing at a loopback-only config.
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


def _dds(asset_name: str):
    from cyclonedds.core import Policy, Qos
    from cyclonedds.util import duration

    config_qos = Qos(Policy.Reliability.Reliable(duration(seconds=1)), Policy.Durability.TransientLocal,
                     Policy.History.KeepLast(1))
    return config_qos, Qos(Policy.Partition([asset_name]))


def run_asset(args, loaded, configs, package: str) -> int:
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.pub import DataWriter, Publisher
    from cyclonedds.topic import Topic

    from rapidgen.model.cdr import Codec

    name = loaded.spec.name
    config_qos, partition = _dds(name)
    participant = DomainParticipant(args.domain)
    publisher = Publisher(participant, qos=partition)
    codec = Codec(loaded.model)
    header = {"srcName": name, "assetName": name, "timeStamp": int(time.time() * 1e6), "statusCode": 0,
              "serial": int(time.time())}
    writers = []
    for topic_name, (type_name, value) in configs.items():
        cls = _class_of(package, type_name)
        sample = cls.deserialize(codec.encode(type_name, dict(hdr=header, **value)))
        writer = DataWriter(publisher, Topic(participant, topic_name, cls), qos=config_qos)
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

    name = loaded.spec.name
    config_qos, partition = _dds(name)
    participant = DomainParticipant(args.domain)
    subscriber = Subscriber(participant, qos=partition)
    codec = Codec(loaded.model)
    readers = {t: (ty, DataReader(subscriber, Topic(participant, t, _class_of(package, ty)), qos=config_qos))
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
    parser.add_argument("generated", help="the generated python folder (holds the package)")
    parser.add_argument("--domain", type=int, default=30)
    parser.add_argument("--seconds", type=float, default=10.0)
    args = parser.parse_args()
    if "127.0.0.1" not in open(os.environ.get("CYCLONEDDS_URI", "").removeprefix("file://") or os.devnull).read():
        print("demo_live: set CYCLONEDDS_URI to a loopback-only Cyclone config first", file=sys.stderr)
        return 2
    loaded, configs = _load(args.asset_file)
    package = next(p for p in sorted(os.listdir(args.generated))
                   if os.path.isfile(os.path.join(args.generated, p, "__init__.py")))
    sys.path.insert(0, os.path.abspath(args.generated))
    run = run_asset if args.role == "asset" else run_ground
    return run(args, loaded, configs, package)


if __name__ == "__main__":
    raise SystemExit(main())
