"""Mutation testing of the Python runtime's protocol modules: how much of its behaviour do
the protocol specification's cases and a passing `rapidgen conform` run pin down?

    python bench/mutation.py [--sample 200] [--seed 1] [--oracle spec|conform|both]
                             [--domain 9] [--json out.json] [--mutant NAME ...] [--function NAME]

mutmut (3.x) writes every mutant of runtime/rapid_runtime/{manager,validate,access,cmdqueue,
acks}.py into a copy of the runtime, each behind mutmut's trampoline (MUTANT_UNDER_TEST
picks one at run time). A sample of them is judged by the oracles:

- spec: the cases of runtime/spec replayed by the Python driver (tests/runtime/
  test_spec_cases.py), with the mutant's runtime first on PYTHONPATH;
- conform: K10's generated Python bridge (simulated) run on the mutant's runtime on a
  loopback-only domain, and `rapidgen conform specs/assets/k10.yaml` (on the unmutated tools)
  against it. `both` runs conform only on what the cases let live.

A mutant is killed when its oracle fails (or hangs past its bound). The score is
killed / judged with a 95% Wilson interval; survivors are listed with the line they change
(review them: an equivalent mutant, one no observer could tell from the original, is listed
in bench/README.md with the reason). The unmutated runtime must pass every oracle first.
"""
from __future__ import annotations

import argparse
import difflib
import json
import math
import os
import random
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MODULES = ("manager", "validate", "access", "cmdqueue", "acks")
SPEC_TIMEOUT = 120.0
CONFORM_TIMEOUT = 240.0
PACKAGE = "rapid_k10red"


def mutate(work: Path) -> dict[str, tuple[str, str, bool]]:
    """Copy the runtime into work/ and write every module's mutants; returns
    {MUTANT_UNDER_TEST name: (module, the changed lines, log-only)}."""
    shutil.copytree(ROOT / "runtime" / "rapid_runtime", work / "rapid_runtime",
                    ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    (work / "setup.cfg").write_text("[mutmut]\nsource_paths=rapid_runtime\n")
    here = os.getcwd()
    os.chdir(work)  # mutmut reads its configuration from the working folder
    try:
        from mutmut.mutation.file_mutation import mutate_file_contents
        mutants: dict[str, tuple[str, str, bool]] = {}
        for name in MODULES:
            path = Path("rapid_runtime") / f"{name}.py"
            source = path.read_text()
            mutated = mutate_file_contents(str(path), source)
            path.write_text(mutated.code)
            functions = _functions(mutated.code)
            for m in mutated.mutant_names:
                mutants[f"rapid_runtime.{name}.{m}"] = (name, *_change(functions, m))
        return mutants
    finally:
        os.chdir(here)


def _functions(code: str) -> dict[str, str]:
    """Function name -> its source, from a mutated module (mutants and their originals)."""
    import ast
    tree = ast.parse(code)
    lines = code.splitlines()
    out = {}
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            out[node.name] = "\n".join(lines[node.lineno - 1:node.end_lineno])
    return out


def _change(functions: dict[str, str], mutant: str) -> tuple[str, bool]:
    """(the lines a mutant changes, - original | + mutant; whether every changed line lies in
    a log call or a thread's name: text no RAPID observer reads, reported apart)."""
    orig = functions.get(mutant.rsplit("__mutmut_", 1)[0] + "__mutmut_orig", "")
    new = functions.get(mutant, "")
    a, b = orig.splitlines()[1:], new.splitlines()[1:]
    changed = [i + 2 for tag, i1, i2, _j1, _j2 in difflib.SequenceMatcher(a=a, b=b).get_opcodes() if tag != "equal"
               for i in range(i1, max(i2, i1 + 1))]
    diff = [d for d in difflib.unified_diff(a, b, lineterm="", n=0) if d[:1] in "+-" and not d.startswith(("+++", "---"))]
    return " | ".join(d.strip() for d in diff)[:300], bool(changed) and all(_in_log(orig, ln) for ln in changed)


def _in_log(source: str, line: int) -> bool:
    """Line `line` of a function's source lies in a call of *log*(...) or a name= argument."""
    import ast
    import textwrap
    try:
        tree = ast.parse(textwrap.dedent(source))
    except SyntaxError:
        return False
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and node.lineno <= line <= (node.end_lineno or node.lineno):
            f = node.func
            name = f.attr if isinstance(f, ast.Attribute) else f.id if isinstance(f, ast.Name) else ""
            if "log" in name.lower():
                return True
            if any(k.arg == "name" and k.value.lineno <= line <= (k.value.end_lineno or k.value.lineno)
                   for k in node.keywords):
                return True
    return False


def _env(work: Path, mutant: str, extra_path: str = "") -> dict:
    env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1", MUTANT_UNDER_TEST=mutant,
               PYTHONPATH=os.pathsep.join(p for p in (str(work), extra_path, str(ROOT)) if p))
    return env


