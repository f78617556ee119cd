//! Republishing a config (docs/rust-backend.md, "Configs"): the bridge publishes every config at
//! start with the start serial; the user's code may publish one again later through the running
//! bridge's [`Configs`] (`rapid_dds::configs::get()`, as the Python bridge's `publish_config` and
//! the C++ bridge's config publish). Other content gets a new, larger serial
//! (`rapid_runtime::configs::Serials`), recorded in the restart journal, written in the sample's
//! header, and carried from then on by the telemetry paired with that config; the same content
//! is not written again.
use std::collections::BTreeMap;
use std::sync::{Arc, Mutex, OnceLock};

use rapid_runtime::configs::Serials;

use rapid_types::rapid;

use crate::convert;
use crate::dds::Writer;

/// The serials of the asset's configs, shared by the config publisher and the telemetry.
pub type SharedSerials = Arc<Mutex<Serials>>;

/// Told of a serial issued after the start (the bridge records it in the journal).
pub type Record = Arc<dyn Fn(i64) + Send + Sync>;

/// The running bridge's config publisher.
pub struct Configs {
    name: String,
    /// the configs' hdr.srcName: the asset's name (a test build's config-without-source: empty)
    source: String,
    serials: SharedSerials,
    /// topic -> its transient-local writer, made at start
    writers: BTreeMap<String, Writer>,
    record: OnceLock<Record>,
}

static RUNNING: OnceLock<Arc<Configs>> = OnceLock::new();

/// The running bridge's config publisher (None before the bridge published its configs).
pub fn get() -> Option<Arc<Configs>> {
    RUNNING.get().cloned()
}

impl Configs {
    pub(crate) fn new(name: &str, serials: SharedSerials, writers: BTreeMap<String, Writer>) -> Configs {
        Configs { name: name.to_string(), source: name.to_string(), serials, writers, record: OnceLock::new() }
    }

    /// The configs' hdr.srcName (a test build's config-without-source, crate::breaks).
    #[cfg(feature = "test-breaks")]
    pub(crate) fn with_source(self, source: &str) -> Configs {
        Configs { source: source.to_string(), ..self }
    }

    /// Makes it the one `get()` gives (once per process: a bridge runs once).
    pub(crate) fn install(self: &Arc<Configs>) {
        let _ = RUNNING.set(self.clone());
    }

    /// Where serials issued from now on are recorded (the journal, through the manager).
    pub(crate) fn record_with(&self, record: Record) {
        let _ = self.record.set(record);
    }

    pub fn serials(&self) -> SharedSerials {
        self.serials.clone()
    }

    /// The serial the topic's config carries now.
    pub fn serial(&self, topic: &str) -> i32 {
        self.serials.lock().unwrap_or_else(|e| e.into_inner()).of(topic)
    }

    /// Publishes the topic's config: `sample` is its CDR_LE encoding (header left default, as
    /// the generated crate's computed configs). Content unchanged: nothing written, the serial
    /// it has. Changed: a new serial, recorded, then the sample with it. Returns the serial.
    pub fn publish(&self, topic: &str, sample: &[u8]) -> Result<i32, String> {
        let writer = self.writers.get(topic).ok_or_else(|| format!("{topic}: not a config of {}", self.name))?;
        self.publish_with(topic, sample, |bytes| writer.write(bytes).map_err(|e| format!("{topic}: {e}")))
    }

    /// publish() with the writing given (the tests': no DDS).
    pub(crate) fn publish_with(&self, topic: &str, sample: &[u8], write: impl FnOnce(&[u8]) -> Result<(), String>) -> Result<i32, String> {
        // the header is not content: the same config with another stamp keeps its serial
        let content = convert::with_header(sample, &rapid::Header::default())?;
        self.put(topic, sample, &content, write)
    }

    /// serial-drift (a test build's, crate::breaks): the topic's config published again with
    /// a new serial, its content compared with `salt` added (always "changed").
    #[cfg(feature = "test-breaks")]
    pub(crate) fn publish_salted(&self, topic: &str, sample: &[u8], salt: &[u8]) -> Result<i32, String> {
        let writer = self.writers.get(topic).ok_or_else(|| format!("{topic}: not a config of {}", self.name))?;
        let mut content = convert::with_header(sample, &rapid::Header::default())?;
        content.extend_from_slice(salt);
        self.put(topic, sample, &content, |bytes| writer.write(bytes).map_err(|e| format!("{topic}: {e}")))
    }

    /// The sample written with a new serial when `content` changed; the serial it has.
    fn put(&self, topic: &str, sample: &[u8], content: &[u8], write: impl FnOnce(&[u8]) -> Result<(), String>) -> Result<i32, String> {
        // the lock held to the write: two publishers of one topic go out in serial order
        let mut serials = self.serials.lock().unwrap_or_else(|e| e.into_inner());
        let (serial, changed) = serials.update(topic, content);
        if changed {
            if let Some(r) = self.record.get() {
                r(serial as i64); // on disk before the serial is seen (a restart comes back above it)
            }
            write(&convert::with_header(sample, &convert::header(&self.source, &self.name, serial, 0))?)?;
        }
        Ok(serial)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rapid_types::cdr::{self, Endianness};
    use std::sync::atomic::{AtomicI64, Ordering};

    fn sample(frame: &str) -> Vec<u8> {
        let c = rapid::PositionConfig { frame_name: frame.into(), ..Default::default() };
        cdr::serialize(&c, Endianness::Little).unwrap()
    }

    fn serial_in(bytes: &[u8]) -> i32 {
        let c: rapid::PositionConfig = cdr::deserialize(bytes).unwrap();
        c.hdr.serial
    }

    #[test]
    fn a_changed_config_goes_out_with_a_larger_serial_recorded() {
        let at = Arc::new(AtomicI64::new(2000));
        let clock = at.clone();
        let serials: SharedSerials = Arc::new(Mutex::new(Serials::new(Some(1000), Box::new(move || clock.load(Ordering::SeqCst)), None)));
        serials.lock().unwrap().update("pos", &convert::with_header(&sample("site"), &rapid::Header::default()).unwrap());
        let c = Configs::new("A", serials.clone(), BTreeMap::new());
        let recorded = Arc::new(Mutex::new(Vec::new()));
        let r2 = recorded.clone();
        c.record_with(Arc::new(move |s| r2.lock().unwrap().push(s)));
        let written = Mutex::new(Vec::new());
        let keep = |b: &[u8]| {
            written.lock().unwrap().push(b.to_vec());
            Ok(())
        };
        // the start's content again (another stamp in its header): no new serial, nothing written
        let mut stamped = sample("site");
        stamped = convert::with_header(&stamped, &convert::header("A", "A", 7, 0)).unwrap();
        assert_eq!(c.publish_with("pos", &stamped, keep), Ok(1000));
        assert!(written.lock().unwrap().is_empty());
        // other content: a larger serial, recorded, in the written sample's header
        assert_eq!(c.publish_with("pos", &sample("base"), keep), Ok(2000));
        assert_eq!(written.lock().unwrap().len(), 1);
        assert_eq!(serial_in(&written.lock().unwrap()[0]), 2000);
        assert_eq!(*recorded.lock().unwrap(), [2000]);
        assert_eq!(c.serial("pos"), 2000);
        // a failed write still leaves the serial issued (as the other runtimes: never reused)
        assert!(c.publish_with("pos", &sample("arm"), |_| Err("down".into())).is_err());
        assert_eq!(c.serial("pos"), 2001);
        assert!(c.publish("nope", &sample("")).unwrap_err().contains("not a config of A"));
    }
}
