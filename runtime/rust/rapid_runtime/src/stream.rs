//! Setpoint streams (docs/realtime.md): what one stream is (the descriptor's `streams:` entry
//! as the generated code states it) and its state machine, without DDS, so the rules are
//! tested without a network. The twin of the C++ runtime's rapid_runtime/stream.hpp.
//!
//! ```text
//!   waiting --sample--> active --deadline missed / writer lost--> lost --sample--> active
//! ```
//!
//! A sample with a NaN or an infinity is not a sample: it never reaches the handler, is
//! counted ([`StreamMonitor::non_finite`]), and does not keep the stream alive. DDS's own
//! DEADLINE is met by any sample, so the monitor keeps the time of the last finite one and a
//! non-finite sample that arrives after the deadline since then loses the stream as a missed
//! deadline would (cause [`LossCause::NonFinite`]). The first non-finite sample of a run of
//! them (after a finite one, or the first ever) is flagged so the reporting thread says so
//! once per run, not once per sample.
//!
//! Counters are atomics: samples arrive on the middleware's receive thread, deadlines on its
//! event thread, and the reporting thread reads them; nothing here allocates or locks.
use std::sync::atomic::{AtomicBool, AtomicI32, AtomicI64, AtomicU32, AtomicU64, Ordering};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LossAction {
    Stop,
    Hold,
    None,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StreamState {
    Waiting = 0,
    Active = 1,
    Lost = 2,
}

/// What made an active stream lost: its DEADLINE passed without a sample, or its writer's
/// LIVELINESS lapsed (the writer process is gone or frozen, or left the domain). NonFinite:
/// samples kept coming past the deadline, but none finite (NaN or Inf: dropped).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LossCause {
    Deadline = 0,
    Liveliness = 1,
    NonFinite = 2,
}

impl StreamState {
    pub fn name(self) -> &'static str {
        match self {
            StreamState::Active => "active",
            StreamState::Lost => "lost",
            StreamState::Waiting => "waiting",
        }
    }
}

impl LossAction {
    pub fn name(self) -> &'static str {
        match self {
            LossAction::Stop => "stop",
            LossAction::Hold => "hold",
            LossAction::None => "none",
        }
    }

    /// The TextMessage's words for the action taken on a loss (as the C++ runtime's).
    pub fn text(self) -> &'static str {
        match self {
            LossAction::Stop => "motion stopped",
            LossAction::Hold => "holding the last setpoint",
            LossAction::None => "no action",
        }
    }
}

/// One stream as the descriptor declares it (the generated bridge's constants).
#[derive(Clone, Copy, Debug)]
pub struct StreamSpec {
    pub name: &'static str,
    pub input: bool,
    /// DDS type name (rapid::PositionSample)
    pub type_name: &'static str,
    pub topic: &'static str,
    /// the writer's
    pub partition: &'static str,
    pub rate_hz: f64,
    pub deadline_ms: f64,
    pub liveliness_ms: f64,
    pub on_loss: LossAction,
    /// the subsystem it drives ("" none)
    pub subsystem: &'static str,
    /// agent value keys the runtime fills ("" none)
    pub state_key: &'static str,
    pub missed_key: &'static str,
}

/// Milliseconds as the C++ runtime prints them (`%g ms`: 200 ms, 2.5 ms).
pub fn format_ms(ms: f64) -> String {
    format!("{ms} ms")
}

/// What [`StreamMonitor::non_finite_sample`] found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NonFinite {
    /// the stream was just lost
    pub lost: bool,
    /// this sample begins a run of non-finite ones (worth one report)
    pub first_of_run: bool,
}

const STATE: i32 = 0xf;
const CAUSE_SHIFT: i32 = 4;

fn pack(s: StreamState, c: LossCause) -> i32 {
    s as i32 | ((c as i32) << CAUSE_SHIFT)
}

/// The process's monotonic epoch: the last finite sample's time is kept as nanoseconds since it.
fn epoch() -> Instant {
    static EPOCH: OnceLock<Instant> = OnceLock::new();
    *EPOCH.get_or_init(Instant::now)
}

/// `t` as nanoseconds since the epoch (0 for a time before it).
pub fn nanos(t: Instant) -> i64 {
    i64::try_from(t.saturating_duration_since(epoch()).as_nanos()).unwrap_or(i64::MAX)
}

/// One stream's state and counters.
pub struct StreamMonitor {
    /// the state and the cause of a loss in one atomic: the reporting thread never reads a
    /// "lost" with the cause of an earlier loss
    state: AtomicI32,
    alive: AtomicU32,
    samples: AtomicU64,
    missed: AtomicU64,
    losses: AtomicU64,
    gone: AtomicU64,
    non_finite: AtomicU64,
    runs: AtomicU64,
    in_run: AtomicBool,
    /// ns since epoch(); -1 none yet
    last_finite: AtomicI64,
}

