//! RAPID messages as the generated types (rapid_types) and the runtime's plain data: a
//! received Command into a `Cmd`, the manager's answers into Ack, QueueState and
//! AccessControlState, each as the Python runtime's messages.py builds them.
use std::time::{SystemTime, UNIX_EPOCH};

use rapid_runtime::{AckStatus, Cmd, Completion, QueueAction, Record, RecordResult, RecordStatus, Value};
use rapid_types::cdr::{self, DecodeError, EncodeError, Endianness};
use rapid_types::rapid;

pub fn now_us() -> i64 {
    SystemTime::now().duration_since(UNIX_EPOCH).map(|d| d.as_micros() as i64).unwrap_or(0)
}

pub fn header(src: &str, asset: &str, serial: i32, status: i32) -> rapid::Header {
    rapid::Header { src_name: src.into(), asset_name: asset.into(), time_stamp: now_us(), status_code: status, serial }
}

fn value(p: &rapid::ParameterUnion) -> Value {
    match p {
        rapid::ParameterUnion::B(x) => Value::Bool(*x),
        rapid::ParameterUnion::D(x) => Value::Double(*x),
        rapid::ParameterUnion::F(x) => Value::Float(*x),
        rapid::ParameterUnion::I(x) => Value::Int(*x),
        rapid::ParameterUnion::Ll(x) => Value::LongLong(*x),
        rapid::ParameterUnion::S(x) => Value::String(x.clone()),
        rapid::ParameterUnion::Vec3d(x) => Value::Vec3d(*x),
        rapid::ParameterUnion::Mat33f(x) => Value::Mat33f(*x),
    }
}

/// A runtime value as the wire's ParameterUnion.
pub fn union(v: &Value) -> rapid::ParameterUnion {
    match v {
        Value::Bool(x) => rapid::ParameterUnion::B(*x),
        Value::Double(x) => rapid::ParameterUnion::D(*x),
        Value::Float(x) => rapid::ParameterUnion::F(*x),
        Value::Int(x) => rapid::ParameterUnion::I(*x),
        Value::LongLong(x) => rapid::ParameterUnion::Ll(*x),
        Value::String(x) => rapid::ParameterUnion::S(x.clone()),
        Value::Vec3d(x) => rapid::ParameterUnion::Vec3d(*x),
        Value::Mat33f(x) => rapid::ParameterUnion::Mat33f(*x),
    }
}

/// A received Command's bytes as a `Cmd` (hostile bytes: the codec's checked decode).
pub fn command_in(bytes: &[u8]) -> Result<Cmd, DecodeError> {
    let c: rapid::Command = cdr::deserialize(bytes)?;
    Ok(Cmd {
        cmd_id: c.cmd_id,
        cmd_src: c.cmd_src,
        subsystem: c.subsys_name,
        name: c.cmd_name,
        args: c.arguments.iter().map(value).collect(),
        action: QueueAction::from_wire(c.cmd_action as i32),
        target: c.target_cmd_id,
        src_name: c.hdr.src_name,
        asset_name: c.hdr.asset_name,
        serial: c.hdr.serial,
        stamp: c.hdr.time_stamp,
    })
}

fn action(a: QueueAction) -> rapid::QueueAction {
    match a {
        QueueAction::Append => rapid::QueueAction::QueueAppend,
        QueueAction::Delete => rapid::QueueAction::QueueDelete,
        QueueAction::Insert => rapid::QueueAction::QueueInsert,
        QueueAction::Replace => rapid::QueueAction::QueueReplace,
        QueueAction::Bypass | QueueAction::Other(_) => rapid::QueueAction::QueueBypass,
    }
}

/// A `Cmd` as the Command it came as (QueueState records carry commands).
pub fn command_out(c: &Cmd) -> rapid::Command {
    rapid::Command {
        hdr: rapid::Header {
            src_name: c.src_name.clone(),
            asset_name: c.asset_name.clone(),
            time_stamp: c.stamp,
            status_code: 0,
            serial: c.serial,
        },
        cmd_name: c.name.clone(),
        cmd_id: c.cmd_id.clone(),
        cmd_src: c.cmd_src.clone(),
        subsys_name: c.subsystem.clone(),
        arguments: c.args.iter().map(union).collect(),
        cmd_action: action(c.action),
        target_cmd_id: c.target.clone(),
    }
}

