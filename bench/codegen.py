#!/usr/bin/env python3
"""Code-generation speed: `rapidgen generate` (each target, and all four at once) beside
Cyclone DDS `idlc` (C) and eProsima `fastddsgen` (C++), on the same IDL files, in one run.

It prints figures and ratios and never passes or fails on time (exit 0 unless its own
arguments are wrong). The IDL is bench/parse.py's synthetic generator (N structs of 8-13
members, modules, unions, typedefs, cross-module references). Standard library only; idlc
and fastddsgen are Debian packages (cyclonedds-tools, fastddsgen): a missing one is skipped
and its column says how to get it (`--install` installs both, as root).
"""
from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from parse import write_idl  # noqa: E402 (bench/parse.py: the same synthetic IDL)

REPO = Path(__file__).resolve().parent.parent
TARGETS = ("python", "cpp", "rust", "qos")
APT_PACKAGES = {"idlc": "cyclonedds-tools", "fastddsgen": "fastddsgen"}
GOALS = ("goals: all four targets at 1000 structs in <= 0.5x idlc's time, at 100 within 1.5x; "
         "linear to 5000; peak RSS < 200 MiB; >= 10x faster than fastddsgen; "
         "`rapidgen check` on this repository < 2 s")


@dataclass
class Tool:
    name: str
    argv: list[str]  # the output folder and the IDL file are filled in by command()
    package: str | None = None  # Debian package, when not installed
    env: dict[str, str] | None = None
    cwd: Path = REPO  # rapidgen runs from this checkout (`python -m rapidgen` imports it from there)

    def installed(self) -> bool:
        return shutil.which(self.argv[0]) is not None

    def command(self, idl: Path, out: Path) -> list[str]:
        return [a.replace("{out}", str(out)).replace("{idl}", str(idl)) for a in self.argv]


@dataclass
class Run:
    seconds: float
    rss_mib: float


def run_once(argv: list[str], env: dict[str, str] | None, cwd: Path = REPO) -> Run:
    """Spawn argv and reap it with wait4: wall time from spawn to reap, the child's own peak
    RSS (with what it reaped: rapidgen's second process)."""
    with tempfile.TemporaryFile() as err:
        start = time.perf_counter()
        proc = subprocess.Popen(argv, cwd=cwd, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                stderr=err, env=env)
        _, status, usage = os.wait4(proc.pid, 0)
        elapsed = time.perf_counter() - start
        code = os.waitstatus_to_exitcode(status)
        if code != 0:
            err.seek(0)
            lines = [ln.strip() for ln in err.read().decode(errors="replace").splitlines() if ln.strip()]
            raise RuntimeError(lines[-1] if lines else f"exit status {code}")
    return Run(elapsed, usage.ru_maxrss / 1024)  # Linux: KiB


def tools_for(python: str, env: dict[str, str], baseline: Path | None = None) -> list[Tool]:
    rapidgen = [python, "-m", "rapidgen", "generate", "{idl}", "-o", "{out}", "--lang"]
    tools = [Tool(f"rapidgen {t}", [*rapidgen, t], env=env) for t in TARGETS]
    tools.append(Tool("rapidgen all four", [*rapidgen, ",".join(TARGETS)], env=env))
    if baseline is not None:  # another checkout of rapidgen (an older commit), the same commands
        tools += [Tool(f"baseline {t}", [*rapidgen, t], env=env, cwd=baseline) for t in TARGETS]
        tools.append(Tool("baseline all four", [*rapidgen, ",".join(TARGETS)], env=env, cwd=baseline))
    tools.append(Tool("idlc", ["idlc", "-o", "{out}", "{idl}"], APT_PACKAGES["idlc"]))
    tools.append(Tool("fastddsgen", ["fastddsgen", "-d", "{out}", "{idl}"], APT_PACKAGES["fastddsgen"]))
    return tools


def measure(tools: list[Tool], idl: Path, repeat: int) -> dict[str, list[Run] | str]:
    """Every tool `repeat` times on the same file, taking turns (a busy moment of the machine
    hits every tool alike), each run into a fresh output folder; after one untimed run of
    each (page cache, Python's bytecode cache)."""
    results: dict[str, list[Run] | str] = {}
    for t in tools:
        if not t.installed():
            results[t.name] = f"not installed (apt: {t.package})" if t.package else "not found"
    for rep in range(repeat + 1):
        for t in tools:
            if isinstance(results.get(t.name), str):
                continue
            with tempfile.TemporaryDirectory(prefix="bench-codegen-") as out:
                try:
                    run = run_once(t.command(idl, Path(out)), t.env, t.cwd)
                except (RuntimeError, OSError) as exc:
                    results[t.name] = f"failed: {exc}"
                    continue
            if rep:  # the first round warms up
                results.setdefault(t.name, [])
                results[t.name].append(run)  # type: ignore[union-attr]
    return results


def best(result: list[Run] | str) -> float | None:
    return None if isinstance(result, str) else min(r.seconds for r in result)


def cell(result: list[Run] | str) -> str:
    if isinstance(result, str):
        return result
    times = [r.seconds for r in result]
    return f"{min(times):.3f} / {statistics.median(times):.3f}, {max(r.rss_mib for r in result):.0f} MiB"


