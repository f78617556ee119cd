//! The protocol specification (runtime/spec/cases/*.yaml) replayed by the Rust runtime, without
//! DDS: each case drives a CommandManager on the seed's tables through a collecting outbox and
//! scripted handlers (runtime/spec/README.md). tests/runtime/test_spec_cases.py is the reference
//! driver: same steps, same comparisons.
//!
//! The cases come as the JSON `python -m rapidgen.protocol_cases json OUT.json` writes (arguments
//! typed), from the file named by RAPID_SPEC_CASES; the seeds' tables as JSON from the Python
//! runtime's (tests/rust_runtime/test_spec_cases.py writes both), from RAPID_SPEC_TABLES. Every
//! case runs; each failing one is reported by file:line and name, then the test fails.
//! RAPID_SPEC_ONLY=text runs only the cases whose name holds text.

use std::collections::{HashMap, HashSet};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

use rapid_runtime::intake::{Intake, PER_WRITER, SHED_ANSWERS};
use rapid_runtime::journal::Log;
use rapid_runtime::manager::COMMAND_WINDOW;
use rapid_runtime::*;
use serde_json::Value as Json;

const WAIT: Duration = Duration::from_secs(10);
const SLICE: Duration = Duration::from_millis(50);

// ---- what the manager writes, as a ground tool would see it (plus the log, retirements, calls) ----

type Ack = (String, String, String); // status without ACK_, completion without ACK_COMPLETED_, message

#[derive(Default)]
struct Seen {
    acks: HashMap<String, Vec<Ack>>,
    /// cmdIds in the order of their first ack
    first: Vec<String>,
    /// the asset's shutdown callback's calls (Admin/shutdown)
    stopped: usize,
    queue: Option<(i32, Vec<String>, Vec<String>)>,
    /// the last QueueState's pending and active records' statuses, by cmdId
    statuses: HashMap<String, String>,
    /// the last QueueState's completed records' cmdIds
    completed: Vec<String>,
    access: Option<(String, Vec<String>)>,
    retired: Vec<String>,
    logs: Vec<String>,
    calls: Vec<(String, Vec<Value>)>,
}

#[derive(Default)]
struct Shared {
    seen: Mutex<Seen>,
    changed: Condvar,
}

impl Shared {
    fn with<R>(&self, f: impl FnOnce(&mut Seen) -> R) -> R {
        let mut s = self.seen.lock().unwrap_or_else(|e| e.into_inner());
        let r = f(&mut s);
        self.changed.notify_all();
        r
    }

    fn wait(&self) {
        let s = self.seen.lock().unwrap_or_else(|e| e.into_inner());
        let _ = self.changed.wait_timeout(s, SLICE);
    }
}

/// One manager's outbox: once its process "dies" (a restart step), nothing it writes is seen.
struct Gate {
    shared: Arc<Shared>,
    alive: AtomicBool,
}

impl Gate {
    fn live(&self, f: impl FnOnce(&mut Seen)) {
        if self.alive.load(Ordering::SeqCst) {
            self.shared.with(f)
        }
    }
}

impl Outbox for Gate {
    fn ack(&self, cmd: &Cmd, status: AckStatus, completion: Completion, message: &str) {
        let a = (
            status.name().trim_start_matches("ACK_").to_string(),
            completion.name().trim_start_matches("ACK_COMPLETED_").to_string(),
            message.to_string(),
        );
        self.live(|s| {
            if !s.acks.contains_key(&cmd.cmd_id) {
                s.first.push(cmd.cmd_id.clone());
            }
            s.acks.entry(cmd.cmd_id.clone()).or_default().push(a)
        });
    }
    fn queue_state(&self, code: i32, pending: &[Record], active: &[Record], completed: &[Record]) {
        let ids = |rs: &[Record]| rs.iter().map(|r| r.cmd.cmd_id.clone()).collect::<Vec<_>>();
        self.live(|s| {
            s.queue = Some((code, ids(pending), ids(active)));
            s.completed = ids(completed);
            s.statuses = pending.iter().chain(active).map(|r| (r.cmd.cmd_id.clone(), r.status.name().to_string())).collect();
        });
    }
    fn access_state(&self, controller: &str, requestors: &[String]) {
        self.live(|s| s.access = Some((controller.to_string(), requestors.to_vec())));
    }
    fn retire(&self, cmd: &Cmd) {
        self.live(|s| s.retired.push(cmd.cmd_id.clone()));
    }
    fn log(&self, text: &str) {
        self.live(|s| s.logs.push(text.to_string()));
    }
}

// ---- every handler: behaves as the case's `handler:` for the cmdId says ----------------------------

#[derive(Clone)]
struct Behaviour {
    kind: String,
    text: String,
    texts: Vec<String>,
}

struct Scripted {
    shared: Arc<Shared>, // a call wakes the expectations too
    behaviour: Mutex<HashMap<String, Behaviour>>,
    released: Mutex<HashSet<String>>,
    release: Condvar,
}

impl Scripted {
    fn is_released(&self, id: &str) -> bool {
        self.released.lock().unwrap_or_else(|e| e.into_inner()).contains(id)
    }

    fn release(&self, id: &str) {
        self.released.lock().unwrap_or_else(|e| e.into_inner()).insert(id.to_string());
        self.release.notify_all();
    }
}

