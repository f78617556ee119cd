"""The 1 kHz, 64-joint JointSample setpoint stream of bench/setpoint_stream.py, on the Rust
runtime (issue 38): bench/setpoint/*.yaml generated with `--lang rust,qos`, Pilot64's Rust
bridge writing its output stream `setpoints` at 1 kHz from a thread of its own (absolute
clock_nanosleep), Arm64's Rust bridge reading it as an input stream (deadline 3 ms) in its
typed callback; both programs' handlers.rs carry the bench's lines (below, what a robot team
writes in theirs) and are built --release with rapid_dds's feature `alloc-count`
(src/alloc_count.rs: a counting #[global_allocator] and malloc taken over from glibc, both
per thread).

    python bench/rust_setpoint.py [--samples 10000] [--domain 82] [--cpp]

Prints, after a warm-up of 1000 samples, what bench/setpoint_stream.py prints (period jitter
at the reader, the writer's wake-up lateness, end-to-end latency, samples lost, deadlines
missed) and heap allocations per sample on the reader's callback thread (Cyclone's delivery:
reception, take, decode, callback) and on the writer's thread (fill, stamp, encode, write),
twice: Rust's own (the global allocator) and every malloc (Cyclone DDS's C code included); and
every malloc of each whole process in the window (Cyclone's other threads too), with the
stream topic's pool of serialized samples as the bridge logs it at stop.
--cpp runs bench/setpoint_stream.py (the C++ bridges, Fast DDS) right after, for the same
machine state. Cyclone DDS on loopback with a discovery tag of this run's own. Not a test:
figures depend on the machine's load (bench/README.md "Setpoint stream, Rust runtime").
"""
from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from bench.setpoint_stream import DEADLINE_NS, PERIOD_NS, WARMUP, pct  # noqa: E402

HERE = ROOT / "bench" / "setpoint"
WORKSPACE = """[workspace]
resolver = "2"
members = ["generated/*/rust/bridge"]
exclude = ["runtime", "generated/rapid"]
"""

COMMON = r"""
#[global_allocator]
static ALLOC: rapid_dds::alloc_count::Counting = rapid_dds::alloc_count::Counting;

fn ns_of(clock: libc::clockid_t) -> i64 {
    let mut t = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: a timespec to fill
    unsafe { libc::clock_gettime(clock, &mut t) };
    t.tv_sec * 1_000_000_000 + t.tv_nsec
}

fn samples_wanted() -> usize {
    std::env::var("SETPOINT_SAMPLES").ok().and_then(|n| n.parse().ok()).unwrap_or(10000)
}

/// SCHED_FIFO when the machine grants it (not needed to run).
fn realtime_priority() -> bool {
    let p = libc::sched_param { sched_priority: 80 };
    // SAFETY: this thread, a valid parameter
    unsafe { libc::pthread_setschedparam(libc::pthread_self(), libc::SCHED_FIFO, &p) == 0 }
}

/// arrival (reader) or wake-up (writer) CLOCK_MONOTONIC; arrival CLOCK_REALTIME (reader) or the
/// planned wake-up (writer); hdr.timeStamp (reader); this thread's Rust and malloc counts; hdr.serial;
/// the whole process's malloc count
#[derive(Clone, Copy, Default)]
struct Record(i64, i64, i64, u64, u64, i64, u64);

fn dump(env: &str, rt: i32, records: &[Record]) {
    let Ok(path) = std::env::var(env) else { return };
    let mut out = format!("rt {rt}\n");
    for r in records {
        out += &format!("{} {} {} {} {} {} {}\n", r.0, r.1, r.2, r.3, r.4, r.5, r.6);
    }
    let _ = std::fs::write(path, out);
}
"""