def check_time(python: str, env: dict[str, str], repeat: int, cwd: Path = REPO) -> str:
    """`rapidgen check` on a checkout (every seed and the RAPID set, all their targets)."""
    times, code = [], 0
    for rep in range(repeat + 1):
        start = time.perf_counter()
        proc = subprocess.run([python, "-m", "rapidgen", "check"], cwd=cwd, env=env, capture_output=True)
        if rep:
            times.append(time.perf_counter() - start)
        code = proc.returncode
    state = "up to date" if code == 0 else f"exit status {code}: the working tree's generated/ is stale"
    return f"{min(times):.3f} s best, {statistics.median(times):.3f} s median of {repeat} ({state})"


def ratio(a: float | None, b: float | None) -> str:
    return f"{a / b:.2f}" if a is not None and b else "n/a"


def report(rows: list[tuple[int, int, dict]], tools: list[Tool]) -> None:
    print("| structs | lines | " + " | ".join(t.name for t in tools) + " |")
    print("| ---: | ---: | " + " | ".join("---" for _ in tools) + " |")
    for n, lines, results in rows:
        print(f"| {n} | {lines:,} | " + " | ".join(cell(results[t.name]) for t in tools) + " |")
    print("\n(best / median wall seconds over the runs, peak RSS of the child: max over the runs)")
    notes = sorted({(name, r) for _, _, res in rows for name, r in res.items() if isinstance(r, str)})
    for name, message in notes:
        print(f"{name}: {message}")
    print("\nratios (best times):")
    for n, _, res in rows:
        every = best(res["rapidgen all four"])
        idlc, fast = best(res["idlc"]), best(res["fastddsgen"])
        alone = [best(res.get(f"rapidgen {t}", "")) for t in TARGETS]
        parts = [f"all four / idlc {ratio(every, idlc)}", f"fastddsgen / all four {ratio(fast, every)}"]
        if "baseline all four" in res:
            parts.append(f"baseline / all four {ratio(best(res['baseline all four']), every)}")
        if all(a is not None for a in alone):
            parts.append(f"the four one at a time / all four at once {ratio(sum(alone), every)}")  # type: ignore[arg-type]
        print(f"  {n:>5} structs: " + "; ".join(parts))
    sizes = [n for n, _, _ in rows]
    if len(sizes) >= 2:
        big = sizes[-1]
        small = 1000 if 1000 in sizes and big != 1000 else sizes[-2]
        by_n = {n: res for n, _, res in rows}
        print(f"\nlinearity, time {big}/{small} (linear: {big / small:.2f}):")
        for t in tools:
            print(f"  {t.name:<18} {ratio(best(by_n[big][t.name]), best(by_n[small][t.name]))}")


def devices_report(python: str, env: dict[str, str], sizes: list[int], repeat: int, seed: int) -> None:
    """Runs with every speed device, then without each one (RAPIDGEN_WITHOUT,
    rapidgen.speed_devices), taking turns: `generate` of all four targets and `ir` (the front
    end alone) at each size, `generate` of K10's descriptor (all four targets; the qos target
    alone), `rapidgen check` on this repository. A device pays when it saves at least a tenth
    of the run it targets (of the run without it)."""
    from rapidgen.speed_devices import DEVICES

    def tools(argv: list[str]) -> list[Tool]:
        return [Tool("every device", argv, env=env),
                *[Tool(f"without {d}", argv, env=dict(env, RAPIDGEN_WITHOUT=d)) for d in DEVICES]]

    def table(title: str, results: dict) -> None:
        on = statistics.median(r.seconds for r in results["every device"])
        print(f"{title}: every device {on * 1000:.0f} ms (median of {repeat})")
        for d in DEVICES:
            off = statistics.median(r.seconds for r in results[f"without {d}"])
            share = (off - on) / off
            print(f"  without {d:<22} {off * 1000:6.0f} ms  saves {(off - on) * 1000:5.0f} ms = "
                  f"{share:5.1%} of the run  {'pays' if share >= 0.10 else 'below a tenth'}")

    rapidgen = [python, "-m", "rapidgen"]
    generate = [*rapidgen, "generate", "{idl}", "-o", "{out}", "--lang", ",".join(TARGETS)]
    with tempfile.TemporaryDirectory(prefix="bench-codegen-idl-") as tmp:
        for n in sizes:
            idl, lines = write_idl(Path(tmp), n, seed)
            table(f"generate, all four targets, {n} structs ({lines:,} lines)", measure(tools(generate), idl, repeat))
            table(f"ir (the front end alone), {n} structs", measure(tools([*rapidgen, "ir", "{idl}"]), idl, repeat))
        k10 = REPO / "specs" / "assets" / "k10.yaml"  # a robot's descriptor: the QoS library is read
        table("generate, K10's descriptor, all four targets", measure(tools(generate), k10, repeat))
        table("generate, K10's descriptor, qos alone", measure(tools([*generate[:-1], "qos"]), k10, repeat))
    table("rapidgen check (this repository)", measure(tools([*rapidgen, "check"]), REPO, repeat))
    print("\nRAPIDGEN_WITHOUT names: " + "; ".join(f"{d}: {what}" for d, what in DEVICES.items()))