impl Handlers for Scripted {
    fn execute(&self, ctx: &Context) -> Outcome {
        let id = ctx.cmd().cmd_id.clone();
        self.shared.with(|s| s.calls.push((id.clone(), ctx.args().to_vec())));
        let h = self.behaviour.lock().unwrap_or_else(|e| e.into_inner()).get(&id).cloned().unwrap_or(Behaviour {
            kind: "ok".into(),
            text: String::new(),
            texts: Vec::new(),
        });
        match h.kind.as_str() {
            "ok" => Outcome::Ok(h.text),
            "fail" => Outcome::Failed(h.text),
            "error" => panic!("{}", h.text),
            // (a payload that is no text, as a C++ handler's `throw 42`)
            "odd_error" => std::panic::panic_any(42_i32),
            "not_implemented" => Outcome::NotImplemented,
            "progress" => {
                for t in &h.texts {
                    ctx.progress(t);
                }
                Outcome::ok()
            }
            "block" => {
                while !self.is_released(&id) {
                    if !ctx.sleep(Duration::from_millis(5)) {
                        return Outcome::ok(); // told to stop: returns (CANCELED, or REQUEUED when preempted)
                    }
                }
                Outcome::Ok("released".into())
            }
            "stubborn" => {
                let end = Instant::now() + Duration::from_secs(60);
                let mut r = self.released.lock().unwrap_or_else(|e| e.into_inner());
                while !r.contains(&id) && Instant::now() < end {
                    r = self.release.wait_timeout(r, SLICE).unwrap_or_else(|e| e.into_inner()).0;
                }
                drop(r);
                if !h.text.is_empty() {
                    ctx.progress(&h.text); // (once released: after its answer, it must go nowhere)
                }
                Outcome::Ok("released".into())
            }
            other => panic!("unknown handler behaviour {other}"),
        }
    }
}

// ---- the disk ------------------------------------------------------------------------------------

/// A case's `disk: failing` makes the journal's fdatasync (File::sync_data) fail with EIO, `disk:
/// full` its writes to a journal file with ENOSPC, until `disk: ok`: these definitions stand in
/// for libc's in this program (std and the runtime are linked into it statically, and call
/// fdatasync and write by those names).
static DISK_FAILING: AtomicBool = AtomicBool::new(false);
static DISK_FULL: AtomicBool = AtomicBool::new(false);

#[cfg(target_arch = "x86_64")]
const SYS_WRITE: std::os::raw::c_long = 1;
#[cfg(target_arch = "aarch64")]
const SYS_WRITE: std::os::raw::c_long = 64;

#[no_mangle]
pub extern "C" fn write(fd: std::os::raw::c_int, data: *const std::os::raw::c_void, size: usize) -> isize {
    if DISK_FULL.load(Ordering::SeqCst)
        && std::fs::read_link(format!("/proc/self/fd/{fd}")).is_ok_and(|p| p.to_string_lossy().contains(".journal"))
    {
        // SAFETY: errno is this thread's
        unsafe { *__errno_location() = 28 }; // ENOSPC
        return -1;
    }
    // SAFETY: the write system call with the caller's descriptor and buffer
    unsafe { syscall(SYS_WRITE, fd, data, size) as isize }
}

extern "C" {
    fn syscall(number: std::os::raw::c_long, ...) -> std::os::raw::c_long;
    fn __errno_location() -> *mut std::os::raw::c_int;
}

#[no_mangle]
pub extern "C" fn fdatasync(fd: std::os::raw::c_int) -> std::os::raw::c_int {
    if DISK_FAILING.load(Ordering::SeqCst) {
        // SAFETY: errno is this thread's
        unsafe { *__errno_location() = 5 }; // EIO
        return -1;
    }
    #[cfg(target_arch = "x86_64")]
    const SYS_FDATASYNC: std::os::raw::c_long = 75;
    #[cfg(target_arch = "aarch64")]
    const SYS_FDATASYNC: std::os::raw::c_long = 83;
    // SAFETY: the fdatasync system call on a descriptor the caller owns
    unsafe { syscall(SYS_FDATASYNC, fd) as std::os::raw::c_int }
}

// ---- the cases' JSON ----------------------------------------------------------------------------------

fn s(j: &Json, key: &str) -> String {
    j.get(key).and_then(Json::as_str).unwrap_or_default().to_string()
}

fn strings(j: &Json) -> Vec<String> {
    j.as_array().map(|a| a.iter().filter_map(|x| x.as_str().map(String::from)).collect()).unwrap_or_default()
}

fn number(j: &Json) -> Result<f64, String> {
    j.as_f64().ok_or_else(|| format!("{j} is not a number"))
}

fn value_of(t: DataType, v: &Json) -> Result<Value, String> {
    let nums = |n: usize| -> Result<Vec<f64>, String> {
        let a = v.as_array().filter(|a| a.len() == n).ok_or_else(|| format!("{v} is not {n} numbers"))?;
        a.iter().map(number).collect()
    };
    Ok(match t {
        DataType::Bool => Value::Bool(v.as_bool().ok_or_else(|| format!("{v} is not a boolean"))?),
        DataType::Double => Value::Double(number(v)?),
        DataType::Float => Value::Float(number(v)? as f32),
        DataType::Int => Value::Int(v.as_i64().and_then(|x| i32::try_from(x).ok()).ok_or_else(|| format!("{v}: not an int"))?),
        DataType::LongLong => Value::LongLong(v.as_i64().ok_or_else(|| format!("{v}: not a long long"))?),
        DataType::String => Value::String(v.as_str().ok_or_else(|| format!("{v} is not a string"))?.to_string()),
        DataType::Vec3d => Value::Vec3d(nums(3)?.try_into().map_err(|_| "3 numbers")?),
        DataType::Mat33f => {
            let n = nums(9)?;
            Value::Mat33f(std::array::from_fn(|i| n[i] as f32))
        }
    })
}

