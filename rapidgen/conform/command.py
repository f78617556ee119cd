"""`rapidgen conform ASSET.yaml`: load the asset's bindings, find it over DDS, run the
suite, print progress and the table, write JUnit/JSON. Exit 0 only when every required
check passes (or does not apply); 1 when one does not, or the asset is not found or its
descriptor has errors; 2 usage."""
from __future__ import annotations

import os
import sys
import time
from rapidgen.argtypes import domain_id
from rapidgen.live.dds import add_enclave_argument, security_refusal
from rapidgen.cmd.timing import round_trip
from rapidgen.textsafe import visible


def add_parser(sub) -> None:
    p = sub.add_parser("conform", help="check a live asset against the RAPID protocol (needs cyclonedds)")
    p.add_argument("file", metavar="ASSET.yaml")
    p.add_argument("--domain", type=domain_id, default=None, metavar="N", help="DDS domain (default: the descriptor's)")
    p.add_argument("--transport", choices=("local", "lan", "wan"), default=None,
                   help="Cyclone transport from the generated QoS files (default: CYCLONEDDS_URI if set, else local)")
    add_enclave_argument(p)
    p.add_argument("--only", action="append", default=[], metavar="IDS",
                   help="run only these checks (comma-separated ids or prefixes: CMD-,DDS-01)")
    p.add_argument("--skip", action="append", default=[], metavar="IDS", help="leave these checks out")
    p.add_argument("--junit", metavar="FILE", help="write a JUnit XML report")
    p.add_argument("--json", metavar="FILE", help="write a JSON report")
    p.add_argument("--timeout", type=float, default=10.0, metavar="S",
                   help="seconds to wait for an asset's answer (default 10)")
    p.add_argument("--rtt", type=round_trip, default=0.0, metavar="SECONDS",
                   help="the link's round trip (e.g. 2.6 for the Moon): every wait allows for it, so a check "
                        "judges the asset, not the delay (default 0: a LAN)")
    p.add_argument("--participant", action="append", default=[], type=_guid_prefix, metavar="GUID",
                   help="judge the participant(s) whose GUID starts with this (hex, 8 digits or more; default: the "
                        "participant with the most of the asset's endpoints in its partition)")
    p.add_argument("--allow-motion", action="store_true",
                   help="let the checks that need a long drive (QUE-02's second half, QUE-04) send one: "
                        "Mobility/simpleMove or move 1000 m ahead, cancelled within seconds; without it (and without "
                        "the descriptor's conformance section) nothing that moves the asset is sent")
    p.add_argument("--list", action="store_true", help="list the checks and exit")


def _guid_prefix(text: str) -> str:
    import argparse
    digits = "".join(ch for ch in text.lower() if ch not in "-:.")
    if len(digits) < 8 or any(ch not in "0123456789abcdef" for ch in digits):
        raise argparse.ArgumentTypeError(f"not a GUID prefix (8 or more hex digits): {text!r}")
    return digits


def _ids(values: list[str]) -> list[str]:
    return [v.strip() for item in values for v in item.split(",") if v.strip()]


def run_conform(args, sink, report) -> int:
    from rapidgen.conform.model import all_checks
    from rapidgen.conform.runner import select

    checks = all_checks()
    if args.list:
        for c in checks.values():
            print(f"{c.id:<7} {c.level:<11} {c.title}  [{c.rule}]")
        return 0
    chosen, unknown = select(checks, _ids(args.only), _ids(args.skip))
    if unknown:
        print(f"rapidgen conform: unknown check id(s): {', '.join(unknown)} (see --list)", file=sys.stderr)
        return 2
    from rapidgen.live.dds import dds_missing, use_transport
    if dds_missing("conform"):
        return 1
    from rapidgen.live.bindings import load_bindings

    bindings = load_bindings(args.file, sink, prefix="rapidconform")
    if bindings is None:
        report(sink)
        return 1
    use_transport(bindings.transport_file(args.transport or "local"), keep_environment=args.transport is None,
                  enclave=args.enclave)
    return _run(args, bindings, chosen, _motion(args.file))


