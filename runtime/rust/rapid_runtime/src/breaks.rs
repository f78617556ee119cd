//! Deliberately broken protocol behaviour, for the conformance tests only (the cargo feature
//! `test-breaks`, off by default: a robot's build has neither this module nor a branch on
//! it). A bridge built with the feature takes `--break KIND` and breaks one rule the way
//! tests/conformance/broken/ breaks the Python runtime and the C++ runtime's `--break` its
//! bridge (runtime/cpp/dds/include/rapid_runtime/dds/breaks.hpp), so that `rapidgen conform`
//! can be shown to catch a Rust bridge doing it (tests/rust_runtime/test_broken.py).
//!
//! Where each kind is injected: in front of the manager (`intake`, `tables`), on the way out
//! of it (`outbox`: acks, QueueState, AccessControlState), in the manager's own decisions
//! (`CommandManager`, through `Options::breaks`) and in the bridge's config serial
//! (zero-serial). The kinds of the DDS layer's writers (the ack topic and its durability, the
//! configs, the simulated telemetry) are listed here too, the one list of the kinds (it
//! refuses an unknown one; tests/rust_runtime/test_broken.py reads it), and injected by
//! rapid_dds (its `breaks` module, under its feature test-breaks, which turns this one on).

use std::collections::{BTreeSet, HashSet};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

use crate::manager::{Outbox, Record};
use crate::tables::Tables;
use crate::texts;
use crate::value::{DataType, Value};
use crate::vocabulary::{AckStatus, Completion, RecordStatus};
use crate::Cmd;

/// kind -> the conformance check it fails (tests/conformance/broken/ has the same names)
pub const KINDS: &[(&str, &str)] = &[
    // in front of the manager (intake, tables)
    ("any-subsystem", "CMD-05"),
    ("unknown-command-ok", "CMD-06"),
    ("extra-args-ignored", "CMD-07"),
    ("args-converted", "CMD-08"),
    ("other-asset-accepted", "CMD-09"),
    ("crash-on-bad-input", "CMD-14"),
    ("ranges-unchecked", "CMD-15"),
    ("allowed-unchecked", "CMD-15"),
    ("minimum-unchecked", "CMD-15"),
    ("nan-unanswered", "CMD-16"),
    ("every-20th-lost", "CMD-16"),
    // the acks and state topics (outbox)
    ("noop-unimplemented", "CMD-02"),
    ("wrong-ack-order", "CMD-03"),
    ("ack-after-final", "CMD-04"),
    ("long-ack-message", "CMD-11"),
    ("ack-names-commander", "CMD-12"),
    ("ack-ids-truncated", "CMD-12"),
    ("queue-status-code", "QUE-01"),
    ("queue-record-status", "QUE-05"),
    ("access-state-unwritten", "ACC-01"),
    // the manager's decisions
    ("no-dedup", "CMD-10"),
    ("request-unpublished", "ACC-02"),
    ("no-control-gate", "ACC-03"),
    ("grab-refused", "ACC-04"),
    ("grab-unpublished", "ACC-04"),
    ("release-by-anyone", "ACC-05"),
    ("stop-needs-control", "ACC-06"),
    ("request-steals-control", "ACC-07"),
    ("former-controller-keeps-rights", "ACC-08"),
    ("release-unpublished", "ACC-09"),
    ("allow-list-ignored", "ACC-10"),
    ("transfer-to-any-name", "SPEC-01"),
    ("queue-lifo", "QUE-02"),
    ("queue-parallel", "QUE-02"),
    ("append-target-ignored", "QUE-03"),
    ("delete-wrong-command", "QUE-04"),
    ("insert-at-back", "QUE-06"),
    ("replace-at-back", "QUE-06"),
    ("queue-state-stale", "QUE-07"),
    // the bridge's config serial (rapid_dds::bridge, through journal::restart_serial)
    ("zero-serial", "CFG-05"),
    // the DDS layer's (rapid_dds::breaks): the ack writer
    ("ack-topic-suffixed", "CMD-01"),
    ("volatile-acks", "CMD-13"),
    // the configs
    ("position-config-unpublished", "CFG-01"),
    ("volatile-config", "CFG-02"),
    ("wrong-config", "CFG-03"),
    ("config-without-source", "CFG-04"),
    ("serial-drift", "CFG-05"),
    // the simulated telemetry
    ("position-silent", "TEL-01"),
    ("wrong-serial", "TEL-02"),
    ("misaligned-values", "TEL-03"),
    ("millisecond-stamps", "TEL-04"),
    ("frozen-stamps", "TEL-04"),
    ("sample-without-source", "TEL-05"),
    ("slow-rate", "TEL-06"),
    ("millivolts", "TEL-07"),
    ("gps-silent", "TEL-08"),
];