def spec_oracle(work: Path, mutant: str) -> tuple[bool, str]:
    """(killed, why): the cases replayed on the mutant's runtime."""
    env = _env(work, mutant)
    env["RAPID_SPEC_WAIT"] = "5"  # a case waits this long for what does not come (a loaded machine needs seconds)
    try:
        # (in the campaign's folder: a mutant that builds a path wrongly writes there, not in the checkout)
        res = subprocess.run([sys.executable, "-m", "pytest", str(ROOT / "tests/runtime/test_spec_cases.py"), "-x", "-q",
                              "--rootdir", str(ROOT), "-p", "no:cacheprovider", "-p", "no:randomly"], cwd=work, env=env,
                             capture_output=True, text=True, timeout=SPEC_TIMEOUT)
    except subprocess.TimeoutExpired:
        return True, "spec: hung"
    if res.returncode == 0:
        return False, ""
    failed = [ln for ln in res.stdout.splitlines() if ln.startswith("FAILED") or ln.startswith("ERROR")]
    return True, "spec: " + (failed[0][:200] if failed else res.stdout.strip().splitlines()[-1][:200])


def conform_oracle(work: Path, mutant: str, domain: int) -> tuple[bool, str]:
    """(killed, why): K10's bridge on the mutant's runtime, judged by rapidgen conform."""
    pydir = ROOT / "generated" / "k10" / "python"
    local = pydir / PACKAGE / "qos_files" / "cyclonedds" / "local.xml"
    state = tempfile.mkdtemp(prefix="rapid-mutant-")
    env = _env(work, mutant, str(pydir))
    env.update(CYCLONEDDS_URI=f"file://{local}", RAPID_STATE_DIR=state)
    bridge = subprocess.Popen([sys.executable, "-m", f"{PACKAGE}.bridge", "--simulate", "--domain", str(domain),
                               "--sim-speed", "20"], cwd=pydir, env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.DEVNULL, text=True)
    try:
        assert bridge.stdout is not None
        first = bridge.stdout.readline()
        if not first.startswith("bridge ready"):
            return True, "conform: the bridge did not start"
        tools = dict(os.environ, CYCLONEDDS_URI=f"file://{local}", PYTHONDONTWRITEBYTECODE="1")
        tools.pop("MUTANT_UNDER_TEST", None)
        report = Path(state) / "report.json"
        try:
            res = subprocess.run([sys.executable, "-m", "rapidgen", "conform", "specs/assets/k10.yaml", "--domain",
                                  str(domain), "--json", str(report), "--allow-motion"], cwd=ROOT, env=tools,
                                 capture_output=True, text=True, timeout=CONFORM_TIMEOUT)
        except subprocess.TimeoutExpired:
            return True, "conform: hung"
        if bridge.poll() is not None:
            return True, "conform: the bridge died"
        if res.returncode == 0:
            return False, ""
        return True, conform_finding(report, res.stdout, res.returncode)
    finally:
        stop_bridge(bridge, state)


def conform_finding(report: Path, output: str, code: int) -> str:
    """What a failed conform run found: its failed checks, else its last line (both campaigns)."""
    try:
        checks = json.loads(report.read_text())["checks"]
        bad = [c["id"] for c in checks if c.get("outcome") in ("FAIL", "ERROR")]
    except (OSError, ValueError, KeyError, TypeError):
        bad = [output.strip().splitlines()[-1][:120] if output.strip() else f"exit {code}"]
    return "conform: " + ", ".join(bad[:6])


