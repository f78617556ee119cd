//! The ground side (soraCore's CommandAckPair role): send a command by name with typed
//! arguments, checked against the asset's dictionary (its tables, or the CommandConfig it
//! publishes), and follow its acks until the final COMPLETED, with a deadline. The Rust twin
//! of the C++ runtime's dds::Client and the Python runtime's Commander.
//!
//! ```no_run
//! # use std::time::Duration;
//! # use rapid_dds::client::{Client, ClientOptions, SendOptions};
//! # use rapid_runtime::Value;
//! # fn demo() -> Result<(), rapid_dds::client::ClientError> {
//! let mut client = Client::new(ClientOptions { asset: "K10Red".into(), ..ClientOptions::default() }, None)?;
//! client.read_dictionary(Duration::from_secs(2)); // the asset's CommandConfig
//! client.wait_for_asset(Duration::from_secs(10));
//! let acks = client.command("Mobility", "simpleMove",
//!                           &[("frame", Value::String("SITE".into())), ("xyt", Value::Vec3d([1.0, 2.0, 0.0]))],
//!                           &SendOptions::default(), Duration::from_secs(30))?;
//! assert!(acks.last().is_some_and(|a| a.ok())); // QUEUED? EXECUTING ... COMPLETED OK
//! # Ok(()) }
//! ```
//!
//! Acks are correlated by cmdId alone and read keep-all, so no intermediate one is lost; only
//! the acks of followed commands (those sent, or follow()ed) are kept, at most
//! ACKS_PER_COMMAND each; the others are counted (strangers()) and dropped, so acks for
//! cmdIds nobody here sent do not grow the client. No thread of its own: the waits take the
//! acks (until then they wait in the DDS reader, so none is lost before a follow()).
use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use rapid_runtime::args::{complete, complete_text};
use rapid_runtime::text::visible;
use rapid_runtime::value::DATA_TYPES;
use rapid_runtime::{AckStatus, Cmd, CommandSpec, Completion, Param, QueueAction, Subsystem, SubsystemType, Tables, Value};
use rapid_types::cdr::{self, Endianness};
use rapid_types::rapid;

use crate::convert;
use crate::dds::{Participant, Reader, Side, Waiter, Writer};

pub const COMMAND_TOPIC: &str = "rapid_command";
pub const ACK_TOPIC: &str = "rapid_ack";
pub const COMMAND_CONFIG_TOPIC: &str = "rapid_command_config";
/// acks kept per followed command (a handler's progress acks beyond are dropped)
pub const ACKS_PER_COMMAND: usize = 64;

/// One ack of a command.
#[derive(Clone, Debug, PartialEq)]
pub struct AckEvent {
    pub status: AckStatus,
    pub completed: Completion,
    pub message: String,
}

impl AckEvent {
    pub fn is_final(&self) -> bool {
        self.status == AckStatus::Completed
    }

    pub fn ok(&self) -> bool {
        self.is_final() && self.completed == Completion::Ok
    }

    /// "QUEUED", "COMPLETED OK  text": as `rapidgen cmd` and rapid_cmd print an ack (the
    /// message made visible: the wire's text never reaches a terminal raw).
    pub fn describe(&self) -> String {
        let mut text = self.status.name()["ACK_".len()..].to_string();
        if self.status == AckStatus::Completed || self.completed != Completion::Not {
            text += " ";
            text += &self.completed.name()["ACK_COMPLETED_".len()..];
        }
        if !self.message.is_empty() {
            text += "  ";
            text += &visible(&self.message, 200);
        }
        text
    }
}

#[derive(Debug)]
pub enum ClientError {
    /// refused before anything was sent: unknown subsystem or command, bad arguments, a queue
    /// action the asset cannot take (every problem, joined by "; ")
    Refused(String),
    /// DDS failed
    Dds(String),
}

impl std::fmt::Display for ClientError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ClientError::Refused(t) | ClientError::Dds(t) => f.write_str(t),
        }
    }
}

impl std::error::Error for ClientError {}

