//! Keys for cyclors' blob topics. The blob type (cyclocut) carries raw CDR and computes no
//! key: every sample of a writer is one instance, so a keep-last history is shared by every
//! key. `make_keyed` gives one blob type per-key instances, as a typed topic has: its serdata
//! operations are replaced by a copy whose hash, key equality and key hash come from the key
//! members the generated codec reads out of the sample (`key` below), and whose untyped form
//! (what Cyclone's instance map keeps) keeps the sample's bytes so its key can be read again.
//! Everything else stays cyclocut's.
use std::os::raw::c_void;
use std::sync::Mutex;

use cyclors::*;

use crate::md5::md5;

/// the types given keys (their sertypes' addresses)
static PATCHED: Mutex<Vec<usize>> = Mutex::new(Vec::new());

/// A type's key: its key members' bytes from a sample's CDR (None: not a sample of the type).
pub type KeyOf = fn(&[u8]) -> Option<Vec<u8>>;

extern "C" {
    // the C library's own: cyclocut frees the payload with free()
    fn malloc(size: usize) -> *mut c_void;
}

/// cyclocut's serdata (cdds_blob.c, struct cdds_ddsi_payload)
#[repr(C)]
struct Payload {
    sd: ddsi_serdata,
    size: usize,
    kind: ddsi_serdata_kind,
    payload: *mut u8,
}

/// The replaced operations first, so a serdata's `ops` pointer leads to the rest.
#[repr(C)]
struct KeyedOps {
    ops: ddsi_serdata_ops,
    orig: ddsi_serdata_ops,
    key: KeyOf,
    /// the key's largest encoding exceeds 16 bytes: its hash is its MD5
    md5: bool,
}

unsafe fn keyed(sd: *const ddsi_serdata) -> &'static KeyedOps {
    // SAFETY: every serdata of a keyed type was made with KeyedOps' ops (make_keyed)
    &*((*sd).ops as *const KeyedOps)
}

unsafe fn key_of(sd: *const ddsi_serdata) -> Vec<u8> {
    let p = sd as *const Payload;
    if (*p).payload.is_null() {
        return Vec::new();
    }
    let bytes = std::slice::from_raw_parts((*p).payload, (*p).size);
    (keyed(sd).key)(bytes).unwrap_or_default()
}

fn fnv(bytes: &[u8]) -> u32 {
    bytes.iter().fold(0x811c_9dc5u32, |h, b| (h ^ *b as u32).wrapping_mul(0x0100_0193))
}

unsafe fn with_hash(tp: *const ddsi_sertype, sd: *mut ddsi_serdata) -> *mut ddsi_serdata {
    if !sd.is_null() {
        (*sd).hash = fnv(&key_of(sd)) ^ (*tp).serdata_basehash;
    }
    sd
}

unsafe extern "C" fn from_ser(
    tp: *const ddsi_sertype,
    kind: ddsi_serdata_kind,
    chain: *const ddsi_rdata,
    size: usize,
) -> *mut ddsi_serdata {
    let ko = &*((*tp).serdata_ops as *const KeyedOps);
    match ko.orig.from_ser {
        Some(f) => with_hash(tp, f(tp, kind, chain, size)),
        None => std::ptr::null_mut(),
    }
}

unsafe extern "C" fn from_ser_iov(
    tp: *const ddsi_sertype,
    kind: ddsi_serdata_kind,
    niov: ddsrt_msg_iovlen_t,
    iov: *const ddsrt_iovec_t,
    size: usize,
) -> *mut ddsi_serdata {
    let ko = &*((*tp).serdata_ops as *const KeyedOps);
    match ko.orig.from_ser_iov {
        Some(f) => with_hash(tp, f(tp, kind, niov, iov, size)),
        None => std::ptr::null_mut(),
    }
}

unsafe extern "C" fn eqkey(a: *const ddsi_serdata, b: *const ddsi_serdata) -> bool {
    key_of(a) == key_of(b)
}

unsafe extern "C" fn to_untyped(sd: *const ddsi_serdata) -> *mut ddsi_serdata {
    let Some(f) = keyed(sd).orig.to_untyped else { return std::ptr::null_mut() };
    let out = f(sd) as *mut Payload;
    if out.is_null() {
        return std::ptr::null_mut();
    }
    // keep the bytes (cyclocut keeps none): the instance map compares keys with them
    let src = sd as *const Payload;
    (*out).payload = std::ptr::null_mut();
    (*out).size = 0;
    if !(*src).payload.is_null() && (*src).size > 0 {
        let copy = malloc((*src).size) as *mut u8;
        if !copy.is_null() {
            std::ptr::copy_nonoverlapping((*src).payload, copy, (*src).size);
            (*out).payload = copy;
            (*out).size = (*src).size;
        }
    }
    out as *mut ddsi_serdata
}

unsafe extern "C" fn get_keyhash(sd: *const ddsi_serdata, buf: *mut ddsi_keyhash, force_md5: bool) {
    let key = key_of(sd);
    let value = if keyed(sd).md5 || force_md5 {
        md5(&key)
    } else {
        let mut v = [0u8; 16];
        let n = key.len().min(16);
        v[..n].copy_from_slice(&key[..n]);
        v
    };
    (*buf).value = value;
}

/// Gives `topic`'s type per-key instances (once per type: the type is shared by every topic
/// of its name in the domain). `key` reads a sample's key members (big-endian CDR from offset
/// 0, the key hash's input); `md5`: the key's largest encoding exceeds 16 bytes.
///
/// # Safety
/// `topic` is a cyclors blob topic, and no sample of its type exists yet.
pub unsafe fn make_keyed(topic: dds_entity_t, key: KeyOf, md5: bool) -> Result<(), String> {
    let mut st: *const ddsi_sertype = std::ptr::null();
    if dds_get_entity_sertype(topic, &mut st) < 0 || st.is_null() {
        return Err("the topic's type".into());
    }
    let mut done = PATCHED.lock().unwrap_or_else(|e| e.into_inner());
    if done.contains(&(st as usize)) {
        return Ok(()); // a second topic of the type
    }
    let orig = *(*st).serdata_ops;
    let mut ops = orig;
    ops.eqkey = Some(eqkey);
    ops.from_ser = Some(from_ser);
    ops.from_ser_iov = Some(from_ser_iov);
    ops.to_untyped = Some(to_untyped);
    ops.get_keyhash = Some(get_keyhash);
    // lives as long as the process: serdatas of the type point to it
    let ko: &'static KeyedOps = Box::leak(Box::new(KeyedOps { ops, orig, key, md5 }));
    (*(st as *mut ddsi_sertype)).serdata_ops = &ko.ops;
    done.push(st as usize);
    Ok(())
}
