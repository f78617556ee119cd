//! Setpoint streams on Cyclone DDS (docs/realtime.md "In the Rust runtime"): input streams
//! read outside the command queue, a typed callback per sample; output streams written from
//! one kept sample. The twin of the C++ runtime's rapid_runtime/dds/stream.hpp.
//!
//! ```ignore
//! let mut set = StreamSet::new(&dp, env, SPECS, hooks);
//! set.read::<rapid::PositionSample>(0, decode, finite, move |s| { ... })?;  // Cyclone's receive thread
//! set.output(1, &HAND_POSE)?;        // HAND_POSE: a static OutputStream<T>
//! set.start();                      // the reporting thread
//! ```
//!
//! Readers: DEADLINE = the declared deadline, AUTOMATIC LIVELINESS with the declared lease,
//! best effort, volatile, keep last 1, in the writer's partition (a subscriber of their own).
//! A Cyclone listener takes each sample on the thread that delivers it: its CDR bytes go into
//! one buffer kept for the whole run, the generated codec decodes them over one sample kept
//! for the whole run (`cdr::deserialize_into`: strings and sequences reuse their capacity, so
//! no allocation once the first sample sized them), a sample with a NaN or an
//! infinity is dropped (`finite`, given per type by the generated glue), the callback gets the
//! rest. Cyclone's deadline and liveliness listeners (its event thread) only flip the
//! stream's StreamMonitor and wake the reporting thread, which runs the declared action
//! (stop: the on_state hook and, when the asset has Mobility, stopAllMotion through the
//! command manager; hold: the hook; none: nothing), publishes a TextMessage in the C++
//! runtime's words and the AgentState with the state and missed keys.
use std::ffi::{c_void, CString};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard, OnceLock};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use cyclors::*;
use rapid_runtime::stream::{format_ms, LossAction, LossCause, StreamMonitor, StreamSpec, StreamState};
use rapid_runtime::text::{clip, visible};
use rapid_runtime::{Cmd, CommandManager, Value};
use rapid_types::cdr::{self, Endianness};
use rapid_types::rapid;

use crate::convert;
use crate::dds::{DdsError, Participant, Side, Writer};
use crate::pooled::{self, Pool};
use crate::tables_json::Asset;
use crate::telemetry;

/// The bridge's log line (`[Asset] text` on stderr).
pub type Log = Arc<dyn Fn(&str) + Send + Sync>;
/// A sample's CDR bytes (encapsulation header included) into a kept value (its capacity reused).
pub type Decode<T> = fn(&[u8], &mut T) -> Result<(), String>;
/// A sample's CDR_LE bytes (encapsulation header included) into a kept buffer (cleared first).
pub type Encode<T> = fn(&T, &mut Vec<u8>) -> Result<(), String>;
/// Whether every floating-point number of a setpoint is finite.
pub type Finite<T> = fn(&T) -> bool;

/// The agent entry AgentState goes out on: its topic, rate and value keys (in the config's
/// order, each with its declared default or a plausible value).
#[derive(Clone)]
pub struct AgentEntry {
    pub topic: String,
    /// its AgentConfig's topic ("" none): AgentState carries that config's serial now
    pub config: String,
    pub rate: f64,
    pub keys: Vec<(String, rapid::ParameterUnion)>,
}

/// What the streams need of the bridge.
pub struct Env {
    pub name: String,
    /// the configs' serial at start (TextMessages carry it; AgentState its config's serial now)
    pub serial: i32,
    pub log: Log,
    /// stopAllMotion on a `stop` loss goes here (unset: nothing sent; StreamSet::set_manager)
    pub manager: OnceLock<Arc<CommandManager>>,
    /// the asset's first Mobility subsystem ("" none: no stopAllMotion)
    pub mobility: String,
    pub agent: Option<AgentEntry>,
    /// the asset's text telemetry topic ("" none: the log only)
    pub text_topic: String,
    /// the writer side of a topic's QoS profile (text and agent writers)
    pub qos: fn(&str) -> Option<Side>,
}

