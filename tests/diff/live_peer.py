"""One side of the diff live check; a subprocess whose CYCLONEDDS_URI pins DDS to loopback.

    python -m tests.diff.live_peer reader|writer PKG_DIR PKG TYPE --domain N --timeout S

reader: a reader of TYPE (from the generated package PKG under PKG_DIR) on topic
        `diff_probe`; prints {"matched": bool, "received": [fields]} once it has a sample or
        the time is up.
writer: a writer of TYPE; once matched writes a default sample every 50 ms until the time
        is up; prints {"matched": bool}.
Both refuse to start unless CYCLONEDDS_URI keeps Cyclone on loopback.
"""
from __future__ import annotations

import argparse
import dataclasses
import importlib
import json
import os
import sys
import time

from tests.python_backend.live_peer import loopback_refusal


def _class(pkg_dir: str, pkg: str, scoped: str) -> type:
    sys.path.insert(0, pkg_dir)
    module, _, name = scoped.rpartition("::")
    return getattr(importlib.import_module(f"{pkg}.{module.replace('::', '.')}"), name)


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("role", choices=("reader", "writer"))
    ap.add_argument("pkg_dir")
    ap.add_argument("pkg")
    ap.add_argument("type")
    ap.add_argument("--domain", type=int, required=True)
    ap.add_argument("--timeout", type=float, default=4.0)
    args = ap.parse_args()
    why = loopback_refusal(os.environ.get("CYCLONEDDS_URI"))
    if why:
        print(json.dumps({"error": why}))
        return 2
    from cyclonedds.core import Policy, Qos
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.pub import DataWriter
    from cyclonedds.sub import DataReader
    from cyclonedds.topic import Topic

    cls = _class(args.pkg_dir, args.pkg, args.type)
    qos = Qos(Policy.Reliability.Reliable(max_blocking_time=1_000_000_000), Policy.History.KeepLast(4))
    dp = DomainParticipant(args.domain)
    topic = Topic(dp, "diff_probe", cls)
    end = time.monotonic() + args.timeout
    if args.role == "reader":
        reader = DataReader(dp, topic, qos=qos)
        matched, got = False, None
        while time.monotonic() < end and got is None:
            matched = matched or reader.get_subscription_matched_status().current_count > 0
            for s in reader.take(4):
                if getattr(s, "sample_info", None) is None or s.sample_info.valid_data:
                    got = [str(getattr(s, f.name)) for f in dataclasses.fields(s)]
                    break
            time.sleep(0.05)
        print(json.dumps({"matched": matched, "received": got}))
        return 0
    writer = DataWriter(dp, topic, qos=qos)
    matched = False
    while time.monotonic() < end:
        if writer.get_publication_matched_status().current_count > 0:
            matched = True
            writer.write(cls())
        time.sleep(0.05)
    print(json.dumps({"matched": matched}))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
