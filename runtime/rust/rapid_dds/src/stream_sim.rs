//! The streams on the simulated robot (`--simulate`), as the C++ SimulatedStreams: input
//! streams are read with the same QoS, state, TextMessages and AgentState keys (stream.rs), and
//! each setpoint drives the subsystem the stream names: a JointSample's positions its joints
//! (those whose frame starts with the subsystem's name, else its joint entry's, else for no
//! subsystem the first joint entry's; in order, clamped to their limits) at JOINT_SPEED, a
//! PositionSample's xyz the body (no subsystem, or a Mobility one: x and y at
//! bridge::DRIVE_SPEED) or that subsystem's own pose (its position entries report it, at
//! DRIVE_SPEED). A loss with on_loss stop halts what the stream drives (stopAllMotion reaches
//! the simulated handlers too); hold and none let it go on to the last setpoint. Output
//! streams are written at their rate by one thread with the simulated state and a slow sweep
//! (the pose circling 10 cm every 20 s, joints swinging 0.2 rad every 10 s), as the C++
//! simulated_output.
use std::collections::BTreeMap;
use std::f64::consts::TAU;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use rapid_runtime::stream::{LossAction, StreamSpec, StreamState};

use crate::bridge::DRIVE_SPEED;
use crate::dds::DdsError;
use crate::tables_json::Asset;
use crate::telemetry::{self, Body};

/// rad/s: how fast a stream's setpoint moves simulated joints (as the C++ simulator's).
pub const JOINT_SPEED: f64 = 1.0;
const TICK: Duration = Duration::from_millis(20);

/// An output stream's send under simulation: fills the sample for simulated time t (s) and
/// writes it (the generated glue's closure).
pub type Fill = Box<dyn FnMut(&SimStreams, f64) + Send>;

/// What the simulated telemetry reports besides the body: every joint entry's joint positions
/// (in the entries' order) and the poses of subsystems a stream moves.
#[derive(Debug, Default)]
pub struct Parts {
    pub joints: Vec<Vec<f64>>,
    pub poses: BTreeMap<String, [f64; 3]>,
}

impl Parts {
    /// The joint entries at rest (telemetry::joint_rest), no pose of its own yet.
    pub fn of(asset: &Asset) -> Parts {
        let joints = asset
            .telemetry
            .iter()
            .filter(|t| t.kind == "joint")
            .map(|t| t.joints.iter().map(|j| telemetry::joint_rest(j.min, j.max)).collect())
            .collect();
        Parts { joints, poses: BTreeMap::new() }
    }
}

/// What one stream drives.
#[derive(Clone, Debug, PartialEq)]
enum Drives {
    Body,
    Pose(String),
    /// (joint entry, joint) pairs, in the stream's order
    Joints(Vec<(usize, usize)>),
    Nothing,
}

#[derive(Default)]
struct Goals {
    body: Option<[f64; 2]>,
    poses: BTreeMap<String, Option<[f64; 3]>>,
    joints: Vec<Vec<Option<f64>>>,
}

pub struct SimStreams {
    body: Arc<Mutex<Body>>,
    parts: Arc<Mutex<Parts>>,
    drives: Vec<Drives>,
    inputs: Vec<bool>,
    limits: Vec<Vec<(Option<f64>, Option<f64>)>>,
    goals: Mutex<Goals>,
    stop: AtomicBool,
    threads: Mutex<Vec<JoinHandle<()>>>,
}

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// The joints a stream of `subsystem` drives (as the C++ Simulator's stream_targets).
fn joints_of(asset: &Asset, subsystem: &str) -> Vec<(usize, usize)> {
    let entries: Vec<_> = asset.telemetry.iter().filter(|t| t.kind == "joint").collect();
    if subsystem.is_empty() {
        return entries.first().map(|t| (0..t.joints.len()).map(|j| (0, j)).collect()).unwrap_or_default();
    }
    let by_frame: Vec<_> = entries
        .iter()
        .enumerate()
        .flat_map(|(e, t)| t.joints.iter().enumerate().map(move |(j, joint)| (e, j, joint)))
        .filter(|(_, _, joint)| joint.frame.split('/').next() == Some(subsystem))
        .map(|(e, j, _)| (e, j))
        .collect();
    if !by_frame.is_empty() {
        return by_frame;
    }
    entries
        .iter()
        .position(|t| t.subsystem == subsystem)
        .map(|e| (0..entries[e].joints.len()).map(|j| (e, j)).collect())
        .unwrap_or_default()
}

fn step_toward(at: &mut [f64], goal: &[f64], step: f64) {
    let d: f64 = at.iter().zip(goal).map(|(a, g)| (g - a) * (g - a)).sum::<f64>().sqrt();
    if d <= step {
        at.copy_from_slice(goal);
    } else {
        for (a, g) in at.iter_mut().zip(goal) {
            *a += (g - *a) / d * step;
        }
    }
}

