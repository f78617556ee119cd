//! An asset's bridge, the whole program but for what the generated crate knows (its tables,
//! configs, QoS profiles, transports, extension types) and the user's handlers:
//!
//!   <crate>_bridge [--simulate] [--domain N] [--transport local|lan|wan] [--tables FILE]
//!                  [--command-window N] [--journal DIR | --no-journal]
//!
//! The configs go out first (transient-local: commanders read the CommandConfig to find the
//! asset), then the manager's states; commands are read in the asset's partition and handed
//! through the door (`rapid_runtime::intake`) to the runtime's CommandManager. The restart
//! journal (docs/runtime.md, "Restarts"; the Python and C++ bridges' file) is on by default:
//! after a crash the commands accepted and not finished are answered, the last final acks
//! written again, and the configs come back with a larger serial; `--simulate` runs simulated handlers (`Simulated`) and
//! publishes simulated telemetry (`telemetry`). Cyclone's configuration is CYCLONEDDS_URI when
//! set, else the transport's generated XML (loopback only for `local`, the default).
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use rapid_runtime::intake::{Intake, PER_WRITER, SHED_ANSWERS};
use rapid_runtime::journal::{self, Log};
use rapid_runtime::configs::{now_seconds, Serials};
use rapid_runtime::{Journal, Recovered};
use rapid_runtime::{CommandManager, Context, Handlers, Options, Outbox, Outcome, Value};

use crate::configs::{Configs, SharedSerials};
use crate::dds::{DdsError, Participant, Side};
use crate::stream::{Env, Hooks, StreamSet};
use crate::stream_sim::{Fill, Parts, SimStreams};
use crate::telemetry::{self, Body, Custom, Source};
use crate::{convert, outbox, tables_json, DdsOutbox};
use rapid_runtime::stream::StreamSpec;

/// What the generated crate gives the bridge.
pub struct Asset {
    /// the tables as rapidgen's Rust back end writes them (tables_json::asset_of)
    pub tables_json: &'static str,
    /// every computed config: topic, DDS type name, its CDR_LE sample (header left default)
    pub configs: Vec<(&'static str, &'static str, Vec<u8>)>,
    /// the writer side of a topic's QoS profile
    pub qos: fn(&str) -> Option<Side>,
    /// transport name -> Cyclone DDS XML (the generated qos target's cyclonedds/<name>.xml)
    pub transports: &'static [(&'static str, &'static str)],
    /// extension telemetry made from the crate's own types (`--simulate`)
    pub customs: Vec<Custom>,
}

/// Makes the real robot's stream readers (the user's callbacks) and output writers.
pub type RealSetup = Box<dyn FnOnce(&mut StreamSet) -> Result<(), DdsError>>;
/// Makes them under --simulate (setpoints to the simulated robot); the outputs' fills.
pub type SimSetup = Box<dyn FnOnce(&mut StreamSet, &Arc<SimStreams>) -> Result<Vec<(f64, Fill)>, DdsError>>;

/// The asset's setpoint streams, as the generated glue (dispatch.rs stream_glue) gives them.
pub struct Streams {
    pub specs: &'static [StreamSpec],
    /// the readers (the user's callbacks) and output writers of the real robot
    pub real: RealSetup,
    /// the same under --simulate: setpoints to the simulated robot; the outputs' fills
    pub sim: SimSetup,
    /// the user's on_state and agent values (the real robot's)
    pub hooks: Hooks,
}

/// Handlers of a simulated robot, as the Python runtime's simulate.py: Mobility simpleMove and
/// move drive the body to x, y and heading (xyt), move6DOF to x, y (xyz), at DRIVE_SPEED and
/// TURN_SPEED, until there or told to stop; stopAllMotion stops it; anything else completes
/// after a short pause. Position telemetry reports the body.
pub struct Simulated {
    pub body: Arc<Mutex<Body>>,
}

pub const DRIVE_SPEED: f64 = 0.5; // m/s
pub const TURN_SPEED: f64 = 0.5; // rad/s
const TICK: Duration = Duration::from_millis(50);