impl Default for StreamMonitor {
    fn default() -> StreamMonitor {
        epoch(); // fixed before any sample
        StreamMonitor {
            state: AtomicI32::new(StreamState::Waiting as i32),
            alive: AtomicU32::new(0),
            samples: AtomicU64::new(0),
            missed: AtomicU64::new(0),
            losses: AtomicU64::new(0),
            gone: AtomicU64::new(0),
            non_finite: AtomicU64::new(0),
            runs: AtomicU64::new(0),
            in_run: AtomicBool::new(false),
            last_finite: AtomicI64::new(-1),
        }
    }
}

impl StreamMonitor {
    pub fn new() -> StreamMonitor {
        StreamMonitor::default()
    }

    /// A valid (finite) sample arrived at `now`; true when the stream became active (first
    /// sample, recovery).
    pub fn sample(&self, now: Instant) -> bool {
        self.samples.fetch_add(1, Ordering::Relaxed);
        self.last_finite.store(nanos(now), Ordering::Relaxed);
        self.in_run.store(false, Ordering::Relaxed);
        self.set(StreamState::Active, LossCause::Deadline)
    }

    /// A sample with a NaN or an infinity arrived (dropped, not handed to anyone). Counted;
    /// when the stream is active and no finite sample came within `deadline`, it is lost as a
    /// missed deadline (one more missed, cause NonFinite).
    pub fn non_finite_sample(&self, deadline: Duration, now: Instant) -> NonFinite {
        let mut out = NonFinite::default();
        self.non_finite.fetch_add(1, Ordering::Relaxed);
        out.first_of_run = !self.in_run.swap(true, Ordering::Relaxed);
        if out.first_of_run {
            self.runs.fetch_add(1, Ordering::Relaxed);
        }
        let last = self.last_finite.load(Ordering::Relaxed);
        let late = last < 0 || nanos(now).saturating_sub(last) > i64::try_from(deadline.as_nanos()).unwrap_or(i64::MAX);
        if !deadline.is_zero() && late && self.state() == StreamState::Active {
            self.missed.fetch_add(1, Ordering::Relaxed);
            out.lost = self.lose(LossCause::NonFinite);
        }
        out
    }

    /// The reader's DEADLINE passed without a sample (`count` of them); true when the stream
    /// was active and is now lost.
    pub fn deadline_missed(&self, count: u64) -> bool {
        self.missed.fetch_add(count, Ordering::Relaxed);
        self.lose(LossCause::Deadline)
    }

    /// LIVELINESS: alive writers now; true when the stream was active and is now lost, or when
    /// the last writer just went (reported even when a deadline lost the stream first).
    pub fn writers_alive(&self, alive: u32) -> bool {
        let was = self.alive.swap(alive, Ordering::AcqRel);
        if alive > 0 || was == 0 {
            return false;
        }
        self.gone.fetch_add(1, Ordering::Relaxed);
        self.lose(LossCause::Liveliness);
        true
    }

    pub fn state(&self) -> StreamState {
        match self.state.load(Ordering::Acquire) & STATE {
            1 => StreamState::Active,
            2 => StreamState::Lost,
            _ => StreamState::Waiting,
        }
    }

    /// Why the stream was last lost (meaningful while state() is Lost).
    pub fn cause(&self) -> LossCause {
        match self.state.load(Ordering::Acquire) >> CAUSE_SHIFT {
            1 => LossCause::Liveliness,
            2 => LossCause::NonFinite,
            _ => LossCause::Deadline,
        }
    }

    /// The state and the cause read together.
    pub fn state_and_cause(&self) -> (StreamState, LossCause) {
        let v = self.state.load(Ordering::Acquire);
        let s = match v & STATE {
            1 => StreamState::Active,
            2 => StreamState::Lost,
            _ => StreamState::Waiting,
        };
        let c = match v >> CAUSE_SHIFT {
            1 => LossCause::Liveliness,
            2 => LossCause::NonFinite,
            _ => LossCause::Deadline,
        };
        (s, c)
    }

    pub fn samples(&self) -> u64 {
        self.samples.load(Ordering::Relaxed)
    }
    /// Samples dropped for a NaN or an infinity (never handed to the handler).
    pub fn non_finite(&self) -> u64 {
        self.non_finite.load(Ordering::Relaxed)
    }
    /// Runs of non-finite samples begun (see non_finite_sample): the reporting thread's cue.
    pub fn non_finite_runs(&self) -> u64 {
        self.runs.load(Ordering::Relaxed)
    }
    pub fn missed(&self) -> u64 {
        self.missed.load(Ordering::Relaxed)
    }
    pub fn losses(&self) -> u64 {
        self.losses.load(Ordering::Relaxed)
    }
    /// Times the last alive writer went (LIVELINESS lapsed or the writer left).
    pub fn writers_gone(&self) -> u64 {
        self.gone.load(Ordering::Relaxed)
    }

