//! Simulated telemetry (`--simulate`), as the Python runtime's simulate.py publishes it: every
//! declared entry on its topics, each sample's header copying its config's (the asset's name,
//! its config's serial as it is now: a republished config's new one, `configs.rs`) with the
//! time it was made. Position, agent and joint entries at their
//! declared rate (1 Hz without one), values aligned with their config (one per value key, of
//! its DataType, inside its declared range); images (a synthetic grey picture of the declared
//! size and MIME type, with the camera's state) at their rate, or every IDLE_PERIOD seconds
//! when none is declared and no command of the subsystem takes pictures; extension (custom)
//! entries from samples the bridge makes (the generated types), header replaced; a text
//! message at start (and at a declared rate). Position samples report the body
//! bridge::Simulated drives (speed and odometer value keys too); joints stay at rest.
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use rapid_runtime::{DataType, Value};
use rapid_types::cdr::{self, Endianness};
use rapid_types::rapid;

use crate::configs::SharedSerials;
use crate::convert;
use crate::dds::{DdsError, Participant, Side, Writer};
use crate::images;
use crate::stream_sim::Parts;
use crate::tables_json::{Asset, Telemetry, TelemetryValue};

/// Seconds between samples of an entry without a declared rate (extension samples, cameras
/// no command triggers); as the other runtimes.
pub const IDLE_PERIOD: f64 = 5.0;
const TICK: Duration = Duration::from_millis(50);

/// The simulated robot's body, in the site frame: what position samples report.
#[derive(Clone, Debug, Default)]
pub struct Body {
    /// m
    pub xyz: [f64; 3],
    /// rad
    pub heading: f64,
    /// m/s
    pub velocity: [f64; 3],
    /// m driven
    pub odometer: f64,
}

/// An extension entry's message made by the bridge (it knows the generated type): a sample
/// whose header is replaced (`convert::with_header`) before it goes out.
pub struct Custom {
    pub topic: String,
    pub type_name: String,
    pub keyed: bool,
    pub make: Box<dyn Fn() -> Result<Vec<u8>, String> + Send>,
}

/// What the publishing thread needs to know of the asset.
pub struct Source {
    /// the simulated robot's body (bridge::Simulated drives it)
    pub body: Arc<Mutex<Body>>,
    pub name: String,
    /// the configs' serials: a sample carries its entry's config's (the start one without)
    pub serials: SharedSerials,
    /// the writer side of a topic's QoS profile (the generated asset::topic_qos)
    pub qos: fn(&str) -> Option<Side>,
    /// values merged into AgentState by key (the setpoint streams' state and missed keys)
    pub agent_values: Option<AgentValues>,
    /// joint positions and subsystems' own poses the setpoint streams move (stream_sim.rs)
    pub parts: Option<Arc<Mutex<Parts>>>,
    /// what a test build's --break does to the telemetry (crate::breaks)
    #[cfg(feature = "test-breaks")]
    pub breaks: Option<Arc<crate::breaks::Breaks>>,
}

/// Agent values by key, asked for at each AgentState.
pub type AgentValues = Arc<dyn Fn() -> Vec<(String, Value)> + Send + Sync>;

enum Kind {
    Position { values: Vec<(String, rapid::ParameterUnion)>, encoding: String, subsystem: String },
    Agent(Vec<(String, rapid::ParameterUnion)>),
    Joint { positions: Vec<f32>, fields: Vec<String>, entry: usize },
    Image { state: Writer, meta: rapid::ImageMetadata, mime: String, frame: u32 },
    Text { category: String },
    Custom(Box<dyn Fn() -> Result<Vec<u8>, String> + Send>),
}

struct Job {
    topic: String,
    /// the entry's config topic: its serial is the samples'
    config: Option<String>,
    writer: Writer,
    period: Duration,
    next: Instant,
    kind: Kind,
}

