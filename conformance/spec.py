"""The protocol specification's cases (runtime/spec/cases), replayed live: the rules every
runtime replays offline, judged on this asset from the wire (rapidgen/conform/replay.py
says which cases apply and what is compared)."""
from __future__ import annotations

from rapidgen.conform.model import RECOMMENDED, Blocked, Fail, Unsupported, check, expect
from rapidgen.conform.replay import Replay, applicable, cases_and_seeds, describe_skip, free_control, run_prefix


@check("SPEC-01", RECOMMENDED, "The protocol specification's cases hold live",
       "runtime/spec/cases (docs/testing.md): acks, QueueState, AccessControlState", needs=("CMD-01",))
def spec_cases(s):
    s.needs_commands()
    found = cases_and_seeds()
    if found is None:
        raise Unsupported("the protocol's cases are not here (runtime/spec in a rapidgen checkout)")
    cases, seed_tables = found
    # a rule a dedicated check judges and failed: its cases would fail with it, each after a
    # state wait (--timeout): deferred before replaying (access-state-unwritten took > 240 s)
    first = _failed_rule_checks(s)
    if first:
        raise Blocked(f"{', '.join(first)} did not pass")
    prefix = run_prefix()
    replayed: list[str] = []
    skipped: list[str] = []
    failed: list[str] = []
    for n, case in enumerate(cases):
        tables = seed_tables(case["asset"])
        why = applicable(case, tables, s.facts, lambda _cmd: s.allow_motion, s.secured_as)
        if why is None:
            sources = {st["src"] for st in case["steps"] if st["op"] == "send"} | {s.source}
            if not free_control(s, sources):
                why = "control is held by a source the case does not use"
        if why is not None:
            skipped.append(describe_skip(case, why))
            continue
        try:
            Replay(s, case, tables.name, f"{prefix}{n}-").run()
            replayed.append(case["name"])
        except Fail as f:
            failed.append(f"{f.expected}, seen {f.seen}")
        finally:
            free_control(s, sources)
    if not replayed and not failed:
        raise Unsupported(f"no case applies to this asset ({len(skipped)} cases; e.g. {skipped[0] if skipped else ''})")
    s.memo["spec"] = {"replayed": replayed, "skipped": skipped}
    if failed:
        # a rule a dedicated check judges and failed is that check's finding, not a second one here
        first = _failed_rule_checks(s)
        if first:
            raise Blocked(f"{', '.join(first)} did not pass; {len(failed)} case(s) fail with them")
    expect(not failed, f"every applicable case holds ({len(replayed) + len(failed)} replayed)", "; ".join(failed[:3]))
    return f"{len(replayed)} case(s) replayed, {len(skipped)} do not apply here"


def _failed_rule_checks(s) -> list[str]:
    """The command, queue and access-control checks that ran before and did not pass."""
    results = getattr(s, "results", {})
    return sorted(cid for cid, r in results.items() if cid.startswith(("CMD-", "QUE-", "ACC-"))
                  and r.outcome in ("FAIL", "ERROR", "BLOCKED"))
