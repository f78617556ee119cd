//! Cyclone DDS entities through cyclors, safe to use: a participant, blob topics (a type name
//! and raw CDR), writers and readers with the RAPID QoS sides (reliability, durability,
//! history) in one partition. The transport is Cyclone's: CYCLONEDDS_URI (the generated
//! qos/cyclonedds/local.xml keeps it on 127.0.0.1).
use std::ffi::CString;
use std::time::Duration;

use cyclors::*;

#[derive(Debug)]
pub struct DdsError(pub String);

impl std::fmt::Display for DdsError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for DdsError {}

fn check(what: &str, ret: dds_entity_t) -> Result<dds_entity_t, DdsError> {
    if ret < 0 {
        Err(DdsError(format!("{what}: DDS error {ret}")))
    } else {
        Ok(ret)
    }
}

/// One side of a RAPID QoS profile (the generated asset::QosSide's facts).
#[derive(Clone, Copy, Debug)]
pub struct Side {
    pub reliable: bool,
    pub transient_local: bool,
    /// None: keep all
    pub depth: Option<i32>,
}

struct Qos(*mut dds_qos_t);

impl Qos {
    fn new(partition: Option<&str>, side: Option<Side>) -> Qos {
        // SAFETY: a fresh qos object, owned by this value and deleted on drop
        unsafe {
            let q = dds_create_qos();
            if let Some(p) = partition {
                let c = CString::new(p).unwrap_or_default();
                let mut names = [c.as_ptr()];
                dds_qset_partition(q, 1, names.as_mut_ptr());
            }
            if let Some(s) = side {
                if s.reliable {
                    dds_qset_reliability(q, dds_reliability_kind_DDS_RELIABILITY_RELIABLE, 100_000_000);
                } else {
                    dds_qset_reliability(q, dds_reliability_kind_DDS_RELIABILITY_BEST_EFFORT, 0);
                }
                let d = if s.transient_local {
                    dds_durability_kind_DDS_DURABILITY_TRANSIENT_LOCAL
                } else {
                    dds_durability_kind_DDS_DURABILITY_VOLATILE
                };
                dds_qset_durability(q, d);
                let (kind, depth) = match s.depth {
                    Some(n) => (dds_history_kind_DDS_HISTORY_KEEP_LAST, n),
                    None => (dds_history_kind_DDS_HISTORY_KEEP_ALL, 0),
                };
                dds_qset_history(q, kind, depth);
                // What a late-joining reader gets is durability_service's history in Cyclone
                // (default: the last sample per instance), not the writer's: the same depth
                if s.transient_local {
                    dds_qset_durability_service(q, 0, kind, depth, -1, -1, -1);
                }
            }
            Qos(q)
        }
    }
}

impl Drop for Qos {
    fn drop(&mut self) {
        // SAFETY: created by dds_create_qos, deleted once
        unsafe { dds_delete_qos(self.0) }
    }
}

/// A domain participant with one publisher and one subscriber in the asset's partition.
pub struct Participant {
    dp: dds_entity_t,
    publisher: dds_entity_t,
    subscriber: dds_entity_t,
}

// SAFETY: Cyclone's entity handles are integers its API takes from any thread
unsafe impl Send for Participant {}
unsafe impl Sync for Participant {}

impl Participant {
    pub fn new(domain: u32, partition: &str) -> Result<Participant, DdsError> {
        // SAFETY: plain calls of Cyclone's C API with valid arguments
        unsafe {
            let dp = check("participant", dds_create_participant(domain, std::ptr::null(), std::ptr::null()))?;
            let q = Qos::new(Some(partition), None);
            let publisher = check("publisher", dds_create_publisher(dp, q.0, std::ptr::null()))?;
            let subscriber = check("subscriber", dds_create_subscriber(dp, q.0, std::ptr::null()))?;
            Ok(Participant { dp, publisher, subscriber })
        }
    }

    /// A topic carrying CDR bytes of `type_name`; keyed: a WITH_KEY topic (the blob type
    /// computes no key: every sample is one instance on the writer's side).
    pub fn topic(&self, name: &str, type_name: &str, keyed: bool) -> Result<Topic, DdsError> {
        let n = CString::new(name).map_err(|_| DdsError(format!("topic name {name:?}")))?;
        let t = CString::new(type_name).map_err(|_| DdsError(format!("type name {type_name:?}")))?;
        // SAFETY: the strings outlive the call; cyclocut copies them
        let topic = unsafe { cdds_create_blob_topic(self.dp, n.as_ptr() as *mut _, t.as_ptr() as *mut _, !keyed) };
        Ok(Topic(check(&format!("topic {name}"), topic)?))
    }

