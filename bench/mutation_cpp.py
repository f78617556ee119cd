"""Mutation testing of the C++ runtime's protocol logic: how much of runtime/cpp/src's
behaviour do the protocol specification's cases and a passing `rapidgen conform` run pin
down? (The Python runtime's campaign is bench/mutation.py; figures in bench/README.md.)

    python bench/mutation_cpp.py [--sample 200] [--seed 1] [--oracle spec|conform|both]
                                 [--domain 59] [--jobs 1] [--json out.json]
                                 [--mutant ID ...] [--where FILE[:FIRST-LAST|:FUNCTION]]

The operators are universalmutator's (PyPI, 1.14.1): its regular-expression rules for C++
(universal.rules, c_like.rules, cpp.rules: arithmetic, relational and logical operators
swapped, conditions negated or made constant, statements commented out or followed by
break/continue, numeric literals changed, min/max and begin/end swapped, ...) applied line
by line to FILES below; mutants that change only a string literal are left out by the tool.
A mutant is named FILE:LINE:K (the K-th mutant of that line, in the tool's order).

Not judged, counted apart: mutants of lines inside a log call (text no RAPID observer
reads) and of code compiled only into test builds (#ifdef RAPID_RUNTIME_TEST_BREAKS).
The rest are walked in a seeded random order until --sample of them have been judged; on
the way, a mutant that does not build (compile or link) is counted as invalid, and one whose object file is
byte for byte the original's is counted as equivalent (trivial compiler equivalence: the
compiler proved it). Both are left out of the score.

Everything is built in a temporary folder, never in runtime/cpp: a copy of runtime/cpp
(the mutated file is written there), K10's and Chariot's generated C++ packages, and three
CMake build folders (Release, -j --jobs, under nice): the runtime's core, the spec cases'
driver or the logic suite (tests/cpp_runtime, copied) and K10's generated bridge. Each mutant
recompiles its one file and relinks what the oracle runs; afterwards the file and its object
are put back. With --prebuilt (tests/cpp_runtime/test_mutation.py passes the pytest run's
build of tests/cpp_runtime) the seeds' tables and the cases' driver are linked from that build
instead of compiled again: no mutant changes them.

- spec: the cases of runtime/spec replayed by the C++ driver (`spec_cases`,
  tests/cpp_runtime/test_spec_cases.cpp alone), about a second a mutant besides its compile;
- conform: K10's generated C++ bridge (--simulate, its built-in loopback profile, a journal
  folder of its own) on the mutant, judged by `rapidgen conform specs/assets/k10.yaml
  --allow-motion` (the unmutated tools, cyclonedds on loopback); `both` runs conform only on
  what the cases let live;
- suite: the whole logic suite (the runtime's own unit tests besides the cases), no DDS:
  not a protocol oracle, a second look at survivors (`--mutant ID ... --oracle suite`).

A mutant is killed when its oracle fails, hangs past its bound, or the bridge does not
start or dies. The score is killed / judged with bench/mutation.py's 95% Wilson interval;
survivors are listed with the line they change. The unmutated runtime must pass every
oracle first (exit 1 otherwise).
"""
from __future__ import annotations

import argparse
import json
import os
import queue
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))
from mutation import conform_finding, stop_bridge, wilson  # noqa: E402  (shared with the Python campaign)

# The protocol logic of runtime/cpp/src: file -> the lines mutated (None: all). value.cpp only
# where it checks an argument's shape and limits (the rest formats values for texts).
FILES: dict[str, tuple[int, int] | None] = {
    "manager.cpp": None,      # intake, command window, acks, queue commands, access gate, shutdown
    "pending.cpp": None,      # the queue's order (insert, replace, pop)
    "validate.cpp": None,     # a command checked against the tables
    "value.cpp": (139, 173),  # shape_error, limit_error: ranges and allowed lists
    "access.cpp": None,       # access control
    "intake.cpp": None,       # the intake thread, per-writer limits
    "journal.cpp": None,      # the restart journal
}
RULES = ["universal.rules", "c_like.rules", "cpp.rules"]
PACKAGE = "rapid_k10red"
SPEC_TIMEOUT = 60.0  # (the cases run in about a second; one waits 10 s at most for what does not come)
CONFORM_TIMEOUT = 240.0
READY_TIMEOUT = 30.0
LOG_CALL = re.compile(r"\b(?:out_\.log|log_|log)\(")