def stop_bridge(bridge: subprocess.Popen, state) -> None:
    bridge.terminate()
    try:
        bridge.wait(timeout=20)
    except subprocess.TimeoutExpired:
        bridge.kill()
        bridge.wait()
    shutil.rmtree(state, ignore_errors=True)


def wilson(k: int, n: int, z: float = 1.96) -> tuple[float, float]:
    if n == 0:
        return 0.0, 1.0
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return max(0.0, centre - half), min(1.0, centre + half)


def judge(work: Path, name: str, oracle: str, domain: int) -> tuple[bool, str]:
    if oracle in ("spec", "both"):
        killed, why = spec_oracle(work, name)
        if killed or oracle == "spec":
            return killed, why
    return conform_oracle(work, name, domain)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--sample", type=int, default=200, help="mutants judged (a seeded sample of all)")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--oracle", choices=("spec", "conform", "both"), default="both")
    p.add_argument("--domain", type=int, default=9, help="DDS domain of the conform oracle (loopback only)")
    p.add_argument("--mutant", action="append", default=[], help="judge these mutants (names as listed) only")
    p.add_argument("--function", help="sample the mutants of the functions of this name only (e.g. insert_after)")
    p.add_argument("--json", help="write every verdict here")
    args = p.parse_args(argv)

    work = Path(tempfile.mkdtemp(prefix="rapid-mutants-"))
    try:
        t0 = time.monotonic()
        mutants = mutate(work)
        logs = sorted(n for n, (_m, _c, log_only) in mutants.items() if log_only)
        wire = sorted(n for n in mutants if n not in set(logs))
        if args.function:  # the pool: that function's mutants
            wire = [n for n in wire if n.rsplit("__mutmut_", 1)[0].endswith(("ǁ" + args.function, "x_" + args.function))]
        names = args.mutant or random.Random(args.seed).sample(wire, min(args.sample, len(wire)))
        if not names:
            print("error: no mutant to judge", file=sys.stderr)
            return 2
        unknown = [n for n in names if n not in mutants]
        if unknown:
            print(f"error: unknown mutant(s): {', '.join(unknown)}", file=sys.stderr)
            return 2
        print(f"{len(mutants)} mutants of rapid_runtime/{{{','.join(MODULES)}}}.py "
              f"({time.monotonic() - t0:.1f} s); {len(logs)} change only log text or a thread's name (not judged); "
              f"judging {len(names)} of the other {len(wire)} with the {args.oracle} oracle")
        baseline, why = judge(work, "", args.oracle, args.domain)
        if baseline:
            print(f"error: the unmutated runtime fails its oracle: {why}", file=sys.stderr)
            return 1
        verdicts = []
        for i, name in enumerate(names, 1):
            start = time.monotonic()
            killed, why = judge(work, name, args.oracle, args.domain)
            module, change, _log_only = mutants[name]
            verdicts.append({"mutant": name, "module": module, "killed": killed, "by": why, "change": change,
                             "seconds": round(time.monotonic() - start, 1)})
            print(f"[{i}/{len(names)}] {'killed  ' if killed else 'SURVIVED'} {name}  {why or change}", flush=True)
        dead = sum(bool(v["killed"]) for v in verdicts)
        lo, hi = wilson(dead, len(verdicts))
        print(f"\nscore: {dead}/{len(verdicts)} killed = {100 * dead / max(1, len(verdicts)):.1f}% "
              f"(95% CI {100 * lo:.1f}-{100 * hi:.1f}%), {time.monotonic() - t0:.0f} s")
        for v in verdicts:
            if not v["killed"]:
                print(f"  survivor {v['mutant']}: {v['change']}")
        if args.json:
            Path(args.json).write_text(json.dumps({"oracle": args.oracle, "seed": args.seed, "total": len(mutants), "log_only": len(logs),
                                                   "killed": dead, "judged": len(verdicts), "ci95": [lo, hi],
                                                   "verdicts": verdicts}, indent=1) + "\n")
        return 0
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