/// The exit status of crash-on-bad-input (the C++ kind's).
pub const CRASH_STATUS: i32 = 70;
/// every-20th-lost: one command in this many read is lost (the Python kind's)
pub const LOST_EVERY: u64 = 20;

/// The kinds turned on; none: nothing is broken.
#[derive(Debug, Default)]
pub struct Breaks {
    on: BTreeSet<String>,
    /// ack-after-final's cmdIds: the stray EXECUTING goes out once per command (a resent
    /// cmdId's stored final ack, which CMD-10 accepts, goes out as it was)
    after_final: Mutex<HashSet<String>>,
    /// former-controller-keeps-rights: every source that has held control
    held: Mutex<HashSet<String>>,
    /// every-20th-lost: commands read so far
    read: AtomicU64,
}

impl Breaks {
    /// Err names an unknown kind.
    pub fn new(names: &[String]) -> Result<Breaks, String> {
        let mut on = BTreeSet::new();
        for n in names {
            if !KINDS.iter().any(|(k, _)| k == n) {
                let known: Vec<&str> = KINDS.iter().map(|(k, _)| *k).collect();
                return Err(format!("unknown break {n:?} (one of {})", known.join(", ")));
            }
            on.insert(n.clone());
        }
        Ok(Breaks { on, ..Breaks::default() })
    }

    pub fn on(&self, kind: &str) -> bool {
        self.on.contains(kind)
    }

    pub fn any(&self) -> bool {
        !self.on.is_empty()
    }

    /// The controller now (former-controller-keeps-rights remembers each).
    pub fn controller(&self, name: &str) {
        if self.on("former-controller-keeps-rights") && !name.is_empty() {
            self.held.lock().unwrap_or_else(|e| e.into_inner()).insert(name.to_string());
        }
    }

    /// former-controller-keeps-rights: the control gate's question, "held it once?"
    pub fn held_once(&self, source: &str) -> bool {
        self.on("former-controller-keeps-rights") && self.held.lock().unwrap_or_else(|e| e.into_inner()).contains(source)
    }

    /// What the manager validates against (ranges-unchecked: no ranges; minimum-unchecked: no
    /// minimum; allowed-unchecked: no allowed values).
    pub fn tables(&self, mut tables: Tables) -> Tables {
        for p in tables.types.iter_mut().flat_map(|t| t.commands.iter_mut()).flat_map(|c| c.params.iter_mut()) {
            if self.on("ranges-unchecked") || self.on("minimum-unchecked") {
                p.min = None;
            }
            if self.on("ranges-unchecked") {
                p.max = None;
            }
            if self.on("allowed-unchecked") {
                p.allowed.clear();
            }
        }
        tables
    }