ARM = r"""// bench/rust_setpoint.py: Arm64's typed callback records each sample's arrival.
use std::sync::Mutex;

use crate::dispatch::*;
""" + COMMON + r"""
struct Bench {
    records: Mutex<(Vec<Record>, usize, i32)>, // preallocated, how many, SCHED_FIFO granted
}

impl Streams for Bench {
    fn setpoints(&self, sample: &rapid_arm64::rapid::JointSample) {
        let mut g = self.records.lock().unwrap();
        let (records, n, rt) = &mut *g;
        if *n == 0 {
            *rt = i32::from(realtime_priority()); // the delivering thread
        }
        if *n < records.len() {
            records[*n] = Record(ns_of(libc::CLOCK_MONOTONIC), ns_of(libc::CLOCK_REALTIME), sample.hdr.time_stamp,
                                 rapid_dds::alloc_count::rust_allocs(), rapid_dds::alloc_count::all_allocs(),
                                 i64::from(sample.hdr.serial), rapid_dds::alloc_count::process_allocs());
            *n += 1;
        }
    }
}

impl Drop for Bench {
    fn drop(&mut self) {
        let g = self.records.lock().unwrap();
        dump("SETPOINT_READER_OUT", g.2, &g.0[..g.1]);
    }
}

pub fn make_handlers() -> Dispatch {
    let records = vec![Record::default(); samples_wanted() + 1000]; // up front: recording allocates nothing
    HandlerSet {}.with_streams(Bench { records: Mutex::new((records, 0, -1)) })
}
"""

PILOT = r"""// bench/rust_setpoint.py: Pilot64 writes a 64-joint JointSample at 1 kHz from a thread of its own.
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

use crate::dispatch::*;
""" + COMMON + r"""
fn write_setpoints(writing: Arc<AtomicBool>) -> (i32, Vec<Record>) {
    let rt = i32::from(realtime_priority());
    let mut records = vec![Record::default(); samples_wanted() + 5000]; // the reader's window starts after discovery
    let mut n = 0;
    {
        let mut s = setpoints_sample();
        s.angle_pos = vec![0.0; 64]; // 64 joints: sized once, rewritten in place
        s.angle_vel = vec![0.0; 64];
        s.torque = vec![0.0; 64];
    }
    while writing.load(Ordering::Relaxed) && !send_setpoints() {
        std::thread::sleep(std::time::Duration::from_millis(10)); // until the bridge attached the writer
    }
    let mut next = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: a timespec to fill
    unsafe { libc::clock_gettime(libc::CLOCK_MONOTONIC, &mut next) };
    let mut i: i64 = 0;
    while writing.load(Ordering::Relaxed) {
        next.tv_nsec += 1_000_000; // 1 kHz
        if next.tv_nsec >= 1_000_000_000 {
            next.tv_nsec -= 1_000_000_000;
            next.tv_sec += 1;
        }
        // SAFETY: an absolute time on CLOCK_MONOTONIC
        unsafe { libc::clock_nanosleep(libc::CLOCK_MONOTONIC, libc::TIMER_ABSTIME, &next, std::ptr::null_mut()) };
        let woke = ns_of(libc::CLOCK_MONOTONIC);
        {
            let mut s = setpoints_sample();
            for (j, p) in s.angle_pos.iter_mut().enumerate() {
                *p = (i % 1000) as f32 * 1e-3 + j as f32;
            }
            s.hdr.serial = i as i32;
            if !s.send() {
                break; // the bridge stopped
            }
        }
        if n < records.len() {
            records[n] = Record(woke, next.tv_sec * 1_000_000_000 + next.tv_nsec, 0, rapid_dds::alloc_count::rust_allocs(),
                                rapid_dds::alloc_count::all_allocs(), i, rapid_dds::alloc_count::process_allocs());
            n += 1;
        }
        i += 1;
    }
    records.truncate(n);
    (rt, records)
}

struct Bench {
    writing: Arc<AtomicBool>,
    thread: Mutex<Option<JoinHandle<(i32, Vec<Record>)>>>,
}

impl Streams for Bench {}

impl Drop for Bench {
    fn drop(&mut self) {
        self.writing.store(false, Ordering::Relaxed);
        if let Some(t) = self.thread.lock().unwrap().take() {
            if let Ok((rt, records)) = t.join() {
                dump("SETPOINT_WRITER_OUT", rt, &records);
            }
        }
    }
}

pub fn make_handlers() -> Dispatch {
    let writing = Arc::new(AtomicBool::new(true));
    let w = writing.clone();
    let thread = std::thread::spawn(move || write_setpoints(w));
    HandlerSet {}.with_streams(Bench { writing, thread: Mutex::new(Some(thread)) })
}
"""


def run(cmd: list, cwd: Path = ROOT, env: dict | None = None, timeout: float = 3600) -> None:
    res = subprocess.run([str(c) for c in cmd], cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)
    if res.returncode != 0:
        raise SystemExit(f"{' '.join(map(str, cmd))}\n{res.stdout[-3000:]}\n{res.stderr[-6000:]}")