impl From<crate::dds::DdsError> for ClientError {
    fn from(e: crate::dds::DdsError) -> ClientError {
        ClientError::Dds(e.0)
    }
}

#[derive(Clone, Debug)]
pub struct ClientOptions {
    /// hdr.assetName of the commands (empty: the tables' name)
    pub asset: String,
    /// empty: the tables' partition when they are the asset's, else the asset's name
    pub partition: String,
    /// cmdSrc and hdr.srcName
    pub source: String,
    /// None: the tables' domain (else 0)
    pub domain: Option<u32>,
}

impl Default for ClientOptions {
    fn default() -> ClientOptions {
        ClientOptions { asset: String::new(), partition: String::new(), source: "rapid_cmd".into(), domain: None }
    }
}

#[derive(Clone, Debug)]
pub struct SendOptions {
    pub action: QueueAction,
    /// INSERT, REPLACE, DELETE: the queued command acted on
    pub target: String,
    /// empty: a fresh one (Client::new_id)
    pub cmd_id: String,
    /// false: ranges and allowed values unchecked (the asset answers them)
    pub limits: bool,
}

impl Default for SendOptions {
    fn default() -> SendOptions {
        SendOptions { action: QueueAction::Bypass, target: String::new(), cmd_id: String::new(), limits: true }
    }
}

/// the writers counted per followed command (one answers; more say there is a stranger)
const WRITERS_COUNTED: usize = 8;

#[derive(Default)]
struct Followed {
    acks: HashMap<String, Vec<AckEvent>>,
    /// the DDS writers (publication handles) each followed command's acks came from
    writers: HashMap<String, Vec<u64>>,
    strangers: u64,
}

pub struct Client {
    options: ClientOptions,
    domain: u32,
    /// the tables given (limits, units and defaults the CommandConfig does not carry)
    given: Option<Tables>,
    /// the live CommandConfig merged with them (read_dictionary)
    live: Option<Tables>,
    commands: Writer,
    acks: Reader,
    waiter: Waiter,
    followed: Mutex<Followed>,
    counter: AtomicU64,
    dp: Participant,
}

const ACK_READER: Side = Side { reliable: true, transient_local: true, depth: None }; // every intermediate ack
const COMMAND_WRITER: Side = Side { reliable: true, transient_local: false, depth: None };
const CONFIG_READER: Side = Side { reliable: true, transient_local: true, depth: None };

impl Client {
    /// A participant on the asset's domain with a command writer and an ack reader in its
    /// partition. Cyclone's configuration is CYCLONEDDS_URI (dds::use_transport sets it from a
    /// generated transport). `tables`, when given, is the dictionary until a live one is read.
    pub fn new(mut options: ClientOptions, tables: Option<Tables>) -> Result<Client, ClientError> {
        if options.asset.is_empty() {
            options.asset = tables.as_ref().map(|t| t.name.clone()).unwrap_or_default();
        }
        if options.asset.is_empty() {
            return Err(ClientError::Refused("no asset to command: give its name or its tables".into()));
        }
        let own = tables.as_ref().filter(|t| t.name == options.asset);
        if options.partition.is_empty() {
            options.partition = own.map(|t| t.partition.clone()).filter(|p| !p.is_empty()).unwrap_or(options.asset.clone());
        }
        let domain = options.domain.unwrap_or_else(|| own.map_or(0, |t| t.domain.max(0) as u32));
        let dp = Participant::new(domain, &options.partition)?;
        let acks = dp.reader(&dp.topic(ACK_TOPIC, "rapid::Ack", true)?, ACK_READER)?;
        let waiter = dp.waiter(&acks)?;
        let commands = dp.writer(&dp.topic(COMMAND_TOPIC, "rapid::Command", true)?, COMMAND_WRITER)?;
        let given = own.cloned();
        Ok(Client { options, domain, given, live: None, commands, acks, waiter, followed: Mutex::default(),
                    counter: AtomicU64::new(0), dp })
    }

    pub fn asset(&self) -> &str {
        &self.options.asset
    }

    pub fn partition(&self) -> &str {
        &self.options.partition
    }