impl Env {
    /// The agent and text entries of the asset's tables (the first of each kind).
    pub fn of(asset: &Asset, name: &str, serial: i32, log: Log, qos: fn(&str) -> Option<Side>) -> Env {
        let agent = asset.telemetry.iter().find(|t| t.kind == "agent").and_then(|t| {
            t.topics.get("state").map(|topic| AgentEntry {
                topic: topic.clone(),
                config: t.topics.get("config").cloned().unwrap_or_default(),
                rate: t.rate.filter(|r| *r > 0.0).unwrap_or(1.0),
                keys: t.values.iter().map(|v| (v.name.clone(), telemetry::plausible(v))).collect(),
            })
        });
        let text_topic = asset
            .telemetry
            .iter()
            .find(|t| t.kind == "text")
            .and_then(|t| t.topics.get("sample").cloned())
            .unwrap_or_default();
        let mobility = asset.tables.subsystems_of_type("Mobility").into_iter().next().unwrap_or_default();
        Env { name: name.into(), serial, log, manager: OnceLock::new(), mobility, agent, text_topic, qos }
    }
}

/// The on_state hook: a stream and its new state.
pub type StateHook = Box<dyn Fn(&StreamSpec, StreamState) + Send + Sync>;
/// Agent values by key.
pub type ValuesHook = Box<dyn Fn() -> Vec<(String, Value)> + Send + Sync>;

/// What the generated glue tells the stream set about the user's code.
pub struct Hooks {
    /// A stream with on_loss stop or hold changed state (lost: the declared action is being
    /// taken; active: first sample or recovered). Not called for on_loss none.
    pub on_state: Option<StateHook>,
    /// The asset's own agent values, under the stream keys (none: declared defaults).
    pub agent_values: Option<ValuesHook>,
    /// false: AgentState only when a stream's state or missed count changed (the simulated
    /// robot publishes it at the agent entry's rate, the stream keys merged in).
    pub periodic_agent: bool,
}

impl Default for Hooks {
    fn default() -> Hooks {
        Hooks { on_state: None, agent_values: None, periodic_agent: true }
    }
}

// ---- whether a setpoint is finite ---------------------------------------------------------

pub fn finite_f32(v: &[f32]) -> bool {
    v.iter().all(|x| x.is_finite())
}

