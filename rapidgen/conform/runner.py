"""Run the selected checks in order (checks marked late last, they judge the whole run),
skip those whose needs did not pass (BLOCKED) or do not apply (UNSUPPORTED), report
each as it ends."""
from __future__ import annotations

import time
import traceback

from rapidgen.conform.model import (BLOCKED, ERROR, FAIL, PASS, REQUIRED, UNSUPPORTED, Blocked, Check, Fail,
                                    Result, Unsupported)


def select(checks: dict[str, Check], only: list[str], skip: list[str]) -> tuple[list[Check], list[str]]:
    """(checks to run, unknown ids). An id may be a prefix ending in '-' or '*': CMD-, CMD*."""
    def matches(pattern: str, cid: str) -> bool:
        p = pattern.upper()
        return cid == p or (p.endswith(("-", "*")) and cid.startswith(p.rstrip("*")))
    unknown = [p for p in only + skip if not any(matches(p, c) for c in checks)]
    chosen = [c for cid, c in checks.items()
              if (not only or any(matches(p, cid) for p in only)) and not any(matches(p, cid) for p in skip)]
    return chosen, unknown


def run_checks(session, checks: list[Check], on_result=None) -> list[Result]:
    ordered = sorted(checks, key=lambda c: c.late)
    results: dict[str, Result] = {}
    if session is not None:
        session.results = results  # what ran so far (SPEC-01 defers to the check of a rule that failed)
    begin = getattr(session, "begin", None)  # the session names each command with the check that sent it
    for c in ordered:
        blockers = [n for n in c.needs if n in results and results[n].outcome not in (PASS, UNSUPPORTED)]
        moot = [n for n in c.needs if n in results and results[n].outcome == UNSUPPORTED]
        start = time.monotonic()
        if moot and not blockers:
            res = Result(c, UNSUPPORTED, f"does not apply: {', '.join(moot)} does not")
        elif blockers:
            res = Result(c, BLOCKED, f"not judged: {', '.join(blockers)} did not pass")
        else:
            try:
                if begin is not None:
                    begin(c.id)
                note = c.run(session)
                res = Result(c, PASS, note or "")
            except Fail as f:
                res = Result(c, FAIL, str(f), f.expected, f.seen)
            except Unsupported as u:
                res = Result(c, UNSUPPORTED, str(u))
            except Blocked as b:
                res = Result(c, BLOCKED, f"not judged: {b}")
            except Exception as exc:  # a check's own bug, or DDS refusing something: reported, run goes on
                where = traceback.extract_tb(exc.__traceback__)[-1]
                res = Result(c, ERROR, f"{type(exc).__name__}: {exc} ({where.filename.rsplit('/', 1)[-1]}:{where.lineno})")
        res.seconds = time.monotonic() - start
        results[c.id] = res
        if on_result is not None:
            on_result(res)
    return [results[c.id] for c in ordered]


def passed(results: list[Result]) -> bool:
    """Every required check passed or does not apply."""
    return all(r.outcome in (PASS, UNSUPPORTED) for r in results if r.check.level == REQUIRED)


__all__ = ["BLOCKED", "ERROR", "FAIL", "PASS", "UNSUPPORTED", "passed", "run_checks", "select"]