fn data_type(name: &str) -> Result<DataType, String> {
    DataType::from_name(name).ok_or_else(|| format!("unknown DataType {name}"))
}

/// A seed's tables as tests/rust_runtime/test_spec_cases.py writes them from the Python runtime's.
fn tables_of(j: &Json) -> Result<Tables, String> {
    let mut t = Tables {
        name: s(j, "name"),
        kind: s(j, "kind"),
        domain: j.get("domain").and_then(Json::as_i64).unwrap_or(0) as i32,
        partition: s(j, "partition"),
        ..Tables::default()
    };
    for sub in j["subsystems"].as_array().ok_or("subsystems")? {
        t.subsystems.push(Subsystem { name: s(sub, "name"), type_name: s(sub, "type") });
    }
    for ty in j["types"].as_array().ok_or("types")? {
        let mut st = SubsystemType { name: s(ty, "name"), commands: Vec::new() };
        for c in ty["commands"].as_array().ok_or("commands")? {
            let mut spec = CommandSpec {
                name: s(c, "name"),
                abortable: c["abortable"].as_bool().unwrap_or(false),
                suspendable: c["suspendable"].as_bool().unwrap_or(false),
                standard: c["standard"].as_bool().unwrap_or(false),
                description: s(c, "description"),
                stop_timeout_ms: c["stop_timeout_ms"].as_u64().unwrap_or(0),
                params: Vec::new(),
            };
            for p in c["params"].as_array().ok_or("params")? {
                let dt = data_type(&s(p, "type"))?;
                let mut param = Param::new(&s(p, "name"), dt);
                param.unit = s(p, "unit");
                param.min = p["min"].as_f64();
                param.max = p["max"].as_f64();
                for a in p["allowed"].as_array().into_iter().flatten() {
                    param.allowed.push(value_of(dt, a)?);
                }
                spec.params.push(param);
            }
            st.commands.push(spec);
        }
        t.types.push(st);
    }
    if let Some(acc) = j.get("access").filter(|a| !a.is_null()) {
        t.access = Some(AccessSpec {
            allow_by_default: s(acc, "default") == "allow",
            rules: acc["rules"]
                .as_array()
                .ok_or("rules")?
                .iter()
                .map(|r| AccessRule { source: s(r, "source"), allow: strings(&r["allow"]) })
                .collect(),
        });
    }
    Ok(t)
}

fn cmd_of(step: &Json) -> Result<Cmd, String> {
    let mut args = Vec::new();
    for a in step["args"].as_array().into_iter().flatten() {
        args.push(value_of(data_type(&s(a, "type"))?, &a["value"])?);
    }
    let action = s(step, "action");
    Ok(Cmd {
        cmd_id: s(step, "id"),
        cmd_src: s(step, "src"),
        subsystem: s(step, "subsystem"),
        name: s(step, "name"),
        args,
        // a name outside the enumeration: a number outside it, as the wire would carry
        action: QueueAction::from_name(&action).unwrap_or(QueueAction::Other(99)),
        target: s(step, "target"),
        src_name: s(step, "src_name"),
        asset_name: s(step, "asset"),
        ..Cmd::default()
    })
}

// ---- comparisons --------------------------------------------------------------------------------------

fn close(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= f64::max(1e-6 * f64::max(a.abs(), b.abs()), 1e-9)
}

/// A handler's argument against the case's plain value (floats within a relative 1e-6).
fn same(seen: &Value, want: &Json) -> bool {
    match seen {
        Value::Bool(b) => want.as_bool() == Some(*b),
        Value::Double(x) => want.as_f64().is_some_and(|w| close(*x, w)),
        Value::Float(x) => want.as_f64().is_some_and(|w| close(*x as f64, w)),
        Value::Int(x) => want.as_f64().is_some_and(|w| close(*x as f64, w)),
        Value::LongLong(x) => want.as_f64().is_some_and(|w| close(*x as f64, w)),
        Value::String(t) => want.as_str() == Some(t.as_str()),
        Value::Vec3d(v) => want.as_array().is_some_and(|a| {
            a.len() == 3 && v.iter().zip(a).all(|(x, w)| w.as_f64().is_some_and(|w| close(*x, w)))
        }),
        Value::Mat33f(m) => want.as_array().is_some_and(|a| {
            a.len() == 9 && m.iter().zip(a).all(|(x, w)| w.as_f64().is_some_and(|w| close(*x as f64, w)))
        }),
    }
}

fn ack_matches(seen: &Ack, want: &Json) -> bool {
    let (status, completion, message) = seen;
    if *status != s(want, "status") {
        return false;
    }
    if let Some(c) = want["completion"].as_str() {
        if completion != c {
            return false;
        }
    }
    match want["message"].as_str() {
        None => true,
        Some(m) if want["prefix"].as_bool().unwrap_or(false) => message.starts_with(m),
        Some(m) => message == m,
    }
}

// ---- one case ---------------------------------------------------------------------------------------------