pub fn finite_f64(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

// ---- readers ------------------------------------------------------------------------------

/// A reader's per-sample work, its type erased: takes what the reader holds.
trait Sink: Send {
    fn take_all(&mut self, reader: dds_entity_t, shared: &Shared, index: usize);
}

struct Typed<T, F> {
    buf: Vec<u8>, // the CDR bytes, capacity kept for the whole run
    sample: T,    // decoded into, capacity kept for the whole run
    decode: Decode<T>,
    finite: Finite<T>,
    callback: F,
    decode_errors: u64,
}

impl<T: Send, F: FnMut(&T) + Send> Sink for Typed<T, F> {
    fn take_all(&mut self, reader: dds_entity_t, shared: &Shared, index: usize) {
        loop {
            let mut info: dds_sample_info_t;
            // SAFETY: dds_takecdr hands over one serdata reference, released below; to_ser
            // writes get_size bytes into a buffer of that length
            unsafe {
                let mut sd: *mut ddsi_serdata = std::ptr::null_mut();
                info = std::mem::zeroed();
                if dds_takecdr(reader, &mut sd, 1, &mut info, DDS_ANY_STATE) <= 0 || sd.is_null() {
                    return;
                }
                let ops = (*sd).ops;
                let ok = match ((*ops).get_size, (*ops).to_ser) {
                    (Some(size), Some(to_ser)) if info.valid_data => {
                        let n = size(sd) as usize;
                        self.buf.clear();
                        self.buf.resize(n, 0); // within the kept capacity once the first sized it
                        to_ser(sd, 0, n, self.buf.as_mut_ptr() as *mut _);
                        true
                    }
                    _ => false,
                };
                ddsi_serdata_unref(sd);
                if !ok {
                    continue; // a dispose or unregister: no data
                }
            }
            let now = Instant::now();
            let sample = &mut self.sample;
            match (self.decode)(&self.buf, sample) {
                Ok(()) => {}
                Err(e) => {
                    self.decode_errors += 1;
                    if self.decode_errors == 1 {
                        (shared.env.log)(&format!("stream {}: a sample that does not decode dropped: {} (further ones \
                                                   counted, not logged)", visible(shared.specs[index].name, 64), visible(&e, 160)));
                    }
                    continue;
                }
            };
            let m = &shared.monitors[index];
            if !(self.finite)(sample) {
                // never handed on, and not a sample that keeps the stream alive
                let r = m.non_finite_sample(Duration::from_secs_f64(shared.specs[index].deadline_ms / 1000.0), now);
                if r.lost || r.first_of_run {
                    shared.poke();
                }
                continue;
            }
            (self.callback)(sample);
            // after the callback: a state hook never sees "active" before its sample
            if m.sample(now) {
                shared.poke();
            }
        }
    }
}

/// The listener's argument: lives until the reader is deleted (StreamSet::stop).
struct Slot {
    shared: Arc<Shared>,
    index: usize,
    sink: Mutex<Box<dyn Sink>>,
}

unsafe extern "C" fn on_data(reader: dds_entity_t, arg: *mut c_void) {
    // SAFETY: arg is the reader's Slot, alive while the reader is (deleted before it)
    let slot = unsafe { &*(arg as *const Slot) };
    let mut sink = slot.sink.lock().unwrap_or_else(|e| e.into_inner());
    sink.take_all(reader, &slot.shared, slot.index);
}

unsafe extern "C" fn on_deadline(_: dds_entity_t, st: dds_requested_deadline_missed_status_t, arg: *mut c_void) {
    // SAFETY: as on_data
    let slot = unsafe { &*(arg as *const Slot) };
    let n = u64::try_from(st.total_count_change).ok().filter(|n| *n > 0).unwrap_or(1);
    slot.shared.monitors[slot.index].deadline_missed(n);
    slot.shared.poke(); // the missed count changed even when the state did not
}

unsafe extern "C" fn on_liveliness(_: dds_entity_t, st: dds_liveliness_changed_status_t, arg: *mut c_void) {
    // SAFETY: as on_data
    let slot = unsafe { &*(arg as *const Slot) };
    if slot.shared.monitors[slot.index].writers_alive(st.alive_count) {
        slot.shared.poke();
    }
}

fn ns(ms: f64) -> i64 {
    (ms * 1e6).round().clamp(1.0, i64::MAX as f64) as i64
}

/// A stream's QoS (the RapidStream_<name> profile's): best effort, volatile, keep last 1,
/// DEADLINE, AUTOMATIC LIVELINESS; `partition` for a subscriber's or publisher's.
struct StreamQos(*mut dds_qos_t);

impl StreamQos {
    fn endpoint(s: &StreamSpec) -> StreamQos {
        // SAFETY: a fresh qos object, owned by this value and deleted on drop
        unsafe {
            let q = dds_create_qos();
            dds_qset_reliability(q, dds_reliability_kind_DDS_RELIABILITY_BEST_EFFORT, 0);
            dds_qset_durability(q, dds_durability_kind_DDS_DURABILITY_VOLATILE);
            dds_qset_history(q, dds_history_kind_DDS_HISTORY_KEEP_LAST, 1);
            if s.deadline_ms > 0.0 {
                dds_qset_deadline(q, ns(s.deadline_ms));
            }
            if s.liveliness_ms > 0.0 {
                dds_qset_liveliness(q, dds_liveliness_kind_DDS_LIVELINESS_AUTOMATIC, ns(s.liveliness_ms));
            }
            StreamQos(q)
        }
    }

    fn partition(p: &str) -> StreamQos {
        // SAFETY: as endpoint; Cyclone copies the names
        unsafe {
            let q = dds_create_qos();
            let c = CString::new(p).unwrap_or_default();
            let mut names = [c.as_ptr()];
            dds_qset_partition(q, 1, names.as_mut_ptr());
            StreamQos(q)
        }
    }
}

impl Drop for StreamQos {
    fn drop(&mut self) {
        // SAFETY: created by dds_create_qos, deleted once
        unsafe { dds_delete_qos(self.0) }
    }
}

// ---- output streams -----------------------------------------------------------------------

/// An output stream's one sample, filled in place and written (a `static` of the generated
/// glue: `<name>_sample()`, `send_<name>()`). Its header's names are set when the bridge
/// attaches the writer; `send` stamps hdr.timeStamp (microseconds, UTC).
pub struct OutputStream<T> {
    sample: Mutex<Option<T>>,
    writer: Mutex<Option<Writer>>,
    encode: Encode<T>,
    header: fn(&mut T, &str, i64),
    bytes: Mutex<Vec<u8>>, // the encoding, capacity kept for the whole run
}

/// The sample, locked (drop it, or call `send`, before `send_<name>()`).
pub struct SampleGuard<'a, T: Default>(MutexGuard<'a, Option<T>>, &'a OutputStream<T>);

impl<T: Default> std::ops::Deref for SampleGuard<'_, T> {
    type Target = T;
    fn deref(&self) -> &T {
        self.0.as_ref().expect("filled by OutputStream::sample")
    }
}