fn number(v: &TelemetryValue) -> f64 {
    let (lo, hi) = (v.min.unwrap_or(f64::NEG_INFINITY), v.max.unwrap_or(f64::INFINITY));
    if lo <= 0.0 && 0.0 <= hi {
        0.0
    } else if lo.is_finite() && hi.is_finite() {
        (lo + hi) / 2.0
    } else if lo.is_finite() {
        lo
    } else {
        hi
    }
}

/// A plausible value of a value key: its default, else its first allowed value, else zero
/// (or the middle of its range when zero is outside it).
pub fn plausible(v: &TelemetryValue) -> rapid::ParameterUnion {
    let value = v.default.clone().or_else(|| v.allowed.first().cloned()).unwrap_or_else(|| {
        let x = number(v);
        match v.data_type {
            DataType::Bool => Value::Bool(false),
            DataType::Double => Value::Double(x),
            DataType::Float => Value::Float(x as f32),
            DataType::Int => Value::Int(x.round() as i32),
            DataType::LongLong => Value::LongLong(x.round() as i64),
            DataType::String => Value::String(String::new()),
            DataType::Vec3d => Value::Vec3d([0.0; 3]),
            DataType::Mat33f => Value::Mat33f([1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]),
        }
    });
    convert::union(&value)
}

/// A simulated agent value key's value: a battery without a default starts full (a charge at
/// its maximum, a voltage at 85% of its range), as the Python and C++ simulators' do (a 0 V
/// battery would be no battery); any other key its plausible value.
fn initial(v: &TelemetryValue) -> rapid::ParameterUnion {
    let name = v.name.to_ascii_lowercase();
    match (v.default.is_none() && name.contains("battery"), v.data_type, v.max) {
        (true, DataType::Float | DataType::Double, Some(max)) => {
            let x = if name.contains("charge") { max } else { (max + v.min.unwrap_or(0.0)) * 0.85 };
            with_number(&plausible(v), x)
        }
        _ => plausible(v),
    }
}

/// A rotation by `heading` about z in a pose encoding, in Transform3D's nine floats (QUAT:
/// x, y, z, w; M33: row-major; XYZ and ZYX: the angles in that order; NONE and others: zeros).
fn rotation(encoding: &str, heading: f64) -> [f32; 9] {
    let mut r = [0.0f32; 9];
    let (s, c) = heading.sin_cos();
    match encoding {
        "RAPID_ROT_QUAT" => {
            let (hs, hc) = (heading / 2.0).sin_cos();
            r[2] = hs as f32;
            r[3] = hc as f32;
        }
        "RAPID_ROT_M33" => r = [c as f32, -s as f32, 0.0, s as f32, c as f32, 0.0, 0.0, 0.0, 1.0],
        "RAPID_ROT_XYZ" => r[2] = heading as f32,
        "RAPID_ROT_ZYX" => r[0] = heading as f32,
        _ => {}
    }
    r
}

fn identity(encoding: &str) -> [f32; 9] {
    rotation(encoding, 0.0)
}

/// A number value key's value as its DataType holds it.
fn with_number(v: &rapid::ParameterUnion, x: f64) -> rapid::ParameterUnion {
    match v {
        rapid::ParameterUnion::D(_) => rapid::ParameterUnion::D(x),
        rapid::ParameterUnion::F(_) => rapid::ParameterUnion::F(x as f32),
        rapid::ParameterUnion::I(_) => rapid::ParameterUnion::I(x.round() as i32),
        rapid::ParameterUnion::Ll(_) => rapid::ParameterUnion::Ll(x.round() as i64),
        other => other.clone(),
    }
}

fn period(rate: Option<f64>, idle: f64) -> Duration {
    Duration::from_secs_f64(1.0 / rate.unwrap_or(1.0 / idle))
}

struct Publisher {
    #[cfg(feature = "test-breaks")]
    breaks: Option<Arc<crate::breaks::Breaks>>,
    agent_values: Option<AgentValues>,
    parts: Option<Arc<Mutex<Parts>>>,
    body: Arc<Mutex<Body>>,
    name: String,
    serials: SharedSerials,
    jobs: Vec<Job>,
}