impl SimStreams {
    /// `parts`: shared with the simulated telemetry (telemetry::Source::parts).
    pub fn new(specs: &[StreamSpec], asset: &Asset, body: Arc<Mutex<Body>>, parts: Arc<Mutex<Parts>>) -> Arc<SimStreams> {
        let mut goals = Goals::default();
        let body_of = |s: &StreamSpec| s.subsystem.is_empty() || asset.tables.type_of(s.subsystem) == Some("Mobility");
        // a subsystem an input PositionSample stream moves gets a pose of its own (made here:
        // no allocation per sample), reported by its position entries and carried by outputs
        for s in specs.iter().filter(|s| s.input && s.type_name == "rapid::PositionSample" && !body_of(s)) {
            goals.poses.insert(s.subsystem.to_string(), None);
            lock(&parts).poses.entry(s.subsystem.to_string()).or_insert([0.0; 3]);
        }
        let drives = specs
            .iter()
            .map(|s| match s.type_name {
                "rapid::PositionSample" if goals.poses.contains_key(s.subsystem) => Drives::Pose(s.subsystem.to_string()),
                "rapid::PositionSample" => Drives::Body,
                "rapid::JointSample" => Drives::Joints(joints_of(asset, s.subsystem)),
                _ => Drives::Nothing,
            })
            .collect();
        let entries: Vec<_> = asset.telemetry.iter().filter(|t| t.kind == "joint").collect();
        goals.joints = entries.iter().map(|t| vec![None; t.joints.len()]).collect();
        let limits = entries.iter().map(|t| t.joints.iter().map(|j| (j.min, j.max)).collect()).collect();
        Arc::new(SimStreams {
            body,
            parts,
            drives,
            inputs: specs.iter().map(|s| s.input).collect(),
            limits,
            goals: Mutex::new(goals),
            stop: AtomicBool::new(false),
            threads: Mutex::new(Vec::new()),
        })
    }

    /// A PositionSample setpoint of the index-th stream (its pose's xyz).
    pub fn position(&self, index: usize, xyz: [f64; 3]) {
        let mut g = lock(&self.goals);
        match self.drives.get(index) {
            Some(Drives::Body) if self.inputs[index] => g.body = Some([xyz[0], xyz[1]]),
            Some(Drives::Pose(name)) => {
                if let Some(goal) = g.poses.get_mut(name) {
                    *goal = Some(xyz);
                }
            }
            _ => {}
        }
    }

    /// A JointSample setpoint of the index-th stream: its positions, in order, clamped.
    pub fn joints(&self, index: usize, positions: &[f32]) {
        let Some(Drives::Joints(targets)) = self.drives.get(index) else { return };
        let mut g = lock(&self.goals);
        for (&(e, j), p) in targets.iter().zip(positions) {
            let (lo, hi) = self.limits[e][j];
            g.joints[e][j] = Some(f64::from(*p).max(lo.unwrap_or(f64::NEG_INFINITY)).min(hi.unwrap_or(f64::INFINITY)));
        }
    }

    /// The on_state hook under simulation: a stream lost with on_loss stop halts what it drives.
    pub fn on_state(&self, index: usize, s: &StreamSpec, state: StreamState) {
        if state != StreamState::Lost || s.on_loss != LossAction::Stop {
            return;
        }
        let mut g = lock(&self.goals);
        match self.drives.get(index) {
            Some(Drives::Body) => {
                g.body = None;
                lock(&self.body).velocity = [0.0; 3];
            }
            Some(Drives::Pose(name)) => {
                if let Some(goal) = g.poses.get_mut(name) {
                    *goal = None;
                }
            }
            Some(Drives::Joints(targets)) => {
                for &(e, j) in targets {
                    g.joints[e][j] = None;
                }
            }
            _ => {}
        }
    }

    /// The pose the index-th (output) stream carries at simulated time t: its subsystem's pose
    /// (or the body's) circling 10 cm every 20 s.
    pub fn pose_at(&self, index: usize, t: f64) -> ([f64; 3], [f32; 9]) {
        let xyz = match self.drives.get(index) {
            Some(Drives::Pose(name)) => lock(&self.parts).poses.get(name).copied().unwrap_or_default(),
            _ => lock(&self.body).xyz,
        };
        let a = TAU * t / 20.0;
        ([xyz[0] + 0.1 * a.cos(), xyz[1] + 0.1 * a.sin(), xyz[2]], [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0])
    }