impl<T: Default> std::ops::DerefMut for SampleGuard<'_, T> {
    fn deref_mut(&mut self) -> &mut T {
        self.0.as_mut().expect("filled by OutputStream::sample")
    }
}

impl<T: Default> SampleGuard<'_, T> {
    /// Stamps and writes the sample held (as OutputStream::send).
    pub fn send(mut self) -> bool {
        let out = self.1;
        out.write(self.0.as_mut().expect("filled by OutputStream::sample"))
    }
}

impl<T: Default> OutputStream<T> {
    /// `encode`: the sample's CDR_LE bytes; `header`: sets hdr.srcName and hdr.assetName to
    /// the name given and hdr.timeStamp to the time given (microseconds).
    pub const fn new(encode: Encode<T>, header: fn(&mut T, &str, i64)) -> Self {
        OutputStream { sample: Mutex::new(None), writer: Mutex::new(None), encode, header, bytes: Mutex::new(Vec::new()) }
    }

    /// The sample, to fill in place (kept between sends: sequences keep their capacity).
    pub fn sample(&self) -> SampleGuard<'_, T> {
        let mut g = self.sample.lock().unwrap_or_else(|e| e.into_inner());
        if g.is_none() {
            *g = Some(T::default());
        }
        SampleGuard(g, self)
    }

    /// Stamps hdr.timeStamp and writes the sample; false before the bridge started or after
    /// it stopped, or when the codec or Cyclone refused it.
    pub fn send(&self) -> bool {
        let mut g = self.sample();
        let s: &mut T = &mut g;
        self.write(s)
    }

    fn write(&self, s: &mut T) -> bool {
        let Some(w) = *self.writer.lock().unwrap_or_else(|e| e.into_inner()) else { return false };
        (self.header)(s, "", convert::now_us());
        let mut bytes = self.bytes.lock().unwrap_or_else(|e| e.into_inner());
        match (self.encode)(s, &mut bytes) {
            Ok(()) => w.write(&bytes).is_ok(),
            Err(_) => false,
        }
    }

    fn attach(&self, w: Option<Writer>, name: &str) {
        if w.is_some() {
            let mut g = self.sample();
            (self.header)(&mut g, name, 0);
        }
        *self.writer.lock().unwrap_or_else(|e| e.into_inner()) = w;
    }
}

/// An output stream of any type, as the set keeps it (to detach at stop).
trait Attached: Send + Sync {
    fn detach(&self);
}

impl<T: Default + Send> Attached for OutputStream<T> {
    fn detach(&self) {
        self.attach(None, "");
    }
}

// ---- the set ------------------------------------------------------------------------------

struct Wake {
    stopping: bool,
    poked: bool,
}

struct Shared {
    specs: &'static [StreamSpec],
    monitors: Vec<StreamMonitor>,
    env: Env,
    hooks: Hooks,
    wake: Mutex<Wake>,
    cv: Condvar,
    text: Option<Writer>,
    agent: Option<Writer>,
    stops: Mutex<u64>,
}

impl Shared {
    /// From the listeners: a state may have changed (no allocation: a flag and a notify).
    fn poke(&self) {
        self.wake.lock().unwrap_or_else(|e| e.into_inner()).poked = true;
        self.cv.notify_one();
    }

    /// The stream keys' values now (state and missed count of every input stream naming them).
    fn stream_values(&self) -> Vec<(String, Value)> {
        let mut out = Vec::new();
        for (s, m) in self.specs.iter().zip(&self.monitors) {
            if !s.state_key.is_empty() {
                out.push((s.state_key.to_string(), Value::String(m.state().name().into())));
            }
            if !s.missed_key.is_empty() {
                out.push((s.missed_key.to_string(), Value::Int(m.missed().min(i32::MAX as u64) as i32)));
            }
        }
        out
    }

    fn say(&self, text: &str, level: rapid::MessageLevel) {
        (self.env.log)(text);
        let Some(w) = self.text else { return };
        let msg = rapid::TextMessage {
            hdr: convert::header(&self.env.name, &self.env.name, self.env.serial, 0),
            level,
            category: "stream".into(),
            message: clip(text, 127).to_string(),
        };
        let sent = cdr::serialize(&msg, Endianness::Little).map_err(|e| e.to_string()).and_then(|b| w.write(&b).map_err(|e| e.to_string()));
        if let Err(e) = sent {
            (self.env.log)(&format!("stream text not sent: {e}"));
        }
    }