    pub fn domain(&self) -> u32 {
        self.domain
    }

    /// The live dictionary once read, else the tables given.
    pub fn dictionary(&self) -> Option<&Tables> {
        self.live.as_ref().or(self.given.as_ref())
    }

    /// An asset's command reader matched the command writer and its ack writer the ack
    /// reader, now.
    pub fn asset_matched(&self) -> bool {
        self.commands.matched() > 0 && self.acks.matched() > 0
    }

    pub fn wait_for_asset(&self, timeout: Duration) -> bool {
        let end = Instant::now() + timeout;
        loop {
            if self.asset_matched() {
                return true;
            }
            if Instant::now() >= end {
                return false;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// Reads the asset's CommandConfig (transient-local: published once) for up to
    /// `timeout`: it becomes the dictionary, a parameter keeping the given tables' unit,
    /// range, allowed values and default when its name and type agree. False: none came.
    pub fn read_dictionary(&mut self, timeout: Duration) -> bool {
        let Ok(topic) = self.dp.topic(COMMAND_CONFIG_TOPIC, "rapid::CommandConfig", true) else { return false };
        let Ok(reader) = self.dp.reader(&topic, CONFIG_READER) else { return false };
        let Ok(waiter) = self.dp.waiter(&reader) else { return false };
        let end = Instant::now() + timeout;
        loop {
            while let Some((bytes, _)) = reader.take() {
                // a config that does not decode, or another asset's: not this one's
                if let Ok(c) = cdr::deserialize::<rapid::CommandConfig>(&bytes) {
                    if c.hdr.asset_name == self.options.asset {
                        self.live = Some(merged(&c, self.given.as_ref(), &self.options));
                        return true;
                    }
                }
            }
            let left = end.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return false;
            }
            waiter.wait(left.min(Duration::from_millis(100)));
        }
    }

    /// The command's entry in the dictionary, or why there is none.
    pub fn entry(&self, subsystem: &str, command: &str) -> Result<&CommandSpec, ClientError> {
        let refused = |t: String| Err(ClientError::Refused(t));
        let Some(t) = self.dictionary() else {
            return refused(format!("no command dictionary for {} (give its tables, or read its CommandConfig first)",
                                   visible(&self.options.asset, 64)));
        };
        let Some(type_name) = t.type_of(subsystem) else {
            let names: Vec<&str> = t.subsystems.iter().map(|s| s.name.as_str()).collect();
            return refused(format!("asset {} has no subsystem '{}' (known: {})", visible(&self.options.asset, 64),
                                   visible(subsystem, 64), names.join(", ")));
        };
        match t.command(subsystem, command) {
            Some(r) => Ok(t.spec(r)),
            None => {
                let names: Vec<&str> = t
                    .subsystem_type(type_name)
                    .map(|st| st.commands.iter().map(|c| c.name.as_str()).collect())
                    .unwrap_or_default();
                refused(format!("subsystem {} has no command '{}' (known: {})", visible(subsystem, 64),
                                visible(command, 64), names.join(", ")))
            }
        }
    }

    fn check_action(&self, how: &SendOptions) -> Result<(), ClientError> {
        let name = how.action.name().unwrap_or("QUEUE_?");
        let targeted = matches!(how.action, QueueAction::Insert | QueueAction::Replace | QueueAction::Delete);
        if targeted == how.target.is_empty() {
            return Err(ClientError::Refused(format!("{name} {}", if targeted { "needs a target cmdId" } else { "takes no target cmdId" })));
        }
        if let Some(t) = self.dictionary() {
            if how.action != QueueAction::Bypass && !t.has_type("Queue") {
                return Err(ClientError::Refused(format!("{name}: asset {} has no command queue", visible(&t.name, 64))));
            }
        }
        Ok(())
    }

    fn prepared(&self, subsystem: &str, command: &str, args: Result<Vec<Value>, Vec<String>>, how: &SendOptions) -> Result<Cmd, ClientError> {
        self.check_action(how)?;
        let args = args.map_err(|e| ClientError::Refused(e.join("; ")))?;
        Ok(Cmd {
            cmd_id: how.cmd_id.clone(),
            subsystem: subsystem.into(),
            name: command.into(),
            args,
            action: how.action,
            target: how.target.clone(),
            ..Cmd::default()
        })
    }

    /// The command send() would send, checked, not sent (send_raw() sends it).
    pub fn prepare(&self, subsystem: &str, command: &str, args: &[(&str, Value)], how: &SendOptions) -> Result<Cmd, ClientError> {
        let spec = self.entry(subsystem, command)?;
        self.prepared(subsystem, command, complete(spec, args, how.limits), how)
    }

    /// The same from `key=value` words (the command line's).
    pub fn prepare_text(&self, subsystem: &str, command: &str, words: &[String], how: &SendOptions) -> Result<Cmd, ClientError> {
        let spec = self.entry(subsystem, command)?;
        self.prepared(subsystem, command, complete_text(spec, words, how.limits), how)
    }

    /// Checked against the dictionary, sent, followed; returns the cmdId.
    pub fn send(&self, subsystem: &str, command: &str, args: &[(&str, Value)], how: &SendOptions) -> Result<String, ClientError> {
        let cmd = self.prepare(subsystem, command, args, how)?;
        self.send_raw(cmd)
    }

    /// Sends, then waits for the final ack: the whole ack sequence (without a final one when
    /// `timeout` passed first).
    pub fn command(&self, subsystem: &str, command: &str, args: &[(&str, Value)], how: &SendOptions,
                   timeout: Duration) -> Result<Vec<AckEvent>, ClientError> {
        let id = self.send(subsystem, command, args, how)?;
        Ok(self.wait_final(&id, timeout))
    }

    /// A command as given, unchecked; the cmdId, cmdSrc, the header's names and its time
    /// are filled in when empty. Followed; returns the cmdId.
    pub fn send_raw(&self, mut cmd: Cmd) -> Result<String, ClientError> {
        if cmd.cmd_id.is_empty() {
            cmd.cmd_id = self.new_id();
        }
        for (field, value) in [(&mut cmd.cmd_src, &self.options.source), (&mut cmd.src_name, &self.options.source),
                               (&mut cmd.asset_name, &self.options.asset)] {
            if field.is_empty() {
                field.clone_from(value);
            }
        }
        if cmd.stamp == 0 {
            cmd.stamp = convert::now_us();
        }
        let bytes = cdr::serialize(&convert::command_out(&cmd), Endianness::Little)
            .map_err(|e| ClientError::Refused(format!("command {}: {e}", visible(&cmd.cmd_id, 64))))?;
        self.follow(&cmd.cmd_id);
        self.commands.write(&bytes)?;
        Ok(cmd.cmd_id)
    }

    /// Unique: counter, source, process and time (rapid-protocol.md 5), as the other clients'.
    pub fn new_id(&self) -> String {
        let ms = convert::now_us() / 1000;
        let n = self.counter.fetch_add(1, Ordering::Relaxed) + 1;
        format!("{n}-{}-{}-{ms}", self.options.source, std::process::id())
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Followed> {
        self.followed.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Keep cmd_id's acks (a command someone else sent: DELETE's target).
    pub fn follow(&self, cmd_id: &str) {
        self.lock().acks.entry(cmd_id.into()).or_default();
    }

    /// Forget a command's acks (a long run keeps its memory flat).
    pub fn forget(&self, cmd_id: &str) {
        let mut f = self.lock();
        f.acks.remove(cmd_id);
        f.writers.remove(cmd_id);
    }

    /// How many DDS writers the acks of cmd_id came from: 1 when only the asset answered (all
    /// of a command's acks go through one writer in every RAPID runtime); more when something
    /// else on the partition answers as the asset (a second bridge, a stranger).
    pub fn writers(&self, cmd_id: &str) -> usize {
        self.lock().writers.get(cmd_id).map_or(0, Vec::len)
    }

    /// Acks taken that no followed command's were.
    pub fn strangers(&self) -> u64 {
        self.lock().strangers
    }

    /// The acks of cmd_id taken so far.
    pub fn acks(&self, cmd_id: &str) -> Vec<AckEvent> {
        self.pump();
        self.lock().acks.get(cmd_id).cloned().unwrap_or_default()
    }

    /// Takes what the ack reader holds into the followed commands' lists.
    fn pump(&self) {
        let mut f = self.lock();
        while let Some((bytes, writer)) = self.acks.take() {
            let Ok(a) = cdr::deserialize::<rapid::Ack>(&bytes) else {
                f.strangers += 1; // not an Ack this client can read: nobody's it follows
                continue;
            };
            match f.acks.get_mut(&a.cmd_id) {
                Some(list) => {
                    if list.len() < ACKS_PER_COMMAND {
                        list.push(ack_event(&a));
                    }
                    let seen = f.writers.entry(a.cmd_id).or_default();
                    if seen.len() < WRITERS_COUNTED && !seen.contains(&writer) {
                        seen.push(writer);
                    }
                }
                None => f.strangers += 1,
            }
        }
    }

    /// Until `done` says so of cmd_id's acks, or `timeout`: its acks.
    fn wait(&self, cmd_id: &str, timeout: Duration, done: impl Fn(&[AckEvent]) -> bool) -> Vec<AckEvent> {
        let end = Instant::now() + timeout;
        loop {
            self.pump();
            let acks = self.lock().acks.get(cmd_id).cloned().unwrap_or_default();
            let left = end.saturating_duration_since(Instant::now());
            if done(&acks) || left.is_zero() {
                return acks;
            }
            self.waiter.wait(left.min(Duration::from_millis(100)));
        }
    }

    /// The acks of cmd_id up to its final COMPLETED, or what came within `timeout`.
    pub fn wait_final(&self, cmd_id: &str, timeout: Duration) -> Vec<AckEvent> {
        self.wait(cmd_id, timeout, |acks| acks.iter().any(AckEvent::is_final))
    }

    /// Until `count` acks of cmd_id are in (or its final one), or `timeout`: its acks.
    pub fn wait_count(&self, cmd_id: &str, count: usize, timeout: Duration) -> Vec<AckEvent> {
        self.wait(cmd_id, timeout, |acks| acks.len() >= count || acks.iter().any(AckEvent::is_final))
    }
}

fn ack_event(a: &rapid::Ack) -> AckEvent {
    AckEvent {
        status: match a.status {
            rapid::AckStatus::AckQueued => AckStatus::Queued,
            rapid::AckStatus::AckExecuting => AckStatus::Executing,
            rapid::AckStatus::AckRequeued => AckStatus::Requeued,
            rapid::AckStatus::AckCompleted => AckStatus::Completed,
        },
        completed: match a.completed_status {
            rapid::AckCompletedStatus::AckCompletedNot => Completion::Not,
            rapid::AckCompletedStatus::AckCompletedOk => Completion::Ok,
            rapid::AckCompletedStatus::AckCompletedBadSyntax => Completion::BadSyntax,
            rapid::AckCompletedStatus::AckCompletedExecFailed => Completion::ExecFailed,
            rapid::AckCompletedStatus::AckCompletedCanceled => Completion::Canceled,
        },
        message: a.message.clone(),
    }
}

/// The live CommandConfig as tables: its subsystems and commands; a parameter keeps the given
/// tables' unit, range, allowed values and default when its name and type agree (as
/// `rapidgen cmd`'s merged_tables and the C++ client's).
fn merged(config: &rapid::CommandConfig, given: Option<&Tables>, o: &ClientOptions) -> Tables {
    let mut t = given.cloned().unwrap_or_default();
    t.name = o.asset.clone();
    t.partition = o.partition.clone();
    t.subsystems = config
        .available_subsystems
        .iter()
        .map(|s| Subsystem { name: s.name.clone(), type_name: s.subsystem_type_name.clone() })
        .collect();
    t.types = config
        .available_subsystem_types
        .iter()
        .map(|st| {
            let mine = given.and_then(|g| g.subsystem_type(&st.name));
            let commands = st
                .commands
                .iter()
                .map(|c| {
                    let known = mine.and_then(|m| m.commands.iter().find(|k| k.name == c.name));
                    let params = c
                        .parameters
                        .iter()
                        .filter_map(|p| {
                            let dtype = *DATA_TYPES.get(p.type_ as i32 as usize)?;
                            let same = known.and_then(|k| k.params.iter().find(|q| q.name == p.key && q.data_type == dtype));
                            Some(same.cloned().unwrap_or_else(|| Param::new(&p.key, dtype)))
                        })
                        .collect();
                    CommandSpec {
                        name: c.name.clone(),
                        params,
                        abortable: c.abortable,
                        suspendable: c.suspendable,
                        standard: known.is_some_and(|k| k.standard),
                        ..CommandSpec::default()
                    }
                })
                .collect();
            SubsystemType { name: st.name.clone(), commands }
        })
        .collect();
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_live_dictionary_keeps_the_tables_limits_where_name_and_type_agree() {
        let mut pan = Param::new("pan", rapid_runtime::DataType::Float);
        pan.max = Some(3.05);
        let mut tilt = Param::new("tilt", rapid_runtime::DataType::Float);
        tilt.max = Some(1.0);
        let point = CommandSpec { name: "pointCamera".into(), params: vec![pan.clone(), tilt], standard: false,
                                  ..CommandSpec::default() };
        let given = Tables {
            name: "K10Red".into(),
            partition: "K10Red".into(),
            domain: 3,
            subsystems: vec![Subsystem { name: "PanCam".into(), type_name: "PanCam".into() }],
            types: vec![SubsystemType { name: "PanCam".into(), commands: vec![point] }],
            access: None,
            ..Tables::default()
        };
        let pair = |key: &str, t| rapid::KeyTypePair { key: key.into(), type_: t };
        let config = rapid::CommandConfig {
            available_subsystem_types: vec![rapid::SubsystemType {
                name: "PanCam".into(),
                commands: vec![
                    rapid::CommandDef {
                        name: "pointCamera".into(),
                        abortable: true,
                        suspendable: false,
                        // tilt's type differs from the tables': the live one's, without limits
                        parameters: vec![pair("pan", rapid::DataType::RapidFloat), pair("tilt", rapid::DataType::RapidDouble)],
                    },
                    rapid::CommandDef { name: "wipeLens".into(), ..rapid::CommandDef::default() },
                ],
            }],
            available_subsystems: vec![rapid::Subsystem { name: "Mast".into(), subsystem_type_name: "PanCam".into() }],
            ..rapid::CommandConfig::default()
        };
        let o = ClientOptions { asset: "K10Red".into(), partition: "K10Red".into(), ..ClientOptions::default() };
        let t = merged(&config, Some(&given), &o);
        assert_eq!(t.type_of("Mast"), Some("PanCam"));
        assert_eq!(t.type_of("PanCam"), None);
        let spec = t.spec(t.command("Mast", "pointCamera").expect("pointCamera"));
        assert!(spec.abortable);
        assert_eq!(spec.params[0], pan);
        assert_eq!(spec.params[1], Param::new("tilt", rapid_runtime::DataType::Double));
        assert!(t.command("Mast", "wipeLens").is_some());
        assert_eq!(t.domain, 3);
    }

    #[test]
    fn acks_print_as_the_other_clients_print_them() {
        let ack = |status, completed, message: &str| AckEvent { status, completed, message: message.into() };
        assert_eq!(ack(AckStatus::Queued, Completion::Not, "").describe(), "QUEUED");
        assert_eq!(ack(AckStatus::Completed, Completion::Ok, "").describe(), "COMPLETED OK");
        assert_eq!(ack(AckStatus::Completed, Completion::BadSyntax, "no\x1b").describe(), "COMPLETED BAD_SYNTAX  no\\x1b");
        assert!(ack(AckStatus::Completed, Completion::Canceled, "").is_final());
        assert!(!ack(AckStatus::Completed, Completion::Canceled, "").ok());
    }
}