/// The serial of a sample of an entry whose config is `config`: the config's serial now (the
/// start serial when the entry has none), as the other runtimes' `serials.of(config)`.
pub fn serial_of(serials: &SharedSerials, config: Option<&str>) -> i32 {
    let s = serials.lock().unwrap_or_else(|e| e.into_inner());
    config.map_or_else(|| s.start(), |c| s.of(c))
}

impl Publisher {
    fn header(&self, config: Option<&str>) -> rapid::Header {
        #[allow(unused_mut)] // (a test build's breaks change it)
        let mut h = convert::header(&self.name, &self.name, serial_of(&self.serials, config), 0);
        #[cfg(feature = "test-breaks")]
        if let Some(b) = &self.breaks {
            b.sample_header(&mut h);
        }
        h
    }

    /// Values as they go out (a test build's value breaks, crate::breaks).
    fn values_out(&self, _keys: &[(String, rapid::ParameterUnion)], values: Vec<rapid::ParameterUnion>) -> Vec<rapid::ParameterUnion> {
        #[cfg(feature = "test-breaks")]
        if let Some(b) = &self.breaks {
            return b.values(_keys, values);
        }
        values
    }

    /// A topic whose writer exists and writes nothing (a test build's position-silent,
    /// gps-silent); never in a robot's build.
    fn silent(&self, _topic: &str) -> bool {
        #[cfg(feature = "test-breaks")]
        if let Some(b) = &self.breaks {
            return b.silent(_topic);
        }
        false
    }

    fn bytes(&self, kind: &mut Kind, config: Option<&str>) -> Result<Vec<u8>, String> {
        let hdr = self.header(config);
        let le = Endianness::Little;
        let enc = |e: cdr::EncodeError| e.to_string();
        match kind {
            Kind::Position { values, encoding, subsystem } => {
                let mut b = self.body.lock().unwrap_or_else(|e| e.into_inner()).clone();
                // a subsystem a stream moves reports its own pose (at rest: no heading, no speed)
                let own = self.parts.as_ref().and_then(|p| p.lock().unwrap_or_else(|e| e.into_inner()).poses.get(subsystem.as_str()).copied());
                if let Some(xyz) = own {
                    b = Body { xyz, ..Body::default() };
                }
                let speed = b.velocity[0].hypot(b.velocity[1]);
                let out = values
                    .iter()
                    .map(|(name, v)| match name.as_str() {
                        "speed" => with_number(v, speed),
                        "odometer" => with_number(v, b.odometer),
                        _ => v.clone(),
                    })
                    .collect();
                let values = self.values_out(values, out);
                let s = rapid::PositionSample {
                    hdr,
                    pose: rapid::Transform3D { xyz: b.xyz, rot: rotation(encoding, b.heading) },
                    velocity: rapid::Transform3D { xyz: b.velocity, rot: [0.0; 9] },
                    values,
                };
                cdr::serialize(&s, le).map_err(enc)
            }
            Kind::Agent(values) => {
                let given = self.agent_values.as_ref().map(|f| f()).unwrap_or_default();
                let out = values
                    .iter()
                    .map(|(k, v)| given.iter().find(|(g, _)| g == k).map_or_else(|| v.clone(), |(_, x)| convert::union(x)))
                    .collect();
                let values = self.values_out(values, out);
                cdr::serialize(&rapid::AgentState { hdr, values }, le).map_err(enc)
            }
            Kind::Joint { positions, fields, entry } => {
                if let Some(p) = &self.parts {
                    // where the setpoint streams moved them
                    if let Some(now) = p.lock().unwrap_or_else(|e| e.into_inner()).joints.get(*entry) {
                        *positions = now.iter().map(|x| *x as f32).collect();
                    }
                }
                let n = positions.len();
                let mut s = rapid::JointSample { hdr, angle_pos: positions.clone(), ..Default::default() };
                for f in fields.iter() {
                    match f.as_str() {
                        "angleVel" => s.angle_vel = vec![0.0; n],
                        "angleAcc" => s.angle_acc = vec![0.0; n],
                        "current" => s.current = vec![0.0; n],
                        "torque" => s.torque = vec![0.0; n],
                        "temperature" => s.temperature = vec![20.0; n],
                        "status" => s.status = vec![0; n],
                        _ => {}
                    }
                }
                cdr::serialize(&s, le).map_err(enc)
            }
            Kind::Image { state, meta, mime, frame } => {
                *frame = frame.wrapping_add(1);
                let st = rapid::ImageSensorState { hdr: hdr.clone(), meta: meta.clone() };
                state.write(&cdr::serialize(&st, le).map_err(enc)?).map_err(|e| e.to_string())?;
                let data = images::synthetic(mime, meta.width, meta.height, *frame);
                let s = rapid::ImageSensorSample { hdr, meta: meta.clone(), mime_type: mime.clone(), data };
                cdr::serialize(&s, le).map_err(enc)
            }
            Kind::Text { category } => {
                let s = rapid::TextMessage {
                    hdr,
                    level: rapid::MessageLevel::MsgInfo,
                    category: category.clone(),
                    message: format!("{} simulated", self.name),
                };
                cdr::serialize(&s, le).map_err(enc)
            }
            Kind::Custom(make) => convert::with_header(&make()?, &hdr),
        }
    }