impl Simulated {
    fn drive(&self, ctx: &Context, x: f64, y: f64, th: Option<f64>) -> Outcome {
        let dt = TICK.as_secs_f64();
        loop {
            {
                let mut b = self.body.lock().unwrap_or_else(|e| e.into_inner());
                let (dx, dy) = (x - b.xyz[0], y - b.xyz[1]);
                let dist = dx.hypot(dy);
                let goal = th.unwrap_or(b.heading);
                let dth = (goal - b.heading + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
                if dist < 1e-3 && dth.abs() < 1e-3 {
                    b.velocity = [0.0; 3];
                    return Outcome::Ok(format!("arrived at {x:.2}, {y:.2}"));
                }
                let step = dist.min(DRIVE_SPEED * dt);
                if dist > 0.0 {
                    b.xyz[0] += dx / dist * step;
                    b.xyz[1] += dy / dist * step;
                    b.odometer += step;
                    b.velocity = [dx / dist * DRIVE_SPEED, dy / dist * DRIVE_SPEED, 0.0];
                } else {
                    b.velocity = [0.0; 3];
                }
                b.heading += dth.clamp(-TURN_SPEED * dt, TURN_SPEED * dt);
            }
            if !ctx.sleep(TICK) {
                self.body.lock().unwrap_or_else(|e| e.into_inner()).velocity = [0.0; 3];
                return Outcome::Canceled;
            }
        }
    }
}

impl Handlers for Simulated {
    fn execute(&self, ctx: &Context) -> Outcome {
        let vec3 = ctx.args().iter().find_map(|v| match v {
            Value::Vec3d(x) if x.iter().all(|c| c.is_finite()) => Some(*x),
            _ => None,
        });
        match (ctx.type_name(), ctx.command(), vec3) {
            ("Mobility", "stopAllMotion", _) => {
                self.body.lock().unwrap_or_else(|e| e.into_inner()).velocity = [0.0; 3];
                Outcome::Ok("stopped (simulated)".into())
            }
            ("Mobility", "simpleMove" | "move", Some(v)) => self.drive(ctx, v[0], v[1], Some(v[2])),
            ("Mobility", "move6DOF", Some(v)) => self.drive(ctx, v[0], v[1], None),
            _ => {
                if ctx.sleep(TICK) {
                    Outcome::Ok("done (simulated)".into())
                } else {
                    Outcome::Canceled
                }
            }
        }
    }
}

struct Args {
    window: Option<usize>,
    simulate: bool,
    domain: Option<u32>,
    transport: String,
    tables: Option<String>,
    /// the restart journal's folder (None: Journal::default_dir()); off with --no-journal
    journal: Option<String>,
    no_journal: bool,
    /// --break KIND (a test build's: the feature test-breaks; a plain build refuses any)
    breaks: Vec<String>,
}

const USAGE: &str = "[--simulate] [--domain N] [--transport local|lan|wan] [--tables FILE] [--command-window N] \
                     [--journal DIR | --no-journal]";

/// Why the bridge did not run: --help (exit status 0), a usage error (2), a failure (1).
#[derive(Debug)]
pub enum Failure {
    Help,
    Usage(String),
    Run(String),
}

impl From<String> for Failure {
    fn from(text: String) -> Failure {
        Failure::Run(text)
    }
}

/// The program: runs the bridge, prints why it stopped when it failed; the exit status.
pub fn main(asset: Result<Asset, String>, handlers: Arc<dyn Handlers>) -> i32 {
    finish(asset.map_err(Failure::Run).and_then(|a| run(a, handlers, None)))
}

/// main() of an asset with setpoint streams (docs/realtime.md).
pub fn main_with_streams(asset: Result<Asset, String>, handlers: Arc<dyn Handlers>, streams: Streams) -> i32 {
    finish(asset.map_err(Failure::Run).and_then(|a| run(a, handlers, Some(streams))))
}

fn finish(res: Result<(), Failure>) -> i32 {
    let argv0 = std::env::args().next().unwrap_or_else(|| "bridge".into());
    match res {
        Ok(()) => {
            println!("bridge stopped");
            0
        }
        Err(Failure::Help) => {
            println!("usage: {argv0} {USAGE}");
            0
        }
        Err(Failure::Usage(text)) => {
            eprintln!("{argv0}: {text}\nusage: {argv0} {USAGE}");
            2
        }
        Err(Failure::Run(text)) => {
            eprintln!("{argv0}: {text}");
            1
        }
    }
}

fn parse(args: &[String], transports: &[(&str, &str)]) -> Result<Args, String> {
    let mut out = Args {
        window: None,
        simulate: false,
        domain: None,
        transport: "local".into(),
        tables: None,
        journal: None,
        no_journal: false,
        breaks: Vec::new(),
    };
    let mut it = args.iter().skip(1);
    while let Some(a) = it.next() {
        let mut value = |name: &str| it.next().cloned().ok_or(format!("{name} wants a value"));
        match a.as_str() {
            "--simulate" => out.simulate = true,
            "--domain" => {
                let d = value(a)?;
                out.domain = Some(d.parse().map_err(|_| format!("--domain {d:?}: not a domain id (0-232)"))?);
            }
            "--transport" => {
                let t = value(a)?;
                if !transports.iter().any(|(n, _)| *n == t) {
                    let names: Vec<&str> = transports.iter().map(|(n, _)| *n).collect();
                    return Err(format!("--transport {t:?}: one of {}", names.join(", ")));
                }
                out.transport = t;
            }
            "--tables" => out.tables = Some(value(a)?),
            "--journal" => out.journal = Some(value(a)?),
            "--no-journal" => out.no_journal = true,
            "--break" => out.breaks.push(value(a)?),
            "--command-window" => {
                let n = value(a)?;
                out.window = Some(n.parse().ok().filter(|n| *n > 0).ok_or(format!("--command-window {n:?}: a count of commands, at least 1"))?);
            }
            "-h" | "--help" => return Err("--help".into()),
            other => return Err(format!("unknown argument {other:?}")),
        }
    }
    if out.no_journal && out.journal.is_some() {
        return Err("--journal and --no-journal: one or the other".into());
    }
    Ok(out)
}

/// Runs the bridge until a shutdown command; `handlers` unless `--simulate`; `streams`: the
/// asset's setpoint streams (the user's callbacks, or the simulated robot's).
pub fn run(asset: Asset, handlers: Arc<dyn Handlers>, streams: Option<Streams>) -> Result<(), Failure> {
    let argv: Vec<String> = std::env::args().collect();
    let args = match parse(&argv, asset.transports) {
        Ok(a) => a,
        Err(h) if h == "--help" => return Err(Failure::Help),
        Err(e) => return Err(Failure::Usage(e)),
    };
    let text = match &args.tables {
        Some(f) => std::fs::read_to_string(f).map_err(|e| format!("{f}: {e}"))?,
        None => asset.tables_json.to_string(),
    };
    #[cfg(not(feature = "test-breaks"))]
    if !args.breaks.is_empty() {
        return Err(Failure::Run("--break is for test builds only (the cargo feature test-breaks)".into()));
    }
    #[cfg(feature = "test-breaks")]
    let breaks = Arc::new(rapid_runtime::breaks::Breaks::new(&args.breaks).map_err(Failure::Usage)?);
    let where_ = args.tables.clone().unwrap_or_else(|| "the built-in tables".into());
    let json: serde_json::Value = serde_json::from_str(&text).map_err(|e| format!("{where_}: {e}"))?;
    let tables = tables_json::asset_of(&json).map_err(|e| format!("{where_}: {e}"))?;
    // what rapid_runtime never sees: the ack writer, the configs, the simulated telemetry
    #[cfg(feature = "test-breaks")]
    let dds_breaks = Arc::new(crate::breaks::Breaks::new(breaks.clone(), &tables));
    let domain = args.domain.unwrap_or(tables.tables.domain.max(0) as u32);
    crate::dds::use_transport(asset.transports, &args.transport);
    let name = tables.tables.name.clone();
    let log_name = name.clone();
    let log: Log = Arc::new(move |text: &str| eprintln!("[{log_name}] {text}"));
    let mut options = Options::default();
    if let Some(w) = args.window {
        options.window = w; // commands remembered (repeated cmdIds); also sizes the ack writer generations
    }
    let now = convert::now_us().div_euclid(1_000_000); // (as Python: the start time)
    let (mut journal, recovered) = if args.no_journal {
        (None, Recovered::default())
    } else {
        let dir = args.journal.as_ref().map_or_else(Journal::default_dir, PathBuf::from);
        Journal::open(&dir, &name, domain as i32, options.window, log.clone())
    };
    // configs come back after a crash with a serial above any used before it
    #[cfg(feature = "test-breaks")]
    let requested = breaks.on("zero-serial").then_some(0);
    #[cfg(not(feature = "test-breaks"))]
    let requested = None;
    let serial = journal::start_serial(requested, &recovered, now, journal.as_mut());
    options.journal = journal;
    #[cfg(feature = "test-breaks")]
    {
        options.breaks = breaks.clone();
    }
    let serial = serial as i32;
    let dp = Participant::new(domain, &tables.tables.partition).map_err(|e| e.to_string())?;
    let (ack_topic, ack_side) = (outbox::ACK_TOPIC.to_string(), outbox::ACK_SIDE);
    #[cfg(feature = "test-breaks")]
    let (ack_topic, ack_side) = (dds_breaks.ack_topic(&name, &ack_topic), dds_breaks.ack_side(ack_side));
    let outbox = Arc::new(DdsOutbox::with_acks(&dp, &name, serial, options.window, &ack_topic, ack_side).map_err(|e| e.to_string())?);

    // configs first (transient-local): commanders read the CommandConfig to find the asset;
    // each with the start serial, a new one when the user's code publishes other content
    // (crate::configs::get(): Configs::publish)
    let serials: SharedSerials = Arc::new(Mutex::new(Serials::new(Some(serial as i64), Box::new(now_seconds), None)));
    let source = name.as_str();
    #[cfg(feature = "test-breaks")]
    let source = dds_breaks.config_source(source);
    let hdr = convert::header(source, &name, serial, 0);
    let mut config_writers = BTreeMap::new();
    for (topic, type_name, bytes) in &asset.configs {
        let side = (asset.qos)(topic).unwrap_or(Side { reliable: true, transient_local: true, depth: Some(1) });
        #[cfg(feature = "test-breaks")]
        let (side, bytes) = (dds_breaks.config_side(side), &dds_breaks.config_sample(topic, bytes)?);
        // (the content without its header: a republication compares the same way)
        serials.lock().unwrap_or_else(|e| e.into_inner()).update(topic, &convert::with_header(bytes, &Default::default())?);
        #[cfg(feature = "test-breaks")]
        if dds_breaks.config_unpublished(topic) {
            continue; // (its serial is the start one all the same: its samples carry it)
        }
        let w = dp.writer(&dp.topic(topic, type_name, true).map_err(|e| e.to_string())?, side).map_err(|e| e.to_string())?;
        w.write(&convert::with_header(bytes, &hdr)?).map_err(|e| format!("{topic}: {e}"))?;
        config_writers.insert(topic.to_string(), w);
    }
    let configs = Configs::new(&name, serials.clone(), config_writers);
    #[cfg(feature = "test-breaks")]
    let configs = configs.with_source(source);
    let configs = Arc::new(configs);

    let stop = Arc::new(AtomicBool::new(false));
    #[cfg(feature = "test-breaks")]
    let drift = {
        let sample = asset.configs.iter().find(|c| c.0 == crate::breaks::DRIFTED).map(|c| c.2.clone());
        dds_breaks.drift(configs.clone(), sample, stop.clone())
    };
    let body = Arc::new(Mutex::new(Body::default()));
    // the streams' readers and writers before the telemetry (the simulated AgentState carries
    // their keys); their reporting thread once the command manager exists (stopAllMotion)
    let mut sim_streams = None;
    let parts = Arc::new(Mutex::new(Parts::of(&tables))); // what the streams move, the telemetry reports
    let mut stream_set = match streams {
        None => None,
        Some(st) => {
            let env = Env::of(&tables, &name, serial, log.clone(), asset.qos);
            let err = |e: DdsError| Failure::Run(e.to_string());
            if args.simulate {
                let sim = SimStreams::new(st.specs, &tables, body.clone(), parts.clone());
                let me = sim.clone();
                let specs = st.specs;
                let hooks = Hooks {
                    on_state: Some(Box::new(move |s: &StreamSpec, state| {
                        if let Some(i) = specs.iter().position(|x| x.name == s.name) {
                            me.on_state(i, s, state);
                        }
                    })),
                    agent_values: None,
                    periodic_agent: false, // the simulated telemetry's AgentState carries the keys
                };
                let mut set = StreamSet::new(&dp, env, st.specs, hooks).map_err(err)?;
                let fills = (st.sim)(&mut set, &sim).map_err(err)?;
                sim_streams = Some((sim, fills));
                Some(set)
            } else {
                let mut set = StreamSet::new(&dp, env, st.specs, st.hooks).map_err(err)?;
                (st.real)(&mut set).map_err(err)?;
                Some(set)
            }
        }
    };
    let sim = if args.simulate {
        let agent_values = stream_set.as_ref().map(|s| s.values());
        let source = Source {
            body: body.clone(),
            name: name.clone(),
            serials: serials.clone(),
            qos: asset.qos,
            agent_values,
            parts: stream_set.as_ref().map(|_| parts.clone()),
            #[cfg(feature = "test-breaks")]
            breaks: Some(dds_breaks.clone()),
        };
        Some(telemetry::start(&dp, &tables, source, asset.customs, stop.clone()).map_err(|e| e.to_string())?)
    } else {
        None
    };
    let on_shutdown = {
        let stop = stop.clone();
        Arc::new(move || stop.store(true, Ordering::SeqCst)) as Arc<dyn Fn() + Send + Sync>
    };
    let handlers: Arc<dyn Handlers> = if args.simulate { Arc::new(Simulated { body }) } else { handlers };
    let (out, rules): (Arc<dyn Outbox>, _) = (outbox, tables.tables);
    #[cfg(feature = "test-breaks")]
    let (out, rules) = (breaks.outbox(out), breaks.tables(rules));
    let manager = CommandManager::new(Arc::new(rules), handlers, out.clone(),
                                      Options { on_shutdown: Some(on_shutdown), ..options })
        .map_err(Failure::Run)?;
    manager.publish_states();
    if recovered.crashed {
        // before any new command: a retried cmdId is known
        let (answered, again) = manager.restore(&recovered);
        log(&format!("journal: restarted after a crash; {answered} unfinished command(s) answered, {again} final ack(s) written again"));
    }
    let manager = Arc::new(manager);
    {
        // a republished config's serial is in the journal before the config goes out
        let m = Arc::downgrade(&manager);
        configs.record_with(Arc::new(move |s| {
            if let Some(m) = m.upgrade() {
                m.journal_serial(s);
            }
        }));
        configs.install(); // the user's code reaches it from now on
    }
    if let Some(set) = stream_set.as_mut() {
        set.set_manager(manager.clone());
        set.start().map_err(|e| e.to_string())?;
    }
    if let Some((sim, fills)) = sim_streams.take() {
        sim.start(fills).map_err(|e| e.to_string())?;
        sim_streams = Some((sim, Vec::new()));
    }
    // the door: a writer's flood waits in its own FIFO and is answered "bridge busy" past its
    // share, so the other writers' commands (the operator's) keep their turn (docs/runtime.md)
    let door = Intake::new(manager.clone(), log, PER_WRITER, SHED_ANSWERS);
    door.start();
    let commands = dp.topic("rapid_command", "rapid::Command", true).map_err(|e| e.to_string())?;
    let reader = dp
        .reader(&commands, Side { reliable: true, transient_local: false, depth: None })
        .map_err(|e| e.to_string())?;
    // woken by a command's arrival (a waitset), not by polling: a poll's sleep was most of a
    // command's latency (bench/rust_bridge.py); the stop flags are read at least every TICK
    let arrived = dp.waiter(&reader).map_err(|e| e.to_string())?;
    println!("{name} ready on domain {domain}{}", if args.simulate { " (simulated)" } else { "" });
    let mut drops = Drops::default();
    stop_on_signals();
    while !stop.load(Ordering::SeqCst) && !SIGNALLED.load(Ordering::SeqCst) {
        let mut idle = true;
        while let Some((bytes, writer)) = reader.take() {
            idle = false;
            match convert::command_in(&bytes) {
                Ok(cmd) => {
                    #[cfg(feature = "test-breaks")]
                    let Some(cmd) = breaks.intake(cmd, manager.tables(), out.as_ref()) else { continue };
                    door.offer(cmd, &format!("{writer:x}"))
                }
                Err(e) => drops.dropped(&name, writer, &e.to_string()),
            }
        }
        if idle {
            arrived.wait(TICK);
        }
    }
    stop.store(true, Ordering::SeqCst); // (after a signal: the telemetry thread ends too)
    #[cfg(feature = "test-breaks")]
    if let Some(d) = drift {
        let _ = d.join(); // (before the config writers go with the participant)
    }
    if let Some((sim, _)) = sim_streams {
        sim.stop();
    }
    if let Some(mut set) = stream_set {
        set.stop(); // (before the manager: a loss's stopAllMotion is not sent to a stopped one)
    }
    door.stop();
    manager.shutdown(None);
    if let Some(j) = manager.release_journal() {
        j.close(true); // every command answered: the next start begins afresh
    }
    if let Some(t) = sim {
        let _ = t.join();
    }
    Ok(())
}

/// SIGTERM or SIGINT came: the bridge stops as after Admin/shutdown (what runs answered, the
/// journal closed clean), as the Python and C++ bridges do.
static SIGNALLED: AtomicBool = AtomicBool::new(false);

extern "C" fn on_signal(_: libc::c_int) {
    SIGNALLED.store(true, Ordering::SeqCst); // (an atomic store: safe in a signal handler)
}

fn stop_on_signals() {
    let handler = on_signal as extern "C" fn(libc::c_int) as libc::sighandler_t;
    // SAFETY: the handler only stores to an atomic; signal() replaces the default action
    unsafe {
        libc::signal(libc::SIGTERM, handler);
        libc::signal(libc::SIGINT, handler);
    }
}

/// Writers whose Commands are counted one by one when they do not decode; past this, as
/// "other writers" (a flood of new writers must not grow the table).
const MAX_WRITERS: usize = 256;

/// Commands the codec refuses (a string past its bound, invalid UTF-8, truncated CDR): not
/// answered, as in the Python and C++ runtimes (the sample's cmdId cannot be trusted), each
/// counted against the writer that sent it and logged once per writer.
#[derive(Default)]
struct Drops(BTreeMap<u64, u64>);

impl Drops {
    fn dropped(&mut self, name: &str, writer: u64, why: &str) {
        let key = if self.0.len() >= MAX_WRITERS && !self.0.contains_key(&writer) { 0 } else { writer };
        let n = self.0.entry(key).or_insert(0);
        *n += 1;
        if *n == 1 {
            let who = if key == 0 { "other writers".to_string() } else { format!("writer {writer:x}") };
            eprintln!("[{name}] dropped an undecodable Command from {who}: {} (further ones from it are counted, \
                       not logged)", rapid_runtime::text::visible(why, 160));
        }
    }
}
