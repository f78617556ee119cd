"""Each live tool's DDS holder closed while something still refers to it, then what of DDS
is left: `unshare -n python -m tests.secure.closed_threads ENCLAVE DOMAIN ASSET.yaml` (a
private network namespace: loopback only, brought up here).

A reference kept after close() stands for the reference cycles a real run leaves (a reader
thread's bound method, a listener's closure, a traceback): with them, only an explicit
delete stops the domain's threads before the interpreter ends, and a domain's threads that
outlive it crashed a secured process at exit (runtime/rapid_runtime/teardown.py). Prints one
JSON object: holder -> the names of this process's threads, other than the main one, left
after its close(). A granted `rapidgen cmd` runs beside them (refused_exit.peer()): its writers
are what the watcher opens readers for."""
from __future__ import annotations

import json
import os
import subprocess
import sys

from tests.secure.refused_exit import _other_threads, peer


class _NoFile:
    """The recorder's MCAP sink, writing nothing (no asset runs: nothing is sent)."""

    def channel(self, _channel) -> None:
        pass


def holders(b, domain: int) -> dict:
    """name -> a function making it and its readers (each the DDS side of a tool: spy and
    monitor's watcher, record's recorder, replay's replayer, cmd's commander)."""
    from rapid_runtime.commander import Commander

    from rapidgen.record.recorder import Recorder
    from rapidgen.record.replay import Plan, Replayer
    from rapidgen.spy.watch import Watcher
    partition = b.tables["ASSET"].get("partition", b.tables["ASSET"]["name"])

    def watcher():  # readers of the peer's writers (their topics hold the participant)
        w = Watcher(domain, [b])
        w.run_for(10, until=lambda w: len(w.streams) >= 1)
        assert w.streams, "the watcher saw no writer of the peer"
        return w

    def recorder():
        rec = Recorder(domain, [b], None, lambda _type: None, _NoFile(), {})
        rec.declared(b.qos, partition)
        return rec

    return {
        "spy Watcher": watcher,
        "record Recorder": recorder,
        "replay Replayer": lambda: Replayer(domain, b.type_class, Plan(0, 0, None, None, 1.0, None)),
        "cmd Commander": lambda: Commander(b.rapid, b.qos, b.tables["ASSET"]["name"], "RapidWorkbench", domain),
    }


def main() -> int:
    enclave, domain, asset = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    subprocess.run(["ip", "link", "set", "lo", "up"], check=True)
    from rapidgen.diagnostics import DiagnosticSink
    from rapidgen.live.bindings import load_bindings
    from rapidgen.live.dds import use_transport
    b = load_bindings(asset, DiagnosticSink(), prefix="closed_threads")
    assert b is not None, asset
    use_transport(b.transport_file("local"), keep_environment=False, enclave=enclave)
    other = peer(os.path.dirname(os.path.normpath(enclave)), str(domain), asset)
    kept, left = [], {}
    try:
        for name, make in holders(b, domain).items():
            holder = make()
            kept.append(holder)  # still referred to, as a cycle would
            holder.close()
            left[name] = _other_threads()
    finally:
        other.kill()
        other.wait()
    print(json.dumps(left), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