    fn run(mut self, stop: Arc<AtomicBool>) {
        let mut reported = std::collections::BTreeSet::new();
        while !stop.load(Ordering::SeqCst) {
            let now = Instant::now();
            let mut jobs = std::mem::take(&mut self.jobs);
            for job in jobs.iter_mut().filter(|j| j.next <= now) {
                // the next one is due a period after this one was, not after it went out: the
                // declared rate holds on average (a late sample does not delay the rest)
                job.next += job.period;
                if job.next < now {
                    job.next = now + job.period;
                }
                if self.silent(&job.topic) {
                    continue;
                }
                let out = self.bytes(&mut job.kind, job.config.as_deref()).and_then(|b| job.writer.write(&b).map_err(|e| e.to_string()));
                if let Err(e) = out {
                    // once per topic and message: telemetry may be dropped, the bridge keeps running
                    if reported.insert((job.topic.clone(), e.clone())) {
                        eprintln!("[{}] simulated telemetry on {} not sent: {e}", self.name, job.topic);
                    }
                }
            }
            self.jobs = jobs;
            let next = self.jobs.iter().map(|j| j.next).min().unwrap_or(now + TICK);
            std::thread::sleep(next.saturating_duration_since(Instant::now()).min(TICK));
        }
    }
}

fn writer(dp: &Participant, src: &Source, topic: &str, type_name: &str, keyed: bool) -> Result<Writer, DdsError> {
    let side = (src.qos)(topic).unwrap_or(Side { reliable: false, transient_local: false, depth: Some(5) });
    dp.writer(&dp.topic(topic, type_name, keyed)?, side)
}