    /// A received command as the broken bridge sees it; None: answered here (or exited).
    pub fn intake(&self, mut cmd: Cmd, tables: &Tables, out: &dyn Outbox) -> Option<Cmd> {
        let nan = |v: &Value| match v {
            Value::Double(d) => d.is_nan(),
            Value::Float(f) => f.is_nan(),
            _ => false,
        };
        if self.on("crash-on-bad-input") && cmd.args.iter().any(nan) {
            std::process::exit(CRASH_STATUS); // what an unchecked float conversion in a robot's bridge does
        }
        if self.on("nan-unanswered") && cmd.args.iter().any(nan) {
            return None; // dropped at the reader, no ack
        }
        if self.on("every-20th-lost") && (self.read.fetch_add(1, Ordering::Relaxed) + 1).is_multiple_of(LOST_EVERY) {
            out.log(&format!("broken: lost command {:?}", cmd.cmd_id)); // a ring buffer's off-by-one
            return None;
        }
        if self.on("other-asset-accepted") {
            cmd.asset_name = tables.name.clone();
        }
        let known = tables.type_of(&cmd.subsystem).is_some();
        if self.on("any-subsystem") && !known {
            // dispatched by command name alone
            if let Some(s) = tables.subsystems.iter().find(|s| tables.command(&s.name, &cmd.name).is_some()) {
                cmd.subsystem = s.name.clone();
            }
        }
        let r = tables.command(&cmd.subsystem, &cmd.name);
        if self.on("unknown-command-ok") && known && r.is_none() {
            // a dispatcher's default case
            out.ack(&cmd, AckStatus::Executing, Completion::Not, "");
            out.ack(&cmd, AckStatus::Completed, Completion::Ok, "");
            return None;
        }
        if let Some(r) = r {
            let count = tables.spec(r).params.len();
            if self.on("extra-args-ignored") && cmd.args.len() > count {
                cmd.args.truncate(count);
            }
            if self.on("args-converted") && cmd.args.len() == count {
                for (arg, p) in cmd.args.iter_mut().zip(&tables.spec(r).params) {
                    if let Some(v) = converted(p.data_type, arg) {
                        *arg = v;
                    }
                }
            }
        }
        Some(cmd)
    }

    /// The outbox the manager writes to, breaking what the kinds turned on break.
    pub fn outbox(self: &Arc<Self>, inner: Arc<dyn Outbox>) -> Arc<dyn Outbox> {
        Arc::new(BrokenOutbox { breaks: self.clone(), inner })
    }
}

/// The value read as the parameter's type whatever the union said, as a bridge calling the
/// union's accessor for the declared type would; None: it cannot be (or is of that type).
fn converted(to: DataType, v: &Value) -> Option<Value> {
    if v.data_type() == to {
        return None;
    }
    let x = v.number();
    match (to, x) {
        (DataType::String, _) => Some(Value::String(v.str())),
        (DataType::Double, Some(x)) => Some(Value::Double(x)),
        (DataType::Float, Some(x)) => Some(Value::Float(x as f32)),
        (DataType::Int, Some(x)) if x.fract() == 0.0 && x.abs() < 2e9 => Some(Value::Int(x as i32)),
        (DataType::LongLong, Some(x)) if x.fract() == 0.0 && x.abs() < 9e18 => Some(Value::LongLong(x as i64)),
        _ => None,
    }
}

struct BrokenOutbox {
    breaks: Arc<Breaks>,
    inner: Arc<dyn Outbox>,
}

impl Outbox for BrokenOutbox {
    fn ack(&self, cmd: &Cmd, status: AckStatus, completion: Completion, message: &str) {
        let b = &self.breaks;
        let (mut completion, mut message) = (completion, message.to_string());
        if b.on("noop-unimplemented") && cmd.subsystem == "Admin" && cmd.name == "noOp" && completion == Completion::Ok {
            completion = Completion::ExecFailed;
            message = texts::NOT_IMPLEMENTED.into();
        }
        if b.on("long-ack-message") && !message.is_empty() {
            // Astrobee's 128 bytes (cut at a character's boundary: the codec takes no more)
            message = format!("{message} {}", "x".repeat(128));
            let end = (0..=128).rev().find(|i| message.is_char_boundary(*i)).unwrap_or(0);
            message.truncate(end);
        }
        let mut to = cmd.clone();
        if b.on("ack-names-commander") {
            to.asset_name = cmd.src_name.clone();
        }
        if b.on("ack-ids-truncated") {
            to.cmd_id = cmd.cmd_id.chars().take(12).collect();
        }
        self.inner.ack(&to, status, completion, &message);
        if b.on("wrong-ack-order") && status == AckStatus::Executing {
            self.inner.ack(&to, AckStatus::Queued, Completion::Not, "");
        }
        if b.on("ack-after-final")
            && status == AckStatus::Completed
            && b.after_final.lock().unwrap_or_else(|e| e.into_inner()).insert(cmd.cmd_id.clone())
        {
            self.inner.ack(&to, AckStatus::Executing, Completion::Not, "");
        }
    }