def workdir() -> Path:
    d = Path(os.environ.get("RAPIDGEN_RUST_SETPOINT_BUILD") or Path(tempfile.gettempdir()) /
             f"rapidgen-rust-setpoint-{os.getuid()}")
    d.mkdir(parents=True, exist_ok=True)
    return d


def build(work: Path) -> dict[str, Path]:
    """Arm64's and Pilot64's Rust bridges with the bench's handlers.rs, --release, feature
    alloc-count (incremental: the workspace and target folder are kept)."""
    ws = work / "ws"
    if not ws.exists():
        (ws / "generated").mkdir(parents=True)
        (ws / "runtime").symlink_to(ROOT / "runtime")
        (ws / "generated" / "rapid").symlink_to(ROOT / "generated" / "rapid")
        (ws / "Cargo.toml").write_text(WORKSPACE, encoding="utf-8")
    out = {}
    for stem, code in (("arm", ARM), ("pilot", PILOT)):
        gen = ws / "generated" / stem
        run([sys.executable, "-m", "rapidgen", "generate", HERE / f"{stem}.yaml", "--lang", "rust,qos", "-o", gen])
        bridge = gen / "rust" / "bridge"
        handlers = bridge / "src" / "handlers.rs"
        if not handlers.exists() or handlers.read_text(encoding="utf-8") != code:
            handlers.write_text(code, encoding="utf-8")
        toml = (bridge / "Cargo.toml").read_text(encoding="utf-8")
        if "alloc-count" not in toml:  # the bench's build only
            toml = re.sub(r'(rapid_dds = \{ path = "[^"]+")', r'\1, features = ["alloc-count"]', toml)
            toml += 'libc = "=0.2.191"\n'
            (bridge / "Cargo.toml").write_text(toml, encoding="utf-8")
        name = next(json.loads(ln.split("=", 1)[1]) for ln in toml.splitlines() if ln.startswith("name = "))
        out[stem] = work / "target" / "release" / name
    shutil.copy(ROOT / "runtime" / "rust" / "rapid_dds" / "Cargo.lock", ws / "Cargo.lock")
    cargo = shutil.which("cargo") or str(Path.home() / ".cargo" / "bin" / "cargo")
    env = dict(os.environ, CARGO_TARGET_DIR=str(work / "target"), CARGO_TERM_COLOR="never")
    if "LIBCLANG_PATH" not in env:
        for lib in sorted(Path("/usr/lib").glob("llvm-*/lib/libclang.so*"), reverse=True):
            env["LIBCLANG_PATH"] = str(lib.parent)
            break
    run([cargo, "build", "--release", "--offline"], cwd=ws, env=env)
    local = ws / "generated" / "arm" / "qos" / "cyclonedds" / "local.xml"
    return {**out, "local": local}


def read(path: Path) -> tuple[int, list[list[int]]]:
    lines = path.read_text().splitlines()
    return int(lines[0].split()[1]), [[int(x) for x in line.split()] for line in lines[1:]]


def pool_line(log: str) -> str:
    """The stream's serialized samples as the bridge logs them at stop (rapid_dds pooled.rs)."""
    m = re.search(r"\] stream setpoints: serialized samples: (.*)", log)
    return m.group(1) if m else "?"


