//! The door between the command reader and the manager: a flood from one participant must
//! neither grow the asset without bound nor lock an operator out (runtime/rapid_runtime/intake.py
//! is the reference; docs/runtime.md, "The door").
//!
//! ```text
//! let intake = Intake::new(manager, log, PER_WRITER, SHED_ANSWERS);   // Arc<impl CommandSink>
//! intake.start();                       // a worker thread hands commands to the manager
//! intake.offer(cmd, &writer);           // the reader: every decoded Command, never blocks
//! ```
//!
//! - One FIFO per writer (the DDS writer the sample came from), served in turn.
//! - Control commands go first: a writer whose next command is a control command is served
//!   before the others; a writer's own commands keep their order.
//! - Past `per_writer` waiting, a writer's commands are answered COMPLETED/EXEC_FAILED "bridge
//!   busy" without running; those answers wait in a bounded list (`shed_answers`) and take turns
//!   with real commands; past that too, commands are dropped unanswered, counted, logged once
//!   per writer.
//! - Commands offered before `start` wait for the worker. (No inline hand-over and no batches
//!   as in Python and C++: the Rust manager syncs its journal per command.)

use std::collections::{HashMap, VecDeque};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;

use crate::journal::Log;
use crate::manager::CommandManager;
use crate::text::visible;
use crate::{texts, Cmd};

/// Commands of one writer waiting for the manager.
pub const PER_WRITER: usize = 256;
/// Writers with a FIFO of their own; past that they share one ([`SHARED_WRITER`]).
pub const MAX_WRITERS: usize = 256;
/// "Busy" answers waiting to be written.
pub const SHED_ANSWERS: usize = 4096;
/// The FIFO of writers past [`MAX_WRITERS`].
pub const SHARED_WRITER: &str = "";
const CONTROL: [(&str, &str); 2] = [("Mobility", "stopAllMotion"), ("Queue", "cancelAll")];

/// What the door hands commands to (the manager; a test's stand-in).
pub trait CommandSink: Send + Sync + 'static {
    fn receive(&self, cmd: Cmd);
    fn refuse(&self, cmd: Cmd, why: &str);
    /// A command that goes before other writers' (AccessControl, stopAllMotion, cancelAll).
    fn is_control(&self, cmd: &Cmd) -> bool;
}

impl CommandSink for CommandManager {
    fn receive(&self, cmd: Cmd) {
        CommandManager::receive(self, cmd)
    }
    fn refuse(&self, cmd: Cmd, why: &str) {
        CommandManager::refuse(self, cmd, why)
    }
    fn is_control(&self, cmd: &Cmd) -> bool {
        match self.tables().type_of(&cmd.subsystem) {
            Some("AccessControl") => true,
            Some(kind) => CONTROL.contains(&(kind, cmd.name.as_str())),
            None => false,
        }
    }
}

#[derive(Default)]
struct Door {
    /// The round: writers with commands waiting, the next to serve first.
    fifos: VecDeque<(String, VecDeque<Cmd>)>,
    shed: VecDeque<Cmd>,
    shed_count: HashMap<String, usize>,
    unanswered: HashMap<String, usize>,
    stopping: bool,
    shed_turn: bool,
}

struct Shared<S> {
    sink: Arc<S>,
    log: Log,
    per_writer: usize,
    shed_limit: usize,
    door: Mutex<Door>,
    wake: Condvar,
}

pub struct Intake<S: CommandSink> {
    shared: Arc<Shared<S>>,
    thread: Mutex<Option<JoinHandle<()>>>,
}

impl<S: CommandSink> Intake<S> {
    pub fn new(sink: Arc<S>, log: Log, per_writer: usize, shed_answers: usize) -> Intake<S> {
        let shared = Shared {
            sink,
            log,
            per_writer,
            shed_limit: shed_answers,
            door: Mutex::new(Door::default()),
            wake: Condvar::new(),
        };
        Intake { shared: Arc::new(shared), thread: Mutex::new(None) }
    }

    /// The worker starts handing what waits to the sink (once; not after stop).
    pub fn start(&self) {
        let mut thread = self.thread.lock().unwrap_or_else(|e| e.into_inner());
        if thread.is_none() && !self.shared.lock().stopping {
            let shared = self.shared.clone();
            *thread = Some(std::thread::Builder::new()
                .name("rapid-intake".into())
                .spawn(move || shared.run())
                .expect("the intake thread cannot start"));
        }
    }

