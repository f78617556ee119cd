//! What an asset's handlers see: the command's context and the outcome they return.
//!
//! `Handlers::execute(ctx)` runs on a thread of its own and may run long:
//! - `Outcome::Ok(text)`: COMPLETED/OK (text is Ack.message);
//! - `Outcome::Failed(why)`: COMPLETED/EXEC_FAILED;
//! - having noticed `ctx.cancelled()` (DELETE, REPLACE, cancelAll, stopAllMotion, a preempting
//!   command, shutdown), any return, or `Outcome::Canceled`: COMPLETED/CANCELED, or REQUEUED
//!   when it was preempted and will run again. A handler told to stop that has not returned
//!   within its stop bound (CommandSpec::stop_timeout_ms, else the manager's, 2000 ms) is
//!   answered EXEC_FAILED "handler did not stop" and leaves the queue; what it returns later
//!   is ignored;
//! - a panic: EXEC_FAILED "handler error: panic: ...", one log line, and the asset runs on.
//!
//! `ctx.progress(text)` sends an EXECUTING ack carrying text; `ctx.sleep(d)` waits, waking
//! early when the command is told to stop.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

use crate::command::Cmd;
use crate::tables::CommandSpec;
use crate::value::Value;

/// What a handler answers.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome {
    Ok(String),
    Failed(String),
    /// a handler may judge the arguments itself (Astrobee does)
    BadSyntax(String),
    Canceled,
    /// what an unwritten handler (a generated stub) answers: EXEC_FAILED "not implemented"
    NotImplemented,
}

impl Outcome {
    pub fn ok() -> Outcome {
        Outcome::Ok(String::new())
    }
}

/// The asset's handlers (generated glue implements execute() by unpacking ctx.args() into
/// typed per-command methods). A command no handler serves answers EXEC_FAILED "not implemented".
pub trait Handlers: Send + Sync {
    fn execute(&self, ctx: &Context) -> Outcome {
        let _ = ctx;
        Outcome::NotImplemented
    }
}

type Progress = Box<dyn Fn(&str) + Send + Sync>;

/// One run of a command's handler. Shared: a thread of the handler's own may keep it (an Arc)
/// and call progress() after the handler returned; every call once the command has its final
/// ack is a no-op.
pub struct Context {
    cmd: Arc<Cmd>,
    spec: CommandSpec,
    type_name: String,
    cancelled: Mutex<bool>,
    wake: Condvar,
    closed: AtomicBool,
    progress: Progress,
    pub(crate) serial: u64,
}

impl Context {
    pub(crate) fn new(cmd: Arc<Cmd>, spec: CommandSpec, type_name: String, serial: u64, progress: Progress) -> Context {
        Context {
            cmd,
            spec,
            type_name,
            cancelled: Mutex::new(false),
            wake: Condvar::new(),
            closed: AtomicBool::new(false),
            progress,
            serial,
        }
    }

    /// A context no manager runs (a handler's own tests): progress goes to `progress`.
    pub fn detached(cmd: Cmd, spec: CommandSpec, type_name: &str, progress: impl Fn(&str) + Send + Sync + 'static) -> Context {
        Context::new(Arc::new(cmd), spec, type_name.into(), 0, Box::new(progress))
    }

    pub fn cmd(&self) -> &Cmd {
        &self.cmd
    }
    pub fn spec(&self) -> &CommandSpec {
        &self.spec
    }
    /// The subsystem type (Arm) the command belongs to.
    pub fn type_name(&self) -> &str {
        &self.type_name
    }
    pub fn command(&self) -> &str {
        &self.spec.name
    }
    /// The instance (LeftArm).
    pub fn subsystem(&self) -> &str {
        &self.cmd.subsystem
    }
    pub fn source(&self) -> &str {
        &self.cmd.cmd_src
    }
    /// The arguments, validated against the command's parameters before the handler runs.
    pub fn args(&self) -> &[Value] {
        &self.cmd.args
    }

    /// An EXECUTING ack carrying text (cut to 127 bytes); nothing once the command is done.
    pub fn progress(&self, text: &str) {
        if !self.done() {
            (self.progress)(text)
        }
    }

    /// The command has its final ack.
    pub fn done(&self) -> bool {
        self.closed.load(Ordering::SeqCst)
    }

    /// Told to stop.
    pub fn cancelled(&self) -> bool {
        *self.cancelled.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Wait, waking early when told to stop; true when not told to stop.
    pub fn sleep(&self, d: Duration) -> bool {
        let end = Instant::now() + d;
        let mut told = self.cancelled.lock().unwrap_or_else(|e| e.into_inner());
        while !*told {
            let now = Instant::now();
            if now >= end {
                break;
            }
            told = self.wake.wait_timeout(told, end - now).unwrap_or_else(|e| e.into_inner()).0;
        }
        !*told
    }

    pub(crate) fn cancel(&self) {
        *self.cancelled.lock().unwrap_or_else(|e| e.into_inner()) = true;
        self.wake.notify_all();
    }

    pub(crate) fn close(&self) {
        self.closed.store(true, Ordering::SeqCst);
    }
}