@dataclass
class Mutant:
    id: str
    file: str
    line: int        # 1-based
    original: str
    mutated: str
    rule: str

    def change(self) -> str:
        added = " \\n ".join(ln.strip() for ln in self.mutated.strip().splitlines())  # (break/continue: a line more)
        return f"- {self.original.strip()} | + {added}"[:300]


# ---- the mutants ------------------------------------------------------------------------------

def make_mutants(src: Path) -> tuple[list[Mutant], list[Mutant], list[Mutant]]:
    """(judgeable, log-only, test-only) mutants of FILES in the runtime copy's src/."""
    import contextlib
    import io

    from universalmutator.mutator import mutants_regexp
    judge, logs, tests = [], [], []
    for name, span in FILES.items():
        lines = (src / name).read_text().splitlines(keepends=True)
        with contextlib.redirect_stdout(io.StringIO()):  # (the tool prints its progress)
            found = mutants_regexp(lines, ruleFiles=RULES, ignorePatterns=[], ignoreStringOnly=True)
        in_log, in_tests = _log_lines(lines), _test_only_lines(lines)
        per_line: dict[int, int] = {}
        for lineno, text, rule, _pattern in found:
            if span and not span[0] <= lineno <= span[1]:
                continue
            k = per_line[lineno] = per_line.get(lineno, 0) + 1
            original = lines[lineno - 1]
            m = Mutant(f"{name}:{lineno}:{k}", name, lineno, original, text, rule[0])
            if lineno in in_tests:
                tests.append(m)
            elif _log_only(in_log.get(lineno), original, text):
                logs.append(m)
            else:
                judge.append(m)
    return judge, logs, tests


def _log_lines(lines: list[str]) -> dict[int, int]:
    """Line -> the column where a log call starts on it (0 on a continuation line of one)."""
    out, depth = {}, 0
    for i, text in enumerate(lines, 1):
        if depth > 0:
            out[i] = 0
        else:
            m = LOG_CALL.search(text)
            if not m:
                continue
            out[i] = m.start()
            text = text[m.start():]
        depth = max(0, depth + text.count("(") - text.count(")"))
    return out


def _log_only(start: int | None, original: str, mutated: str) -> bool:
    """The mutant changes its line only at or after the start of a log call on it (and adds no
    statement after it: a break or continue there changes the flow)."""
    if start is None or "\n" in mutated.rstrip("\n"):
        return False
    same = len(os.path.commonprefix([original, mutated]))
    return same >= start


def _test_only_lines(lines: list[str]) -> set[int]:
    """Lines compiled only with RAPID_RUNTIME_TEST_BREAKS (the test bridge's breaks)."""
    out, inside = set(), False
    for i, text in enumerate(lines, 1):
        s = text.strip()
        if s.startswith("#ifdef RAPID_RUNTIME_TEST_BREAKS"):
            inside = True
        elif inside and s.startswith(("#else", "#endif")):
            inside = False
        elif inside:
            out.add(i)
    return out


# ---- the builds -------------------------------------------------------------------------------