def install() -> None:
    if os.geteuid() != 0:
        sys.exit("--install needs root (it runs apt-get install)")
    subprocess.run(["apt-get", "update"], check=True)
    subprocess.run(["apt-get", "install", "-y", *APT_PACKAGES.values()], check=True)


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sizes", default="100,1000,5000", help="comma-separated struct counts (default: %(default)s)")
    p.add_argument("--repeat", type=int, default=3, help="timed runs per tool and size (default: %(default)s)")
    p.add_argument("--seed", type=int, default=1, help="IDL generator seed (default: %(default)s)")
    p.add_argument("--jobs", type=int, help="RAPIDGEN_JOBS for rapidgen (default: its own choice, 2 processes "
                   "on 2 CPUs or more)")
    p.add_argument("--only", metavar="TOOLS", help="comma-separated subset of the columns, e.g. "
                   "'rapidgen all four,idlc'")
    p.add_argument("--no-check", action="store_true", help="do not time `rapidgen check`")
    p.add_argument("--baseline", metavar="DIR", type=Path, help="another rapidgen checkout (e.g. `git worktree add "
                   "DIR REV`): its `generate` of each target and all four as more columns, in the same run")
    p.add_argument("--keep", metavar="DIR", type=Path, help="write the IDL files to DIR and keep them")
    p.add_argument("--install", action="store_true", help="apt-get install cyclonedds-tools fastddsgen first (root)")
    p.add_argument("--devices", action="store_true", help="instead: what each speed device saves (rapidgen generate "
                   "without each, rapidgen.speed_devices), at --sizes and for `rapidgen check`")
    args = p.parse_args(argv)
    args.sizes = [int(s) for s in args.sizes.split(",") if s.strip()]
    if args.repeat < 1 or not args.sizes or any(n < 1 for n in args.sizes):
        p.error("--repeat and --sizes must be positive")
    return args


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    if args.install:
        install()
    # rapidgen as installed: Python's bytecode cache on (a pip install compiles it; this
    # environment may say PYTHONDONTWRITEBYTECODE), warmed by the untimed first round.
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    if args.jobs is not None:
        env["RAPIDGEN_JOBS"] = str(args.jobs)
    if args.devices:
        print(f"machine: {os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.2f}; python {sys.version.split()[0]}")
        devices_report(sys.executable, env, args.sizes, args.repeat, args.seed)
        print(f"load average after: {os.getloadavg()[0]:.2f}")
        return 0
    tools = tools_for(sys.executable, env, args.baseline.resolve() if args.baseline else None)
    if args.only:
        wanted = {w.strip() for w in args.only.split(",")}
        tools = [t for t in tools if t.name in wanted or t.name.removeprefix("rapidgen ") in wanted
                 or t.name.startswith("baseline ") and "baseline" in wanted]
    stale = subprocess.run([sys.executable, "-m", "rapidgen.backends.templating", "--check"], cwd=REPO, env=env,
                           capture_output=True, text=True)
    load_before = os.getloadavg()
    rows, loads = [], []
    with tempfile.TemporaryDirectory(prefix="bench-codegen-idl-") as tmp:
        folder = args.keep or Path(tmp)
        folder.mkdir(parents=True, exist_ok=True)
        for n in args.sizes:
            idl, lines = write_idl(folder.resolve(), n, args.seed)
            rows.append((n, lines, measure(tools, idl, args.repeat)))
            print(f"... {n} structs done (load average {os.getloadavg()[0]:.2f})", file=sys.stderr, flush=True)
            loads.append((n, os.getloadavg()[0]))
    check = None if args.no_check else check_time(sys.executable, env, args.repeat)
    base_check = (check_time(sys.executable, env, args.repeat, args.baseline.resolve())
                  if args.baseline and not args.no_check else None)
    for name in ("rapidgen all four", "idlc", "fastddsgen"):  # the ratios read these columns
        for _, _, res in rows:
            res.setdefault(name, "not measured (--only)")
    print(f"machine: {os.cpu_count()} CPUs, load average {load_before[0]:.2f} before, "
          f"{os.getloadavg()[0]:.2f} after; python {sys.version.split()[0]}; "
          f"RAPIDGEN_JOBS={env.get('RAPIDGEN_JOBS', '(default)')}; load average after each size: "
          + ", ".join(f"{load:.2f} ({n})" for n, load in loads) + "\n")
    report(rows, tools)
    if check is not None:
        print(f"\nrapidgen check (this repository): {check}")
    if base_check is not None:
        print(f"rapidgen check (the baseline, on its own tree): {base_check}")
    if stale.returncode != 0:
        print("\nnote: some precompiled templates are stale, so those are compiled on every run "
              "(python -m rapidgen.backends.templating --write):\n  " + stale.stdout.strip().replace("\n", "\n  "))
    print(f"\n{GOALS}")
    if args.keep:
        print(f"\nIDL files kept in {args.keep}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