struct Replay<'a> {
    case: &'a Json,
    tables: Arc<Tables>,
    shared: Arc<Shared>,
    handlers: Arc<Scripted>,
    gate: Arc<Gate>,
    m: Arc<CommandManager>,
    /// the managers of processes that died: kept (their handler threads run on) but unheard
    dead: Vec<Arc<CommandManager>>,
    /// the door, when the case has one: shut until `open`
    intake: Option<Intake<CommandManager>>,
    journal_dir: Option<PathBuf>,
    /// the case's temporary folder, the journal's state folder inside it
    temp: Option<PathBuf>,
    /// the latest start's serial
    start: Start,
    /// the environment a case's `state:` changed, put back when the replay ends (also early)
    _env: SavedEnv,
}

/// Environment variables as they were before a case changed them: restored when dropped.
#[derive(Default)]
struct SavedEnv(Vec<(String, Option<std::ffi::OsString>)>);

impl SavedEnv {
    fn set(&mut self, var: &str, value: Option<&std::path::Path>) {
        self.0.push((var.to_string(), std::env::var_os(var)));
        match value {
            Some(v) => std::env::set_var(var, v),
            None => std::env::remove_var(var),
        }
    }
}

impl Drop for SavedEnv {
    fn drop(&mut self) {
        for (var, value) in self.0.iter().rev() {
            match value {
                Some(v) => std::env::set_var(var, v),
                None => std::env::remove_var(var),
            }
        }
    }
}

fn options_of(case: &Json, shared: &Arc<Shared>) -> Options {
    let o = &case["options"];
    let mut opts = Options::default();
    let shared = shared.clone();
    opts.on_shutdown = Some(Arc::new(move || shared.with(|s| s.stopped += 1)));
    if let Some(n) = o["window"].as_u64() {
        opts.window = n as usize;
    }
    if let Some(n) = o["queue_limit"].as_u64() {
        opts.queue_limit = n as usize;
    }
    if let Some(n) = o["bypass_limit"].as_u64() {
        opts.bypass_limit = n as usize;
    }
    if let Some(n) = o["stop_timeout_ms"].as_u64() {
        opts.stop_timeout_ms = n;
    }
    opts
}

fn manager(
    case: &Json,
    tables: &Arc<Tables>,
    handlers: &Arc<Scripted>,
    gate: &Arc<Gate>,
    journal_dir: Option<&PathBuf>,
) -> Result<(Arc<CommandManager>, Start), String> {
    let mut opts = options_of(case, &gate.shared);
    let mut recovered = None;
    if let Some(dir) = journal_dir {
        let g = gate.clone();
        let log: Log = Arc::new(move |text: &str| g.log(text));
        // (a case with `state:` starts the asset without a folder: the runtime's default one)
        let dir = if case["state"].is_null() { dir.clone() } else { Journal::default_dir() };
        let (journal, rec) = Journal::open(&dir, &tables.name, 0, opts.window, log);
        opts.journal = Some(journal.ok_or("the journal did not open (see the log)")?);
        recovered = Some(rec);
    }
    // the configs' serial as the bridge chooses it (start_serial, as rapid_dds's bridge.rs): the one asked for,
    // else past the journal's last, else the clock's
    let at = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs() as i64);
    let asked = case["serial"].as_i64();
    let serial = journal::start_serial(asked, recovered.as_ref().unwrap_or(&journal::Recovered::default()), at, opts.journal.as_mut());
    let m = CommandManager::new(tables.clone(), handlers.clone(), gate.clone(), opts)?;
    if let Some(rec) = recovered.filter(|r| r.crashed) {
        m.restore(&rec);
    }
    Ok((Arc::new(m), Start { serial, at }))
}

/// The configs' serial at a start, and the clock's seconds then.
#[derive(Clone, Copy)]
struct Start {
    serial: i64,
    at: i64,
}

/// Each line a sound record (its newline, its CRC) holding the fields given, spelled as the
/// runtimes write them, between `{` or `,` and `,` or `}` (the order of its keys not compared).
fn journal_lines_match(lines: &[&[u8]], want: &[Json]) -> bool {
    lines.len() == want.len()
        && lines.iter().zip(want).all(|(line, fields)| {
            line.len() >= 11 && line.ends_with(b"\n") && line[8] == b' ' && {
                let body = &line[9..line.len() - 1];
                line[..8] == *format!("{:08x}", journal::crc32(body)).as_bytes() && {
                    let body = String::from_utf8_lossy(body);
                    strings(fields).iter().all(|f| ["{", ","].iter().any(|a| [",", "}"].iter().any(|b| body.contains(&format!("{a}{f}{b}")))))
                }
            }
        })
}

/// A file name matched by a pattern as fnmatch reads one (the other drivers' matcher): `*` any
/// run of characters, `?` one, `[0-9]` one in a set of characters and ranges.
fn glob(pattern: &str, name: &str) -> bool {
    fn chars(p: &[char], n: &[char]) -> bool {
        match p.first() {
            None => n.is_empty(),
            Some('*') => (0..=n.len()).any(|k| chars(&p[1..], &n[k..])),
            Some('?') => !n.is_empty() && chars(&p[1..], &n[1..]),
            Some('[') if p.iter().skip(2).any(|c| *c == ']') => {
                let close = 2 + p.iter().skip(2).position(|c| *c == ']').unwrap_or(0);
                let set = &p[1..close];
                let inside = |c: char| {
                    let (mut i, mut hit) = (0, false);
                    while i < set.len() {
                        if i + 2 < set.len() && set[i + 1] == '-' {
                            hit |= (set[i]..=set[i + 2]).contains(&c);
                            i += 3;
                        } else {
                            hit |= set[i] == c;
                            i += 1;
                        }
                    }
                    hit
                };
                !n.is_empty() && inside(n[0]) && chars(&p[close + 1..], &n[1..])
            }
            Some(c) => n.first() == Some(c) && chars(&p[1..], &n[1..]),
        }
    }
    let (p, n): (Vec<char>, Vec<char>) = (pattern.chars().collect(), name.chars().collect());
    chars(&p, &n)
}