    fn lose(&self, cause: LossCause) -> bool {
        let lost = self
            .state
            .compare_exchange(StreamState::Active as i32, pack(StreamState::Lost, cause), Ordering::AcqRel, Ordering::Acquire)
            .is_ok();
        if lost {
            self.losses.fetch_add(1, Ordering::Relaxed);
        }
        lost
    }

    fn set(&self, s: StreamState, cause: LossCause) -> bool {
        let old = self.state.swap(pack(s, cause), Ordering::AcqRel);
        (old & STATE) != s as i32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DEADLINE: Duration = Duration::from_millis(200);

    #[test]
    fn first_sample_activates_and_repeats_do_not() {
        let m = StreamMonitor::new();
        assert_eq!(m.state(), StreamState::Waiting);
        let t = Instant::now();
        assert!(m.sample(t));
        assert!(!m.sample(t));
        assert_eq!(m.state(), StreamState::Active);
        assert_eq!(m.samples(), 2);
    }

    #[test]
    fn a_waiting_stream_is_never_lost() {
        let m = StreamMonitor::new();
        assert!(!m.deadline_missed(3));
        assert_eq!(m.state(), StreamState::Waiting);
        assert_eq!(m.missed(), 3); // counted all the same
        assert_eq!(m.losses(), 0);
    }

    #[test]
    fn deadline_loses_once_and_a_sample_recovers() {
        let m = StreamMonitor::new();
        m.sample(Instant::now());
        assert!(m.deadline_missed(1));
        assert!(!m.deadline_missed(2)); // already lost: counted, not lost again
        assert_eq!((m.state(), m.cause()), (StreamState::Lost, LossCause::Deadline));
        assert_eq!((m.missed(), m.losses()), (3, 1));
        assert!(m.sample(Instant::now()));
        assert_eq!(m.state(), StreamState::Active);
    }

    #[test]
    fn the_last_writer_going_is_reported_even_after_a_deadline() {
        let m = StreamMonitor::new();
        assert!(!m.writers_alive(1)); // a writer came
        m.sample(Instant::now());
        assert!(m.deadline_missed(1));
        assert!(m.writers_alive(0)); // gone: news even though the stream is already lost
        assert_eq!(m.cause(), LossCause::Deadline); // the first cause stays
        assert_eq!((m.writers_gone(), m.losses()), (1, 1));
        assert!(!m.writers_alive(0)); // nothing new
    }

    #[test]
    fn liveliness_loses_an_active_stream() {
        let m = StreamMonitor::new();
        m.writers_alive(2);
        m.sample(Instant::now());
        assert!(!m.writers_alive(1)); // one of two left
        assert_eq!(m.state(), StreamState::Active);
        assert!(m.writers_alive(0));
        assert_eq!(m.state_and_cause(), (StreamState::Lost, LossCause::Liveliness));
    }

    #[test]
    fn non_finite_samples_do_not_keep_it_alive() {
        let m = StreamMonitor::new();
        let t0 = Instant::now();
        m.sample(t0);
        // within the deadline: counted, first of a run, not lost
        let r = m.non_finite_sample(DEADLINE, t0 + Duration::from_millis(50));
        assert_eq!(r, NonFinite { lost: false, first_of_run: true });
        let r = m.non_finite_sample(DEADLINE, t0 + Duration::from_millis(100));
        assert_eq!(r, NonFinite { lost: false, first_of_run: false });
        // past the deadline since the last finite one: lost, one more missed
        let r = m.non_finite_sample(DEADLINE, t0 + Duration::from_millis(250));
        assert_eq!(r, NonFinite { lost: true, first_of_run: false });
        assert_eq!(m.state_and_cause(), (StreamState::Lost, LossCause::NonFinite));
        assert_eq!((m.missed(), m.non_finite(), m.non_finite_runs(), m.samples()), (1, 3, 1, 1));
        // still lost: not lost again
        assert!(!m.non_finite_sample(DEADLINE, t0 + Duration::from_millis(500)).lost);
        // a finite one recovers it and ends the run: the next NaN starts another
        assert!(m.sample(t0 + Duration::from_millis(600)));
        assert!(m.non_finite_sample(DEADLINE, t0 + Duration::from_millis(610)).first_of_run);
        assert_eq!(m.non_finite_runs(), 2);
    }

    #[test]
    fn non_finite_before_any_sample_leaves_it_waiting() {
        let m = StreamMonitor::new();
        let r = m.non_finite_sample(DEADLINE, Instant::now());
        assert_eq!(r, NonFinite { lost: false, first_of_run: true });
        assert_eq!(m.state(), StreamState::Waiting);
    }

    #[test]
    fn words_as_the_cpp_runtime() {
        assert_eq!(format_ms(200.0), "200 ms");
        assert_eq!(format_ms(2.5), "2.5 ms");
        assert_eq!(LossAction::Hold.text(), "holding the last setpoint");
        assert_eq!(StreamState::Lost.name(), "lost");
    }
}
