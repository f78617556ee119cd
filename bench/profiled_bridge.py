"""K10's Python bridge with timestamps at each stage of a command's path, for
bench/command_latency.py --profile (a bench tool: the runtime itself carries no probes).

    python bench/profiled_bridge.py OUT.json [--cprofile] -- <rapid_k10red.bridge arguments>

Wraps, in this process only, the functions a command passes through and records
perf_counter_ns() at each; on exit writes every command's stamps to OUT.json:

  sent      the client's write (the sample's source timestamp; the same machine's clock)
  take0/1   the command reader's take() called / returned (raw take and decode, a batch)
  offered   the intake door's offer() called (the sample made a Cmd)
  recv0/1   the manager's receive() entered / returned on the intake thread (checks,
            access, the builtin noOp, journal records written, acks held for the sync)
  sync0/1   the journal's fdatasync (Journal.sync) around the batch's flush
  ack0/1    each ack's write (Bridge.ack: Ack made, DDS write), EXECUTING then COMPLETED

--cprofile also runs every thread under cProfile and writes OUT.json's "cprofile": the
functions by their own time, summed over threads.
"""
from __future__ import annotations

import json
import sys
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PYDIR = ROOT / "generated" / "k10" / "python"
sys.path[:0] = [str(PYDIR), str(ROOT / "runtime")]

ns = time.perf_counter_ns
stamps: dict[str, dict[str, int]] = {}  # cmdId -> stage -> perf_counter_ns
syncs: list[tuple[int, int]] = []  # (sync0, sync1)
OFFSET = time.time_ns() - ns()  # perf_counter_ns + OFFSET ~ the wall clock (source timestamps)


def _put(cmd_id: str, stage: str, t: int) -> None:
    stamps.setdefault(cmd_id, {}).setdefault(stage, t)


def instrument() -> None:
    from rapid_runtime import bridge, intake, journal, manager, untrusted

    take = untrusted.GuardedReader.take

    def timed_take(self, n=None):
        t0 = ns()
        out = take(self, n)
        t1 = ns()
        for s in out:
            cid = getattr(s, "cmdId", None)
            if cid is not None and hasattr(s, "cmdSrc"):  # commands only
                _put(cid, "take0", t0)
                _put(cid, "take1", t1)
                _put(cid, "sent", s.sample_info.source_timestamp - OFFSET)
        return out
    untrusted.GuardedReader.take = timed_take

    offer = intake.Intake.offer

    def timed_offer(self, cmd, *a, **kw):
        _put(cmd.cmd_id, "offered", ns())
        return offer(self, cmd, *a, **kw)
    intake.Intake.offer = timed_offer

    receive = manager.CommandManager.receive

    def timed_receive(self, cmd):
        _put(cmd.cmd_id, "recv0", ns())
        try:
            return receive(self, cmd)
        finally:
            _put(cmd.cmd_id, "recv1", ns())
    manager.CommandManager.receive = timed_receive

    sync = journal.Journal.sync

    def timed_sync(self):
        t0 = ns()
        try:
            return sync(self)
        finally:
            syncs.append((t0, ns()))
    journal.Journal.sync = timed_sync

    ack = bridge.Bridge.ack

    def timed_ack(self, cmd, status, completed, message):
        tag = "x" if status.endswith("EXECUTING") else "c" if status.endswith("COMPLETED") else status
        _put(cmd.cmd_id, f"ack0{tag}", ns())
        try:
            return ack(self, cmd, status, completed, message)
        finally:
            _put(cmd.cmd_id, f"ack1{tag}", ns())
    bridge.Bridge.ack = timed_ack


def profile_threads(profiles: list) -> None:
    import cProfile
    run = threading.Thread.run

    def profiled(self):
        prof = cProfile.Profile()
        profiles.append(prof)
        prof.enable()
        try:
            run(self)
        finally:
            prof.disable()
    threading.Thread.run = profiled


def main() -> int:
    out = Path(sys.argv[1])
    rest = sys.argv[2:]
    use_cprofile = "--cprofile" in rest[:1]
    if use_cprofile:
        rest = rest[1:]
    if rest[:1] == ["--"]:
        rest = rest[1:]
    instrument()
    profiles: list = []
    if use_cprofile:
        profile_threads(profiles)
    from rapid_runtime.bridge import main as bridge_main
    from rapid_k10red import asset_tables, rapid
    from rapid_k10red.handlers import Handlers
    try:
        return bridge_main(asset_tables, rapid, Handlers, package="rapid_k10red", argv=rest)
    finally:
        doc = {"stamps": stamps, "syncs": syncs}
        if profiles:
            import io
            import pstats
            for p in profiles:
                p.disable()
            st = pstats.Stats(profiles[0], stream=io.StringIO())
            for p in profiles[1:]:
                st.add(p)
            rows = sorted(((v[2], v[3], v[1], f"{k[0].rsplit('/', 2)[-1]}:{k[1]}({k[2]})") for k, v in st.stats.items()),
                          reverse=True)[:40]  # (own time, cumulative, calls, where)
            doc["cprofile"] = rows
        out.write_text(json.dumps(doc))


if __name__ == "__main__":
    sys.exit(main())