impl<'a> Replay<'a> {
    fn new(case: &'a Json, tables: Arc<Tables>, n: usize) -> Result<Replay<'a>, String> {
        let shared = Arc::new(Shared::default());
        let handlers = Arc::new(Scripted {
            shared: shared.clone(),
            behaviour: Mutex::new(HashMap::new()),
            released: Mutex::new(HashSet::new()),
            release: Condvar::new(),
        });
        let gate = Arc::new(Gate { shared: shared.clone(), alive: AtomicBool::new(true) });
        // a case that restarts the asset, or starts on a journal, runs with the restart journal as
        // the bridge does, in a state folder not made yet (the runtime makes it) unless the case's
        // journal is written there first
        let found = &case["journal"];
        let state = &case["state"];
        let restarts = case["steps"].as_array().into_iter().flatten().any(|st| s(st, "op") == "restart");
        let temp = (restarts || !found.is_null() || !state.is_null()).then(|| {
            let dir = std::env::temp_dir().join(format!("rapid-spec-journal-{}-{n}", std::process::id()));
            let _ = std::fs::remove_dir_all(&dir);
            dir
        });
        let journal_dir = temp.as_ref().map(|t| match state["dir"].as_str() {
            Some(dir) => t.join(dir),
            None => t.join("state").join("rapid_runtime"),
        });
        let mut env = SavedEnv::default();
        if let Some(t) = temp.as_ref().filter(|_| !state.is_null()) {
            // (the journal's default folder named by these, in the case's folder; one case at a time)
            for var in state["unset"].as_array().into_iter().flatten().filter_map(Json::as_str) {
                env.set(var, None);
            }
            for (var, rel) in state["set"].as_object().into_iter().flatten() {
                env.set(var, Some(&t.join(rel.as_str().unwrap_or_default())));
            }
        }
        if let (Some(dir), false) = (&journal_dir, found.is_null()) {
            std::fs::create_dir_all(dir)
                .and_then(|_| std::fs::write(dir.join(s(found, "file")), s(found, "text")))
                .map_err(|e| format!("the case's journal cannot be written in {}: {e}", dir.display()))?;
            if let Some(left) = found["new"].as_str() {
                // (what a crash in the middle of a compaction left)
                std::fs::write(dir.join(format!("{}.new", s(found, "file"))), left)
                    .map_err(|e| format!("the case's .new file cannot be written in {}: {e}", dir.display()))?;
            }
        }
        let (m, start) = manager(case, &tables, &handlers, &gate, journal_dir.as_ref())?;
        // a case with a door offers commands there as the bridge's reader does; shut until `open`
        let door = &case["door"];
        let intake = (!door.is_null()).then(|| {
            let g = gate.clone();
            let log: Log = Arc::new(move |text: &str| g.log(text));
            let limit = |key: &str, default: usize| door[key].as_u64().map_or(default, |n| n as usize);
            Intake::new(m.clone(), log, limit("per_writer", PER_WRITER), limit("shed_answers", SHED_ANSWERS))
        });
        Ok(Replay { case, tables, shared, handlers, gate, m, dead: Vec::new(), intake, journal_dir, temp, start, _env: env })
    }

    /// The process dies: the journal as the disk has it (no clean stop record), nothing more
    /// heard from the old manager; a new one starts on the journal.
    fn crash(&mut self) -> Result<(), String> {
        self.gate.alive.store(false, Ordering::SeqCst);
        drop(self.m.release_journal());
        self.gate = Arc::new(Gate { shared: self.shared.clone(), alive: AtomicBool::new(true) });
        let (m, start) = manager(self.case, &self.tables, &self.handlers, &self.gate, self.journal_dir.as_ref())?;
        self.start = start;
        self.dead.push(std::mem::replace(&mut self.m, m));
        Ok(())
    }

    /// A clean stop as the bridge's (every command answered, the journal closed with its stop
    /// record), then a start on that journal.
    fn stop_and_start(&mut self) -> Result<(), String> {
        self.m.shutdown(Some(Duration::from_secs(5)));
        if let Some(journal) = self.m.release_journal() {
            journal.close(true);
        }
        let (m, start) = manager(self.case, &self.tables, &self.handlers, &self.gate, self.journal_dir.as_ref())?;
        self.start = start;
        self.dead.push(std::mem::replace(&mut self.m, m));
        Ok(())
    }

    /// Wait (woken by every write and handler call; the manager's own view in short slices)
    /// until ok, else Err with what was seen.
    fn until(&self, what: String, ok: impl Fn(&Replay) -> bool, seen: impl Fn(&Replay) -> String) -> Result<(), String> {
        let end = Instant::now() + WAIT;
        loop {
            if ok(self) {
                return Ok(());
            }
            if Instant::now() >= end {
                return Err(format!("expected {what}; seen {}", seen(self)));
            }
            self.shared.wait();
        }
    }

    fn peek<R>(&self, f: impl FnOnce(&Seen) -> R) -> R {
        f(&self.shared.seen.lock().unwrap_or_else(|e| e.into_inner()))
    }

    fn step(&mut self, st: &Json) -> Result<(), String> {
        let op = s(st, "op");
        match op.as_str() {
            "send" | "offer" => {
                let h = &st["handler"];
                let b = Behaviour { kind: s(h, "kind"), text: s(h, "text"), texts: strings(&h["texts"]) };
                self.handlers.behaviour.lock().unwrap_or_else(|e| e.into_inner()).insert(s(st, "id"), b);
                match (&self.intake, op.as_str()) {
                    (Some(door), "offer") => door.offer(cmd_of(st)?, &s(st, "writer")),
                    (None, "offer") => return Err("`offer` in a case without a door".into()),
                    _ => self.m.receive(cmd_of(st)?),
                }
            }
            "open" => self.intake.as_ref().ok_or("`open` in a case without a door")?.start(),
            "refuse" => self.m.refuse(cmd_of(st)?, &s(st, "why")),
            "release" => self.handlers.release(&s(st, "id")),
            "restart" if st["clean"].as_bool() == Some(true) => self.stop_and_start()?,
            "restart" => self.crash()?,
            "idle" => {
                if !self.m.wait_idle(WAIT) {
                    return Err("the manager never became idle".into());
                }
            }
            "shutdown" => {
                let ms = st["timeout_ms"].as_i64().unwrap_or(-1);
                let bound = Duration::from_millis(if ms >= 0 { ms as u64 } else { 5000 });
                self.m.shutdown(Some(bound));
            }
            "acks" => {
                let id = s(st, "id");
                let want = st["acks"].as_array().cloned().unwrap_or_default();
                let got = |r: &Replay| r.peek(|s| s.acks.get(&id).cloned().unwrap_or_default());
                self.until(
                    format!("acks of {id}: {}", st["acks"]),
                    |r| {
                        let g = got(r);
                        g.len() == want.len() && g.iter().zip(&want).all(|(a, w)| ack_matches(a, w))
                    },
                    |r| format!("{:?}", got(r)),
                )?;
            }
            "queue" => {
                let code = st.get("code").and_then(Json::as_i64);
                let pending = st.get("pending").map(strings);
                let active = st.get("active").map(strings);
                let completed = st.get("completed").map(strings);
                let statuses: Vec<(String, String)> = st
                    .get("statuses")
                    .and_then(Json::as_object)
                    .map(|o| o.iter().map(|(k, v)| (k.clone(), v.as_str().unwrap_or_default().to_string())).collect())
                    .unwrap_or_default();
                self.until(
                    format!("QueueState {st}"),
                    |r| {
                        r.peek(|s| match &s.queue {
                            None => false,
                            Some((c, p, a)) => {
                                code.is_none_or(|w| w == *c as i64)
                                    && pending.as_ref().is_none_or(|w| w == p)
                                    && active.as_ref().is_none_or(|w| w == a)
                                    && completed.as_ref().is_none_or(|w| *w == s.completed)
                                    && statuses.iter().all(|(id, w)| s.statuses.get(id) == Some(w))
                            }
                        })
                    },
                    |r| r.peek(|s| format!("{:?} completed {:?} {:?}", s.queue, s.completed, s.statuses)),
                )?;
            }
            "control" => {
                let controller = st.get("controller").and_then(Json::as_str).map(String::from);
                let requestors = st.get("requestors").map(strings);
                self.until(
                    format!("AccessControlState {st}"),
                    |r| {
                        r.peek(|s| match &s.access {
                            None => false,
                            Some((c, q)) => {
                                controller.as_ref().is_none_or(|w| w == c) && requestors.as_ref().is_none_or(|w| w == q)
                            }
                        })
                    },
                    |r| r.peek(|s| format!("{:?}", s.access)),
                )?;
            }
            "calls" => {
                let want = st["calls"].as_array().cloned().unwrap_or_default();
                self.until(
                    format!("handler calls {}", st["calls"]),
                    |r| {
                        r.peek(|s| {
                            s.calls.len() == want.len()
                                && s.calls.iter().zip(&want).all(|((id, vals), w)| {
                                    let wv = w["values"].as_array().cloned().unwrap_or_default();
                                    *id == s_of(w, "id")
                                        && vals.len() == wv.len()
                                        && vals.iter().zip(&wv).all(|(v, x)| same(v, x))
                                })
                        })
                    },
                    |r| r.peek(|s| format!("{:?}", s.calls)),
                )?;
            }
            "retired" => {
                let want = strings(&st["ids"]);
                self.until(
                    format!("retired {want:?}"),
                    |r| r.peek(|s| s.retired == want),
                    |r| r.peek(|s| format!("{:?}", s.retired)),
                )?;
            }
            "pending" => {
                let want = strings(&st["ids"]);
                self.until(
                    format!("pending {want:?}"),
                    |r| r.m.pending_ids() == want,
                    |r| format!("{:?}", r.m.pending_ids()),
                )?;
            }
            // (waits for that many, then no more)
            "log_count" => {
                let text = s(st, "text");
                let want = st["count"].as_u64().unwrap_or(0) as usize;
                let count = |r: &Replay| r.peek(|s| s.logs.iter().filter(|l| l.contains(&text)).count());
                let last = |r: &Replay| r.peek(|s| format!("{:?}", &s.logs[s.logs.len().saturating_sub(10)..]));
                self.until(format!("{want} log lines with {text:?}"), |r| count(r) >= want, last)?;
                if count(self) != want {
                    return Err(format!("expected {want} log lines with {text:?}; seen {}", last(self)));
                }
            }
            "disk" => {
                DISK_FAILING.store(st["failing"].as_bool().unwrap_or(false), Ordering::SeqCst);
                DISK_FULL.store(st["full"].as_bool().unwrap_or(false), Ordering::SeqCst);
            }
            "log" => {
                let text = s(st, "text");
                self.until(
                    format!("a log line with {text:?}"),
                    |r| r.peek(|s| s.logs.iter().any(|l| l.contains(&text))),
                    |r| r.peek(|s| format!("{:?}", &s.logs[s.logs.len().saturating_sub(10)..])),
                )?;
            }
            // (at this step: what came before it has been waited for)
            "no_log" => {
                let text = s(st, "text");
                if let Some(line) = self.peek(|s| s.logs.iter().find(|l| l.contains(&text)).cloned()) {
                    return Err(format!("expected no log line with {text:?}; seen {line:?}"));
                }
            }
            "order" => {
                let want = strings(&st["ids"]);
                let firsts = |r: &Replay| r.peek(|s| s.first.iter().filter(|id| want.contains(id)).cloned().collect::<Vec<_>>());
                self.until(format!("first acks in the order {want:?}"), |r| firsts(r).len() == want.len(), |r| format!("{:?}", firsts(r)))?;
                if firsts(self) != want {
                    return Err(format!("expected first acks in the order {want:?}; seen {:?}", firsts(self)));
                }
            }
            "stopped" => {
                let want = st["count"].as_u64().unwrap_or(0) as usize;
                let got = |r: &Replay| r.peek(|s| s.stopped);
                self.until(format!("the shutdown callback called {want} times"), |r| got(r) >= want, |r| got(r).to_string())?;
                if got(self) != want {
                    return Err(format!("expected the shutdown callback called {want} times; seen {}", got(self)));
                }
            }
            "serial" => {
                let clock = st["clock"].as_bool().unwrap_or(false);
                let want = st["value"].as_i64().unwrap_or(-1);
                let ok = if clock { (self.start.serial - self.start.at).abs() <= 2 } else { self.start.serial == want };
                if !ok {
                    let what = if clock { "the clock's".to_string() } else { want.to_string() };
                    return Err(format!("expected the configs' serial {what}; seen {}", self.start.serial));
                }
            }
            "files" => {
                let patterns = strings(&st["names"]);
                let mut names: Vec<String> = match self.journal_dir.as_ref().map(std::fs::read_dir) {
                    Some(Ok(dir)) => dir.flatten().map(|e| e.file_name().to_string_lossy().into_owned()).collect(),
                    _ => Vec::new(),
                };
                names.sort();
                let ok = names.len() == patterns.len()
                    && names.iter().all(|n| patterns.iter().any(|p| glob(p, n)))
                    && patterns.iter().all(|p| names.iter().any(|n| glob(p, n)));
                if !ok {
                    return Err(format!("expected the journal folder holding {patterns:?}; seen {names:?}"));
                }
            }
            "journal_file" => {
                // (checked at once: the steps before it waited for what they describe)
                let path = self.journal_dir.as_ref().map(|d| d.join(s(st, "file"))).unwrap_or_default();
                if let Some(want) = st["mode"].as_str() {
                    use std::os::unix::fs::PermissionsExt;
                    let mode = std::fs::metadata(&path).map_or("none".to_string(), |m| format!("0{:03o}", m.permissions().mode() & 0o777));
                    if mode != want {
                        return Err(format!("expected the journal's mode {want}; seen {mode}"));
                    }
                }
                if let Some(want) = st["lines"].as_array() {
                    let raw = std::fs::read(&path).unwrap_or_default();
                    let mut lines: Vec<&[u8]> = raw.split_inclusive(|b| *b == b'\n').collect();
                    if st["tail"].as_bool().unwrap_or(false) && lines.len() > want.len() {
                        lines.drain(..lines.len() - want.len()); // (the file's last lines only)
                    }
                    if !journal_lines_match(&lines, want) {
                        let seen: Vec<String> = lines.iter().map(|l| String::from_utf8_lossy(l).into_owned()).collect();
                        return Err(format!("expected the journal's lines holding {want:?}; seen {seen:?}"));
                    }
                }
            }
            other => return Err(format!("unknown step {other}")),
        }
        Ok(())
    }

    fn close(self) {
        DISK_FAILING.store(false, Ordering::SeqCst);
        DISK_FULL.store(false, Ordering::SeqCst);
        if let Some(door) = &self.intake {
            door.stop();
        }
        let ids: Vec<String> = self.handlers.behaviour.lock().unwrap_or_else(|e| e.into_inner()).keys().cloned().collect();
        for id in ids {
            self.handlers.release(&id);
        }
        self.m.shutdown(Some(Duration::from_secs(2)));
        for m in &self.dead {
            m.shutdown(Some(Duration::from_secs(2)));
        }
        if let Some(dir) = &self.temp {
            let _ = std::fs::remove_dir_all(dir);
        }
    }
}

fn s_of(j: &Json, key: &str) -> String {
    s(j, key)
}

fn run_case(case: &Json, tables: Arc<Tables>, n: usize) -> Result<(), String> {
    let first = &case["steps"][0];
    if s(first, "op") == "refused" {
        // (its only step: the manager refuses the case's options)
        let text = s(first, "text");
        return match Replay::new(case, tables, n) {
            Ok(replay) => {
                replay.close();
                Err(format!("expected the options refused ({text}); the asset started"))
            }
            Err(e) if e.contains(&text) => Ok(()),
            Err(e) => Err(format!("expected the options refused ({text}); refused with {e}")),
        };
    }
    let mut replay = Replay::new(case, tables, n)?;
    let mut result = Ok(());
    for (i, st) in case["steps"].as_array().into_iter().flatten().enumerate() {
        if let Err(e) = replay.step(st) {
            result = Err(format!("step {} ({}): {e}", i + 1, s(st, "op")));
            break;
        }
    }
    replay.close();
    result
}

fn read_json(var: &str) -> Json {
    let path = std::env::var(var).unwrap_or_else(|_| {
        panic!("{var} is not set (tests/rust_runtime/test_spec_cases.py sets it: the cases and the seeds' tables as JSON)")
    });
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{path}: {e}"))
}

#[test]
fn spec_cases() {
    // a scripted handler's panic is a case's `error:` behaviour: not shown; any other is
    let default_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if !std::thread::current().name().is_some_and(|n| n.starts_with("cmd-")) {
            default_hook(info);
        }
    }));
    let cases = read_json("RAPID_SPEC_CASES");
    let seeds = read_json("RAPID_SPEC_TABLES");
    let only = std::env::var("RAPID_SPEC_ONLY").unwrap_or_default();
    let mut tables: HashMap<String, Arc<Tables>> = HashMap::new();
    for (seed, t) in seeds.as_object().expect("the tables file: seed -> tables") {
        tables.insert(seed.clone(), Arc::new(tables_of(t).unwrap_or_else(|e| panic!("tables of {seed}: {e}"))));
    }
    let all = cases["cases"].as_array().expect("the cases file: {cases: [...]}");
    assert!(!all.is_empty(), "no case in RAPID_SPEC_CASES");
    let (mut passed, mut failed, mut ran) = (0, Vec::new(), 0);
    for (n, case) in all.iter().enumerate() {
        let name = s(case, "name");
        if !name.contains(&only) {
            continue;
        }
        ran += 1;
        let where_ = format!("{}:{} {:?}", s(case, "file"), case["line"], name);
        let start = Instant::now();
        let seed = s(case, "asset");
        let result = match tables.get(&seed) {
            // (the seed's tables under the case's asset_name, if it has one)
            Some(t) => match case["asset_name"].as_str() {
                Some(name) => run_case(case, Arc::new(Tables { name: name.into(), ..(**t).clone() }), n),
                None => run_case(case, t.clone(), n),
            },
            None => Err(format!("no tables for seed '{seed}'")),
        };
        match result {
            Ok(()) => {
                passed += 1;
                println!("ok   {where_} ({} ms)", start.elapsed().as_millis());
            }
            Err(e) => {
                println!("FAIL {where_}: {e}");
                failed.push(format!("{where_}: {e}"));
            }
        }
    }
    println!("spec cases: {passed} of {ran} passed (of {} in the file; window default {COMMAND_WINDOW})", all.len());
    assert!(failed.is_empty(), "{} case(s) failed:\n{}", failed.len(), failed.join("\n"));
}