    /// The joint positions the index-th (output) stream carries at time t, into `out` (its
    /// capacity kept): the joints it names (or the first joint entry's) plus 0.2 rad swinging
    /// every 10 s.
    pub fn joints_at(&self, index: usize, t: f64, out: &mut Vec<f32>) {
        let swing = 0.2 * (TAU * t / 10.0).sin();
        out.clear();
        let parts = lock(&self.parts);
        if let Some(Drives::Joints(targets)) = self.drives.get(index) {
            out.extend(targets.iter().map(|&(e, j)| (parts.joints[e][j] + swing) as f32));
        }
    }

    /// The mover (stream setpoints approached every 20 ms) and the outputs' writer.
    pub fn start(self: &Arc<Self>, outputs: Vec<(f64, Fill)>) -> Result<(), DdsError> {
        let me = self.clone();
        let mover = std::thread::Builder::new()
            .name("sim-streams".into())
            .spawn(move || me.move_parts())
            .map_err(|e| DdsError(format!("simulated streams: {e}")))?;
        let mut threads = lock(&self.threads);
        threads.push(mover);
        if !outputs.is_empty() {
            let me = self.clone();
            let t = std::thread::Builder::new()
                .name("sim-stream-out".into())
                .spawn(move || me.write_outputs(outputs))
                .map_err(|e| DdsError(format!("simulated streams: {e}")))?;
            threads.push(t);
        }
        Ok(())
    }

    pub fn stop(&self) {
        self.stop.store(true, Ordering::SeqCst);
        for t in lock(&self.threads).drain(..) {
            let _ = t.join();
        }
    }

    fn move_parts(&self) {
        while !self.stop.load(Ordering::SeqCst) {
            self.step(TICK.as_secs_f64());
            std::thread::sleep(TICK);
        }
    }

    /// `dt` seconds pass: the body, subsystems' poses and joints approach their setpoints.
    fn step(&self, dt: f64) {
        let g = lock(&self.goals);
        if let Some([x, y]) = g.body {
            let mut b = lock(&self.body);
            let (dx, dy) = (x - b.xyz[0], y - b.xyz[1]);
            let dist = dx.hypot(dy);
            if dist < 1e-3 {
                b.velocity = [0.0; 3];
            } else {
                let step = dist.min(DRIVE_SPEED * dt);
                b.xyz[0] += dx / dist * step;
                b.xyz[1] += dy / dist * step;
                b.odometer += step;
                b.velocity = [dx / dist * DRIVE_SPEED, dy / dist * DRIVE_SPEED, 0.0];
            }
        }
        let mut parts = lock(&self.parts);
        for (name, goal) in &g.poses {
            if let (Some(goal), Some(at)) = (goal, parts.poses.get_mut(name)) {
                step_toward(at, goal, DRIVE_SPEED * dt);
            }
        }
        for (e, joints) in g.joints.iter().enumerate() {
            for (j, goal) in joints.iter().enumerate() {
                if let (Some(goal), Some(at)) = (goal, parts.joints.get_mut(e).and_then(|v| v.get_mut(j))) {
                    *at += (goal - *at).clamp(-JOINT_SPEED * dt, JOINT_SPEED * dt);
                }
            }
        }
    }