    fn publish_agent(&self) {
        let (Some(w), Some(agent)) = (self.agent, &self.env.agent) else { return };
        let mut given = self.hooks.agent_values.as_ref().map(|f| f()).unwrap_or_default();
        given.extend(self.stream_values()); // the stream keys are the runtime's
        let values = agent
            .keys
            .iter()
            .map(|(k, default)| given.iter().rev().find(|(g, _)| g == k).map(|(_, v)| convert::union(v)).unwrap_or_else(|| default.clone()))
            .collect();
        let serial = agent_serial(crate::configs::get().as_deref(), &agent.config, self.env.serial);
        let s = rapid::AgentState { hdr: convert::header(&self.env.name, &self.env.name, serial, 0), values };
        let sent = cdr::serialize(&s, Endianness::Little).map_err(|e| e.to_string()).and_then(|b| w.write(&b).map_err(|e| e.to_string()));
        if let Err(e) = sent {
            (self.env.log)(&format!("stream AgentState not sent: {e}"));
        }
    }

    /// stopAllMotion's effect through the runtime: the command manager runs it as if the
    /// asset had sent it (it cancels Mobility commands, then the handler stops the hardware).
    fn stop_motion(&self, s: &StreamSpec) {
        let (Some(manager), false) = (self.env.manager.get(), self.env.mobility.is_empty()) else { return };
        let n = {
            let mut n = self.stops.lock().unwrap_or_else(|e| e.into_inner());
            *n += 1;
            *n
        };
        let name = &self.env.name;
        manager.receive(Cmd {
            cmd_id: format!("stream-{}-stop-{n}", s.name),
            cmd_src: name.clone(),
            subsystem: self.env.mobility.clone(),
            name: "stopAllMotion".into(),
            src_name: name.clone(),
            asset_name: name.clone(),
            stamp: convert::now_us(),
            ..Cmd::default()
        });
    }

    fn changed(&self, i: usize, was: StreamState, now: StreamState) {
        // Only an active stream is lost (StreamMonitor): waiting then lost at two polls is a
        // first sample and a missed deadline between them, said in the order they came
        if was == StreamState::Waiting && now == StreamState::Lost {
            self.changed(i, was, StreamState::Active);
        }
        let s = &self.specs[i];
        let m = &self.monitors[i];
        let name = visible(s.name, 64);
        let text = match now {
            StreamState::Lost => {
                let why = match m.cause() {
                    LossCause::Liveliness => format!("its writer is gone: no liveliness within {}", format_ms(s.liveliness_ms)),
                    LossCause::NonFinite => format!("no finite sample within its {} deadline, {} with NaN or Inf dropped",
                                                    format_ms(s.deadline_ms), m.non_finite()),
                    LossCause::Deadline => format!("no sample within its {} deadline", format_ms(s.deadline_ms)),
                };
                if s.on_loss == LossAction::Stop {
                    self.stop_motion(s);
                }
                format!("stream {name} lost ({why}; {} deadlines missed): {}", m.missed(), s.on_loss.text())
            }
            StreamState::Active if was == StreamState::Lost => format!("stream {name} recovered"),
            StreamState::Active => format!("stream {name} active"),
            StreamState::Waiting => String::new(),
        };
        if s.on_loss != LossAction::None {
            // none: reported, nothing done
            if let Some(hook) = &self.hooks.on_state {
                if std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| hook(s, now))).is_err() {
                    (self.env.log)(&format!("stream {name}: handler failed (panicked)"));
                }
            }
        }
        if !text.is_empty() {
            let level = if now == StreamState::Lost { rapid::MessageLevel::MsgWarn } else { rapid::MessageLevel::MsgInfo };
            self.say(&text, level);
        }
    }

    fn report_loop(&self) {
        let reports = self.specs.iter().any(|s| !s.state_key.is_empty() || !s.missed_key.is_empty());
        let rate = self.env.agent.as_ref().map_or(1.0, |a| a.rate);
        let period = Duration::from_secs_f64(1.0 / rate);
        let n = self.specs.len();
        let mut reported = vec![StreamState::Waiting; n];
        let mut gone = vec![0u64; n]; // writers gone, as reported
        let mut runs = vec![0u64; n]; // runs of non-finite samples, as reported
        loop {
            let poked = {
                let g = self.wake.lock().unwrap_or_else(|e| e.into_inner());
                let (mut g, _) = self
                    .cv
                    .wait_timeout_while(g, period, |w| !w.stopping && !w.poked)
                    .unwrap_or_else(|e| e.into_inner());
                if g.stopping {
                    return;
                }
                std::mem::replace(&mut g.poked, false)
            };
            for i in 0..n {
                let m = &self.monitors[i];
                let s = &self.specs[i];
                let now = m.state();
                let went = m.writers_gone() != gone[i];
                gone[i] = m.writers_gone();
                if m.non_finite_runs() != runs[i] {
                    runs[i] = m.non_finite_runs();
                    self.say(&format!("stream {}: samples with NaN or Inf dropped ({} so far); lost without a finite one in {}",
                                      visible(s.name, 64), m.non_finite(), format_ms(s.deadline_ms)),
                             rapid::MessageLevel::MsgWarn);
                }
                if now != reported[i] {
                    let was = std::mem::replace(&mut reported[i], now);
                    self.changed(i, was, now);
                }
                if went && now == StreamState::Lost && m.cause() == LossCause::Deadline {
                    // a deadline lost it first: the writer's going is news of its own
                    self.say(&format!("stream {}: its writer is gone (no liveliness within {})", visible(s.name, 64),
                                      format_ms(s.liveliness_ms)),
                             rapid::MessageLevel::MsgWarn);
                }
            }
            if reports && (poked || self.hooks.periodic_agent) {
                self.publish_agent();
            }
        }
    }
}