/// Writers for every entry, the messages sent once at start, and the thread publishing the
/// rest until `stop`.
pub fn start(
    dp: &Participant,
    asset: &Asset,
    src: Source,
    customs: Vec<Custom>,
    stop: Arc<AtomicBool>,
) -> Result<JoinHandle<()>, DdsError> {
    let mut p = Publisher {
        #[cfg(feature = "test-breaks")]
        breaks: src.breaks.clone(),
        agent_values: src.agent_values.clone(),
        parts: src.parts.clone(),
        body: src.body.clone(),
        name: src.name.clone(),
        serials: src.serials.clone(),
        jobs: Vec::new(),
    };
    let now = Instant::now();
    let mut once = Vec::new();
    let mut joints = 0; // joint entries so far (Parts::joints is by joint entry)
    let entries = &asset.telemetry;
    #[cfg(feature = "test-breaks")]
    let slowed = src.breaks.as_ref().and_then(|b| b.telemetry(entries));
    #[cfg(feature = "test-breaks")]
    let entries = slowed.as_ref().unwrap_or(entries);
    for t in entries {
        let topic = |role: &str| t.topics.get(role).cloned();
        let config = topic("config");
        let mut job = |topic: String, type_name: &str, rate: Option<f64>, kind: Kind| -> Result<(), DdsError> {
            let writer = writer(dp, &src, &topic, type_name, true)?;
            p.jobs.push(Job { topic, config: config.clone(), writer, period: period(rate, 1.0), next: now, kind });
            Ok(())
        };
        match t.kind.as_str() {
            "position" => {
                if let Some(s) = topic("sample") {
                    let values = t.values.iter().map(|v| (v.name.clone(), plausible(v))).collect();
                    let kind = Kind::Position { values, encoding: t.pose_encoding.clone(), subsystem: t.subsystem.clone() };
                    job(s, "rapid::PositionSample", t.rate, kind)?;
                }
            }
            "agent" => {
                if let Some(s) = topic("state") {
                    job(s, "rapid::AgentState", t.rate, Kind::Agent(t.values.iter().map(|v| (v.name.clone(), initial(v))).collect()))?;
                }
            }
            "joint" => {
                let entry = joints;
                joints += 1;
                if let Some(s) = topic("sample") {
                    let positions = t.joints.iter().map(|j| joint_rest(j.min, j.max) as f32).collect();
                    job(s, "rapid::JointSample", t.rate, Kind::Joint { positions, fields: t.fields.clone(), entry })?;
                }
            }
            "image" => image(dp, &src, t, takes_pictures(asset, &t.subsystem), &mut p, now)?,
            "text" => {
                if let Some(s) = topic("sample") {
                    let category =
                        if t.categories.iter().any(|c| c == "system") { "system".into() } else { t.categories.first().cloned().unwrap_or_default() };
                    let w = writer(dp, &src, &s, "rapid::TextMessage", true)?;
                    let kind = Kind::Text { category };
                    match t.rate {
                        Some(r) => p.jobs.push(Job { topic: s, config, writer: w, period: period(Some(r), 1.0), next: now, kind }),
                        None => once.push((s, config, w, kind)),
                    }
                }
            }
            _ => {} // custom: below, from the bridge's samples
        }
    }
    for c in customs {
        let entry = entries.iter().find(|t| t.topics.iter().any(|(_, topic)| *topic == c.topic));
        let role = entry.and_then(|t| t.topics.iter().find(|(_, topic)| **topic == c.topic)).map(|(r, _)| r.as_str());
        let w = writer(dp, &src, &c.topic, &c.type_name, c.keyed)?;
        let kind = Kind::Custom(c.make);
        let config = entry.and_then(|t| t.topics.get("config").cloned());
        match (role, entry) {
            (Some("config"), _) | (_, None) => once.push((c.topic, config, w, kind)),
            (_, Some(t)) => p.jobs.push(Job { topic: c.topic, config, writer: w, period: period(t.rate, IDLE_PERIOD), next: now, kind }),
        }
    }
    for (topic, config, w, mut kind) in once {
        if p.silent(&topic) {
            continue;
        }
        let sent = p.bytes(&mut kind, config.as_deref()).and_then(|b| w.write(&b).map_err(|e| e.to_string()));
        if let Err(e) = sent {
            eprintln!("[{}] simulated telemetry on {topic} not sent: {e}", p.name);
        }
    }
    std::thread::Builder::new()
        .name("sim-telemetry".into())
        .spawn(move || p.run(stop))
        .map_err(|e| DdsError(format!("telemetry thread: {e}")))
}