    /// A WITH_KEY topic whose samples are instances by key, as a typed topic's (keyed.rs):
    /// `key` reads a sample's key members, `md5` when their largest encoding exceeds 16 bytes.
    pub fn keyed_topic(&self, name: &str, type_name: &str, key: crate::keyed::KeyOf, md5: bool) -> Result<Topic, DdsError> {
        let t = self.topic(name, type_name, true)?;
        // SAFETY: a blob topic; its type's samples are made only by writers created after this
        unsafe { crate::keyed::make_keyed(t.0, key, md5) }.map_err(|e| DdsError(format!("topic {name}: {e}")))?;
        Ok(t)
    }

    /// The participant's entity (stream.rs makes its own subscribers and publishers in it).
    pub(crate) fn handle(&self) -> dds_entity_t {
        self.dp
    }

    pub fn writer(&self, topic: &Topic, side: Side) -> Result<Writer, DdsError> {
        self.writers(topic, side).make()
    }

    /// What makes writers of `topic` later, apart from the participant (ack writer generations).
    pub fn writers(&self, topic: &Topic, side: Side) -> Writers {
        Writers { publisher: self.publisher, topic: topic.0, side }
    }

    /// Blocks a thread until `reader` holds a sample (Waiter::wait), instead of polling it.
    pub fn waiter(&self, reader: &Reader) -> Result<Waiter, DdsError> {
        // SAFETY: valid entities; the waitset and condition belong to the participant and
        // go with it
        unsafe {
            let ws = check("waitset", dds_create_waitset(self.dp))?;
            let cond = check("read condition", dds_create_readcondition(reader.0, DDS_ANY_STATE))?;
            check("waitset attach", dds_waitset_attach(ws, cond, 0))?;
            Ok(Waiter(ws))
        }
    }

    pub fn reader(&self, topic: &Topic, side: Side) -> Result<Reader, DdsError> {
        let q = Qos::new(None, Some(side));
        // SAFETY: valid entities and qos
        let r = unsafe { dds_create_reader(self.subscriber, topic.0, q.0, std::ptr::null()) };
        Ok(Reader(check("reader", r)?))
    }
}

impl Drop for Participant {
    fn drop(&mut self) {
        // SAFETY: deletes the participant and everything in it, once
        unsafe {
            dds_delete(self.dp);
        }
    }
}

#[derive(Clone, Copy)]
pub struct Topic(dds_entity_t);

/// Makes writers of one topic with one QoS side.
#[derive(Clone, Copy)]
pub struct Writers {
    publisher: dds_entity_t,
    topic: dds_entity_t,
    side: Side,
}

// SAFETY: entity handles (integers); Cyclone locks internally
unsafe impl Send for Writers {}
unsafe impl Sync for Writers {}

impl Writers {
    pub fn make(&self) -> Result<Writer, DdsError> {
        let q = Qos::new(None, Some(self.side));
        // SAFETY: valid entities and qos
        let w = unsafe { dds_create_writer(self.publisher, self.topic, q.0, std::ptr::null()) };
        Ok(Writer { w: check("writer", w)?, topic: self.topic })
    }
}

#[derive(Clone, Copy)]
pub struct Writer {
    w: dds_entity_t,
    topic: dds_entity_t,
}

// SAFETY: entity handles (integers); Cyclone locks internally
unsafe impl Send for Writer {}
unsafe impl Sync for Writer {}

impl Writer {
    /// A writer made elsewhere in the crate (stream.rs: the streams' QoS) and its topic.
    pub(crate) fn from_raw(w: dds_entity_t, topic: dds_entity_t) -> Writer {
        Writer { w, topic }
    }

    /// How many readers are matched now.
    pub fn matched(&self) -> u32 {
        // SAFETY: a writer entity and a status struct to fill
        unsafe {
            let mut st: dds_publication_matched_status_t = std::mem::zeroed();
            if dds_get_publication_matched_status(self.w, &mut st) < 0 {
                return 0;
            }
            st.current_count
        }
    }

