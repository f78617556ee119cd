//! Command intake and the ack lifecycle: the asset's side of rapid_command / rapid_ack,
//! written as the Python runtime's manager.py (the reference) and the C++ runtime's
//! manager.cpp do it, so the protocol specification's cases (runtime/spec) pass in all three.
//!
//! ```text
//! let manager = CommandManager::new(tables, handlers, outbox, Options::default())?;
//! manager.receive(cmd);          // every Command read from the asset's partition
//! ```
//!
//! Dropped without an ack (logged): a command for another asset, a repeated cmdId. Everything
//! else gets exactly one final COMPLETED ack. Acks go out through the Outbox (a DDS layer
//! writes them; tests collect them), always under the manager's lock, so the acks of one
//! command keep their order.
//!
//! Memory stays bounded: only the last `window` cmdIds are remembered (duplicates detected
//! among them and among those still pending or running), and once more than `window` commands
//! have completed, the oldest one's acks are retired (Outbox::retire). The queue holds at most
//! `queue_limit` commands and `bypass_limit` run beside it; past these a command is answered
//! EXEC_FAILED at once.
//!
//! With a journal (journal.rs) every step an ack promises is on disk before that ack: what a
//! locked operation writes is held back and written, in order, once the journal is synced.

use std::collections::{HashMap, HashSet, VecDeque};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::{Arc, Condvar, Mutex, MutexGuard, Weak};
use std::thread;
use std::time::{Duration, Instant};

use crate::access::{self, Control};
use crate::command::Cmd;
use crate::handlers::{Context, Handlers, Outcome};
use crate::journal::{Journal, JournalEntry, Recovered};
use crate::tables::{CommandRef, Tables};
use crate::text::{outgoing, short, visible, MESSAGE_BYTES};
use crate::texts;
use crate::validate::check_command;
use crate::value::py_string;
use crate::vocabulary::{AckStatus, Completion, QueueAction, RecordResult, RecordStatus, HEAD};

/// Commands whose state is kept: the last 4096 cmdIds received (duplicate detection) and the
/// acks of the last 4096 completed commands (late-joining ack readers).
pub const COMMAND_WINDOW: usize = 4096;
/// Past these, a command is answered EXEC_FAILED at once (docs/runtime.md, "Bounded memory").
pub const QUEUE_LIMIT: usize = 1024;
pub const BYPASS_LIMIT: usize = 64;
/// Finished commands stay in QueueState this long (soraCore).
pub const COMPLETED_KEEP: Duration = Duration::from_secs(20);
/// QueueState's SingleQueue holds at most 64 records.
pub const RECORDS: usize = 64;
/// A told-to-stop handler's default bound (a command's stop_timeout_ms overrides it).
pub const DEFAULT_STOP_TIMEOUT_MS: u64 = 2000;
/// How long a shutdown waits for the handlers told to stop, by default.
pub const DEFAULT_SHUTDOWN_TIMEOUT_MS: u64 = 5000;

/// A decision broken on purpose (breaks.rs, the feature test-breaks): `broken!(self, "kind")`
/// asks whether the kind is on, `broken!(self, held_once(source))` former-controller-keeps-
/// rights' question. Without the feature both are the constant `false`: a plain build has
/// neither the kinds' names nor a branch on them (as the C++ runtime's BROKEN macro).
#[cfg(feature = "test-breaks")]
macro_rules! broken {
    ($inner:expr, held_once($source:expr)) => {
        $inner.breaks.held_once($source)
    };
    ($inner:expr, $kind:literal) => {
        $inner.breaks.on($kind)
    };
}
#[cfg(not(feature = "test-breaks"))]
macro_rules! broken {
    ($inner:expr, $($any:tt)*) => {
        NOTHING_BROKEN
    };
}
/// (a constant rather than the literal: clippy would ask for `!false` to be simplified away)
#[cfg(not(feature = "test-breaks"))]
const NOTHING_BROKEN: bool = false;

/// One QueueState record: the command and its result and status.
#[derive(Clone, Debug)]
pub struct Record {
    pub cmd: Arc<Cmd>,
    pub result: RecordResult,
    pub status: RecordStatus,
}

/// Where the manager's answers go: a DDS layer writes them, tests collect them. Called under
/// the manager's lock: an outbox must not call the manager back. A write it cannot make it
/// logs itself (an ack whose write panics is logged by the manager, and the command moves on).
pub trait Outbox: Send + Sync {
    fn ack(&self, cmd: &Cmd, status: AckStatus, completion: Completion, message: &str);
    /// code: 1 running, 0 idle, -1 suspended
    fn queue_state(&self, code: i32, pending: &[Record], active: &[Record], completed: &[Record]);
    fn access_state(&self, controller: &str, requestors: &[String]);
    /// The command's acks need not be kept any longer (cmd holds the ack key only).
    fn retire(&self, cmd: &Cmd);
    fn log(&self, text: &str);
}

pub struct Options {
    pub window: usize,
    pub queue_limit: usize,
    pub bypass_limit: usize,
    /// the stop bound of commands declaring none (>= 1)
    pub stop_timeout_ms: u64,
    /// shutdown()'s default bound
    pub shutdown_timeout_ms: u64,
    /// after Admin/shutdown's COMPLETED ack, on a thread of its own
    pub on_shutdown: Option<Arc<dyn Fn() + Send + Sync>>,
    /// the restart journal; None: nothing survives a crash
    pub journal: Option<Journal>,
    /// decisions broken on purpose (test builds only: the feature test-breaks)
    #[cfg(feature = "test-breaks")]
    pub breaks: Arc<crate::breaks::Breaks>,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            window: COMMAND_WINDOW,
            queue_limit: QUEUE_LIMIT,
            bypass_limit: BYPASS_LIMIT,
            stop_timeout_ms: DEFAULT_STOP_TIMEOUT_MS,
            shutdown_timeout_ms: DEFAULT_SHUTDOWN_TIMEOUT_MS,
            on_shutdown: None,
            journal: None,
            #[cfg(feature = "test-breaks")]
            breaks: Arc::default(),
        }
    }
}

type RunId = u64;

struct Run {
    cmd: Arc<Cmd>,
    r: CommandRef,
    /// came through the queue (not BYPASS)
    queued: bool,
    ctx: Option<Arc<Context>>,
    /// preempted: goes back to the queue's front when its handler returns
    requeue: bool,
    /// its COMPLETED ack is written: nothing follows it
    done: bool,
    record_status: RecordStatus,
    /// its handler has been called and has not returned
    running: bool,
    /// told to stop: the handler's deadline
    stop_by: Option<Instant>,
    /// stopAllMotion: the motion runs it told to stop
    stopped: Vec<RunId>,
}

/// A finished command's final ack, written again when its cmdId is sent again.
#[derive(Clone)]
struct Final {
    key: Arc<Cmd>,
    completion: Completion,
    message: String,
}