    /// The worker ends after the command it is handing over; what waits is not handed over.
    pub fn stop(&self) {
        self.shared.lock().stopping = true;
        self.shared.wake.notify_all();
        let handle = self.thread.lock().unwrap_or_else(|e| e.into_inner()).take();
        if let Some(handle) = handle {
            if handle.thread().id() != std::thread::current().id() {
                let _ = handle.join();
            }
        }
    }

    /// A command read from `writer` (the DDS writer's id): to its FIFO, else shed, else dropped.
    pub fn offer(&self, cmd: Cmd, writer: &str) {
        let shared = &self.shared;
        let mut door = shared.lock();
        let mut writer = writer;
        let mut at = door.fifos.iter().position(|(w, _)| w == writer);
        if at.is_none() && door.fifos.len() >= MAX_WRITERS {
            writer = SHARED_WRITER;
            at = door.fifos.iter().position(|(w, _)| w == writer);
        }
        match at {
            Some(i) if door.fifos[i].1.len() >= shared.per_writer => shared.shed(&mut door, cmd, writer),
            Some(i) => door.fifos[i].1.push_back(cmd),
            None => door.fifos.push_back((writer.to_string(), VecDeque::from([cmd]))),
        }
        drop(door);
        shared.wake.notify_one();
    }

    /// Commands waiting at the door (shed ones included).
    pub fn waiting(&self) -> usize {
        let door = self.shared.lock();
        door.shed.len() + door.fifos.iter().map(|(_, f)| f.len()).sum::<usize>()
    }

    /// The writer's commands dropped unanswered so far.
    pub fn unanswered(&self, writer: &str) -> usize {
        self.shared.lock().unanswered.get(writer).copied().unwrap_or(0)
    }
}

impl<S: CommandSink> Drop for Intake<S> {
    fn drop(&mut self) {
        self.stop();
    }
}

impl<S: CommandSink> Shared<S> {
    fn lock(&self) -> MutexGuard<'_, Door> {
        self.door.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn shed(&self, door: &mut Door, cmd: Cmd, writer: &str) {
        if door.shed.len() < self.shed_limit {
            door.shed.push_back(cmd);
            if first(&mut door.shed_count, writer) {
                (self.log)(&format!(
                    "writer {} floods: {} commands waiting; answering its next ones 'bridge busy' (counted, not logged)",
                    visible(writer, 200),
                    self.per_writer
                ));
            }
        } else if first(&mut door.unanswered, writer) {
            (self.log)(&format!(
                "writer {} floods past {} busy answers: dropping its commands unanswered (counted, not logged)",
                visible(writer, 200),
                self.shed_limit
            ));
        }
    }

    /// The next command to hand over (shed or not), None once stopping.
    fn next(&self) -> Option<(Cmd, bool)> {
        let mut door = self.lock();
        loop {
            if door.stopping {
                return None;
            }
            let control = door.fifos.iter().position(|(_, f)| f.front().is_some_and(|c| self.sink.is_control(c)));
            if control.is_none() && !door.shed.is_empty() && (door.shed_turn || door.fifos.is_empty()) {
                door.shed_turn = false; // busy answers take turns with real commands
                return door.shed.pop_front().map(|c| (c, true));
            }
            if let Some((writer, mut fifo)) = door.fifos.remove(control.unwrap_or(0)) {
                door.shed_turn = true;
                let cmd = fifo.pop_front().expect("a FIFO in the round holds a command");
                if !fifo.is_empty() {
                    door.fifos.push_back((writer, fifo)); // to the back of the round
                }
                return Some((cmd, false));
            }
            door = self.wake.wait(door).unwrap_or_else(|e| e.into_inner());
        }
    }

    fn run(&self) {
        while let Some((cmd, shed)) = self.next() {
            let id = cmd.cmd_id.clone();
            let handed = catch_unwind(AssertUnwindSafe(|| {
                if shed {
                    self.sink.refuse(cmd, &texts::bridge_busy(self.per_writer))
                } else {
                    self.sink.receive(cmd)
                }
            }));
            if handed.is_err() {
                // a bad command must not stop intake
                (self.log)(&format!("command '{}' not handled: it panicked", visible(&id, 200)));
            }
        }
    }
}

/// Counts one more for the writer; true the first time (what is logged once per writer).
fn first(counts: &mut HashMap<String, usize>, writer: &str) -> bool {
    let n = counts.entry(writer.to_string()).or_default();
    *n += 1;
    *n == 1
}