/// AgentState's header serial: its config's now (a config republished through
/// rapid_dds::configs has a new one), the start serial without a running bridge's configs or
/// an AgentConfig.
fn agent_serial(configs: Option<&crate::configs::Configs>, config: &str, start: i32) -> i32 {
    match configs {
        Some(c) if !config.is_empty() => c.serial(config),
        _ => start,
    }
}

/// The asset's streams: readers, output writers and the reporting thread.
pub struct StreamSet {
    shared: Arc<Shared>,
    dp: dds_entity_t,
    publisher: Option<dds_entity_t>,
    readers: Vec<(dds_entity_t, dds_entity_t, *mut Slot)>, // reader, subscriber, listener arg
    outputs: Vec<&'static dyn Attached>,
    /// each stream's topic's serialized samples (pooled.rs), by stream index
    pools: Vec<(usize, &'static Pool)>,
    thread: Option<JoinHandle<()>>,
    stopped: AtomicBool,
}

// SAFETY: the raw Slot pointers are freed only in stop(), after their readers are deleted
// (Cyclone waits for running listeners); entity handles are integers
unsafe impl Send for StreamSet {}
unsafe impl Sync for StreamSet {}

impl StreamSet {
    /// `specs`: the asset's streams (the generated glue's constants), by index.
    pub fn new(dp: &Participant, env: Env, specs: &'static [StreamSpec], hooks: Hooks) -> Result<StreamSet, DdsError> {
        let writer = |topic: &str, type_name: &str| -> Result<Option<Writer>, DdsError> {
            if topic.is_empty() {
                return Ok(None);
            }
            let side = (env.qos)(topic).unwrap_or(Side { reliable: true, transient_local: false, depth: Some(1) });
            Ok(Some(dp.writer(&dp.topic(topic, type_name, true)?, side)?))
        };
        let text = writer(&env.text_topic, "rapid::TextMessage")?;
        let agent_topic = env.agent.as_ref().map(|a| a.topic.clone()).unwrap_or_default();
        let agent = writer(&agent_topic, "rapid::AgentState")?;
        let shared = Arc::new(Shared {
            specs,
            monitors: specs.iter().map(|_| StreamMonitor::new()).collect(),
            env,
            hooks,
            wake: Mutex::new(Wake { stopping: false, poked: false }),
            cv: Condvar::new(),
            text,
            agent,
            stops: Mutex::new(0),
        });
        Ok(StreamSet { shared, dp: dp.handle(), publisher: None, readers: Vec::new(), outputs: Vec::new(), pools: Vec::new(), thread: None,
                       stopped: AtomicBool::new(false) })
    }