class Builds:
    """The runtime copy and its three build folders in `work`."""

    def __init__(self, work: Path, jobs: int, prebuilt: str | None = None) -> None:
        self.work, self.jobs, self.prebuilt = work, jobs, prebuilt
        self.src = work / "runtime" / "src"
        self.runtime, self.tests, self.bridge = work / "build" / "runtime", work / "build" / "tests", work / "build" / "bridge"
        self.objects = self.runtime / "CMakeFiles" / "rapid_runtime_core.dir" / "src"
        self.saved: dict[str, tuple[str, bytes]] = {}

    def copy(self) -> None:
        """The runtime and the logic suite's sources, copied once: the shared checkout may
        change under a campaign (the mutants are made from this copy)."""
        shutil.copytree(ROOT / "runtime" / "cpp", self.work / "runtime",
                        ignore=shutil.ignore_patterns("build*", "__pycache__"))
        shutil.copytree(ROOT / "tests" / "cpp_runtime", self.work / "tests",
                        ignore=shutil.ignore_patterns("*.py", "__pycache__"))

    def setup(self, bridge: bool, suite: str = "spec") -> None:
        gen = self.work / "gen"
        for seed in ("k10", "chariot", "robonaut2"):  # the spec cases' seeds
            _run([sys.executable, "-m", "rapidgen", "generate", str(ROOT / "specs" / "assets" / f"{seed}.yaml"),
                  "--lang", "cpp", "-o", str(gen / seed)])
        from rapidgen.protocol_cases import load_cases
        self.cases = self.work / "cases.json"
        self.cases.write_text(json.dumps({"cases": load_cases()}, ensure_ascii=False), encoding="utf-8")
        release = ["-DCMAKE_BUILD_TYPE=Release"]
        _run(["cmake", "-S", str(self.work / "runtime"), "-B", str(self.runtime), *release])
        self.build(self.runtime)
        found = f"-Drapid_runtime_cpp_DIR={self.runtime}"
        _run(["cmake", "-S", str(self.work / "tests"), "-B", str(self.tests), *release, found,
              f"-DK10_BRIDGE_DIR={gen / 'k10' / 'cpp' / 'bridge'}",
              f"-DCHARIOT_BRIDGE_DIR={gen / 'chariot' / 'cpp' / 'bridge'}",
              f"-DR2_BRIDGE_DIR={gen / 'robonaut2' / 'cpp' / 'bridge'}",
              f"-DODDITY_BRIDGE_DIR={ROOT / 'generated' / 'spec-oddity' / 'cpp' / 'bridge'}",  # (committed)
              *([f"-DSPEC_PREBUILT={self.prebuilt}"] if self.prebuilt else [])])
        self.build(self.tests, _target(suite))
        if bridge:
            _run(["cmake", "-S", str(gen / "k10" / "cpp"), "-B", str(self.bridge), *release, found])
            self.build(self.bridge, f"{PACKAGE}_bridge")
        for name in FILES:  # the originals, put back after each mutant
            self.saved[name] = ((self.src / name).read_text(), (self.objects / f"{name}.o").read_bytes())

    def build(self, folder: Path, *targets: str) -> subprocess.CompletedProcess:
        extra = [a for t in targets for a in ("--target", t)]
        return _run(["nice", "-n", "19", "cmake", "--build", str(folder), "-j", str(self.jobs), *extra], check=False)

    def apply(self, m: Mutant) -> str:
        """Write the mutant and rebuild the core: 'ok', 'invalid' (no compile) or 'equivalent'
        (the same object code as the original)."""
        lines = self.saved[m.file][0].splitlines(keepends=True)
        assert lines[m.line - 1] == m.original, f"{m.id}: the line is not the one mutated"
        lines[m.line - 1] = m.mutated
        path, obj = self.src / m.file, self.objects / f"{m.file}.o"
        path.write_text("".join(lines))
        newer = obj.stat().st_mtime + 1  # (make compares times: the mutant is newer than its object)
        os.utime(path, (newer, newer))
        if self.build(self.runtime).returncode != 0:
            return "invalid"
        return "equivalent" if obj.read_bytes() == self.saved[m.file][1] else "ok"

    def restore(self, m: Mutant) -> None:
        """The original file (its old time) and object (a new time: the library is re-archived
        from it by the next build, nothing recompiled)."""
        path, obj = self.src / m.file, self.objects / f"{m.file}.o"
        text, code = self.saved[m.file]
        path.write_text(text)
        os.utime(path, (1_000_000_000, 1_000_000_000))
        obj.write_bytes(code)
        now = time.time()
        os.utime(obj, (now, now))


