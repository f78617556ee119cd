//! The manager's Outbox on DDS: acks (transient-local, as RAPID's ack readers ask), QueueState
//! and AccessControlState written in the asset's partition.
//!
//! Acks are keyed as RAPID's Ack is (the command's hdr.srcName, hdr.assetName and cmdId: one
//! instance per command, keyed.rs), the last ACK_HISTORY of each kept for a late joiner. As in
//! the Python runtime (ack_writers.py), commands are dealt to writer generations: all the
//! acks of one command go through the writer that took it, and a generation no longer current
//! is deleted once all its commands are retired (Cyclone keeps memory for every instance a
//! writer ever wrote, until the writer goes), so memory stays bounded whatever the uptime.
use std::collections::HashMap;
use std::sync::atomic::{AtomicI32, Ordering};
use std::sync::Mutex;

use rapid_runtime::{AckStatus, Cmd, Completion, Outbox, Record};
use rapid_types::cdr;
use rapid_types::rapid;

use crate::convert;
use crate::dds::{DdsError, Participant, Side, Writer, Writers};

/// the acks of a command a late joiner still gets (QUEUED, EXECUTING, REQUEUED, EXECUTING,
/// COMPLETED and a few progress acks), as the Python runtime
pub const ACK_HISTORY: i32 = 8;
/// a new ack writer every window / ACK_GENERATIONS commands, at least every ACK_GENERATION_MIN
/// (each new writer is discovered anew by every ack reader), as the Python runtime
pub const ACK_GENERATIONS: usize = 4;
pub const ACK_GENERATION_MIN: usize = 256;

/// An Ack's key members from its CDR (keyed.rs).
fn ack_key(bytes: &[u8]) -> Option<Vec<u8>> {
    let a: rapid::Ack = cdr::deserialize(bytes).ok()?;
    cdr::key_bytes(&a).ok()
}

type CmdKey = (String, String, String);

fn key(cmd: &Cmd) -> CmdKey {
    (cmd.src_name.clone(), cmd.asset_name.clone(), cmd.cmd_id.clone())
}

struct Generation {
    writer: Writer,
    taken: usize,
    live: usize,
}

/// The ack writer generations.
struct AckWriters {
    make: Writers,
    size: usize,
    gens: HashMap<u64, Generation>,
    current: u64,
    /// made half a generation early: readers have matched it by the time it writes
    next: Option<Writer>,
    of: HashMap<CmdKey, u64>,
    /// writers made so far
    created: u64,
}

impl AckWriters {
    fn writer_for(&mut self, k: CmdKey) -> Result<Writer, DdsError> {
        if let Some(g) = self.of.get(&k) {
            return Ok(self.gens[g].writer);
        }
        let cur = &self.gens[&self.current];
        if cur.taken >= self.size {
            let w = match self.next.take() {
                Some(w) => w,
                None => self.make.make()?,
            };
            let old = self.current;
            self.created += 1;
            self.current = self.created;
            self.gens.insert(self.current, Generation { writer: w, taken: 0, live: 0 });
            self.drop_if_done(old);
        } else if self.next.is_none() && cur.taken >= self.size / 2 {
            self.next = Some(self.make.make()?);
        }
        let g = self.gens.get_mut(&self.current).expect("the current generation");
        g.taken += 1;
        g.live += 1;
        self.of.insert(k, self.current);
        Ok(g.writer)
    }

    fn retire(&mut self, k: &CmdKey) {
        if let Some(id) = self.of.remove(k) {
            if let Some(g) = self.gens.get_mut(&id) {
                g.live -= 1;
            }
            self.drop_if_done(id);
        }
    }

    fn drop_if_done(&mut self, id: u64) {
        if id != self.current && self.gens.get(&id).is_some_and(|g| g.live == 0) {
            if let Some(g) = self.gens.remove(&id) {
                // in a thread of its own: Cyclone lingers until readers have acknowledged,
                // and the caller holds the manager's lock
                let _ = std::thread::Builder::new().name("rapid-ack-writer-delete".into()).spawn(move || {
                    if let Err(e) = g.writer.delete() {
                        eprintln!("an old ack writer not deleted: {e}");
                    }
                });
            }
        }
    }
}