    /// The index-th stream's reader (an input stream): `callback` gets every finite sample on
    /// Cyclone's delivering thread (keep it short: no lock another thread holds long).
    pub fn read<T, F>(&mut self, index: usize, decode: Decode<T>, finite: Finite<T>, callback: F) -> Result<(), DdsError>
    where
        T: Default + Send + 'static,
        F: FnMut(&T) + Send + 'static,
    {
        let s = self.spec(index);
        let sink: Box<dyn Sink> =
            Box::new(Typed { buf: Vec::with_capacity(4096), sample: T::default(), decode, finite, callback, decode_errors: 0 });
        let slot = Box::into_raw(Box::new(Slot { shared: self.shared.clone(), index, sink: Mutex::new(sink) }));
        let fail = |what: &str, ret: i32, slot: *mut Slot| {
            // SAFETY: no reader holds the slot (its creation failed)
            drop(unsafe { Box::from_raw(slot) });
            DdsError(format!("stream {}: {what}: DDS error {ret}", s.name))
        };
        let topic = CString::new(s.topic).map_err(|_| DdsError(format!("topic name {:?}", s.topic)))?;
        let type_name = CString::new(s.type_name).map_err(|_| DdsError(format!("type name {:?}", s.type_name)))?;
        // SAFETY: plain calls of Cyclone's C API; the listener's argument outlives the reader
        unsafe {
            let (t, pool) = match pooled::topic(self.dp, &topic, &type_name) {
                Ok(t) => t,
                Err(e) => return Err(fail("topic", e, slot)),
            };
            let pq = StreamQos::partition(s.partition); // the writing asset's partition
            let sub = dds_create_subscriber(self.dp, pq.0, std::ptr::null());
            if sub < 0 {
                return Err(fail("subscriber", sub, slot));
            }
            let l = dds_create_listener(slot as *mut c_void);
            dds_lset_data_available(l, Some(on_data));
            dds_lset_requested_deadline_missed(l, Some(on_deadline));
            dds_lset_liveliness_changed(l, Some(on_liveliness));
            let q = StreamQos::endpoint(&s);
            let r = dds_create_reader(sub, t, q.0, l);
            dds_delete_listener(l); // the reader keeps its own copy
            if r < 0 {
                dds_delete(sub);
                return Err(fail("reader", r, slot));
            }
            self.readers.push((r, sub, slot));
            self.pools.push((index, pool));
        }
        Ok(())
    }

    /// The index-th stream's writer (an output stream), attached to `out` until stop.
    pub fn output<T: Default + Send + 'static>(&mut self, index: usize, out: &'static OutputStream<T>) -> Result<(), DdsError> {
        let s = self.spec(index);
        // SAFETY: plain calls of Cyclone's C API
        let w = unsafe {
            let publisher = match self.publisher {
                Some(p) => p,
                None => {
                    let pq = StreamQos::partition(s.partition);
                    let p = dds_create_publisher(self.dp, pq.0, std::ptr::null());
                    if p < 0 {
                        return Err(DdsError(format!("stream {}: publisher: DDS error {p}", s.name)));
                    }
                    self.publisher = Some(p);
                    p
                }
            };
            let topic = CString::new(s.topic).map_err(|_| DdsError(format!("topic name {:?}", s.topic)))?;
            let type_name = CString::new(s.type_name).map_err(|_| DdsError(format!("type name {:?}", s.type_name)))?;
            let (t, pool) = pooled::topic(self.dp, &topic, &type_name)
                .map_err(|e| DdsError(format!("stream {}: topic: DDS error {e}", s.name)))?;
            let q = StreamQos::endpoint(&s);
            let w = dds_create_writer(publisher, t, q.0, std::ptr::null());
            if w < 0 {
                return Err(DdsError(format!("stream {}: writer: DDS error {w}", s.name)));
            }
            self.pools.push((index, pool));
            Writer::from_raw(w, t)
        };
        out.attach(Some(w), &self.shared.env.name);
        self.outputs.push(out);
        Ok(())
    }

    /// Where a `stop` loss sends stopAllMotion (once; the manager exists after the readers).
    pub fn set_manager(&self, manager: Arc<CommandManager>) {
        let _ = self.shared.env.manager.set(manager);
    }

    /// The reporting thread: actions, TextMessages, AgentState.
    pub fn start(&mut self) -> Result<(), DdsError> {
        if self.thread.is_some() {
            return Ok(());
        }
        let shared = self.shared.clone();
        let t = std::thread::Builder::new()
            .name("stream-report".into())
            .spawn(move || shared.report_loop())
            .map_err(|e| DdsError(format!("stream reporting thread: {e}")))?;
        self.thread = Some(t);
        Ok(())
    }