    fn write_outputs(&self, mut outputs: Vec<(f64, Fill)>) {
        let t0 = Instant::now();
        let mut next: Vec<f64> = vec![0.0; outputs.len()];
        while !self.stop.load(Ordering::SeqCst) {
            let now = t0.elapsed().as_secs_f64();
            let mut soonest = now + 0.1;
            for (i, (period, fill)) in outputs.iter_mut().enumerate() {
                if now >= next[i] {
                    fill(self, now);
                    next[i] = (next[i] + *period).max(now);
                }
                soonest = soonest.min(next[i]);
            }
            std::thread::sleep(Duration::from_secs_f64((soonest - t0.elapsed().as_secs_f64()).clamp(0.0, 0.1)));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tables_json::asset_of;

    fn spec(name: &'static str, type_name: &'static str, subsystem: &'static str, on_loss: LossAction) -> StreamSpec {
        StreamSpec { name, input: true, type_name, topic: "t", partition: "P", rate_hz: 50.0, deadline_ms: 200.0,
                     liveliness_ms: 600.0, on_loss, subsystem, state_key: "", missed_key: "" }
    }

    /// tests/streams/rig.yaml's shape: a Mobility, an Arm with three joints (one entry, frames
    /// Arm/...), a Mast with a position entry of its own.
    fn rig() -> Asset {
        let j = serde_json::json!({
            "name": "Rig", "partition": "Rig", "types": [],
            "subsystems": [{"name": "Mobility", "type": "Mobility"}, {"name": "Arm", "type": "Arm"},
                           {"name": "Mast", "type": "Arm"}],
            "telemetry": [
                {"kind": "position", "topics": {"sample": "rapid_position_sample"}},
                {"kind": "position", "subsystem": "Mast", "topics": {"sample": "rapid_position_sample-mastHead"}},
                {"kind": "joint", "topics": {"sample": "rapid_joint_sample"}, "joints": [
                    {"frame": "Arm/Joint0", "min": -2.0, "max": 2.0}, {"frame": "Arm/Joint1", "min": -2.0, "max": 2.0},
                    {"frame": "Arm/Joint2", "min": -2.0, "max": 2.0}]}
            ]
        });
        asset_of(&j).unwrap()
    }

    #[test]
    fn a_stream_drives_what_its_subsystem_names() {
        let a = rig();
        assert_eq!(joints_of(&a, "Arm"), vec![(0, 0), (0, 1), (0, 2)]); // by frame
        assert_eq!(joints_of(&a, ""), vec![(0, 0), (0, 1), (0, 2)]); // none named: the first entry's
        assert!(joints_of(&a, "Mast").is_empty());
        let specs = [spec("drive", "rapid::PositionSample", "Mobility", LossAction::Stop),
                     spec("mast", "rapid::PositionSample", "Mast", LossAction::None),
                     spec("arm", "rapid::JointSample", "Arm", LossAction::Stop)];
        let parts = Arc::new(Mutex::new(Parts::of(&a)));
        let sim = SimStreams::new(&specs, &a, Arc::new(Mutex::new(Body::default())), parts.clone());
        assert_eq!(sim.drives, vec![Drives::Body, Drives::Pose("Mast".into()), Drives::Joints(vec![(0, 0), (0, 1), (0, 2)])]);
        assert_eq!(lock(&parts).poses.get("Mast"), Some(&[0.0; 3])); // reported from the start
    }

    #[test]
    fn setpoints_are_approached_clamped_and_halted_by_stop() {
        let a = rig();
        let specs = [spec("drive", "rapid::PositionSample", "", LossAction::Stop),
                     spec("mast", "rapid::PositionSample", "Mast", LossAction::Hold),
                     spec("arm", "rapid::JointSample", "Arm", LossAction::Stop)];
        let body = Arc::new(Mutex::new(Body::default()));
        let parts = Arc::new(Mutex::new(Parts::of(&a)));
        let sim = SimStreams::new(&specs, &a, body.clone(), parts.clone());
        sim.position(0, [2.0, 0.0, 9.0]);
        sim.position(1, [0.0, 0.0, 1.0]);
        sim.joints(2, &[5.0, -0.5]); // clamped to 2; the third joint has no setpoint
        sim.step(1.0);
        assert_eq!(lock(&body).xyz, [DRIVE_SPEED, 0.0, 0.0]); // x, y only
        assert_eq!(lock(&parts).poses["Mast"], [0.0, 0.0, DRIVE_SPEED]);
        assert_eq!(lock(&parts).joints[0], vec![JOINT_SPEED, -0.5, 0.0]);
        sim.step(5.0);
        assert_eq!(lock(&parts).joints[0], vec![2.0, -0.5, 0.0]);
        sim.position(0, [2.0, 0.0, 0.0]);
        sim.joints(2, &[-2.0, -2.0, -2.0]);
        // lost: stop halts what the stream drives, hold lets it go on
        for (i, s) in specs.iter().enumerate() {
            sim.on_state(i, s, StreamState::Lost);
        }
        let x = lock(&body).xyz[0];
        sim.step(1.0);
        assert_eq!(lock(&body).xyz[0], x);
        assert_eq!(lock(&parts).joints[0], vec![2.0, -0.5, 0.0]);
        assert_eq!(lock(&parts).poses["Mast"], [0.0, 0.0, 1.0]); // hold: reached its setpoint
    }

    #[test]
    fn outputs_carry_the_simulated_state() {
        let a = rig();
        let mut out = spec("pose", "rapid::PositionSample", "", LossAction::None);
        out.input = false;
        let mut joints = spec("joints", "rapid::JointSample", "Arm", LossAction::None);
        joints.input = false;
        let body = Arc::new(Mutex::new(Body { xyz: [1.0, 2.0, 3.0], ..Body::default() }));
        let sim = SimStreams::new(&[out, joints], &a, body, Arc::new(Mutex::new(Parts::of(&a))));
        let (xyz, _) = sim.pose_at(0, 0.0);
        assert_eq!(xyz, [1.1, 2.0, 3.0]); // the body, 10 cm out at t = 0
        sim.position(0, [9.0, 9.0, 9.0]); // an output stream's own pose is never a setpoint
        sim.step(1.0);
        assert_eq!(sim.pose_at(0, 0.0).0, [1.1, 2.0, 3.0]);
        let mut v = Vec::new();
        sim.joints_at(1, 2.5, &mut v); // a quarter period: +0.2 rad
        assert_eq!(v, vec![0.2f32; 3]);
    }
}