/// A joint's resting position: zero, or the middle of its limits when zero is outside them.
pub(crate) fn joint_rest(min: Option<f64>, max: Option<f64>) -> f64 {
    let v = TelemetryValue { name: String::new(), data_type: DataType::Double, min, max, allowed: Vec::new(), default: None };
    number(&v)
}

fn image(
    dp: &Participant,
    src: &Source,
    t: &Telemetry,
    on_command: bool,
    p: &mut Publisher,
    now: Instant,
) -> Result<(), DdsError> {
    let (Some(state_topic), Some(sample_topic)) = (t.topics.get("state"), t.topics.get("sample")) else {
        return Ok(());
    };
    let state = writer(dp, src, state_topic, "rapid::ImageSensorState", true)?;
    let meta = rapid::ImageMetadata {
        sensor_name: t.sensor.clone(),
        sensor_type: t.sensor_type.clone(),
        offset: rapid::Transform3D { xyz: [0.0; 3], rot: identity("RAPID_ROT_M33") },
        width: t.width,
        height: t.height,
        ..Default::default()
    };
    // the camera's state at start (durable): its size and name before any picture
    let config = t.topics.get("config").map(String::as_str);
    let hdr = p.header(config);
    let st = rapid::ImageSensorState { hdr, meta: meta.clone() };
    match cdr::serialize(&st, Endianness::Little) {
        Ok(b) => state.write(&b)?,
        Err(e) => eprintln!("[{}] {state_topic} not sent: {e}", p.name),
    }
    if t.rate.is_some() || !on_command {
        let writer = writer(dp, src, sample_topic, "rapid::ImageSensorSample", true)?;
        let mime = if t.mime.is_empty() { "image/jpeg".to_string() } else { t.mime.clone() };
        p.jobs.push(Job {
            topic: sample_topic.clone(),
            config: config.map(String::from),
            writer,
            period: period(t.rate, IDLE_PERIOD),
            next: now,
            kind: Kind::Image { state, meta, mime, frame: 0 },
        });
    }
    Ok(())
}

/// Whether a command name says it takes pictures (as the other runtimes' simulators).
pub fn picture_command(name: &str) -> bool {
    let n = name.to_ascii_lowercase();
    ["picture", "image", "photo", "snap", "capture", "panorama", "acquire", "shoot"].iter().any(|w| n.contains(w))
}

/// Whether some command of the subsystem takes pictures: its cameras publish on command.
fn takes_pictures(asset: &Asset, subsystem: &str) -> bool {
    let t = &asset.tables;
    t.subsystems.iter().filter(|s| s.name == subsystem).any(|s| {
        t.types.iter().filter(|ty| ty.name == s.type_name).any(|ty| ty.commands.iter().any(|c| picture_command(&c.name)))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rapid_runtime::configs::Serials;

    #[test]
    fn samples_follow_their_configs_serial() {
        let at = Arc::new(std::sync::atomic::AtomicI64::new(1000));
        let clock = at.clone();
        let serials: SharedSerials = Arc::new(Mutex::new(Serials::new(Some(1000), Box::new(move || clock.load(Ordering::SeqCst)), None)));
        for topic in ["pos_config", "agent_config"] {
            serials.lock().unwrap().update(topic, b"computed"); // the start path: the start serial
        }
        assert_eq!(serial_of(&serials, Some("pos_config")), 1000);
        assert_eq!(serial_of(&serials, None), 1000);
        assert_eq!(serials.lock().unwrap().update("pos_config", b"computed"), (1000, false));
        assert_eq!(serial_of(&serials, Some("pos_config")), 1000);
        at.store(1500, Ordering::SeqCst);
        serials.lock().unwrap().update("pos_config", b"republished");
        // the republished config's samples carry its new serial; the others keep theirs
        assert_eq!(serial_of(&serials, Some("pos_config")), 1500);
        assert_eq!(serial_of(&serials, Some("agent_config")), 1000);
        assert_eq!(serial_of(&serials, None), 1000);
    }
}
