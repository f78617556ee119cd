//! The streams on the simulated robot (`--simulate`), as the C++ SimulatedStreams where the
//! Rust simulator has the part: input streams are read with the same QoS, state, TextMessages
//! and AgentState keys (stream.rs); a PositionSample stream that drives the body (no subsystem,
//! or a Mobility one) moves it to the setpoint's x, y at bridge::DRIVE_SPEED, and a loss with
//! on_loss stop halts it (stopAllMotion reaches the simulated handlers too); hold and none let
//! it go on to the last setpoint. Other setpoints (joints, other subsystems' poses) are counted
//! and watched only: the Rust simulator has no joint or per-subsystem pose model (its joint
//! telemetry stays at rest). Output streams are written at their rate by one thread with the
//! simulated state and a slow sweep (the pose circling 10 cm every 20 s, joints swinging 0.2
//! rad every 10 s), as the C++ simulated_output.
use std::f64::consts::TAU;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use rapid_runtime::stream::{LossAction, StreamSpec, StreamState};
use rapid_runtime::Tables;

use crate::bridge::DRIVE_SPEED;
use crate::dds::DdsError;
use crate::telemetry::Body;

const TICK: Duration = Duration::from_millis(20);

/// An output stream's send under simulation: fills the sample for simulated time t (s) and
/// writes it (the generated glue's closure).
pub type Fill = Box<dyn FnMut(&SimStreams, f64) + Send>;

pub struct SimStreams {
    body: Arc<Mutex<Body>>,
    /// per stream: whether its PositionSample setpoints drive the body
    drives_body: Vec<bool>,
    /// the body's setpoint (None: at rest)
    target: Mutex<Option<[f64; 2]>>,
    /// joint positions at rest (the first joint entry's), for JointSample outputs
    rest: Vec<f64>,
    stop: Arc<AtomicBool>,
    threads: Mutex<Vec<JoinHandle<()>>>,
}

impl SimStreams {
    pub fn new(specs: &[StreamSpec], tables: &Tables, body: Arc<Mutex<Body>>, rest: Vec<f64>) -> Arc<SimStreams> {
        let drives_body = specs
            .iter()
            .map(|s| s.type_name == "rapid::PositionSample" && (s.subsystem.is_empty() || tables.type_of(s.subsystem) == Some("Mobility")))
            .collect();
        Arc::new(SimStreams {
            body,
            drives_body,
            target: Mutex::new(None),
            rest,
            stop: Arc::new(AtomicBool::new(false)),
            threads: Mutex::new(Vec::new()),
        })
    }

    /// A PositionSample setpoint of the index-th stream (its pose's xyz).
    pub fn position(&self, index: usize, xyz: [f64; 3]) {
        if self.drives_body.get(index).copied().unwrap_or(false) {
            *self.target.lock().unwrap_or_else(|e| e.into_inner()) = Some([xyz[0], xyz[1]]);
        }
    }

    /// A JointSample setpoint: counted and watched only (no joint model here).
    pub fn joints(&self, _index: usize, _positions: &[f32]) {}

    /// The on_state hook under simulation: a stream lost with on_loss stop halts what it drives.
    pub fn on_state(&self, index: usize, s: &StreamSpec, state: StreamState) {
        if state == StreamState::Lost && s.on_loss == LossAction::Stop && self.drives_body.get(index).copied().unwrap_or(false) {
            *self.target.lock().unwrap_or_else(|e| e.into_inner()) = None;
            self.body.lock().unwrap_or_else(|e| e.into_inner()).velocity = [0.0; 3];
        }
    }

    /// The pose an output stream carries at simulated time t: the body circling 10 cm every 20 s.
    pub fn pose_at(&self, t: f64) -> ([f64; 3], [f32; 9]) {
        let b = self.body.lock().unwrap_or_else(|e| e.into_inner());
        let a = TAU * t / 20.0;
        ([b.xyz[0] + 0.1 * a.cos(), b.xyz[1] + 0.1 * a.sin(), b.xyz[2]], [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0])
    }

    /// Joint positions an output stream carries at time t, into `out` (resized to the joints
    /// at rest: its capacity is kept): rest plus 0.2 rad swinging every 10 s.
    pub fn joints_at(&self, t: f64, out: &mut Vec<f32>) {
        let swing = 0.2 * (TAU * t / 10.0).sin();
        out.clear();
        out.extend(self.rest.iter().map(|r| (r + swing) as f32));
    }

    /// The body's mover (at DRIVE_SPEED towards the setpoint) and the outputs' writer.
    pub fn start(self: &Arc<Self>, outputs: Vec<(f64, Fill)>) -> Result<(), DdsError> {
        let me = self.clone();
        let mover = std::thread::Builder::new()
            .name("sim-streams".into())
            .spawn(move || me.move_body())
            .map_err(|e| DdsError(format!("simulated streams: {e}")))?;
        let mut threads = self.threads.lock().unwrap_or_else(|e| e.into_inner());
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
        for t in self.threads.lock().unwrap_or_else(|e| e.into_inner()).drain(..) {
            let _ = t.join();
        }
    }

    fn move_body(&self) {
        let dt = TICK.as_secs_f64();
        while !self.stop.load(Ordering::SeqCst) {
            let target = *self.target.lock().unwrap_or_else(|e| e.into_inner());
            if let Some([x, y]) = target {
                let mut b = self.body.lock().unwrap_or_else(|e| e.into_inner());
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
            std::thread::sleep(TICK);
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