pub struct DdsOutbox {
    name: String,
    /// the serial of the asset's configs, in the states' headers
    pub serial: AtomicI32,
    acks: Mutex<AckWriters>,
    queue: Writer,
    access: Writer,
}

const STATE: Side = Side { reliable: true, transient_local: true, depth: Some(1) };
/// the Ack topic (5b: plain rapid_ack) and its writers' side: RapidReliableDurableQos, a late
/// joiner gets each command's last ACK_HISTORY acks
pub const ACK_TOPIC: &str = "rapid_ack";
pub const ACK_SIDE: Side = Side { reliable: true, transient_local: true, depth: Some(ACK_HISTORY) };

impl DdsOutbox {
    /// `window`: the manager's command window (Options::window).
    pub fn new(dp: &Participant, name: &str, serial: i32, window: usize) -> Result<DdsOutbox, DdsError> {
        DdsOutbox::with_acks(dp, name, serial, window, ACK_TOPIC, ACK_SIDE)
    }

    /// new() with the ack writers' topic and QoS side given (a test build's ack breaks,
    /// crate::breaks).
    pub(crate) fn with_acks(dp: &Participant, name: &str, serial: i32, window: usize, topic: &str, side: Side) -> Result<DdsOutbox, DdsError> {
        let md5 = <rapid::Ack as cdr::Cdr>::KEY_MAX_SIZE > 16;
        let acks = dp.keyed_topic(topic, "rapid::Ack", ack_key, md5)?;
        let queue = dp.topic("rapid_queue_state", "rapid::QueueState", true)?;
        let access = dp.topic("rapid_accesscontrol_state", "rapid::AccessControlState", true)?;
        Ok(DdsOutbox {
            name: name.into(),
            serial: AtomicI32::new(serial),
            acks: Mutex::new({
                let make = dp.writers(&acks, side);
                let first = Generation { writer: make.make()?, taken: 0, live: 0 };
                AckWriters {
                    make,
                    size: (window / ACK_GENERATIONS).max(ACK_GENERATION_MIN),
                    gens: HashMap::from([(1, first)]),
                    current: 1,
                    next: None,
                    of: HashMap::new(),
                    created: 1,
                }
            }),
            queue: dp.writer(&queue, STATE)?,
            access: dp.writer(&access, STATE)?,
        })
    }

    fn put(&self, what: &str, w: &Writer, bytes: Result<Vec<u8>, impl std::fmt::Display>) {
        match bytes {
            Ok(b) => {
                if let Err(e) = w.write(&b) {
                    self.log(&format!("{what} not written: {e}"));
                }
            }
            Err(e) => self.log(&format!("{what} not encoded: {e}")),
        }
    }
}

impl Outbox for DdsOutbox {
    fn ack(&self, cmd: &Cmd, status: AckStatus, completion: Completion, message: &str) {
        let writer = self.acks.lock().unwrap_or_else(|e| e.into_inner()).writer_for(key(cmd));
        match writer {
            Ok(w) => self.put("an ack", &w, convert::ack(cmd, status, completion, message)),
            Err(e) => self.log(&format!("an ack not written: {e}")),
        }
    }

    fn queue_state(&self, code: i32, pending: &[Record], active: &[Record], completed: &[Record]) {
        let hdr = convert::header(&self.name, &self.name, self.serial.load(Ordering::Relaxed), code);
        self.put("QueueState", &self.queue, convert::queue_state(hdr, pending, active, completed));
    }

    fn access_state(&self, controller: &str, requestors: &[String]) {
        let hdr = convert::header(&self.name, &self.name, self.serial.load(Ordering::Relaxed), 0);
        self.put("AccessControlState", &self.access, convert::access_state(hdr, controller, requestors));
    }

    fn retire(&self, cmd: &Cmd) {
        // its generation's writer goes once all of its commands are retired
        self.acks.lock().unwrap_or_else(|e| e.into_inner()).retire(&key(cmd));
    }

    fn log(&self, text: &str) {
        eprintln!("[{}] {}", self.name, text);
    }
}

impl DdsOutbox {
    /// Ack writers made so far and those alive (tests, benches).
    pub fn ack_writers(&self) -> (u64, usize) {
        let a = self.acks.lock().unwrap_or_else(|e| e.into_inner());
        (a.created + u64::from(a.next.is_some()), a.gens.len() + usize::from(a.next.is_some()))
    }
}