def start(exe: Path, domain: int, env: dict, err: Path) -> subprocess.Popen:
    p = subprocess.Popen([str(exe), "--domain", str(domain), "--no-journal"], env=env, stdout=subprocess.PIPE,
                         stderr=err.open("w"), text=True)
    assert p.stdout is not None
    line = p.stdout.readline()
    if "ready" not in line:
        p.kill()
        raise SystemExit(f"{exe.name} did not start: {line!r} {err.read_text()[-2000:]}")
    return p


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--samples", type=int, default=10000)
    ap.add_argument("--domain", type=int, default=82)
    ap.add_argument("--cpp", action="store_true", help="bench/setpoint_stream.py (C++, Fast DDS) right after")
    args = ap.parse_args()
    t0 = time.monotonic()
    progs = build(workdir())
    print(f"built in {time.monotonic() - t0:.0f} s", file=sys.stderr)
    out = Path(tempfile.mkdtemp(prefix="rust-setpoint-"))
    tag = f"rapidgen-rust-setpoint-{os.getpid()}"
    env = dict(os.environ, SETPOINT_SAMPLES=str(args.samples), SETPOINT_READER_OUT=str(out / "reader"),
               SETPOINT_WRITER_OUT=str(out / "writer"),
               CYCLONEDDS_URI=f'file://{progs["local"]},<CycloneDDS><Domain id="any"><Discovery><Tag>{tag}</Tag>'
                              f'</Discovery></Domain></CycloneDDS>')
    reader = start(progs["arm"], args.domain, env, out / "reader.err")
    writer = start(progs["pilot"], args.domain, env, out / "writer.err")
    time.sleep((args.samples + WARMUP + 1500) / 1000)
    for p in (reader, writer):  # the reader first: no deadline is missed because the writer stopped
        p.terminate()
        p.wait(timeout=30)
    log = (out / "reader.err").read_text()
    rt_r, rec = read(out / "reader")
    rt_w, wrec = read(out / "writer")
    steady = rec[WARMUP:WARMUP + args.samples]
    if len(steady) < args.samples // 2:
        print(f"only {len(rec)} samples arrived", file=sys.stderr)
        return 1
    jitter = [abs((b[0] - a[0]) - PERIOD_NS) / 1000 for a, b in zip(steady, steady[1:])]
    latency = [(r[1] - r[2] * 1000) / 1000 for r in steady]
    n = len(steady)
    rust, every = steady[-1][3] - steady[0][3], steady[-1][4] - steady[0][4]
    first, last = steady[0][5], steady[-1][5]
    lost = (last - first + 1) - n
    wsteady = [w for w in wrec if first <= w[5] <= last]
    wake = [(w[0] - w[1]) / 1000 for w in wsteady]
    wn = len(wsteady)
    wrust, wevery = wsteady[-1][3] - wsteady[0][3], wsteady[-1][4] - wsteady[0][4]
    proc_r, proc_w = steady[-1][6] - steady[0][6], wsteady[-1][6] - wsteady[0][6]
    secs = (steady[-1][0] - steady[0][0]) / 1e9
    gaps = sum(int((b[0] - a[0]) // DEADLINE_NS) for a, b in zip(steady, steady[1:]))
    missed = [int(m.group(1)) for m in re.finditer(r"stream setpoints: \d+ samples, (\d+) deadlines missed", log)]
    print(f"Rust runtime (Cyclone DDS 0.11 via cyclors, --release): 1 kHz JointSample setpoint stream, 64 joints "
          f"(anglePos, angleVel, torque), loopback, {n} samples after {WARMUP} of warm-up; SCHED_FIFO granted: "
          f"reader {rt_r > 0}, writer {rt_w > 0}")
    print(f"  period jitter at the reader  p50 {pct(jitter, 50):.1f} us  p99 {pct(jitter, 99):.1f} us  "
          f"max {max(jitter):.1f} us")
    print(f"  writer wake-up lateness      p50 {pct(wake, 50):.1f} us  p99 {pct(wake, 99):.1f} us  max {max(wake):.1f} us")
    print(f"  end-to-end latency           p50 {pct(latency, 50):.1f} us  p99 {pct(latency, 99):.1f} us  "
          f"max {max(latency):.1f} us  (hdr.timeStamp has 1 us resolution)")
    print(f"  samples lost                 {lost} of {last - first + 1} written in the window")
    print(f"  missed deadlines (3 ms)      {gaps} in the window (gaps of 3 ms or more); the runtime counted "
          f"{missed[-1] if missed else '?'} in the whole run, start-up included")
    print(f"  heap allocations per sample  reader callback thread: Rust {rust / n:.3f}, every malloc {every / n:.3f} "
          f"({rust} and {every} in {n}); writer thread: Rust {wrust / wn:.3f}, every malloc {wevery / wn:.3f} "
          f"({wrust} and {wevery} in {wn})")
    print(f"  whole process, every malloc   reader {proc_r / n:.3f} per sample ({proc_r} in {secs:.1f} s), writer "
          f"{proc_w / wn:.3f} ({proc_w}): Cyclone's own threads too (discovery, liveliness messages), by time, not "
          f"by sample; each stream's pool at stop: {pool_line(log)}, {pool_line((out / 'writer.err').read_text())}")
    sys.stdout.flush()
    if args.cpp:
        subprocess.run([sys.executable, str(ROOT / "bench" / "setpoint_stream.py"), "--samples", str(args.samples)],
                       cwd=ROOT, check=False)
    return 0


if __name__ == "__main__":
    sys.exit(main())