/// What a locked operation writes, held until its end (after the journal's sync).
enum Write {
    Ack(Arc<Cmd>, AckStatus, Completion, String),
    Queue(i32, Vec<Record>, Vec<Record>, Vec<Record>),
    Access(String, Vec<String>),
    Retire(Arc<Cmd>),
    Log(String),
    /// a handler's thread: started with the acks, after the journal's sync (a handler never
    /// moves hardware for a command whose "running" step a power cut could still erase)
    Start(RunId, Arc<Context>),
    OnShutdown,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Builtin {
    Echo,
    NoOp,
    Shutdown,
    CancelAll,
    StopAllMotion,
    Control(ControlOp),
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum ControlOp {
    Request,
    Grab,
    Release,
    Transfer,
}

fn builtin_of(type_name: &str, name: &str) -> Option<Builtin> {
    Some(match (type_name, name) {
        ("Admin", "echo") => Builtin::Echo,
        ("Admin", "noOp") => Builtin::NoOp,
        ("Admin", "shutdown") => Builtin::Shutdown,
        ("Queue", "cancelAll") => Builtin::CancelAll,
        ("Mobility", "stopAllMotion") => Builtin::StopAllMotion,
        ("AccessControl", "requestControl") => Builtin::Control(ControlOp::Request),
        ("AccessControl", "grabControl") => Builtin::Control(ControlOp::Grab),
        ("AccessControl", "releaseControl") => Builtin::Control(ControlOp::Release),
        ("AccessControl", "transferControl") => Builtin::Control(ControlOp::Transfer),
        _ => return None,
    })
}

struct State {
    runs: HashMap<RunId, Run>,
    next_run: RunId,
    next_ctx: u64,
    /// the last `window` cmdIds, oldest first, with their final ack once they have one
    seen: HashMap<String, Option<Final>>,
    seen_order: VecDeque<String>,
    /// completed commands whose acks are kept (the ack key), oldest first
    acked: VecDeque<Arc<Cmd>>,
    pending: VecDeque<RunId>,
    /// the queue's running command
    active: Option<RunId>,
    /// BYPASS commands running
    bypass: Vec<RunId>,
    completed: VecDeque<(Instant, Arc<Cmd>, Completion)>,
    suspended: bool,
    control: Control,
    shutdown_after: Option<RunId>,
    journal: Option<Journal>,
    outgoing: Vec<Write>,
    /// told-to-stop handlers, each until it returns or its bound passes
    stopping: HashSet<RunId>,
    watchdog: bool,
    /// shutting down: nothing starts, nothing is requeued
    closing: bool,
    handlers_running: usize,
}

struct Inner {
    tables: Arc<Tables>,
    handlers: Arc<dyn Handlers>,
    out: Arc<dyn Outbox>,
    window: usize,
    queue_limit: usize,
    bypass_limit: usize,
    stop_timeout_ms: u64,
    shutdown_timeout_ms: u64,
    on_shutdown: Option<Arc<dyn Fn() + Send + Sync>>,
    has_queue: bool,
    has_control: bool,
    #[cfg(feature = "test-breaks")]
    breaks: Arc<crate::breaks::Breaks>,
    /// itself, for the threads it starts (handlers, the watchdog) and the contexts' progress
    me: Weak<Inner>,
    state: Mutex<State>,
    /// a run finished, the queue moved (wait_idle, shutdown)
    idle: Condvar,
    /// a stop deadline added (the watchdog)
    watch: Condvar,
}

/// The asset's command manager. Dropping it tells running handlers to stop and starts nothing
/// more; it does not wait for them (a handler that ignores being told keeps its thread).
pub struct CommandManager {
    inner: Arc<Inner>,
}

type Refusal = Option<(Completion, String)>;

impl CommandManager {
    /// Err for a window, limit or stop bound of 0.
    pub fn new(
        tables: Arc<Tables>,
        handlers: Arc<dyn Handlers>,
        out: Arc<dyn Outbox>,
        options: Options,
    ) -> Result<CommandManager, String> {
        if options.window < 1 {
            return Err(format!("command window {}: at least 1", options.window));
        }
        if options.queue_limit < 1 || options.bypass_limit < 1 {
            return Err(format!(
                "queue limit {}, bypass limit {}: at least 1 each",
                options.queue_limit, options.bypass_limit
            ));
        }
        if options.stop_timeout_ms < 1 {
            return Err(format!("stop timeout {} ms: at least 1", options.stop_timeout_ms));
        }
        let has_queue = tables.has_type("Queue");
        let has_control = tables.has_type("AccessControl");
        let state = State {
            runs: HashMap::new(),
            next_run: 1,
            next_ctx: 1,
            seen: HashMap::new(),
            seen_order: VecDeque::new(),
            acked: VecDeque::new(),
            pending: VecDeque::new(),
            active: None,
            bypass: Vec::new(),
            completed: VecDeque::new(),
            suspended: false,
            control: Control::default(),
            shutdown_after: None,
            journal: options.journal,
            outgoing: Vec::new(),
            stopping: HashSet::new(),
            watchdog: false,
            closing: false,
            handlers_running: 0,
        };
        let manager = CommandManager {
            inner: Arc::new_cyclic(|me| Inner {
                me: me.clone(),
                tables,
                handlers,
                out,
                window: options.window,
                queue_limit: options.queue_limit,
                bypass_limit: options.bypass_limit,
                stop_timeout_ms: options.stop_timeout_ms,
                shutdown_timeout_ms: options.shutdown_timeout_ms,
                on_shutdown: options.on_shutdown,
                has_queue,
                has_control,
                #[cfg(feature = "test-breaks")]
                breaks: options.breaks,
                state: Mutex::new(state),
                idle: Condvar::new(),
                watch: Condvar::new(),
            }),
        };
        #[cfg(feature = "test-breaks")]
        if manager.inner.breaks.on("queue-lifo") {
            let weak = manager.inner.weak();
            let _ = thread::Builder::new().name("rapid-lifo-tick".into()).spawn(move || loop {
                thread::sleep(Duration::from_millis(100));
                let Some(inner) = weak.upgrade() else { return };
                let mut st = inner.lock();
                if st.closing {
                    return;
                }
                inner.lifo_tick(&mut st);
                inner.flush(&mut st);
            });
        }
        Ok(manager)
    }

    pub fn tables(&self) -> &Tables {
        &self.inner.tables
    }

    /// A Command read from the asset's partition.
    pub fn receive(&self, cmd: Cmd) {
        let inner = &self.inner;
        let mut st = inner.lock();
        inner.receive(&mut st, cmd);
        inner.flush(&mut st);
    }

    /// Answer a command shed at the door COMPLETED/EXEC_FAILED without running it or
    /// remembering its id (it may be sent again). Not answered: another asset's, an empty id,
    /// or the id of a command seen or live (its acks are that command's).
    pub fn refuse(&self, cmd: Cmd, why: &str) {
        let inner = &self.inner;
        let mut st = inner.lock();
        if cmd.asset_name != inner.tables.name || cmd.cmd_id.is_empty() {
            return;
        }
        if st.seen.contains_key(&cmd.cmd_id) || st.live(&cmd.cmd_id) {
            return;
        }
        inner.ack(&mut st, &Arc::new(cmd), AckStatus::Completed, Completion::ExecFailed, why, false);
        inner.flush(&mut st);
    }

    /// Publish QueueState and AccessControlState as they are (at start-up).
    pub fn publish_states(&self) {
        let inner = &self.inner;
        let mut st = inner.lock();
        inner.publish_queue(&mut st);
        if inner.has_control {
            inner.publish_access(&mut st);
        }
        inner.flush(&mut st);
    }

    /// After a crash (the journal's recovery): answer what was accepted and not finished (never
    /// run again), write the last outcomes' final acks again, remember their cmdIds. Before the
    /// first command is read. Returns (commands answered now, final acks written again).
    pub fn restore(&self, recovered: &Recovered) -> (usize, usize) {
        let inner = &self.inner;
        let mut st = inner.lock();
        for e in &recovered.finished {
            let key = Arc::new(entry_cmd(e));
            let completion = Completion::from_name(&e.completion).unwrap_or(Completion::ExecFailed);
            st.remember(&e.cmd_id, inner.window);
            st.answered(Final { key: key.clone(), completion, message: e.message.clone() });
            st.outgoing.push(Write::Ack(key.clone(), AckStatus::Completed, completion, e.message.clone()));
            inner.keep(&mut st, key);
        }
        for e in &recovered.unfinished {
            st.remember(&e.cmd_id, inner.window);
            let (completion, why) = if e.state == 'q' {
                (Completion::Canceled, texts::RESTARTED_QUEUED)
            } else {
                (Completion::ExecFailed, texts::RESTARTED_RUNNING)
            };
            inner.ack(&mut st, &Arc::new(entry_cmd(e)), AckStatus::Completed, completion, why, true);
        }
        inner.flush(&mut st);
        (recovered.unfinished.len(), recovered.finished.len())
    }

    /// The asset shuts down (Admin/shutdown, a signal): nothing starts any more; every pending
    /// command is answered COMPLETED/CANCELED "asset shutting down", every running handler told
    /// to stop; they get up to `timeout` to return (their own outcome), then each one still
    /// running is answered EXEC_FAILED "handler did not stop" (its thread ends with the
    /// process). None: the options' bound. Returns (commands in flight at the start, handlers
    /// that did not stop).
    pub fn shutdown(&self, timeout: Option<Duration>) -> (usize, usize) {
        let inner = &self.inner;
        let timeout = timeout.unwrap_or(Duration::from_millis(inner.shutdown_timeout_ms));
        let end = Instant::now() + timeout;
        let mut st = inner.lock();
        st.closing = true;
        let mut runs: Vec<RunId> = st.pending.iter().copied().collect();
        runs.extend(st.active);
        runs.extend(st.bypass.iter().copied());
        while let Some(id) = st.pending.pop_front() {
            let cmd = st.runs[&id].cmd.clone();
            st.run(id).done = true;
            inner.ack(&mut st, &cmd, AckStatus::Completed, Completion::Canceled, texts::ASSET_SHUTTING_DOWN, true);
            inner.record_done(&mut st, &cmd, Completion::Canceled);
            st.forget_if_finished(id);
        }
        for id in st.active.iter().chain(st.bypass.iter()).copied().collect::<Vec<_>>() {
            let run = st.run(id);
            run.requeue = false;
            if let Some(ctx) = &run.ctx {
                ctx.cancel(); // told to stop; the shutdown's bound, not the command's
            }
        }
        inner.publish_queue(&mut st);
        inner.flush(&mut st);
        let unfinished = |st: &State| runs.iter().any(|id| st.runs.get(id).is_some_and(|r| r.running && !r.done));
        while unfinished(&st) {
            let now = Instant::now();
            if now >= end {
                break;
            }
            st = inner.idle.wait_timeout(st, (end - now).min(Duration::from_millis(50))).unwrap_or_else(|e| e.into_inner()).0;
        }
        let stuck: Vec<RunId> = runs.iter().copied().filter(|id| st.runs.get(id).is_some_and(|r| !r.done)).collect();
        for &id in &stuck {
            st.bypass.retain(|b| *b != id);
            let what = inner.what(&st, id);
            st.outgoing.push(Write::Log(format!(
                "{what}: handler did not stop within the shutdown bound ({} ms); answered EXEC_FAILED \"{}\"; the robot must stop it in hardware",
                timeout.as_millis(),
                texts::DID_NOT_STOP
            )));
            inner.complete(&mut st, id, Completion::ExecFailed, texts::DID_NOT_STOP, false);
        }
        st.active = None;
        st.bypass.clear();
        inner.publish_queue(&mut st);
        inner.idle.notify_all();
        inner.flush(&mut st);
        (runs.len(), stuck.len())
    }

    /// Answer every pending and running command now, not waiting for any handler.
    pub fn abandon(&self) -> usize {
        self.shutdown(Some(Duration::ZERO)).0
    }

    /// A config serial issued after the start (a republished config): in the journal, synced,
    /// before the config goes out (a restart's serials come back above it).
    pub fn journal_serial(&self, serial: i64) {
        let mut st = self.inner.lock();
        if let Some(j) = st.journal.as_mut() {
            j.serial(serial);
            j.sync();
        }
    }

    /// No journal from now on (the bridge closes it, or a test drops it as a crash would);
    /// returns the one there was.
    pub fn release_journal(&self) -> Option<Journal> {
        let inner = &self.inner;
        let mut st = inner.lock();
        inner.flush(&mut st);
        st.journal.take()
    }

    /// True once no queued or bypass command runs, or the queue is suspended with nothing running.
    pub fn wait_idle(&self, timeout: Duration) -> bool {
        let inner = &self.inner;
        let end = Instant::now() + timeout;
        let mut st = inner.lock();
        while st.active.is_some() || !st.bypass.is_empty() || (!st.pending.is_empty() && !st.closing) {
            let now = Instant::now();
            if now >= end || (st.suspended && st.active.is_none() && st.bypass.is_empty()) {
                return st.active.is_none() && st.bypass.is_empty();
            }
            st = inner.idle.wait_timeout(st, (end - now).min(Duration::from_millis(50))).unwrap_or_else(|e| e.into_inner()).0;
        }
        true
    }

    /// The queue's pending commands, front first (tests).
    pub fn pending_ids(&self) -> Vec<String> {
        let st = self.inner.lock();
        st.pending.iter().map(|id| st.runs[id].cmd.cmd_id.clone()).collect()
    }

    pub fn suspended(&self) -> bool {
        self.inner.lock().suspended
    }

    pub fn controller(&self) -> String {
        self.inner.lock().control.controller.clone()
    }

    /// Handler calls made and not returned, answered or not (threads a stop leaves behind).
    pub fn handlers_running(&self) -> usize {
        self.inner.lock().handlers_running
    }

    /// cmdIds in the duplicate window.
    pub fn remembered(&self) -> usize {
        self.inner.lock().seen.len()
    }
}

impl Drop for CommandManager {
    fn drop(&mut self) {
        let mut st = self.inner.lock();
        st.closing = true;
        st.suspended = true;
        for id in st.active.iter().chain(st.bypass.iter()) {
            if let Some(ctx) = st.runs.get(id).and_then(|r| r.ctx.as_ref()) {
                ctx.cancel();
            }
        }
        drop(st);
        self.inner.watch.notify_all();
    }
}

impl State {
    fn run(&mut self, id: RunId) -> &mut Run {
        self.runs.get_mut(&id).expect("a run the manager holds")
    }

    fn remember(&mut self, cmd_id: &str, window: usize) {
        if self.seen.contains_key(cmd_id) {
            return; // it keeps its place
        }
        self.seen.insert(cmd_id.to_string(), None);
        self.seen_order.push_back(cmd_id.to_string());
        while self.seen_order.len() > window {
            if let Some(old) = self.seen_order.pop_front() {
                self.seen.remove(&old);
            }
        }
    }

    /// The cmdId's final outcome (when the id is still among the remembered).
    fn answered(&mut self, f: Final) {
        if let Some(slot) = self.seen.get_mut(&f.key.cmd_id) {
            *slot = Some(f);
        }
    }

    fn queued_run(&self, cmd_id: &str) -> Option<RunId> {
        if let Some(a) = self.active {
            if self.runs[&a].cmd.cmd_id == cmd_id {
                return Some(a);
            }
        }
        self.pending.iter().copied().find(|id| self.runs[id].cmd.cmd_id == cmd_id)
    }

    fn bypass_run(&self, cmd_id: &str) -> Option<RunId> {
        self.bypass.iter().copied().find(|id| self.runs[id].cmd.cmd_id == cmd_id)
    }

    /// A command of that id is pending or running (however many came after it).
    fn live(&self, cmd_id: &str) -> bool {
        self.queued_run(cmd_id).is_some() || self.bypass_run(cmd_id).is_some()
    }

    fn busy(&self, subsystem: &str) -> bool {
        self.bypass.iter().any(|id| {
            let r = &self.runs[id];
            r.cmd.subsystem == subsystem && !r.done
        })
    }

    /// A run answered and whose handler has returned is let go (its id may still be named in
    /// a stopAllMotion's list: a missing run counts as stopped).
    fn forget_if_finished(&mut self, id: RunId) {
        if self.runs.get(&id).is_some_and(|r| r.done && !r.running)
            && self.active != Some(id)
            && !self.bypass.contains(&id)
            && !self.pending.contains(&id)
        {
            self.runs.remove(&id);
        }
    }
}

fn entry_cmd(e: &JournalEntry) -> Cmd {
    Cmd {
        cmd_id: e.cmd_id.clone(),
        src_name: e.src_name.clone(),
        asset_name: e.asset_name.clone(),
        serial: e.serial as i32,
        ..Cmd::default()
    }
}

fn panic_text(payload: &(dyn std::any::Any + Send)) -> Option<String> {
    if let Some(s) = payload.downcast_ref::<&str>() {
        Some(s.to_string())
    } else {
        payload.downcast_ref::<String>().cloned()
    }
}

impl Inner {
    fn lock(&self) -> MutexGuard<'_, State> {
        // a panic under the lock is the runtime's bug; the state is still the best there is
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    // ---- the end of a locked operation: the journal synced, then what it promised -----------

    fn flush(&self, st: &mut State) {
        // (a write may add writes: a handler with no thread to run on is answered at once)
        while !st.outgoing.is_empty() {
            if let Some(j) = st.journal.as_mut() {
                j.sync(); // a failure is logged once; the answers go out all the same
            }
            for write in std::mem::take(&mut st.outgoing) {
                match write {
                    Write::Ack(cmd, status, completion, message) => {
                        // a write that fails is said: the command's state moves on all the same
                        // (a lost ack must not leave the queue stuck)
                        let wrote = catch_unwind(AssertUnwindSafe(|| self.out.ack(&cmd, status, completion, &message)));
                        if wrote.is_err() {
                            self.out.log(&format!(
                                "{} ack of {} not written: the outbox panicked",
                                status.name(),
                                py_string(&cmd.cmd_id)
                            ));
                        }
                    }
                    Write::Queue(code, p, a, c) => self.out.queue_state(code, &p, &a, &c),
                    Write::Access(controller, requestors) => self.out.access_state(&controller, &requestors),
                    Write::Retire(cmd) => self.out.retire(&cmd),
                    Write::Log(text) => self.out.log(&text),
                    Write::Start(id, ctx) => {
                        let Some(me) = self.me.upgrade() else { continue };
                        let name = format!("cmd-{}", ctx.cmd().cmd_id.chars().take(20).collect::<String>());
                        if let Err(e) = thread::Builder::new().name(name).spawn(move || me.execute(id, ctx)) {
                            // no thread to be had: the command fails, the asset runs on
                            self.log(st, format!("no thread for a handler: {e}"));
                            st.run(id).running = false;
                            st.handlers_running -= 1;
                            st.bypass.retain(|b| *b != id);
                            self.complete(st, id, Completion::ExecFailed, texts::FAILED, true);
                            self.service(st);
                        }
                    }
                    Write::OnShutdown => {
                        if let Some(f) = self.on_shutdown.clone() {
                            let _ = thread::Builder::new().name("shutdown".into()).spawn(move || f());
                        }
                    }
                }
            }
        }
    }

    fn log(&self, st: &mut State, text: String) {
        st.outgoing.push(Write::Log(text));
    }


    // ---- intake ----------------------------------------------------------------------------

    fn receive(&self, st: &mut State, cmd: Cmd) {
        if cmd.asset_name != self.tables.name {
            self.log(st, format!("ignored {}: addressed to asset {}", py_string(&cmd.cmd_id), py_string(&cmd.asset_name)));
            return;
        }
        let id = cmd.cmd_id.clone();
        if (st.seen.contains_key(&id) && !broken!(self, "no-dedup")) || st.live(&id) {
            let live = st.live(&id);
            let final_ = st.seen.get(&id).cloned().flatten();
            match final_ {
                Some(f) if f.key.src_name == cmd.src_name && !live => {
                    // answered already: nothing runs; the stored final ack is written again
                    st.outgoing.push(Write::Ack(f.key.clone(), AckStatus::Completed, f.completion, f.message.clone()));
                    self.log(st, format!("{} sent again: answered already, its final ack written again", py_string(&id)));
                }
                _ => self.log(st, format!("ignored {}: repeated cmdId", py_string(&id))),
            }
            return;
        }
        st.remember(&id, self.window);
        let cmd = Arc::new(cmd);
        if let Some((completion, text)) = self.intake(st, &cmd) {
            self.ack(st, &cmd, AckStatus::Completed, completion, &text, true);
            let kind = completion.name().trim_start_matches("ACK_COMPLETED_");
            self.log(st, format!("{}: {kind}: {text}", visible(&id, 200)));
        }
    }

    /// Checks then dispatch; Some((completion, message)) when the command ends here.
    fn intake(&self, st: &mut State, cmd: &Arc<Cmd>) -> Refusal {
        if broken!(self, "append-target-ignored") && cmd.action == QueueAction::Append && !cmd.target.is_empty() {
            let untargeted = Cmd { target: String::new(), ..(**cmd).clone() };
            return self.intake(st, &Arc::new(untargeted));
        }
        if cmd.cmd_id.is_empty() {
            return Some((Completion::BadSyntax, texts::EMPTY_CMD_ID.into()));
        }
        let (action, target) = (cmd.action, cmd.target.as_str());
        let Some(act) = action.name() else {
            return Some((Completion::BadSyntax, texts::unknown_queue_action(&action.wire().to_string())));
        };
        if action != QueueAction::Bypass && !self.has_queue {
            return Some((Completion::BadSyntax, texts::no_queue(act)));
        }
        let targeted = matches!(action, QueueAction::Insert | QueueAction::Replace | QueueAction::Delete);
        if !targeted && !target.is_empty() {
            return Some((Completion::BadSyntax, texts::target_not_taken(act, &short(target))));
        }
        if targeted && target.is_empty() {
            return Some((Completion::BadSyntax, texts::target_needed(act)));
        }
        if action == QueueAction::Delete {
            return self.delete(st, cmd);
        }
        let r = match check_command(cmd, &self.tables) {
            Ok(r) => r,
            Err(why) => return Some((Completion::BadSyntax, why)),
        };
        if action == QueueAction::Insert && target != HEAD && st.queued_run(target).is_none() {
            return Some((Completion::BadSyntax, texts::unknown_insert_target(&short(target))));
        }
        if action == QueueAction::Replace && st.queued_run(target).is_none() {
            return Some((Completion::BadSyntax, texts::unknown_target(&short(target))));
        }
        if let Some(denied) = self.authorize(st, &cmd.cmd_src, &cmd.subsystem, r) {
            return Some((Completion::BadSyntax, denied));
        }
        if matches!(action, QueueAction::Append | QueueAction::Insert) && st.pending.len() >= self.queue_limit {
            return Some((Completion::ExecFailed, texts::queue_full(self.queue_limit)));
        }
        if action == QueueAction::Bypass && st.bypass.len() >= self.bypass_limit {
            return Some((Completion::ExecFailed, texts::bypass_full(self.bypass_limit)));
        }
        if st.closing {
            // the asset is stopping: nothing new starts or waits
            return Some((Completion::ExecFailed, texts::ASSET_SHUTTING_DOWN.into()));
        }
        let run = Run {
            cmd: cmd.clone(),
            r,
            queued: action != QueueAction::Bypass,
            ctx: None,
            requeue: false,
            done: false,
            record_status: RecordStatus::Inline,
            running: false,
            stop_by: None,
            stopped: Vec::new(),
        };
        if action == QueueAction::Replace {
            let old = st.queued_run(target).expect("checked above, under the same lock");
            if st.active == Some(old) && !self.abortable(&st.runs[&old]) {
                return Some((Completion::ExecFailed, texts::target_not_abortable(&short(target))));
            }
        }
        let id = st.next_run;
        st.next_run += 1;
        st.runs.insert(id, run);
        match action {
            QueueAction::Bypass => {
                self.start(st, id);
                return None;
            }
            QueueAction::Replace => {
                let old = st.queued_run(target).expect("checked above");
                if st.active == Some(old) {
                    self.cancel(st, old);
                    st.pending.push_front(id);
                } else if broken!(self, "replace-at-back") {
                    st.pending.retain(|p| *p != old);
                    st.pending.push_back(id);
                    self.finish_unstarted(st, old, &texts::replaced_by(&short(&cmd.cmd_id)));
                } else {
                    let at = st.pending.iter().position(|p| *p == old).expect("pending");
                    st.pending[at] = id;
                    self.finish_unstarted(st, old, &texts::replaced_by(&short(&cmd.cmd_id)));
                }
            }
            QueueAction::Insert if broken!(self, "insert-at-back") => st.pending.push_back(id),
            QueueAction::Insert => {
                let at = if target == HEAD {
                    Some(0)
                } else {
                    st.pending.iter().position(|p| st.runs[p].cmd.cmd_id == target).map(|i| i + 1)
                };
                // (after the running command: next)
                st.pending.insert(at.unwrap_or(0), id);
            }
            _ => st.pending.push_back(id),
        }
        self.ack(st, cmd, AckStatus::Queued, Completion::Not, "", true);
        self.service(st);
        None
    }

    /// Why the source may not send this command, or None. Allow-list, then control.
    fn authorize(&self, st: &State, source: &str, subsystem: &str, r: CommandRef) -> Option<String> {
        let type_name = self.tables.type_name(r);
        let name = &self.tables.spec(r).name;
        if access::always_allowed(type_name, name) && !broken!(self, "stop-needs-control") {
            return None;
        }
        if !access::allowed(self.tables.access.as_ref(), source, subsystem, name) && !broken!(self, "allow-list-ignored") {
            return Some(texts::access_not_allowed(&short(source), &short(subsystem), &short(name)));
        }
        let holds = st.control.holds(source) || broken!(self, held_once(source));
        if self.has_control && !broken!(self, "no-control-gate") && type_name != "AccessControl" && source != self.tables.name && !holds {
            return Some(texts::access_no_control(&short(source)));
        }
        None
    }

    fn abortable(&self, run: &Run) -> bool {
        self.tables.spec(run.r).abortable
    }

    fn delete(&self, st: &mut State, cmd: &Arc<Cmd>) -> Refusal {
        if broken!(self, "delete-wrong-command") && st.queued_run(&cmd.target).is_some() {
            // the running command canceled instead of the pending one named
            if let Some(active) = st.active.map(|a| st.runs[&a].cmd.cmd_id.clone()).filter(|a| *a != cmd.target) {
                return self.delete(st, &Arc::new(Cmd { target: active, ..(**cmd).clone() }));
            }
        }
        let Some(target) = st.queued_run(&cmd.target).or_else(|| st.bypass_run(&cmd.target)) else {
            return Some((Completion::BadSyntax, texts::unknown_target(&short(&cmd.target))));
        };
        // the DELETE's sender must be allowed to send the target's command
        let (subsystem, r) = (st.runs[&target].cmd.subsystem.clone(), st.runs[&target].r);
        if let Some(denied) = self.authorize(st, &cmd.cmd_src, &subsystem, r) {
            return Some((Completion::BadSyntax, denied));
        }
        let said = if let Some(at) = st.pending.iter().position(|p| *p == target) {
            st.pending.remove(at);
            self.finish_unstarted(st, target, &texts::deleted_by(&short(&cmd.cmd_id)));
            texts::target_canceled(&short(&cmd.target))
        } else if !self.abortable(&st.runs[&target]) {
            return Some((Completion::ExecFailed, texts::target_not_abortable(&short(&cmd.target))));
        } else {
            // its own final ack follows when its handler returns, or at its stop bound
            self.cancel(st, target);
            texts::cancel_requested(&short(&cmd.target))
        };
        self.ack(st, cmd, AckStatus::Executing, Completion::Not, "", true);
        self.ack(st, cmd, AckStatus::Completed, Completion::Ok, &said, true);
        self.service(st);
        None
    }

    // ---- running ---------------------------------------------------------------------------

    /// Start the queue's front command when nothing queued runs and the queue is not suspended.
    fn service(&self, st: &mut State) {
        self.start_next(st);
        self.publish_queue(st);
        self.idle.notify_all();
    }

    fn start_next(&self, st: &mut State) {
        if broken!(self, "queue-parallel") {
            // each waiting command started at once, none waiting for the one before; kept among
            // the bypass commands, where cancelAll and stopAllMotion still reach it
            while !st.suspended && !st.closing {
                let Some(id) = st.pending.pop_front() else { break };
                st.active = Some(id);
                self.start(st, id);
                if !st.runs.get(&id).is_none_or(|r| r.done) && !st.bypass.contains(&id) {
                    st.bypass.push(id);
                }
            }
            return;
        }
        if broken!(self, "queue-lifo") {
            return; // lifo_tick starts them
        }
        while st.active.is_none() && !st.suspended && !st.closing {
            // the queue runs in order: a front command whose subsystem a bypass command holds waits, and all behind it
            let Some(&front) = st.pending.front() else { break };
            if st.busy(&st.runs[&front].cmd.subsystem) {
                break;
            }
            st.pending.pop_front();
            st.active = Some(front);
            self.start(st, front);
        }
    }

    /// queue-lifo: soraCore's 10 Hz executive tick, serving the newest waiting command first.
    #[cfg(feature = "test-breaks")]
    fn lifo_tick(&self, st: &mut State) {
        while st.active.is_none() && !st.suspended && !st.closing {
            let Some(&back) = st.pending.back() else { break };
            if st.busy(&st.runs[&back].cmd.subsystem) {
                break;
            }
            st.pending.pop_back();
            st.active = Some(back);
            self.start(st, back);
        }
        self.publish_queue(st);
        self.idle.notify_all();
    }

    fn builtin(&self, run: &Run) -> Option<Builtin> {
        let spec = self.tables.spec(run.r);
        if !spec.standard {
            return None;
        }
        builtin_of(self.tables.type_name(run.r), &spec.name)
    }

    fn start(&self, st: &mut State, id: RunId) {
        let (cmd, queued) = (st.runs[&id].cmd.clone(), st.runs[&id].queued);
        let builtin = self.builtin(&st.runs[&id]);
        if !queued {
            self.preempt(st, id);
        }
        self.ack(st, &cmd, AckStatus::Executing, Completion::Not, "", true);
        st.run(id).record_status = RecordStatus::InProcess;
        if let Some(b) = builtin {
            let outcome = self.run_builtin(st, id, b);
            if !queued && matches!(b, Builtin::CancelAll | Builtin::StopAllMotion) {
                self.publish_queue(st); // the queue changed (a queued one: service() publishes it)
            }
            if let Some((completion, message)) = outcome {
                self.complete(st, id, completion, &message, true);
                return;
            }
        }
        if !queued {
            st.bypass.push(id);
        }
        let serial = st.next_ctx;
        st.next_ctx += 1;
        let weak: Weak<Inner> = self.weak();
        let progress = Box::new(move |text: &str| {
            if let Some(inner) = weak.upgrade() {
                inner.progress(id, serial, text);
            }
        });
        let r = st.runs[&id].r;
        let ctx = Arc::new(Context::new(
            cmd,
            self.tables.spec(r).clone(),
            self.tables.type_name(r).to_string(),
            serial,
            progress,
        ));
        let run = st.run(id);
        run.ctx = Some(ctx.clone());
        run.running = true;
        st.handlers_running += 1;
        st.outgoing.push(Write::Start(id, ctx));
    }

    fn weak(&self) -> Weak<Inner> {
        self.me.clone()
    }

    /// A BYPASS command takes its subsystem over: a suspendable command running there from the
    /// queue is requeued, an abortable one canceled; others keep running beside it.
    fn preempt(&self, st: &mut State, id: RunId) {
        if self.builtin(&st.runs[&id]).is_some() {
            return; // the protocol's own commands take nothing over
        }
        let subsystem = st.runs[&id].cmd.subsystem.clone();
        let others: Vec<RunId> = st.active.iter().chain(st.bypass.iter()).copied().collect();
        for other in others {
            let o = &st.runs[&other];
            if o.done || o.cmd.subsystem != subsystem || o.ctx.is_none() {
                continue;
            }
            if o.queued && self.tables.spec(o.r).suspendable {
                self.tell_stop(st, other);
                st.run(other).requeue = true;
            } else if self.abortable(o) {
                self.tell_stop(st, other);
            }
        }
    }

    /// A handler's thread.
    fn execute(self: Arc<Self>, id: RunId, ctx: Arc<Context>) {
        let handlers = self.handlers.clone();
        let result = catch_unwind(AssertUnwindSafe(|| handlers.execute(&ctx)));
        let mut panicked = None;
        let mut unwritten = false;
        let (completion, message) = match result {
            Ok(Outcome::Ok(text)) if !ctx.cancelled() => (Completion::Ok, text),
            Ok(Outcome::Ok(_)) | Ok(Outcome::Canceled) => (Completion::Canceled, texts::CANCELED.into()),
            Ok(Outcome::Failed(why)) => (Completion::ExecFailed, if why.is_empty() { texts::FAILED.into() } else { why }),
            Ok(Outcome::BadSyntax(why)) => (Completion::BadSyntax, if why.is_empty() { texts::FAILED.into() } else { why }),
            Ok(Outcome::NotImplemented) => {
                unwritten = true;
                (Completion::ExecFailed, texts::NOT_IMPLEMENTED.into())
            }
            Err(payload) => {
                let text = panic_text(payload.as_ref());
                panicked = Some(text.clone().unwrap_or_else(|| "unknown panic payload".into()));
                match text {
                    Some(t) => (Completion::ExecFailed, texts::handler_error("panic", &t)),
                    None => (Completion::ExecFailed, texts::HANDLER_ERROR_UNKNOWN.into()),
                }
            }
        };
        let mut st = self.lock();
        st.handlers_running -= 1;
        st.stopping.remove(&id);
        st.bypass.retain(|b| *b != id);
        let Some(run) = st.runs.get_mut(&id) else { return };
        run.running = false;
        self.idle.notify_all();
        if let Some(text) = panicked {
            let what = self.what(&st, id);
            self.log(&mut st, format!("{what}: handler panicked: {}", visible(&text, 300)));
        }
        if st.runs[&id].done {
            // answered already (its stop bound, the asset stopping): nothing follows a COMPLETED
            st.forget_if_finished(id);
            self.flush(&mut st);
            return;
        }
        let (mut completion, mut message) = (completion, message);
        if self.builtin(&st.runs[&id]) == Some(Builtin::StopAllMotion) {
            // the runtime has canceled the motion commands; the handler stops the hardware
            if unwritten {
                completion = Completion::Ok;
                message = texts::NO_HARDWARE_STOP.into();
            }
            let left = st.runs[&id]
                .stopped
                .iter()
                .filter(|o| st.runs.get(o).is_some_and(|r| r.running && !r.done))
                .count();
            if left > 0 {
                let parts: Vec<String> =
                    [message, texts::motion_not_stopped(left)].into_iter().filter(|p| !p.is_empty()).collect();
                message = parts.join("; ");
            }
        }
        if st.runs[&id].requeue && completion == Completion::Canceled && !st.closing {
            let cmd = st.runs[&id].cmd.clone();
            let run = st.run(id);
            run.requeue = false;
            run.ctx = None;
            run.stop_by = None;
            ctx.close();
            self.ack(&mut st, &cmd, AckStatus::Requeued, Completion::Not, texts::PREEMPTED, true);
            st.run(id).record_status = RecordStatus::Paused;
            if st.active == Some(id) {
                st.active = None;
            }
            st.pending.push_front(id);
        } else {
            self.complete(&mut st, id, completion, &message, true);
        }
        if broken!(self, "queue-state-stale") {
            // the handler's completion publishes nothing: the finished command stays listed
            self.start_next(&mut st);
            self.idle.notify_all();
        } else {
            self.service(&mut st);
        }
        self.flush(&mut st);
    }

    /// ctx.progress: nothing once the command is done, or from the context of an earlier run
    /// of a requeued command (a helper thread left behind).
    fn progress(&self, id: RunId, serial: u64, text: &str) {
        let mut st = self.lock();
        let Some(run) = st.runs.get(&id) else { return };
        if run.done || !run.running || run.ctx.as_ref().map(|c| c.serial) != Some(serial) {
            return;
        }
        let cmd = run.cmd.clone();
        self.ack(&mut st, &cmd, AckStatus::Executing, Completion::Not, text, true);
        self.flush(&mut st);
    }

    fn complete(&self, st: &mut State, id: RunId, completion: Completion, message: &str, suspend: bool) {
        let run = st.run(id);
        run.done = true;
        if let Some(ctx) = &run.ctx {
            ctx.close(); // calls on it from now on are no-ops
        }
        let (cmd, queued) = (run.cmd.clone(), run.queued);
        st.stopping.remove(&id);
        self.ack(st, &cmd, AckStatus::Completed, completion, message, true);
        if st.shutdown_after == Some(id) {
            st.outgoing.push(Write::OnShutdown); // once its COMPLETED ack is written
        }
        if queued {
            if st.active == Some(id) {
                st.active = None;
            }
            self.record_done(st, &cmd, completion);
            if completion == Completion::ExecFailed && suspend && !st.closing {
                st.suspended = true; // a failed step stops the plan; Queue/cancelAll resumes
            }
        }
        self.idle.notify_all();
        st.forget_if_finished(id);
    }

    /// A pending command removed before it ran (DELETE, REPLACE, cancelAll, stopAllMotion).
    fn finish_unstarted(&self, st: &mut State, id: RunId, why: &str) {
        st.run(id).done = true;
        let cmd = st.runs[&id].cmd.clone();
        self.ack(st, &cmd, AckStatus::Completed, Completion::Canceled, why, true);
        self.record_done(st, &cmd, Completion::Canceled);
        st.forget_if_finished(id);
    }

    fn record_done(&self, st: &mut State, cmd: &Arc<Cmd>, completion: Completion) {
        st.completed.push_back((Instant::now(), cmd.clone(), completion));
        while st.completed.len() > RECORDS {
            st.completed.pop_front();
        }
    }

    fn cancel(&self, st: &mut State, id: RunId) {
        if st.runs[&id].ctx.is_some() {
            st.run(id).requeue = false;
            self.tell_stop(st, id);
        }
    }

    // ---- told to stop: the stop bound ------------------------------------------------------

    fn bound_ms(&self, run: &Run) -> u64 {
        match self.tables.spec(run.r).stop_timeout_ms {
            0 => self.stop_timeout_ms,
            declared => declared,
        }
    }

    /// Tell a running handler to stop and start its stop bound: if it has not returned by then,
    /// the watchdog answers the command. Told again: the first deadline stays.
    fn tell_stop(&self, st: &mut State, id: RunId) {
        let bound = self.bound_ms(&st.runs[&id]);
        let run = st.run(id);
        let Some(ctx) = &run.ctx else { return };
        if run.done {
            return;
        }
        ctx.cancel();
        if !run.running || run.stop_by.is_some() {
            return;
        }
        run.stop_by = Some(Instant::now() + Duration::from_millis(bound));
        st.stopping.insert(id);
        if !st.watchdog {
            st.watchdog = true;
            if let Some(me) = self.me.upgrade() {
                let spawned = thread::Builder::new().name("rapid-stop-bound".into()).spawn(move || me.watch_loop());
                if spawned.is_err() {
                    st.watchdog = false;
                }
            }
        }
        self.watch.notify_all();
    }

    /// The one watchdog thread: sleeps until the earliest stop deadline, answers what is
    /// overdue; ends when no handler is being stopped (the next tell_stop makes another).
    fn watch_loop(self: Arc<Self>) {
        let mut st = self.lock();
        loop {
            let now = Instant::now();
            let mut due: Vec<(Instant, RunId)> = st
                .stopping
                .iter()
                .filter_map(|id| st.runs.get(id).and_then(|r| r.stop_by).map(|t| (t, *id)))
                .filter(|(t, _)| *t <= now)
                .collect();
            if !due.is_empty() {
                due.sort();
                for (_, id) in due {
                    self.overdue(&mut st, id);
                }
                self.flush(&mut st);
                continue;
            }
            let nearest = st.stopping.iter().filter_map(|id| st.runs.get(id).and_then(|r| r.stop_by)).min();
            let Some(nearest) = nearest else {
                st.watchdog = false;
                return;
            };
            st = self.watch.wait_timeout(st, nearest.saturating_duration_since(now).max(Duration::from_millis(1)))
                .unwrap_or_else(|e| e.into_inner())
                .0;
        }
    }

    /// A told-to-stop handler still running at its bound: the command's final ack now, its
    /// place in the queue freed; the handler's later return is ignored.
    fn overdue(&self, st: &mut State, id: RunId) {
        st.stopping.remove(&id);
        let Some(run) = st.runs.get_mut(&id) else { return };
        if run.done || !run.running {
            return;
        }
        run.requeue = false;
        let bound = self.bound_ms(&st.runs[&id]);
        st.bypass.retain(|b| *b != id);
        let what = self.what(st, id);
        self.log(st, format!(
            "{what}: handler did not stop within {bound} ms of being told to; answered EXEC_FAILED \"{}\"; the robot must stop it in hardware",
            texts::DID_NOT_STOP
        ));
        self.complete(st, id, Completion::ExecFailed, texts::DID_NOT_STOP, false);
        self.service(st);
    }

    /// "cmdId: Subsystem/command" for logs.
    fn what(&self, st: &State, id: RunId) -> String {
        let run = &st.runs[&id];
        format!("{}: {}/{}", visible(&run.cmd.cmd_id, 200), visible(&run.cmd.subsystem, 200), self.tables.spec(run.r).name)
    }

    // ---- state topics ----------------------------------------------------------------------

    /// Every ack goes out here, its message made writable (outgoing(): no NUL, at most 127
    /// bytes), whoever wrote it. With a journal, the step the ack promises is recorded first.
    fn ack(&self, st: &mut State, cmd: &Arc<Cmd>, status: AckStatus, completion: Completion, message: &str, journal: bool) {
        let message = outgoing(message, MESSAGE_BYTES);
        if journal {
            if let Some(j) = st.journal.as_mut() {
                let step = match status {
                    AckStatus::Queued => Some('q'),
                    AckStatus::Executing => Some('x'),
                    AckStatus::Completed => Some('c'),
                    AckStatus::Requeued => None,
                };
                if let Some(step) = step {
                    let c = step == 'c';
                    j.note(JournalEntry {
                        cmd_id: cmd.cmd_id.clone(),
                        src_name: cmd.src_name.clone(),
                        asset_name: cmd.asset_name.clone(),
                        serial: cmd.serial as i64,
                        state: step,
                        completion: if c { completion.name().into() } else { String::new() },
                        message: if c { message.clone() } else { String::new() },
                    });
                }
            }
        }
        st.outgoing.push(Write::Ack(cmd.clone(), status, completion, message.clone()));
        if status == AckStatus::Completed {
            // each command's last ack: keep the last `window` commands' acks
            let key = Arc::new(cmd.key());
            self.keep(st, key.clone());
            st.answered(Final { key, completion, message }); // a resend of its cmdId gets this final ack again
        }
    }

    fn keep(&self, st: &mut State, key: Arc<Cmd>) {
        st.acked.push_back(key);
        while st.acked.len() > self.window {
            let Some(old) = st.acked.pop_front() else { break };
            if !st.live(&old.cmd_id) {
                // (its id sent again after the window and still running: its acks stay)
                st.outgoing.push(Write::Retire(old));
            }
        }
    }

    fn publish_queue(&self, st: &mut State) {
        if !self.has_queue {
            return;
        }
        let now = Instant::now();
        while st.completed.front().is_some_and(|(t, _, _)| now.duration_since(*t) > COMPLETED_KEEP) {
            st.completed.pop_front();
        }
        let record = |id: &RunId, status: RecordStatus| Record {
            cmd: st.runs[id].cmd.clone(),
            result: RecordResult::Init,
            status,
        };
        let pending: Vec<Record> =
            st.pending.iter().take(RECORDS).map(|id| record(id, st.runs[id].record_status)).collect();
        let active: Vec<Record> = st.active.iter().map(|id| record(id, RecordStatus::InProcess)).collect();
        let done: Vec<Record> = st
            .completed
            .iter()
            .map(|(_, cmd, c)| {
                let (result, status) = c.record();
                Record { cmd: cmd.clone(), result, status }
            })
            .collect();
        let code = if st.suspended {
            -1
        } else if st.active.is_some() {
            1
        } else {
            0
        };
        st.outgoing.push(Write::Queue(code, pending, active, done));
    }

    fn publish_access(&self, st: &mut State) {
        st.outgoing.push(Write::Access(st.control.controller.clone(), st.control.requestors.clone()));
    }

    // ---- built-in commands: the protocol's own ------------------------------------------------

    /// The outcome, or None to go on to the handler.
    fn run_builtin(&self, st: &mut State, id: RunId, b: Builtin) -> Refusal {
        let cmd = st.runs[&id].cmd.clone();
        match b {
            Builtin::Echo => Some((Completion::Ok, cmd.args.first().map(|v| v.str()).unwrap_or_default())),
            Builtin::NoOp => Some((Completion::Ok, String::new())),
            Builtin::Shutdown => {
                st.shutdown_after = Some(id); // once its COMPLETED ack is out
                Some((Completion::Ok, texts::SHUTTING_DOWN.into()))
            }
            Builtin::CancelAll => Some((Completion::Ok, self.cancel_all(st, id))),
            Builtin::StopAllMotion => {
                self.stop_all_motion(st, id);
                None // the handler then stops the hardware
            }
            Builtin::Control(op) => {
                let src = cmd.cmd_src.as_str();
                #[cfg(feature = "test-breaks")]
                if let Some(outcome) = self.broken_control(st, op, &cmd) {
                    return Some(outcome);
                }
                let done = match op {
                    ControlOp::Request => st.control.request(src),
                    ControlOp::Grab => st.control.grab(src),
                    ControlOp::Release => st.control.release(src),
                    ControlOp::Transfer => {
                        let new = cmd.args.first().map(|v| v.str()).unwrap_or_default();
                        st.control.transfer(src, &new)
                    }
                };
                #[cfg(feature = "test-breaks")]
                self.breaks.controller(&st.control.controller);
                match done {
                    Ok(note) => {
                        self.publish_access(st);
                        Some((Completion::Ok, note))
                    }
                    Err(why) => Some((Completion::ExecFailed, why)),
                }
            }
        }
    }

    fn cancel_all(&self, st: &mut State, id: RunId) -> String {
        while let Some(p) = st.pending.pop_front() {
            self.finish_unstarted(st, p, texts::CANCELED_BY_CANCEL_ALL);
        }
        let (mut kept, mut asked) = (0, 0);
        let running: Vec<RunId> = st.active.iter().chain(st.bypass.iter()).copied().collect();
        for r in running {
            if r == id || st.runs[&r].done {
                continue;
            }
            if self.abortable(&st.runs[&r]) {
                self.cancel(st, r);
                asked += 1;
            } else {
                kept += 1;
            }
        }
        st.suspended = false;
        let mut parts = Vec::new();
        if asked > 0 {
            parts.push(texts::handlers_asked_to_stop(asked));
        }
        if kept > 0 {
            parts.push(texts::non_abortable_running(kept));
        }
        parts.join("; ")
    }

    /// AccessControl's outcome when a break changes it (as the C++ runtime's broken_control).
    #[cfg(feature = "test-breaks")]
    fn broken_control(&self, st: &mut State, op: ControlOp, cmd: &Cmd) -> Refusal {
        let (b, src) = (&self.breaks, cmd.cmd_src.as_str());
        let (done, publish) = match op {
            ControlOp::Request if b.on("request-steals-control") || b.on("request-unpublished") => {
                let done = if b.on("request-steals-control") { st.control.grab(src) } else { st.control.request(src) };
                (done, !b.on("request-unpublished"))
            }
            ControlOp::Grab if b.on("grab-refused") || b.on("grab-unpublished") => {
                let holder = st.control.controller.clone();
                if b.on("grab-refused") && !holder.is_empty() && holder != src {
                    return Some((Completion::ExecFailed, format!("control is held by {holder}")));
                }
                (st.control.grab(src), !b.on("grab-unpublished"))
            }
            ControlOp::Release if b.on("release-by-anyone") || b.on("release-unpublished") => {
                // release-by-anyone: on behalf of whoever holds it
                let who = if b.on("release-by-anyone") { st.control.controller.clone() } else { src.to_string() };
                (st.control.release(&who), !b.on("release-unpublished"))
            }
            ControlOp::Transfer if b.on("transfer-to-any-name") => {
                let new = cmd.args.first().map(|v| v.str()).unwrap_or_default();
                let done = if st.control.holds(src) {
                    st.control.controller = new.clone(); // blank, or longer than String32: given all the same
                    st.control.requestors.retain(|r| *r != new);
                    Ok(texts::control_transferred(&new))
                } else {
                    Err(texts::no_control(src))
                };
                (done, true)
            }
            _ => return None,
        };
        b.controller(&st.control.controller);
        match done {
            Ok(note) => {
                if publish {
                    self.publish_access(st);
                }
                Some((Completion::Ok, note))
            }
            Err(why) => Some((Completion::ExecFailed, why)),
        }
    }

    /// Motion stops first (every Mobility command canceled, abortable or not), then the handler
    /// stops the hardware.
    fn stop_all_motion(&self, st: &mut State, id: RunId) {
        let mobility = self.tables.subsystems_of_type("Mobility");
        let moving = |st: &State, r: &RunId| mobility.contains(&st.runs[r].cmd.subsystem);
        let waiting: Vec<RunId> = st.pending.iter().copied().filter(|r| moving(st, r)).collect();
        for r in waiting {
            st.pending.retain(|p| *p != r);
            self.finish_unstarted(st, r, texts::CANCELED_BY_STOP_ALL_MOTION);
        }
        let running: Vec<RunId> = st.active.iter().chain(st.bypass.iter()).copied().collect();
        for r in running {
            if r == id || !moving(st, &r) || st.runs[&r].done {
                continue;
            }
            self.cancel(st, r);
            st.run(id).stopped.push(r);
        }
    }
}