def _run(cmd: list[str], check: bool = True, timeout: float = 1800) -> subprocess.CompletedProcess:
    res = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=timeout)
    if check and res.returncode != 0:
        raise SystemExit(f"error: {' '.join(cmd)} failed:\n{res.stdout[-2000:]}\n{res.stderr[-3000:]}")
    return res


# ---- the oracles ------------------------------------------------------------------------------

class Unbuilt(Exception):
    """The mutant compiled and does not link (a definition commented out): not a program."""


def _target(suite: str) -> str:
    """The spec cases' driver alone (test_spec_cases.cpp and the seeds' tables), or the whole
    logic suite."""
    return "spec_cases" if suite == "spec" else "logic"


def spec_oracle(b: Builds, suite: str = "spec") -> tuple[bool, str]:
    """(killed, why): the cases replayed by their driver linked with the mutant (suite
    "spec"), or the logic suite, the runtime's own unit tests besides the cases ("suite")."""
    target = _target(suite)
    if b.build(b.tests, target).returncode != 0:
        raise Unbuilt(target)
    try:
        # (in the campaign's own folder: a mutant that builds a journal path wrongly writes there,
        # never in the checkout; one of seed 2's left K10Red/ in it)
        run = subprocess.run([str(b.tests / target), "--gtest_brief=1", "--gtest_fail_fast"], capture_output=True,
                             text=True, timeout=SPEC_TIMEOUT * (1 if suite == "spec" else 3), cwd=b.work,
                             env=dict(os.environ, RAPID_SPEC_CASES=str(b.cases)))
    except subprocess.TimeoutExpired:
        return True, f"{suite}: hung"
    if run.returncode == 0:
        return False, ""
    failed = re.findall(r"^\[  FAILED  \] (\S+.*?)(?:, where GetParam\(\) = (.*))?$", run.stdout, re.M)
    if failed:
        name, param = failed[0]
        return True, f"{suite}: " + (param or name)[:200]
    tail = (run.stdout + run.stderr).strip().splitlines()
    return True, f"{suite}: exit {run.returncode} " + (tail[-1][:150] if tail else "")


