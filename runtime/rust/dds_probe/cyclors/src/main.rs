//! cyclors probe (issue 38): Cyclone DDS's C library through cyclors' blob topics (raw CDR
//! in and out, so the generated XCDR1 codec is the type support), on a domain:
//!   ack-writer D PARTITION SECONDS   four Acks ("a" x3, "b" x1), transient-local keep-last 1
//!   cmd-reader D PARTITION SECONDS   prints every Command it takes
//!   pong D PARTITION SECONDS         answers each Command with a COMPLETED/OK Ack
//! Loopback only through CYCLONEDDS_URI (K10's generated local.xml).
use std::ffi::CString;
use std::time::{Duration, Instant};

use cyclors::*;
use rapid_k10red::{cdr, rapid};

unsafe fn qos(partition: Option<&str>, tl: bool, depth: i32) -> *mut dds_qos_t {
    let q = dds_create_qos();
    if let Some(p) = partition {
        let c = CString::new(p).unwrap();
        let mut ps = [c.as_ptr()];
        dds_qset_partition(q, 1, ps.as_mut_ptr());
    }
    dds_qset_reliability(q, dds_reliability_kind_DDS_RELIABILITY_RELIABLE, 100_000_000);
    dds_qset_durability(q, if tl { dds_durability_kind_DDS_DURABILITY_TRANSIENT_LOCAL } else { dds_durability_kind_DDS_DURABILITY_VOLATILE });
    dds_qset_history(q, dds_history_kind_DDS_HISTORY_KEEP_LAST, depth);
    q
}

unsafe fn topic(dp: dds_entity_t, name: &str, type_name: &str) -> dds_entity_t {
    let n = CString::new(name).unwrap();
    let t = CString::new(type_name).unwrap();
    cdds_create_blob_topic(dp, n.as_ptr() as *mut _, t.as_ptr() as *mut _, false)
}

unsafe fn write_cdr(w: dds_entity_t, t: dds_entity_t, bytes: &[u8]) -> i32 {
    let mut st: *const ddsi_sertype = std::ptr::null();
    dds_get_entity_sertype(t, &mut st);
    let iov = ddsrt_iovec_t { iov_base: bytes.as_ptr() as *mut _, iov_len: bytes.len() as _ };
    let sd = ((*(*st).serdata_ops).from_ser_iov.unwrap())(st, ddsi_serdata_kind_SDK_DATA, 1, &iov, bytes.len());
    dds_writecdr(w, sd)
}

/// the next sample's bytes (CDR header included), None when there is none
unsafe fn take_cdr(r: dds_entity_t) -> Option<Vec<u8>> {
    let mut sd: *mut ddsi_serdata = std::ptr::null_mut();
    let mut info: dds_sample_info_t = std::mem::zeroed();
    if dds_takecdr(r, &mut sd, 1, &mut info, DDS_ANY_STATE) <= 0 { return None; }
    let ops = (*sd).ops;
    let n = ((*ops).get_size.unwrap())(sd) as usize;
    let mut buf = vec![0u8; n];
    ((*ops).to_ser.unwrap())(sd, 0, n, buf.as_mut_ptr() as *mut _);
    ddsi_serdata_unref(sd);
    if info.valid_data { Some(buf) } else { Some(Vec::new()) }
}

fn rss_kib() -> u64 {
    std::fs::read_to_string("/proc/self/status").ok()
        .and_then(|s| s.lines().find(|l| l.starts_with("VmRSS:")).and_then(|l| l.split_whitespace().nth(1)?.parse().ok()))
        .unwrap_or(0)
}

fn ack(id: &str, n: i32, src: &rapid::Header) -> Vec<u8> {
    let mut a = rapid::Ack::default();
    a.hdr = src.clone();
    a.hdr.serial = n;
    a.cmd_id = id.into();
    a.status = rapid::AckStatus::AckCompleted;
    a.completed_status = rapid::AckCompletedStatus::AckCompletedOk;
    a.message = format!("{id} #{n}");
    cdr::serialize(&a, cdr::Endianness::Little).unwrap()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mode = args.get(1).map(String::as_str).unwrap_or("");
    let domain: u32 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(65);
    let partition = args.get(3).cloned().unwrap_or_else(|| "K10Red".into());
    let secs: u64 = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(10);
    unsafe {
        let t0 = Instant::now();
        let dp = dds_create_participant(domain, std::ptr::null(), std::ptr::null());
        assert!(dp > 0, "participant: {dp}");
        let pq = qos(Some(&partition), false, 1);
        let publisher = dds_create_publisher(dp, pq, std::ptr::null());
        let subscriber = dds_create_subscriber(dp, pq, std::ptr::null());
        let acks = topic(dp, "rapid_ack", "rapid::Ack");
        let cmds = topic(dp, "rapid_command", "rapid::Command");
        let mut hdr = rapid::Header::default();
        hdr.src_name = "K10Red".into();
        hdr.asset_name = "K10Red".into();
        match mode {
            "ack-writer" => {
                let w = dds_create_writer(publisher, acks, qos(None, true, 1), std::ptr::null());
                for (id, n) in [("a", 1), ("a", 2), ("b", 3), ("a", 4)] {
                    assert_eq!(write_cdr(w, acks, &ack(id, n, &hdr)), 0);
                }
                println!("WROTE 4 acks (a x3, b x1) in {partition} after {:?}; rss {} KiB", t0.elapsed(), rss_kib());
                std::thread::sleep(Duration::from_secs(secs));
            }
            "cmd-reader" | "pong" => {
                let r = dds_create_reader(subscriber, cmds, qos(None, false, 100), std::ptr::null());
                let w = dds_create_writer(publisher, acks, qos(None, true, 100), std::ptr::null()); // as RAPID ack readers ask
                println!("READY");
                let end = Instant::now() + Duration::from_secs(secs);
                while Instant::now() < end {
                    while let Some(bytes) = take_cdr(r) {
                        if bytes.is_empty() { continue; }
                        match cdr::deserialize::<rapid::Command>(&bytes) {
                            Ok(c) if mode == "pong" => { write_cdr(w, acks, &ack(&c.cmd_id, 0, &c.hdr)); }
                            Ok(c) => println!("CMD {} {} {} {:?}", c.cmd_id, c.subsys_name, c.cmd_name, c.arguments),
                            Err(e) => println!("BAD {e}"),
                        }
                    }
                    std::thread::sleep(Duration::from_micros(200));
                }
                println!("rss {} KiB", rss_kib());
            }
            _ => { eprintln!("usage: cyclors_probe ack-writer|cmd-reader|pong DOMAIN [PARTITION] [SECONDS]"); std::process::exit(2); }
        }
        dds_delete(dp);
    }
}