    fn queue_state(&self, code: i32, pending: &[Record], active: &[Record], completed: &[Record]) {
        let code = if self.breaks.on("queue-status-code") { 2 } else { code };
        if self.breaks.on("queue-record-status") {
            let pending: Vec<Record> =
                pending.iter().map(|r| Record { status: RecordStatus::Succeeded, ..r.clone() }).collect();
            return self.inner.queue_state(code, &pending, active, completed);
        }
        self.inner.queue_state(code, pending, active, completed);
    }

    fn access_state(&self, controller: &str, requestors: &[String]) {
        if !self.breaks.on("access-state-unwritten") {
            self.inner.access_state(controller, requestors);
        }
    }

    fn retire(&self, cmd: &Cmd) {
        self.inner.retire(cmd);
    }

    fn log(&self, text: &str) {
        self.inner.log(text);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tables::{CommandSpec, Param, Subsystem, SubsystemType};

    #[derive(Default)]
    struct Seen(Mutex<Vec<String>>);

    impl Outbox for Seen {
        fn ack(&self, cmd: &Cmd, status: AckStatus, completion: Completion, message: &str) {
            self.0.lock().unwrap().push(format!("{} {} {:?} {:?} {message}", cmd.asset_name, cmd.cmd_id, status, completion));
        }
        fn queue_state(&self, code: i32, pending: &[Record], _: &[Record], _: &[Record]) {
            let st: Vec<String> = pending.iter().map(|r| format!("{:?}", r.status)).collect();
            self.0.lock().unwrap().push(format!("queue {code} {}", st.join(",")));
        }
        fn access_state(&self, controller: &str, _: &[String]) {
            self.0.lock().unwrap().push(format!("access {controller}"));
        }
        fn retire(&self, _: &Cmd) {}
        fn log(&self, _: &str) {}
    }

    fn tables() -> Tables {
        let mut p = Param::new("x", DataType::Double);
        (p.min, p.max) = (Some(0.0), Some(1.0));
        let spec = |name: &str, params: Vec<Param>| CommandSpec { name: name.into(), params, ..CommandSpec::default() };
        Tables {
            name: "A".into(),
            subsystems: vec![Subsystem { name: "Arm".into(), type_name: "ArmT".into() }],
            types: vec![SubsystemType { name: "ArmT".into(), commands: vec![spec("go", vec![p])] }],
            ..Tables::default()
        }
    }

    fn cmd(subsystem: &str, name: &str, args: Vec<Value>) -> Cmd {
        Cmd {
            cmd_id: "commander-0123456789".into(),
            subsystem: subsystem.into(),
            name: name.into(),
            args,
            src_name: "ground".into(),
            asset_name: "B".into(),
            ..Cmd::default()
        }
    }

    #[test]
    fn unknown_kinds_are_refused() {
        assert!(Breaks::new(&["no-such-kind".into()]).unwrap_err().contains("unknown break \"no-such-kind\""));
        assert!(!Breaks::new(&[]).unwrap().any());
    }

    #[test]
    fn nothing_on_changes_nothing() {
        let b = Arc::new(Breaks::new(&[]).unwrap());
        let seen = Arc::new(Seen::default());
        let c = cmd("Nope", "go", vec![Value::Double(2.0), Value::Int(1)]);
        assert_eq!(b.intake(c.clone(), &tables(), seen.as_ref()), Some(c.clone()));
        assert_eq!(b.tables(tables()).types[0].commands[0].params[0].max, Some(1.0));
        let out = b.outbox(seen.clone());
        out.ack(&c, AckStatus::Completed, Completion::Ok, "fine");
        out.access_state("me", &[]);
        assert_eq!(*seen.0.lock().unwrap(), ["B commander-0123456789 Completed Ok fine", "access me"]);
    }

    #[test]
    fn intake_kinds() {
        let on = |k: &str| Breaks::new(&[k.into()]).unwrap();
        let seen = Seen::default();
        let t = tables();
        let got = on("any-subsystem").intake(cmd("Nope", "go", vec![]), &t, &seen).unwrap();
        assert_eq!(got.subsystem, "Arm");
        assert_eq!(on("other-asset-accepted").intake(cmd("Arm", "go", vec![]), &t, &seen).unwrap().asset_name, "A");
        let got = on("extra-args-ignored").intake(cmd("Arm", "go", vec![Value::Double(0.5), Value::Int(1)]), &t, &seen);
        assert_eq!(got.unwrap().args, [Value::Double(0.5)]);
        assert_eq!(on("unknown-command-ok").intake(cmd("Arm", "fly", vec![]), &t, &seen), None);
        assert_eq!(seen.0.lock().unwrap().len(), 2);
        assert_eq!(on("ranges-unchecked").tables(tables()).types[0].commands[0].params[0].max, None);
        let p = &on("minimum-unchecked").tables(tables()).types[0].commands[0].params[0];
        assert_eq!((p.min, p.max), (None, Some(1.0)));
        let got = on("args-converted").intake(cmd("Arm", "go", vec![Value::Int(1)]), &t, &seen).unwrap();
        assert_eq!(got.args, [Value::Double(1.0)]);
        assert_eq!(on("nan-unanswered").intake(cmd("Arm", "go", vec![Value::Double(f64::NAN)]), &t, &seen), None);
        let lossy = on("every-20th-lost");
        let lost: Vec<usize> = (1..=40).filter(|_| lossy.intake(cmd("Arm", "go", vec![]), &t, &seen).is_none()).collect();
        assert_eq!(lost, [20, 40]);
        assert_eq!(seen.0.lock().unwrap().len(), 2); // (unknown-command-ok's acks; nothing answers the lost ones)
    }

    #[test]
    fn outbox_kinds() {
        let acks = |k: &str, c: &Cmd, status: AckStatus, completion: Completion| {
            let seen = Arc::new(Seen::default());
            let out = Arc::new(Breaks::new(&[k.into()]).unwrap()).outbox(seen.clone());
            out.ack(c, status, completion, "said");
            out.ack(c, status, completion, "said");
            let got = seen.0.lock().unwrap().clone();
            got
        };
        let c = cmd("Arm", "go", vec![]);
        assert_eq!(acks("wrong-ack-order", &c, AckStatus::Executing, Completion::Not)[1],
                   "B commander-0123456789 Queued Not ");
        let after = acks("ack-after-final", &c, AckStatus::Completed, Completion::Ok);
        assert_eq!(after.len(), 3); // once per cmdId
        assert_eq!(after[1], "B commander-0123456789 Executing Not ");
        assert_eq!(acks("ack-names-commander", &c, AckStatus::Completed, Completion::Ok)[0],
                   "ground commander-0123456789 Completed Ok said");
        assert!(acks("ack-ids-truncated", &c, AckStatus::Completed, Completion::Ok)[0].starts_with("B commander-01 "));
        assert_eq!(acks("long-ack-message", &c, AckStatus::Completed, Completion::Ok)[0].len(),
                   "B commander-0123456789 Completed Ok ".len() + 128);
        let seen = Arc::new(Seen::default());
        let out = Arc::new(Breaks::new(&["long-ack-message".into()]).unwrap()).outbox(seen.clone());
        out.ack(&c, AckStatus::Completed, Completion::Ok, &"\u{e9}".repeat(70)); // 2 bytes each
        assert_eq!(seen.0.lock().unwrap()[0].len(), "B commander-0123456789 Completed Ok ".len() + 128);
        let noop = cmd("Admin", "noOp", vec![]);
        assert_eq!(acks("noop-unimplemented", &noop, AckStatus::Completed, Completion::Ok)[0],
                   "B commander-0123456789 Completed ExecFailed not implemented");
        let seen = Arc::new(Seen::default());
        let out = Arc::new(Breaks::new(&["access-state-unwritten".into(), "queue-status-code".into(),
                                         "queue-record-status".into()]).unwrap()).outbox(seen.clone());
        out.access_state("me", &[]);
        let rec = Record { cmd: Arc::new(c), result: crate::RecordResult::Init, status: RecordStatus::Inline };
        out.queue_state(0, &[rec], &[], &[]);
        assert_eq!(*seen.0.lock().unwrap(), ["queue 2 Succeeded"]);
    }
}