def conform_oracle(b: Builds, domain: int) -> tuple[bool, str]:
    """(killed, why): K10's C++ bridge on the mutant, judged by rapidgen conform."""
    if b.build(b.bridge, f"{PACKAGE}_bridge").returncode != 0:
        raise Unbuilt("bridge")
    state = Path(tempfile.mkdtemp(prefix="rapid-cpp-mutant-"))
    env = {k: v for k, v in os.environ.items() if not k.startswith(("FASTDDS_", "FASTRTPS_"))}  # (its rapid_local)
    bridge = subprocess.Popen([str(b.bridge / f"{PACKAGE}_bridge"), "--simulate", "--sim-speed", "20", "--domain",
                               str(domain), "--journal", str(state / "journal"), "--seconds", "600"],
                              cwd=state, env=env, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    try:
        lines: queue.Queue = queue.Queue()
        threading.Thread(target=lambda: [lines.put(ln) for ln in bridge.stdout], daemon=True).start()  # type: ignore[union-attr]
        try:
            first = lines.get(timeout=READY_TIMEOUT)
        except queue.Empty:
            first = ""
        if not first.startswith("bridge ready"):
            return True, "conform: the bridge did not start"
        pydir = ROOT / "generated" / "k10" / "python"
        tools = dict(os.environ, PYTHONDONTWRITEBYTECODE="1",
                     CYCLONEDDS_URI=f"file://{pydir / PACKAGE / 'qos_files' / 'cyclonedds' / 'local.xml'}")
        report = state / "report.json"
        with open(state / "conform.out", "w") as sink:
            runner = subprocess.Popen([sys.executable, "-m", "rapidgen", "conform", "specs/assets/k10.yaml", "--domain",
                                       str(domain), "--json", str(report), "--allow-motion"], cwd=ROOT, env=tools,
                                      stdout=sink, stderr=subprocess.DEVNULL)
        try:
            deadline = time.monotonic() + CONFORM_TIMEOUT
            while runner.poll() is None:  # (a bridge that dies ends the run: its checks would only wait)
                if bridge.poll() is not None:
                    return True, f"conform: the bridge died (exit {bridge.returncode})"
                if time.monotonic() > deadline:
                    return True, "conform: hung"
                time.sleep(0.2)
        finally:
            if runner.poll() is None:
                runner.kill()
            runner.wait()
        out = (state / "conform.out").read_text(errors="replace")
        if bridge.poll() is not None:
            return True, f"conform: the bridge died (exit {bridge.returncode})"
        if runner.returncode == 0:
            return False, ""
        return True, conform_finding(report, out, runner.returncode)
    finally:
        stop_bridge(bridge, state)


def judge(b: Builds, oracle: str, domain: int) -> tuple[bool, str]:
    if oracle == "suite":
        return spec_oracle(b, "suite")
    if oracle in ("spec", "both"):
        killed, why = spec_oracle(b)
        if killed or oracle == "spec":
            return killed, why
    return conform_oracle(b, domain)


# ---- the campaign -----------------------------------------------------------------------------

def _pool(mutants: list[Mutant], where: str | None, src: Path) -> list[Mutant]:
    """The mutants of FILE, of its lines FIRST-LAST, or of its function(s) NAME."""
    if not where:
        return mutants
    name, _, span = where.partition(":")
    if span and not span[0].isdigit():
        lines = _function_lines((src / name).read_text().splitlines(), span)
    else:
        first, _, last = span.partition("-")
        lo, hi = (int(first), int(last or first)) if first else (1, 10 ** 9)
        lines = set(range(lo, hi + 1))
    return [m for m in mutants if m.file == name and m.line in lines]


def _function_lines(lines: list[str], function: str) -> set[int]:
    """The lines of every definition of `function` (its head at column 0, up to the first
    closing brace at column 0)."""
    out: set[int] = set()
    head = re.compile(rf"^\S.*\b{re.escape(function)}\(")
    inside = False
    for i, text in enumerate(lines, 1):
        if not inside and head.match(text) and not text.rstrip().endswith(";"):
            inside = True
        if inside:
            out.add(i)
            if text.startswith("}"):
                inside = False
    return out


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--sample", type=int, default=200, help="mutants judged (walking a seeded order of all)")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--oracle", choices=("spec", "conform", "both", "suite"), default="both",
                   help="suite: the whole logic suite (the runtime's unit tests and the cases), to review survivors")
    p.add_argument("--domain", type=int, default=59, help="DDS domain of the conform oracle (loopback only, < 102)")
    p.add_argument("--jobs", type=int, default=1, help="build jobs (the campaign's builds run under nice)")
    p.add_argument("--mutant", action="append", default=[], help="judge these mutants (FILE:LINE:K) only")
    p.add_argument("--where", help="sample the mutants of FILE, of its lines FIRST-LAST (pending.cpp:17-29) or of a function "
                   "(pending.cpp:insert_after)")
    p.add_argument("--json", help="write every verdict here")
    p.add_argument("--prebuilt", metavar="DIR", help="a build of tests/cpp_runtime (its logic target built) whose "
                   "tables and cases' driver are linked instead of compiled")
    args = p.parse_args(argv)
    if args.where and args.where.partition(":")[0] not in FILES:
        print(f"error: --where {args.where}: not one of {', '.join(FILES)}", file=sys.stderr)
        return 2

    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))  # (the finally clauses: the bridge stopped, work/ gone)
    work = Path(tempfile.mkdtemp(prefix="rapid-cpp-mutants-"))
    try:
        t0 = time.monotonic()
        b = Builds(work, args.jobs, args.prebuilt)
        b.copy()
        wire, logs, tests = make_mutants(b.src)
        by_id = {m.id: m for m in [*wire, *logs, *tests]}
        unknown = [i for i in args.mutant if i not in by_id]
        if unknown:
            print(f"error: unknown mutant(s): {', '.join(unknown)}", file=sys.stderr)
            return 2
        if args.mutant:
            order = [by_id[i] for i in args.mutant]
        else:
            order = _pool(wire, args.where, b.src)
            random.Random(args.seed).shuffle(order)
        if not order:
            print("error: no mutant to judge", file=sys.stderr)
            return 2
        print(f"{len(by_id)} mutants (universalmutator {_version()}) of runtime/cpp/src/{{{','.join(FILES)}}}; "
              f"{len(logs)} lie in a log call and {len(tests)} in test-only code (not judged); "
              f"judging {min(args.sample, len(order)) if not args.mutant else len(order)} of the other "
              f"{len(order) if not args.mutant else len(wire)} with the {args.oracle} oracle", flush=True)
        b.setup(bridge=args.oracle not in ("spec", "suite"), suite="suite" if args.oracle == "suite" else "spec")
        print(f"built in {time.monotonic() - t0:.0f} s", flush=True)
        baseline, why = judge(b, args.oracle, args.domain)
        if baseline:
            print(f"error: the unmutated runtime fails its oracle: {why}", file=sys.stderr)
            return 1
        want = len(order) if args.mutant else args.sample
        verdicts, invalid, equivalent = [], [], []
        for m in order:
            if len(verdicts) >= want:
                break
            start = time.monotonic()
            try:
                built = b.apply(m)
                if built == "ok":
                    killed, why = judge(b, args.oracle, args.domain)
            except Unbuilt:
                built = "invalid"
            finally:
                b.restore(m)
            if built != "ok":
                (invalid if built == "invalid" else equivalent).append(m.id)
                print(f"    {built}: {m.id}", flush=True)
                continue
            verdicts.append({"mutant": m.id, "file": m.file, "line": m.line, "killed": killed, "by": why,
                             "change": m.change(), "rule": m.rule, "seconds": round(time.monotonic() - start, 1)})
            print(f"[{len(verdicts)}/{want}] {'killed  ' if killed else 'SURVIVED'} {m.id}  {why or m.change()}  ({time.monotonic() - start:.0f} s)",
                  flush=True)
        dead = sum(bool(v["killed"]) for v in verdicts)
        lo, hi = wilson(dead, len(verdicts))
        drawn = len(verdicts) + len(invalid) + len(equivalent)
        print(f"\ndrawn {drawn}: {len(invalid)} did not build, {len(equivalent)} compiled to the original's object "
              f"code (equivalent), {len(verdicts)} judged")
        print(f"score: {dead}/{len(verdicts)} killed = {100 * dead / max(1, len(verdicts)):.1f}% "
              f"(95% CI {100 * lo:.1f}-{100 * hi:.1f}%), {time.monotonic() - t0:.0f} s")
        for v in verdicts:
            if not v["killed"]:
                print(f"  survivor {v['mutant']}: {v['change']}")
        if args.json:
            Path(args.json).write_text(json.dumps(
                {"oracle": args.oracle, "seed": args.seed, "total": len(by_id), "log_only": len(logs),
                 "test_only": len(tests), "drawn": drawn, "invalid": invalid, "equivalent": equivalent,
                 "killed": dead, "judged": len(verdicts), "ci95": [lo, hi], "verdicts": verdicts}, indent=1) + "\n")
        return 0
    finally:
        shutil.rmtree(work, ignore_errors=True)


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version("universalmutator")
    except PackageNotFoundError:
        return "?"


if __name__ == "__main__":
    sys.exit(main())
