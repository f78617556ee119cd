//! The broken-asset kinds the DDS layer injects (test builds only: the cargo feature
//! `test-breaks`; a robot's build has neither this module nor a branch on it). The kinds, with
//! the check each fails, are listed once, in `rapid_runtime::breaks::KINDS` (which also
//! refuses an unknown one); this module breaks what rapid_runtime never sees, the way the
//! Python kind of the same name (tests/conformance/broken) and the C++ runtime's `--break`
//! (runtime/cpp/dds/include/rapid_runtime/dds/breaks.hpp) do:
//!
//! - the ack writer (`DdsOutbox`): ack-topic-suffixed, volatile-acks;
//! - the configs (`bridge::run`, `configs`): position-config-unpublished, volatile-config,
//!   wrong-config, config-without-source, serial-drift;
//! - the simulated telemetry (`telemetry`): position-silent, gps-silent, wrong-serial,
//!   millisecond-stamps, frozen-stamps, sample-without-source, misaligned-values,
//!   millivolts, slow-rate.
use std::collections::BTreeSet;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use rapid_types::cdr::{self, Endianness};
use rapid_types::rapid;

use crate::configs::Configs;
use crate::convert;
use crate::dds::Side;
use crate::tables_json::{Asset, Telemetry};

/// serial-drift: seconds between republications (the Python kind's)
pub const DRIFT_PERIOD: Duration = Duration::from_secs(3);
/// serial-drift's config: one no sample follows (drifting a telemetry config too would race
/// TEL-02, a sample stamped before a republication read after it: the Python kind's choice)
pub const DRIFTED: &str = "rapid_command_config";
const TICK: Duration = Duration::from_millis(50);

/// What the DDS layer breaks, from the kinds turned on.
pub struct Breaks {
    kinds: Arc<rapid_runtime::breaks::Breaks>,
    /// frozen-stamps: every sample's stamp (microseconds), the bridge's start
    start_us: i64,
    /// position-config-unpublished: the first position entry's config
    position_config: Option<String>,
    /// telemetry topics whose writer exists and never writes (position-silent: the first
    /// position entry's samples; gps-silent: the first extension entry's)
    silent: BTreeSet<String>,
}

impl Breaks {
    pub fn new(kinds: Arc<rapid_runtime::breaks::Breaks>, asset: &Asset) -> Breaks {
        let first = |kind: &str, role: &str| {
            asset.telemetry.iter().find(|t| t.kind == kind).and_then(|t| t.topics.get(role).cloned())
        };
        let mut silent = BTreeSet::new();
        for (kind, entry) in [("position-silent", "position"), ("gps-silent", "custom")] {
            if let Some(topic) = kinds.on(kind).then(|| first(entry, "sample")).flatten() {
                silent.insert(topic);
            }
        }
        Breaks { position_config: first("position", "config"), silent, start_us: convert::now_us(), kinds }
    }

    fn on(&self, kind: &str) -> bool {
        self.kinds.on(kind)
    }

    // ---- the ack writer ----------------------------------------------------------------------

    /// ack-topic-suffixed: acks on rapid_ack-<asset> (5b: the topic is plain rapid_ack)
    pub fn ack_topic(&self, asset: &str, topic: &str) -> String {
        if self.on("ack-topic-suffixed") {
            format!("{topic}-{asset}")
        } else {
            topic.to_string()
        }
    }

    /// volatile-acks: a late-joining ack reader gets nothing
    pub fn ack_side(&self, side: Side) -> Side {
        Side { transient_local: side.transient_local && !self.on("volatile-acks"), ..side }
    }

    // ---- configs -----------------------------------------------------------------------------

    /// position-config-unpublished: no writer, nothing written (its serial is still the
    /// start one, which its samples carry)
    pub fn config_unpublished(&self, topic: &str) -> bool {
        self.on("position-config-unpublished") && self.position_config.as_deref() == Some(topic)
    }

    /// volatile-config: config writers volatile
    pub fn config_side(&self, side: Side) -> Side {
        Side { transient_local: side.transient_local && !self.on("volatile-config"), ..side }
    }

    /// wrong-config: the CommandConfig lists one subsystem fewer than the descriptor implies
    pub fn config_sample(&self, topic: &str, sample: &[u8]) -> Result<Vec<u8>, String> {
        if !(self.on("wrong-config") && topic == "rapid_command_config") {
            return Ok(sample.to_vec());
        }
        let mut c: rapid::CommandConfig = cdr::deserialize(sample).map_err(|e| format!("{topic}: {e}"))?;
        c.available_subsystems.pop();
        cdr::serialize(&c, Endianness::Little).map_err(|e| format!("{topic}: {e}"))
    }