def _motion(descriptor: str) -> dict[str, list]:
    """The descriptor's conformance.motion: "Subsystem/command" -> the arguments the runner may
    send (checked when the bindings were generated: their errors stopped the run there)."""
    from rapidgen.asset.load import load_asset
    from rapidgen.diagnostics import DiagnosticSink

    loaded = load_asset(descriptor, DiagnosticSink())
    section = loaded.conformance if loaded is not None else None
    return dict(section["motion"]) if section else {}


def _motion_line(motion: dict[str, list], allow: bool) -> str:
    if motion:
        listed = "; ".join(f"{k}({', '.join(repr(v) for _t, v in a)})" for k, a in motion.items())
        return f"motion: only {listed} (the descriptor's conformance section)" + \
            ("; other motion commands with --allow-motion's arguments" if allow else "")
    if allow:
        return "motion: allowed (--allow-motion): a long drive QUE-02 and QUE-04 cancel within seconds"
    return ("motion: none (no conformance section, no --allow-motion): the checks that would move the asset are "
            "UNSUPPORTED")


def _run(args, bindings, chosen, motion: dict[str, list] | None = None) -> int:
    from rapidgen.conform.session import Session

    domain = bindings.tables["ASSET"].get("domain", 0) if args.domain is None else args.domain
    t0 = time.monotonic()
    allow = bool(getattr(args, "allow_motion", False))
    try:
        session = Session(bindings, domain, timeout=args.timeout, participants=tuple(args.participant),
                          rtt=args.rtt, motion=motion, allow_motion=allow,
                          secured_as=os.path.basename(os.path.normpath(args.enclave)) if args.enclave else None)
    except Exception as exc:  # cyclonedds' DDSException: what DDS Security refused, said plainly
        refused = security_refusal("conform", "runner", args.enclave, exc,
                                   "it writes the asset's commands and reads all its topics", "command and audit")
        if refused is None:
            raise
        print(refused, file=sys.stderr)
        return 1
    try:
        return _judge(args, session, domain, chosen, allow, t0)
    finally:  # our participant deleted before the interpreter ends (rapidgen/live/teardown.py)
        session.delete()


def _judge(args, session, domain: int, chosen, allow: bool, t0: float) -> int:
    from rapidgen.conform import report as R
    from rapidgen.conform.runner import passed, run_checks

    name, partition = visible(session.asset), visible(session.facts.partition)
    print(f"rapidgen conform: looking for asset {name} (partition {partition}) in domain {domain} "
          f"via {visible(os.environ.get('CYCLONEDDS_URI', 'Cyclone defaults'))}"
          + (f", waits allowing for a {args.rtt:g} s round trip" if args.rtt else ""), flush=True)
    if not session.find_asset(min(15.0, 1.5 * args.timeout)):
        if args.participant:
            print(f"rapidgen conform: no participant with {name}'s topics in partition {partition} on domain "
                  f"{domain} has a GUID starting with {', '.join(args.participant)}", file=sys.stderr)
        else:
            print(f"rapidgen conform: no participant with {name}'s topics in partition {partition} "
                  f"on domain {domain} (is the asset running, on this domain and transport?)", file=sys.stderr)
        return 1
    print(f"found {name}: {len(session.endpoints())} endpoints of participant "
          f"{', '.join(map(session.participant_text, sorted(session.asset_participants)))}; "
          f"running {len(chosen)} checks", flush=True)
    if session.facts.has_type("Mobility"):
        print(visible(_motion_line(session.motion, allow)), flush=True)
    session.note_controller()
    total = len(chosen)
    counter = iter(range(1, total + 1))
    results = run_checks(session, chosen, lambda r: print(R.progress_line(r, next(counter), total), flush=True))
    try:
        session.hand_back()
    except Exception as exc:  # DDS refusing something at the end: the report is written all the same
        session.control = f"control: not handed back ({type(exc).__name__}: {exc})"
    seconds = time.monotonic() - t0
    session.close()
    notes = session.notes()
    ok = passed(results)
    print()
    print(R.table(results, name, seconds), flush=True)
    text = R.notes_text(notes)
    if text:
        print(text, flush=True)
    if args.junit:
        with open(args.junit, "wb") as fh:
            fh.write(R.junit(results, name, seconds, notes))
    if args.json:
        with open(args.json, "w", encoding="utf-8") as fh:
            fh.write(R.as_json(results, name, seconds, ok, domain, notes))
    return 0 if ok else 1