    /// Readers deleted (no callback after this returns), outputs detached, the thread joined,
    /// a summary line per input stream logged; idempotent.
    pub fn stop(&mut self) {
        if self.stopped.swap(true, Ordering::SeqCst) {
            return;
        }
        for (s, m) in self.shared.specs.iter().zip(&self.shared.monitors) {
            if s.input {
                (self.shared.env.log)(&format!("stream {}: {} samples, {} deadlines missed, {} losses, {} non-finite dropped",
                                               visible(s.name, 64), m.samples(), m.missed(), m.losses(), m.non_finite()));
            }
        }
        for (r, sub, slot) in self.readers.drain(..) {
            // SAFETY: deleting the reader waits for its listeners; then nothing holds the slot
            unsafe {
                dds_delete(r);
                dds_delete(sub);
                drop(Box::from_raw(slot));
            }
        }
        for o in self.outputs.drain(..) {
            o.detach();
        }
        // after the readers went (their histories gave their samples back): what Cyclone's
        // serialized samples cost, e.g. `stream arm: serialized samples: 3 made, 997 reused, 0
        // freed past the pool of 8, 0 held`; an input stream holds none now
        for (i, pool) in &self.pools {
            let p = pool.stats();
            (self.shared.env.log)(&format!("stream {}: serialized samples: {} made, {} reused, {} freed past the pool of {}, {} held",
                                           visible(self.shared.specs[*i].name, 64), p.made, p.reused, p.dropped, pooled::SLOTS, p.out));
        }
        self.shared.wake.lock().unwrap_or_else(|e| e.into_inner()).stopping = true;
        self.shared.cv.notify_all();
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }

    pub fn spec(&self, index: usize) -> StreamSpec {
        self.shared.specs[index]
    }

    pub fn monitor(&self, index: usize) -> &StreamMonitor {
        &self.shared.monitors[index]
    }

    pub fn len(&self) -> usize {
        self.shared.specs.len()
    }

    pub fn is_empty(&self) -> bool {
        self.shared.specs.is_empty()
    }

    /// The stream keys' values now (the simulated robot's AgentState merges them in).
    pub fn values(&self) -> Arc<dyn Fn() -> Vec<(String, Value)> + Send + Sync> {
        let shared = self.shared.clone();
        Arc::new(move || shared.stream_values())
    }
}

impl Drop for StreamSet {
    fn drop(&mut self) {
        self.stop();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Default)]
    struct Sample {
        name: String,
        stamp: i64,
        values: Vec<f32>,
    }

    static OUT: OutputStream<Sample> = OutputStream::new(
        |s, out| {
            out.clear();
            out.extend(s.values.iter().flat_map(|x| x.to_le_bytes()));
            Ok(())
        },
        |s, name, stamp| {
            if !name.is_empty() {
                s.name = name.into();
            }
            if stamp != 0 {
                s.stamp = stamp;
            }
        },
    );

    #[test]
    fn an_output_stream_keeps_its_sample_and_sends_nothing_before_the_bridge_attaches() {
        OUT.sample().values = vec![1.0; 64];
        assert!(!OUT.send()); // no writer yet: false, nothing stamped
        assert!(!OUT.sample().send());
        let s = OUT.sample();
        assert_eq!((s.values.len(), s.stamp, s.name.as_str()), (64, 0, "")); // kept as filled
    }

    #[test]
    fn agent_state_carries_its_configs_serial_as_republished() {
        use std::collections::BTreeMap;
        let serials: crate::configs::SharedSerials =
            Arc::new(Mutex::new(rapid_runtime::configs::Serials::new(Some(1000), Box::new(|| 5000), None)));
        let c = crate::configs::Configs::new("A", serials.clone(), BTreeMap::new());
        serials.lock().unwrap().update("agent_config", b"first");
        assert_eq!(agent_serial(Some(&c), "agent_config", 1000), 1000);
        let (new, changed) = serials.lock().unwrap().update("agent_config", b"second");
        assert!(changed && new > 1000);
        assert_eq!(agent_serial(Some(&c), "agent_config", 1000), new);
        assert_eq!(agent_serial(Some(&c), "", 1000), 1000); // no AgentConfig: the start serial
        assert_eq!(agent_serial(None, "agent_config", 1000), 1000); // no running bridge's configs
    }

    #[test]
    fn finite_checks() {
        assert!(finite_f32(&[1.0, -2.0]) && finite_f64(&[]) && finite_f64(&[1e300]));
        assert!(!finite_f32(&[0.0, f32::NAN]) && !finite_f64(&[f64::NEG_INFINITY]));
    }
}