    /// config-without-source: configs built before the bridge knew its name (srcName empty)
    pub fn config_source<'a>(&self, name: &'a str) -> &'a str {
        if self.on("config-without-source") {
            ""
        } else {
            name
        }
    }

    /// serial-drift: DRIFTED republished every DRIFT_PERIOD with a new serial and the same
    /// content, until `stop` (a bridge stamping each publication anew). None: not on.
    pub fn drift(&self, configs: Arc<Configs>, sample: Option<Vec<u8>>, stop: Arc<AtomicBool>) -> Option<JoinHandle<()>> {
        let sample = sample.filter(|_| self.on("serial-drift"))?;
        let run = move || {
            let mut next = Instant::now() + DRIFT_PERIOD;
            let mut n = 0u64;
            while !stop.load(Ordering::SeqCst) {
                if Instant::now() < next {
                    std::thread::sleep(TICK);
                    continue;
                }
                next += DRIFT_PERIOD;
                n += 1;
                // the content compared for a new serial salted: always "changed"
                if let Err(e) = configs.publish_salted(DRIFTED, &sample, format!("#{n}").as_bytes()) {
                    eprintln!("serial-drift: {e}");
                }
            }
        };
        std::thread::Builder::new().name("serial-drift".into()).spawn(run).ok()
    }

    // ---- simulated telemetry -----------------------------------------------------------------

    /// The telemetry entries as the broken bridge declares them to itself (slow-rate: every
    /// declared rate halved, as the Python kind patches its tables); None: as they are.
    pub fn telemetry(&self, entries: &[Telemetry]) -> Option<Vec<Telemetry>> {
        if !self.on("slow-rate") {
            return None;
        }
        Some(entries.iter().map(|t| Telemetry { rate: t.rate.map(|r| r / 2.0), ..t.clone() }).collect())
    }

    /// position-silent, gps-silent: the topic's writer exists and never writes
    pub fn silent(&self, topic: &str) -> bool {
        self.silent.contains(topic)
    }

    /// A telemetry sample's header as the broken bridge fills it.
    pub fn sample_header(&self, h: &mut rapid::Header) {
        if self.on("wrong-serial") {
            h.serial += 1;
        }
        if self.on("millisecond-stamps") {
            h.time_stamp /= 1000;
        }
        if self.on("frozen-stamps") {
            h.time_stamp = self.start_us; // recent at first, never advancing
        }
        if self.on("sample-without-source") {
            h.src_name.clear();
        }
    }

    /// Telemetry values (one per value key, `keys` in the config's order) as the broken
    /// bridge sends them: millivolts: batteryVoltage in mV (declared V); misaligned-values:
    /// reversed, one more at the end.
    pub fn values(&self, keys: &[(String, rapid::ParameterUnion)], mut values: Vec<rapid::ParameterUnion>) -> Vec<rapid::ParameterUnion> {
        if self.on("millivolts") {
            for ((k, _), v) in keys.iter().zip(values.iter_mut()) {
                match v {
                    rapid::ParameterUnion::F(x) if k == "batteryVoltage" => *x *= 1000.0,
                    rapid::ParameterUnion::D(x) if k == "batteryVoltage" => *x *= 1000.0,
                    _ => {}
                }
            }
        }
        if self.on("misaligned-values") {
            values.reverse();
            values.push(rapid::ParameterUnion::B(true));
        }
        values
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rapid_runtime::configs::Serials;
    use std::sync::Mutex;

    fn asset() -> Asset {
        let entry = |kind: &str, rate: Option<f64>, topics: &[(&str, &str)]| Telemetry {
            kind: kind.into(),
            rate,
            topics: topics.iter().map(|(r, t)| (r.to_string(), t.to_string())).collect(),
            ..Telemetry::default()
        };
        Asset {
            tables: Default::default(),
            telemetry: vec![
                entry("position", Some(1.0), &[("sample", "pos"), ("config", "pos_config")]),
                entry("custom", Some(2.0), &[("sample", "gps"), ("config", "gps_config")]),
                entry("text", None, &[("sample", "text")]),
            ],
            publications: Vec::new(),
        }
    }

    fn on(kinds: &[&str]) -> Breaks {
        let names: Vec<String> = kinds.iter().map(|k| k.to_string()).collect();
        Breaks::new(Arc::new(rapid_runtime::breaks::Breaks::new(&names).unwrap()), &asset())
    }

    #[test]
    fn nothing_on_changes_nothing() {
        let b = on(&[]);
        assert_eq!(b.ack_topic("A", "rapid_ack"), "rapid_ack");
        assert!(b.ack_side(Side { reliable: true, transient_local: true, depth: Some(8) }).transient_local);
        assert!(b.config_side(Side { reliable: true, transient_local: true, depth: Some(1) }).transient_local);
        assert!(!b.config_unpublished("pos_config"));
        assert_eq!(b.config_source("A"), "A");
        assert!(b.telemetry(&asset().telemetry).is_none());
        assert!(!b.silent("pos") && !b.silent("gps"));
        let mut h = convert::header("A", "A", 7, 0);
        let before = h.clone();
        b.sample_header(&mut h);
        assert_eq!(h, before);
        let keys = vec![("batteryVoltage".to_string(), rapid::ParameterUnion::F(51.0))];
        assert_eq!(b.values(&keys, vec![rapid::ParameterUnion::F(51.0)]), [rapid::ParameterUnion::F(51.0)]);
        let serials = Arc::new(Mutex::new(Serials::new(Some(1000), Box::new(|| 1000), None)));
        let configs = Arc::new(Configs::new("A", serials, Default::default()));
        assert!(b.drift(configs, Some(vec![]), Arc::new(AtomicBool::new(true))).is_none());
    }

    #[test]
    fn each_kind_breaks_its_part() {
        assert_eq!(on(&["ack-topic-suffixed"]).ack_topic("K10Red", "rapid_ack"), "rapid_ack-K10Red");
        assert!(!on(&["volatile-acks"]).ack_side(Side { reliable: true, transient_local: true, depth: Some(8) }).transient_local);
        assert!(!on(&["volatile-config"]).config_side(Side { reliable: true, transient_local: true, depth: Some(1) }).transient_local);
        let b = on(&["position-config-unpublished"]);
        assert!(b.config_unpublished("pos_config") && !b.config_unpublished("gps_config"));
        assert_eq!(on(&["config-without-source"]).config_source("A"), "");
        let slowed = on(&["slow-rate"]).telemetry(&asset().telemetry).unwrap();
        assert_eq!(slowed.iter().map(|t| t.rate).collect::<Vec<_>>(), [Some(0.5), Some(1.0), None]);
        assert!(on(&["position-silent"]).silent("pos") && !on(&["position-silent"]).silent("gps"));
        assert!(on(&["gps-silent"]).silent("gps") && !on(&["gps-silent"]).silent("pos"));

        let hdr = |kind: &str| {
            let mut h = convert::header("A", "A", 7, 0);
            on(&[kind]).sample_header(&mut h);
            h
        };
        assert_eq!(hdr("wrong-serial").serial, 8);
        assert!(hdr("millisecond-stamps").time_stamp < convert::now_us() / 100);
        let frozen = on(&["frozen-stamps"]);
        let (mut a, mut b) = (convert::header("A", "A", 7, 0), convert::header("A", "A", 7, 0));
        frozen.sample_header(&mut a);
        std::thread::sleep(Duration::from_millis(2));
        frozen.sample_header(&mut b);
        assert_eq!(a.time_stamp, b.time_stamp);
        assert_eq!(hdr("sample-without-source").src_name, "");

        use rapid::ParameterUnion::{B, F};
        let keys = vec![("batteryVoltage".to_string(), F(51.0)), ("charge".to_string(), F(90.0))];
        assert_eq!(on(&["millivolts"]).values(&keys, vec![F(51.0), F(90.0)]), [F(51000.0), F(90.0)]);
        assert_eq!(on(&["misaligned-values"]).values(&keys, vec![F(51.0), F(90.0)]), [F(90.0), F(51.0), B(true)]);
    }

    #[test]
    fn wrong_config_leaves_a_subsystem_out() {
        let c = rapid::CommandConfig {
            available_subsystems: vec![rapid::Subsystem { name: "Arm".into(), ..Default::default() },
                                       rapid::Subsystem { name: "Mast".into(), ..Default::default() }],
            ..Default::default()
        };
        let bytes = cdr::serialize(&c, Endianness::Little).unwrap();
        let b = on(&["wrong-config"]);
        assert_eq!(b.config_sample("rapid_agent_config", &bytes).unwrap(), bytes);
        let got: rapid::CommandConfig = cdr::deserialize(&b.config_sample("rapid_command_config", &bytes).unwrap()).unwrap();
        assert_eq!(got.available_subsystems.len(), 1);
        assert_eq!(got.available_subsystems[0].name, "Arm");
    }
}