    /// Deletes the writer (its history goes with it); Cyclone lingers in the call until its
    /// readers have acknowledged what it wrote.
    pub fn delete(self) -> Result<(), DdsError> {
        // SAFETY: a writer entity, deleted once (the value is consumed)
        check("delete writer", unsafe { dds_delete(self.w) }).map(|_| ())
    }

    /// Writes one sample given as its CDR bytes (encapsulation header included).
    pub fn write(&self, bytes: &[u8]) -> Result<(), DdsError> {
        // SAFETY: the sertype is the topic's; from_ser_iov copies the bytes into a new serdata,
        // which dds_writecdr takes over
        unsafe {
            let mut st: *const ddsi_sertype = std::ptr::null();
            check("sertype", dds_get_entity_sertype(self.topic, &mut st))?;
            // (ok_or_else: an eager error String was one allocation per write)
            let from = (*(*st).serdata_ops).from_ser_iov.ok_or_else(|| DdsError("no from_ser_iov".into()))?;
            let iov = ddsrt_iovec_t { iov_base: bytes.as_ptr() as *mut _, iov_len: bytes.len() as _ };
            let sd = from(st, ddsi_serdata_kind_SDK_DATA, 1, &iov, bytes.len());
            check("write", dds_writecdr(self.w, sd))?;
        }
        Ok(())
    }
}

#[derive(Clone, Copy)]
pub struct Reader(dds_entity_t);

// SAFETY: entity handle (integer)
unsafe impl Send for Reader {}

impl Reader {
    /// How many writers are matched now.
    pub fn matched(&self) -> u32 {
        // SAFETY: a reader entity and a status struct to fill
        unsafe {
            let mut st: dds_subscription_matched_status_t = std::mem::zeroed();
            if dds_get_subscription_matched_status(self.0, &mut st) < 0 {
                return 0;
            }
            st.current_count
        }
    }

    /// The next sample's CDR bytes and the handle of the writer that sent it; None when there
    /// is none now (a sample without data, a dispose or unregister, is passed over).
    pub fn take(&self) -> Option<(Vec<u8>, u64)> {
        loop {
            // SAFETY: dds_takecdr hands over one serdata reference, released below
            unsafe {
                let mut sd: *mut ddsi_serdata = std::ptr::null_mut();
                let mut info: dds_sample_info_t = std::mem::zeroed();
                if dds_takecdr(self.0, &mut sd, 1, &mut info, DDS_ANY_STATE) <= 0 || sd.is_null() {
                    return None;
                }
                let ops = (*sd).ops;
                let bytes = match ((*ops).get_size, (*ops).to_ser) {
                    (Some(size), Some(to_ser)) if info.valid_data => {
                        let n = size(sd) as usize;
                        let mut buf = vec![0u8; n];
                        to_ser(sd, 0, n, buf.as_mut_ptr() as *mut _);
                        Some(buf)
                    }
                    _ => None,
                };
                ddsi_serdata_unref(sd);
                if let Some(b) = bytes {
                    return Some((b, info.publication_handle));
                }
            }
        }
    }
}

/// A waitset on one reader's samples (Participant::waiter).
pub struct Waiter(dds_entity_t);

// SAFETY: entity handle (integer)
unsafe impl Send for Waiter {}

impl Waiter {
    /// True once the reader holds a sample (at once when it already does), false after `timeout`.
    pub fn wait(&self, timeout: Duration) -> bool {
        let ns = i64::try_from(timeout.as_nanos()).unwrap_or(i64::MAX);
        // SAFETY: a waitset entity; no attachment array is asked for
        unsafe { dds_waitset_wait(self.0, std::ptr::null_mut(), 0, ns) > 0 }
    }
}

/// Cyclone's configuration when CYCLONEDDS_URI is not set: the named transport's XML (the
/// generated qos target's cyclonedds/<name>.xml; `local` keeps DDS on loopback). Call before
/// the first participant.
pub fn use_transport(transports: &[(&str, &str)], name: &str) {
    if std::env::var_os("CYCLONEDDS_URI").is_none() {
        if let Some((_, xml)) = transports.iter().find(|(n, _)| *n == name) {
            // Cyclone takes the configuration itself in CYCLONEDDS_URI (no XML declaration)
            let body = xml.find("<CycloneDDS").map(|i| &xml[i..]).unwrap_or(xml);
            std::env::set_var("CYCLONEDDS_URI", body);
        }
    }
}
