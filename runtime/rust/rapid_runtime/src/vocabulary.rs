//! Ack, queue and record vocabulary: the RAPID IDL's enumerators in the IDL's order, so a DDS
//! layer converts with `as i32` (rapid-protocol.md section 4).

/// Ack.status
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AckStatus {
    Queued,
    Executing,
    Requeued,
    Completed,
}

/// Ack.completedStatus
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Completion {
    Not,
    Ok,
    BadSyntax,
    ExecFailed,
    Canceled,
}

/// Command.queueAction; `Other` carries a value outside the enumeration as it came off the wire.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum QueueAction {
    Bypass,
    Append,
    Delete,
    Insert,
    Replace,
    Other(i32),
}

/// QueueState record result.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RecordResult {
    Init,
    Succeeded,
    Failed,
}

/// QueueState record status (the statuses this runtime writes; the IDL has more).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RecordStatus {
    Init,
    Inline,
    InProcess,
    Paused,
    Canceled,
    Succeeded,
    Failed,
}

/// INSERT's target naming the front of the queue (rapid-protocol.md section 4).
pub const HEAD: &str = "head";

impl AckStatus {
    pub fn name(self) -> &'static str {
        match self {
            AckStatus::Queued => "ACK_QUEUED",
            AckStatus::Executing => "ACK_EXECUTING",
            AckStatus::Requeued => "ACK_REQUEUED",
            AckStatus::Completed => "ACK_COMPLETED",
        }
    }
}

impl Completion {
    pub const ALL: [Completion; 5] =
        [Completion::Not, Completion::Ok, Completion::BadSyntax, Completion::ExecFailed, Completion::Canceled];

    pub fn name(self) -> &'static str {
        match self {
            Completion::Not => "ACK_COMPLETED_NOT",
            Completion::Ok => "ACK_COMPLETED_OK",
            Completion::BadSyntax => "ACK_COMPLETED_BAD_SYNTAX",
            Completion::ExecFailed => "ACK_COMPLETED_EXEC_FAILED",
            Completion::Canceled => "ACK_COMPLETED_CANCELED",
        }
    }

    /// A completion's enumerator name back (a journal's), or None.
    pub fn from_name(name: &str) -> Option<Completion> {
        Completion::ALL.into_iter().find(|c| c.name() == name)
    }

    /// The QueueState record's status and result for a command completed so.
    pub fn record(self) -> (RecordResult, RecordStatus) {
        match self {
            Completion::Ok => (RecordResult::Succeeded, RecordStatus::Succeeded),
            Completion::BadSyntax | Completion::ExecFailed => (RecordResult::Failed, RecordStatus::Failed),
            Completion::Canceled => (RecordResult::Failed, RecordStatus::Canceled),
            Completion::Not => (RecordResult::Init, RecordStatus::Init),
        }
    }
}

impl QueueAction {
    /// "QUEUE_BYPASS" ...; None for a value outside the enumeration.
    pub fn name(self) -> Option<&'static str> {
        match self {
            QueueAction::Bypass => Some("QUEUE_BYPASS"),
            QueueAction::Append => Some("QUEUE_APPEND"),
            QueueAction::Delete => Some("QUEUE_DELETE"),
            QueueAction::Insert => Some("QUEUE_INSERT"),
            QueueAction::Replace => Some("QUEUE_REPLACE"),
            QueueAction::Other(_) => None,
        }
    }

    /// The wire's number (the IDL's order).
    pub fn from_wire(n: i32) -> QueueAction {
        match n {
            0 => QueueAction::Bypass,
            1 => QueueAction::Append,
            2 => QueueAction::Delete,
            3 => QueueAction::Insert,
            4 => QueueAction::Replace,
            other => QueueAction::Other(other),
        }
    }

    pub fn wire(self) -> i32 {
        match self {
            QueueAction::Bypass => 0,
            QueueAction::Append => 1,
            QueueAction::Delete => 2,
            QueueAction::Insert => 3,
            QueueAction::Replace => 4,
            QueueAction::Other(n) => n,
        }
    }

    /// An enumerator name ("QUEUE_APPEND"), or None.
    pub fn from_name(name: &str) -> Option<QueueAction> {
        (0..5).map(QueueAction::from_wire).find(|a| a.name() == Some(name))
    }
}

impl RecordStatus {
    pub fn name(self) -> &'static str {
        match self {
            RecordStatus::Init => "Q_STATUS_INIT",
            RecordStatus::Inline => "Q_STATUS_INLINE",
            RecordStatus::InProcess => "Q_STATUS_INPROCESS",
            RecordStatus::Paused => "Q_STATUS_PAUSED",
            RecordStatus::Canceled => "Q_STATUS_CANCELED",
            RecordStatus::Succeeded => "Q_STATUS_SUCCEEDED",
            RecordStatus::Failed => "Q_STATUS_FAILED",
        }
    }

    /// The IDL's number (rapid::QueueStatus).
    pub fn wire(self) -> i32 {
        match self {
            RecordStatus::Init => 0,
            RecordStatus::Inline => 3,
            RecordStatus::InProcess => 5,
            RecordStatus::Paused => 6,
            RecordStatus::Canceled => 7,
            RecordStatus::Succeeded => 8,
            RecordStatus::Failed => 9,
        }
    }
}