/// The Ack copies the command's header (soraCore), timestamp refreshed.
pub fn ack(cmd: &Cmd, status: AckStatus, completion: Completion, message: &str) -> Result<Vec<u8>, EncodeError> {
    let a = rapid::Ack {
        hdr: header(&cmd.src_name, &cmd.asset_name, cmd.serial, 0),
        cmd_id: cmd.cmd_id.clone(),
        status: match status {
            AckStatus::Queued => rapid::AckStatus::AckQueued,
            AckStatus::Executing => rapid::AckStatus::AckExecuting,
            AckStatus::Requeued => rapid::AckStatus::AckRequeued,
            AckStatus::Completed => rapid::AckStatus::AckCompleted,
        },
        completed_status: match completion {
            Completion::Not => rapid::AckCompletedStatus::AckCompletedNot,
            Completion::Ok => rapid::AckCompletedStatus::AckCompletedOk,
            Completion::BadSyntax => rapid::AckCompletedStatus::AckCompletedBadSyntax,
            Completion::ExecFailed => rapid::AckCompletedStatus::AckCompletedExecFailed,
            Completion::Canceled => rapid::AckCompletedStatus::AckCompletedCanceled,
        },
        message: message.into(),
    };
    cdr::serialize(&a, Endianness::Little)
}

fn records(rs: &[Record]) -> rapid::SingleQueue {
    rapid::SingleQueue {
        records: rs
            .iter()
            .map(|r| rapid::CommandRecord {
                cmd: command_out(&r.cmd),
                tr_result: match r.result {
                    RecordResult::Init => rapid::ResultType::QResultInit,
                    RecordResult::Succeeded => rapid::ResultType::QResultSucceeded,
                    RecordResult::Failed => rapid::ResultType::QResultFailed,
                },
                tr_status: match r.status {
                    RecordStatus::Init => rapid::StatusType::QStatusInit,
                    RecordStatus::Inline => rapid::StatusType::QStatusInline,
                    RecordStatus::InProcess => rapid::StatusType::QStatusInprocess,
                    RecordStatus::Paused => rapid::StatusType::QStatusPaused,
                    RecordStatus::Canceled => rapid::StatusType::QStatusCanceled,
                    RecordStatus::Succeeded => rapid::StatusType::QStatusSucceeded,
                    RecordStatus::Failed => rapid::StatusType::QStatusFailed,
                },
            })
            .collect(),
    }
}

pub fn queue_state(
    hdr: rapid::Header,
    pending: &[Record],
    active: &[Record],
    completed: &[Record],
) -> Result<Vec<u8>, EncodeError> {
    let q = rapid::QueueState {
        hdr,
        pending: records(pending),
        active: records(active),
        completed: records(completed),
        sent: rapid::SingleQueue::default(),
    };
    cdr::serialize(&q, Endianness::Little)
}

pub fn access_state(hdr: rapid::Header, controller: &str, requestors: &[String]) -> Result<Vec<u8>, EncodeError> {
    let a = rapid::AccessControlState { hdr, controller: controller.into(), requestors: requestors.to_vec() };
    cdr::serialize(&a, Endianness::Little)
}

/// A config sample's bytes with its header replaced: the generated asset::configs() leave it
/// at its default. The header is every RAPID message's first member and ends on a multiple
/// of 8 (an i64 then two i32), so the rest keeps its alignment.
pub fn with_header(sample: &[u8], hdr: &rapid::Header) -> Result<Vec<u8>, String> {
    if sample.len() < 4 || sample[1] != 1 {
        return Err("not a CDR_LE sample".into());
    }
    let body = &sample[4..];
    let mut off = 0usize;
    for _ in 0..2 {
        off = (off + 3) & !3;
        let n = body.get(off..off + 4).ok_or("short header")?;
        off += 4 + u32::from_le_bytes([n[0], n[1], n[2], n[3]]) as usize;
    }
    off = ((off + 7) & !7) + 16;
    if off > body.len() {
        return Err("short header".into());
    }
    let mut out = cdr::serialize(hdr, Endianness::Little).map_err(|e| e.to_string())?;
    out.extend_from_slice(&body[off..]);
    out[2] = 0;
    out[3] = 0;
    Ok(out)
}
