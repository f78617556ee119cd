"""Where the suite's CPU goes: a pytest plugin that appends, per test, the CPU seconds of the
test's process and of the children it waited for (compilers under cmake, bridges, conform
runs), when it started and on which xdist worker; a summary by file, and each worker's idle
time (between its tests, and after its last one until the run's end). docs/testing.md, "Where CI time goes", has a run's figures.

    PYTHONPATH=bench CPU_BY_TEST=/tmp/cpu.jsonl bash scripts/test -p cpu_by_test
    python bench/cpu_by_test.py /tmp/cpu.jsonl [TOP]
    python bench/cpu_by_test.py /tmp/cpu.jsonl --durations > tests/durations.json

--durations writes the wall seconds of each unit the xdist workers take (a file; tests/rust
as one) that took 10 s or more: the order scripts/test hands them out in (tests/conftest.py).

A shared build is counted in the first test that asks for it (its setup)."""
from __future__ import annotations

import collections
import json
import os
import resource
import sys
import time

import pytest


def _cpu() -> float:
    own, children = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item, nextitem):
    start, t0, c0 = time.time(), time.monotonic(), _cpu()
    yield
    with open(os.environ.get("CPU_BY_TEST", "cpu_by_test.jsonl"), "a", encoding="utf-8") as f:
        f.write(json.dumps({"id": item.nodeid, "cpu": round(_cpu() - c0, 2), "wall": round(time.monotonic() - t0, 2),
                            "start": round(start, 2), "worker": os.environ.get("PYTEST_XDIST_WORKER", "")}) + "\n")


def durations(rows: list[dict], source: str) -> str:
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    from tests.conftest import _xdist_scope
    by_scope: collections.Counter[str] = collections.Counter()
    for r in rows:
        by_scope[_xdist_scope(r["id"])] += r["wall"]
    return json.dumps({"about": f"wall seconds per unit of xdist work (tests/conftest.py: _xdist_scope) in {source}; "
                                "refresh: python bench/cpu_by_test.py RUN.jsonl --durations",
                       "seconds": {k: round(v) for k, v in by_scope.most_common() if v >= 10}}, indent=1)


def main() -> int:
    rows = [json.loads(line) for line in open(sys.argv[1], encoding="utf-8")]
    if "--durations" in sys.argv[2:]:
        print(durations(rows, f"the profiled run {os.path.basename(sys.argv[1])}"))
        return 0
    top = int(sys.argv[2]) if len(sys.argv) > 2 else 20
    by_file: collections.Counter[str] = collections.Counter()
    for r in rows:
        by_file[r["id"].split("::")[0]] += r["cpu"]
    print(f"{len(rows)} tests, {sum(r['cpu'] for r in rows) / 60:.1f} CPU-minutes")
    for name, cpu in by_file.most_common(top):
        print(f"{cpu:8.1f} s  {name}")
    timed = [r for r in rows if "start" in r]
    if timed:
        first, last = min(r["start"] for r in timed), max(r["start"] + r["wall"] for r in timed)
        print(f"{last - first:.0f} s from the first test's start to the last one's end")
        for worker in sorted({r["worker"] for r in timed}):
            mine = sorted((r for r in timed if r["worker"] == worker), key=lambda r: r["start"])
            busy = sum(r["wall"] for r in mine)
            end = mine[-1]["start"] + mine[-1]["wall"]
            print(f"  worker {worker or '-'}: busy {busy:.0f} s, idle {end - first - busy:.0f} s between tests, "
                  f"done {last - end:.0f} s before the end (last: {mine[-1]['id']})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
