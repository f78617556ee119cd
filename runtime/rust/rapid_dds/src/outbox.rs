//! The manager's Outbox on DDS: acks (transient-local, as RAPID's ack readers ask), QueueState
//! and AccessControlState written in the asset's partition.
use std::sync::atomic::{AtomicI32, Ordering};

use rapid_runtime::{AckStatus, Cmd, Completion, Outbox, Record};

use crate::convert;
use crate::dds::{DdsError, Participant, Side, Writer};

/// the acks a late joiner still gets: cyclors' blob type has no key, so the writer's history
/// is one instance for every command (the Python runtime keeps 8 per command)
pub const ACK_HISTORY: i32 = 64;

pub struct DdsOutbox {
    name: String,
    /// the serial of the asset's configs, in the states' headers
    pub serial: AtomicI32,
    acks: Writer,
    queue: Writer,
    access: Writer,
}

const STATE: Side = Side { reliable: true, transient_local: true, depth: Some(1) };

impl DdsOutbox {
    pub fn new(dp: &Participant, name: &str, serial: i32) -> Result<DdsOutbox, DdsError> {
        let acks = dp.topic("rapid_ack", "rapid::Ack", true)?;
        let queue = dp.topic("rapid_queue_state", "rapid::QueueState", true)?;
        let access = dp.topic("rapid_accesscontrol_state", "rapid::AccessControlState", true)?;
        Ok(DdsOutbox {
            name: name.into(),
            serial: AtomicI32::new(serial),
            acks: dp.writer(&acks, Side { reliable: true, transient_local: true, depth: Some(ACK_HISTORY) })?,
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
        self.put("an ack", &self.acks, convert::ack(cmd, status, completion, message));
    }

    fn queue_state(&self, code: i32, pending: &[Record], active: &[Record], completed: &[Record]) {
        let hdr = convert::header(&self.name, &self.name, self.serial.load(Ordering::Relaxed), code);
        self.put("QueueState", &self.queue, convert::queue_state(hdr, pending, active, completed));
    }

    fn access_state(&self, controller: &str, requestors: &[String]) {
        let hdr = convert::header(&self.name, &self.name, self.serial.load(Ordering::Relaxed), 0);
        self.put("AccessControlState", &self.access, convert::access_state(hdr, controller, requestors));
    }

    fn retire(&self, _cmd: &Cmd) {
        // one instance for all acks (blob type): nothing to unregister; ACK_HISTORY bounds them
    }

    fn log(&self, text: &str) {
        eprintln!("[{}] {}", self.name, text);
    }
}