// ---- the restart journal across runtimes ----------------------------------------------------------------

fn entry_json(e: &JournalEntry) -> Json {
    serde_json::json!({"id": e.cmd_id, "src": e.src_name, "asset": e.asset_name, "serial": e.serial,
                       "state": e.state.to_string(), "c": e.completion, "m": e.message})
}

/// RAPID_JOURNAL_INTEROP=DIR (tests/rust_runtime/test_spec_cases.py): the journal the Python
/// runtime left in DIR/from_python at a crash is recovered here (DIR/rust_recovered.json says
/// what came back), and one this runtime leaves at a crash in DIR/from_rust is for the Python
/// runtime to recover.
#[test]
fn journal_interop() {
    let Ok(dir) = std::env::var("RAPID_JOURNAL_INTEROP") else {
        println!("journal_interop: RAPID_JOURNAL_INTEROP not set, nothing to do");
        return;
    };
    let dir = PathBuf::from(dir);
    let logs = Arc::new(Mutex::new(Vec::<String>::new()));
    let l = logs.clone();
    let log: Log = Arc::new(move |t: &str| l.lock().unwrap().push(t.to_string()));
    let (journal, rec) = Journal::open(&dir.join("from_python"), "K10Red", 7, 8, log.clone());
    assert!(journal.is_some(), "{:?}", logs.lock().unwrap());
    let out = serde_json::json!({
        "unfinished": rec.unfinished.iter().map(entry_json).collect::<Vec<_>>(),
        "finished": rec.finished.iter().map(entry_json).collect::<Vec<_>>(),
        "last_serial": rec.last_serial, "crashed": rec.crashed,
    });
    std::fs::write(dir.join("rust_recovered.json"), out.to_string()).unwrap();
    drop(journal);

    let (journal, rec) = Journal::open(&dir.join("from_rust"), "K10Red", 7, 8, log);
    let mut j = journal.expect("a fresh journal opens");
    assert!(!rec.crashed);
    j.start(5);
    let entry = |id: &str, state: char, c: &str, m: &str| JournalEntry {
        cmd_id: id.into(),
        src_name: "Work bench é".into(),
        asset_name: "K10Red".into(),
        serial: 2,
        state,
        completion: c.into(),
        message: m.into(),
    };
    j.note(entry("a", 'q', "", ""));
    j.note(entry("a", 'x', "", ""));
    j.note(entry("b", 'q', "", ""));
    j.note(entry("c", 'q', "", ""));
    j.note(entry("c", 'c', "ACK_COMPLETED_OK", "done ✓ \"q\" \\ 😀\n\u{7f}"));
    j.serial(9);
    assert!(j.sync());
    drop(j); // a crash: no stop record
}
