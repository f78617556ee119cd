//! The setpoint streams' topics (docs/realtime.md "In the Rust runtime"): a Cyclone type of
//! their own whose serialized samples come from a small free list, so that a stream's writes
//! and receipts allocate nothing once the first few sized their buffers.
//!
//! cyclors' blob type (cyclocut's cdds_blob.c) mallocs a serialized sample, its struct and its
//! bytes, for every write (`from_ser_iov`) and every receipt (`from_ser`), and frees both when
//! the last reference goes. Here every topic made by [`topic`] gets a type (a `ddsi_sertype`
//! with the same type name, keyless semantics and CDR bytes as the blob type's, so nothing
//! changes on the wire) whose serdatas are [`Pooled`]: made from a free list of at most
//! [`SLOTS`] per topic, their byte buffers keeping their capacity (grown only when a sample is
//! larger than any before), given back to the list when Cyclone's last reference goes
//! (`ddsi_serdata_unref` calls `free`), and freed as before once the list is full or the
//! type is gone.
//!
//! The serdata contract (Cyclone 0.11's ddsi_serdata.h): `from_*` return a serdata with one
//! reference (`ddsi_serdata_init`); `to_ser_ref` takes a reference and `to_ser_unref` drops it;
//! `free` is called once, by the unref that drops the count to 0, and nothing of the serdata is
//! used after it. A serdata back on the free list has no reference; taken again it is
//! initialised afresh.
use std::ffi::{c_void, CStr};
use std::ptr::{null, null_mut};
use std::sync::atomic::{AtomicBool, AtomicPtr, AtomicU32, AtomicU64, AtomicUsize, Ordering};

use cyclors::*;

/// Serialized samples kept per topic (a keep-last-1 stream has 2 or 3 alive at once: the
/// reader's history, the one taken, the one arriving).
pub const SLOTS: usize = 8;

extern "C" {
    // the C library's own (Cyclone's and cyclocut's memory comes from them too)
    fn malloc(size: usize) -> *mut c_void;
    fn realloc(p: *mut c_void, size: usize) -> *mut c_void;
    fn free(p: *mut c_void);
}

/// A serialized sample: cyclocut's `struct cdds_ddsi_payload` (the same first fields, so code
/// reading a blob serdata reads this one alike), then the buffer's capacity and its pool.
#[repr(C)]
pub(crate) struct Pooled {
    sd: ddsi_serdata,
    size: usize,
    kind: ddsi_serdata_kind,
    payload: *mut u8,
    cap: usize,
    /// null for an untyped serdata (Cyclone's instance map keeps those): freed, never kept
    pool: *const Pool,
}

/// A topic's free list and its counts.
pub struct Pool {
    slots: [AtomicPtr<Pooled>; SLOTS],
    /// the capacity every buffer grows to: the largest sample's, rounded up to 4
    largest: AtomicUsize,
    /// its type is gone: serdatas coming back are freed
    closed: AtomicBool,
    made: AtomicU64,
    reused: AtomicU64,
    kept: AtomicU64,
    dropped: AtomicU64,
    grown: AtomicU64,
}

/// A pool's counts: serdatas made (malloc), taken from the free list, given back to it, freed
/// on their way back (the list full, or the type gone), buffers grown; `out` = made + reused -
/// kept - dropped, the serdatas alive now.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PoolStats {
    pub made: u64,
    pub reused: u64,
    pub kept: u64,
    pub dropped: u64,
    pub grown: u64,
    pub out: u64,
    pub largest: usize,
}

impl Pool {
    fn new() -> Pool {
        Pool {
            slots: [const { AtomicPtr::new(null_mut()) }; SLOTS],
            largest: AtomicUsize::new(0),
            closed: AtomicBool::new(false),
            made: AtomicU64::new(0),
            reused: AtomicU64::new(0),
            kept: AtomicU64::new(0),
            dropped: AtomicU64::new(0),
            grown: AtomicU64::new(0),
        }
    }

    pub fn stats(&self) -> PoolStats {
        let (made, reused) = (self.made.load(Ordering::Relaxed), self.reused.load(Ordering::Relaxed));
        let (kept, dropped) = (self.kept.load(Ordering::Relaxed), self.dropped.load(Ordering::Relaxed));
        PoolStats { made, reused, kept, dropped, grown: self.grown.load(Ordering::Relaxed),
                    out: (made + reused).saturating_sub(kept + dropped), largest: self.largest.load(Ordering::Relaxed) }
    }

    /// A serdata from the list (each slot owns what it holds: taking is a swap, so two takers
    /// never get the same one).
    fn take(&self) -> Option<*mut Pooled> {
        for s in &self.slots {
            if !s.load(Ordering::Relaxed).is_null() {
                let p = s.swap(null_mut(), Ordering::SeqCst);
                if !p.is_null() {
                    return Some(p);
                }
            }
        }
        None
    }

    /// Keeps `p` on the list; false: the list is full or closed, the caller frees it.
    fn give(&self, p: *mut Pooled) -> bool {
        if self.closed.load(Ordering::SeqCst) {
            return false;
        }
        for s in &self.slots {
            if s.compare_exchange(null_mut(), p, Ordering::SeqCst, Ordering::Relaxed).is_ok() {
                // closed meanwhile: take it back unless close() already freed it (one of the
                // two sees it: the close is ordered before its drain, the put before this load)
                if self.closed.load(Ordering::SeqCst) && s.compare_exchange(p, null_mut(), Ordering::SeqCst, Ordering::Relaxed).is_ok() {
                    return false;
                }
                return true;
            }
        }
        false
    }

    /// The type is gone: what the list holds is freed, and so is what comes back later.
    fn close(&self) {
        self.closed.store(true, Ordering::SeqCst);
        for s in &self.slots {
            let p = s.swap(null_mut(), Ordering::SeqCst);
            if !p.is_null() {
                // SAFETY: the slot owned p (a serdata with no reference left); nothing else has it
                unsafe { release(p) };
            }
        }
    }
}

/// Frees a serdata and its buffer (both from the C library's malloc).
///
/// # Safety
/// `p` is a Pooled nothing refers to any more.
unsafe fn release(p: *mut Pooled) {
    // SAFETY: as the function's contract; free(NULL) is a no-op
    unsafe {
        free((*p).payload as *mut c_void);
        free(p as *mut c_void);
    }
}

/// A stream topic's type: Cyclone's sertype, then its pool (leaked: a serdata that outlived
/// its type, which Cyclone does not do, would still find it).
#[repr(C)]
struct StreamType {
    st: ddsi_sertype,
    pool: &'static Pool,
}

unsafe fn pool_of(tp: *const ddsi_sertype) -> &'static Pool {
    // SAFETY: every sertype with these serdata ops is a StreamType (topic() makes them)
    unsafe { (*(tp as *const StreamType)).pool }
}

fn align4(n: usize) -> usize {
    n.saturating_add(3) & !3
}

/// A serdata of `tp` with room for `size` bytes (plus the padding to 4 Cyclone may read), one
/// reference, `size` set; its bytes still to be written. Null when malloc fails.
unsafe fn make(tp: *const ddsi_sertype, kind: ddsi_serdata_kind, size: usize) -> *mut Pooled {
    // SAFETY: tp is a StreamType (pool_of); p is either the list's (no reference left: ours
    // alone) or a fresh allocation of a Pooled's size, every field written before use
    unsafe {
        let pool = pool_of(tp);
        let p = match pool.take() {
            Some(p) => {
                pool.reused.fetch_add(1, Ordering::Relaxed);
                p
            }
            None => {
                let p = malloc(std::mem::size_of::<Pooled>()) as *mut Pooled;
                if p.is_null() {
                    return null_mut();
                }
                std::ptr::addr_of_mut!((*p).payload).write(null_mut());
                std::ptr::addr_of_mut!((*p).cap).write(0);
                std::ptr::addr_of_mut!((*p).pool).write(pool);
                pool.made.fetch_add(1, Ordering::Relaxed);
                p
            }
        };
        let need = align4(size).max(4);
        if (*p).cap < need {
            let want = need.max(pool.largest.load(Ordering::Relaxed));
            let grown = realloc((*p).payload as *mut c_void, want) as *mut u8;
            if grown.is_null() {
                ddsi_serdata_init(&mut (*p).sd, tp, kind);
                (*p).size = 0;
                free_serdata(&mut (*p).sd); // back to the list, buffer as it was
                return null_mut();
            }
            (*p).payload = grown;
            (*p).cap = want;
            pool.largest.fetch_max(want, Ordering::Relaxed);
            pool.grown.fetch_add(1, Ordering::Relaxed);
        }
        ddsi_serdata_init(&mut (*p).sd, tp, kind);
        (*p).size = size;
        (*p).kind = kind;
        // the padding up to 4 goes out on the wire: never an older sample's bytes
        std::ptr::write_bytes((*p).payload.add(size), 0, align4(size) - size);
        p
    }
}

// ---- the serdata operations -----------------------------------------------------------------

unsafe extern "C" fn from_ser_iov(
    tp: *const ddsi_sertype,
    kind: ddsi_serdata_kind,
    niov: ddsrt_msg_iovlen_t,
    iov: *const ddsrt_iovec_t,
    size: usize,
) -> *mut ddsi_serdata {
    // SAFETY: Cyclone gives niov iovecs whose lengths add up to size (the writer's bytes);
    // make() gave room for size bytes
    unsafe {
        let p = make(tp, kind, size);
        if p.is_null() {
            return null_mut();
        }
        if kind != ddsi_serdata_kind_SDK_EMPTY {
            let mut off = 0usize;
            for v in std::slice::from_raw_parts(iov, niov) {
                let n = v.iov_len.min(size - off);
                std::ptr::copy_nonoverlapping(v.iov_base as *const u8, (*p).payload.add(off), n);
                off += n;
            }
        }
        &mut (*p).sd
    }
}

/// Cyclone's received message (ddsi_radmin.h `struct ddsi_rmsg`), only for its size: a
/// message's bytes follow it (DDSI_RMSG_PAYLOAD).
#[repr(C)]
struct Rmsg {
    refcount: u32,
    lastchunk: *mut c_void,
    trace: bool,
    chunk: RmsgChunk,
}

/// `struct ddsi_rmsg_chunk`: rbuf, next, then a union of uint32_t, int64_t, double and a pointer.
#[repr(C)]
struct RmsgChunk {
    rbuf: *mut c_void,
    next: *mut c_void,
    u: i64,
}

// Cyclone asserts sizeof (struct ddsi_rmsg) == offsetof (chunk) + sizeof (chunk): 48 here
#[cfg(target_pointer_width = "64")]
const _: () = assert!(std::mem::size_of::<Rmsg>() == 48);

/// A fragment of a received sample (ddsi_radmin.h `struct ddsi_rdata`, its leading fields:
/// a debug build of Cyclone has one more after them).
#[repr(C)]
struct Rdata {
    rmsg: *const Rmsg,
    nextfrag: *const Rdata,
    min: u32,
    maxp1: u32,
    submsg_zoff: u16,
    payload_zoff: u16,
}

/// Copies the sample's bytes [0, size) out of a fragment chain into `out`; false when the
/// chain leaves a gap. Fragments may overlap (ddsi_serdata.h): each adds what lies past the
/// bytes already copied.
///
/// # Safety
/// `chain` is a fragment chain as Cyclone hands it to from_ser; `out` has room for size bytes.
unsafe fn copy_fragments(mut chain: *const Rdata, size: usize, out: *mut u8) -> bool {
    let mut off = 0usize;
    // SAFETY: as the function's contract: each fragment's bytes [min, maxp1) lie at its
    // message's payload + payload_zoff
    unsafe {
        while !chain.is_null() && off < size {
            let f = &*chain;
            let (min, maxp1) = (f.min as usize, (f.maxp1 as usize).min(size));
            if min > off {
                return false;
            }
            if maxp1 > off {
                let bytes = (f.rmsg as *const u8).add(std::mem::size_of::<Rmsg>() + f.payload_zoff as usize);
                std::ptr::copy_nonoverlapping(bytes.add(off - min), out.add(off), maxp1 - off);
                off = maxp1;
            }
            chain = f.nextfrag;
        }
    }
    off >= size
}

unsafe extern "C" fn from_ser(
    tp: *const ddsi_sertype,
    kind: ddsi_serdata_kind,
    chain: *const ddsi_rdata,
    size: usize,
) -> *mut ddsi_serdata {
    // SAFETY: make() gave room for size bytes; the chain is Cyclone's (copy_fragments); a
    // serdata that could not be filled goes back with its one reference (free)
    unsafe {
        let p = make(tp, kind, size);
        if p.is_null() {
            return null_mut();
        }
        if kind != ddsi_serdata_kind_SDK_EMPTY && !copy_fragments(chain as *const Rdata, size, (*p).payload) {
            free_serdata(&mut (*p).sd);
            return null_mut(); // Cyclone drops a sample it cannot make
        }
        &mut (*p).sd
    }
}

unsafe extern "C" fn from_keyhash(_: *const ddsi_sertype, _: *const ddsi_keyhash) -> *mut ddsi_serdata {
    null_mut() // no key to make one from (as the blob type)
}

unsafe extern "C" fn free_serdata(sd: *mut ddsi_serdata) {
    let p = sd as *mut Pooled;
    // SAFETY: called once per serdata, by the unref that dropped its count to 0 (or by make
    // and from_ser for one never handed out): nothing refers to it any more
    unsafe {
        let pool = (*p).pool;
        if !pool.is_null() {
            if (*pool).give(p) {
                (*pool).kept.fetch_add(1, Ordering::Relaxed);
                return;
            }
            (*pool).dropped.fetch_add(1, Ordering::Relaxed);
        }
        release(p);
    }
}

unsafe extern "C" fn get_size(sd: *const ddsi_serdata) -> u32 {
    // SAFETY: every serdata with these ops is a Pooled
    unsafe { (*(sd as *const Pooled)).size as u32 }
}

unsafe extern "C" fn eqkey(_: *const ddsi_serdata, _: *const ddsi_serdata) -> bool {
    true // no key: one instance per writer (as the blob type)
}

unsafe extern "C" fn get_keyhash(_: *const ddsi_serdata, buf: *mut ddsi_keyhash, _: bool) {
    // SAFETY: Cyclone's 16-byte key hash to fill
    unsafe { (*buf).value = [0; 16] }
}

unsafe extern "C" fn to_ser(sd: *const ddsi_serdata, off: usize, sz: usize, buf: *mut c_void) {
    // SAFETY: off + sz <= align4(size) (ddsi_serdata.h), which the buffer holds (make)
    unsafe {
        let p = sd as *const Pooled;
        let n = sz.min(align4((*p).size).saturating_sub(off));
        if n > 0 {
            std::ptr::copy_nonoverlapping((*p).payload.add(off), buf as *mut u8, n);
        }
    }
}

unsafe extern "C" fn to_ser_ref(sd: *const ddsi_serdata, off: usize, sz: usize, iov: *mut ddsrt_iovec_t) -> *mut ddsi_serdata {
    // SAFETY: as to_ser; the reference taken keeps the bytes until to_ser_unref. The count is
    // Cyclone's ddsrt_atomic_uint32_t, a plain 32-bit atomic (ddsi_serdata_ref increments it)
    unsafe {
        let p = sd as *const Pooled;
        (*iov).iov_base = (*p).payload.add(off) as *mut c_void;
        (*iov).iov_len = sz as _;
        AtomicU32::from_ptr(std::ptr::addr_of!((*sd).refc.v) as *mut u32).fetch_add(1, Ordering::Relaxed);
        sd as *mut ddsi_serdata
    }
}

unsafe extern "C" fn to_ser_unref(sd: *mut ddsi_serdata, _: *const ddsrt_iovec_t) {
    // SAFETY: drops the reference to_ser_ref took
    unsafe { ddsi_serdata_unref(sd) }
}

unsafe extern "C" fn to_untyped(sd: *const ddsi_serdata) -> *mut ddsi_serdata {
    // SAFETY: a fresh allocation, every field written; untyped (no type, no bytes: the key is
    // empty), outside any pool
    unsafe {
        let p = malloc(std::mem::size_of::<Pooled>()) as *mut Pooled;
        if p.is_null() {
            return null_mut();
        }
        ddsi_serdata_init(&mut (*p).sd, (*sd).type_, ddsi_serdata_kind_SDK_KEY);
        (*p).sd.type_ = null();
        (*p).sd.hash = (*sd).hash;
        (*p).size = 0;
        (*p).kind = ddsi_serdata_kind_SDK_KEY;
        (*p).payload = null_mut();
        (*p).cap = 0;
        (*p).pool = null();
        &mut (*p).sd
    }
}

/// Holds a C operations table (raw pointers in it make it neither Send nor Sync by itself).
struct Table<T>(T);
// SAFETY: the tables are never written after their constant initialisation
unsafe impl<T> Sync for Table<T> {}

static SERDATA_OPS: Table<ddsi_serdata_ops> = Table(ddsi_serdata_ops {
    eqkey: Some(eqkey),
    get_size: Some(get_size),
    from_ser: Some(from_ser),
    from_ser_iov: Some(from_ser_iov),
    from_keyhash: Some(from_keyhash),
    from_sample: None, // the type has no sample form (nor had the blob type)
    to_ser: Some(to_ser),
    to_ser_ref: Some(to_ser_ref),
    to_ser_unref: Some(to_ser_unref),
    to_sample: None,
    to_untyped: Some(to_untyped),
    untyped_to_sample: None,
    free: Some(free_serdata),
    print: None,
    get_keyhash: Some(get_keyhash),
    from_loaned_sample: None,
    from_psmx: None, // no PSMX (shared memory) in rapid_dds
});

// ---- the sertype operations -----------------------------------------------------------------

unsafe extern "C" fn free_type(tp: *mut ddsi_sertype) {
    // SAFETY: Cyclone frees a sertype once, after its last reference; it was a Box (topic())
    unsafe {
        let mut t = Box::from_raw(tp as *mut StreamType);
        t.pool.close();
        ddsi_sertype_fini(&mut t.st);
    }
}

unsafe extern "C" fn zero_samples(_: *const ddsi_sertype, _: *mut c_void, _: usize) {}

unsafe extern "C" fn realloc_samples(_: *mut *mut c_void, _: *const ddsi_sertype, _: *mut c_void, _: usize, _: usize) {
    // only dds_read/dds_take into samples and loans come here; rapid_dds takes serdatas
    // (dds_takecdr) and has no sample form to give (the blob type aborts alike)
    std::process::abort()
}

unsafe extern "C" fn free_samples(_: *const ddsi_sertype, _: *mut *mut c_void, _: usize, _: dds_free_op_t) {}

unsafe extern "C" fn equal(a: *const ddsi_sertype, b: *const ddsi_sertype) -> bool {
    a == b // a type per topic: never merged with another topic's (each its own pool)
}

unsafe extern "C" fn hash(_: *const ddsi_sertype) -> u32 {
    0 // Cyclone hashes the type name already
}

static SERTYPE_OPS: Table<ddsi_sertype_ops> = Table(ddsi_sertype_ops {
    version: Some(ddsi_sertype_v0),
    arg: null_mut(),
    free: Some(free_type),
    zero_samples: Some(zero_samples),
    realloc_samples: Some(realloc_samples),
    free_samples: Some(free_samples),
    equal: Some(equal),
    hash: Some(hash),
    type_id: None,
    type_map: None,
    type_info: None,
    derive_sertype: None,
    get_serialized_size: None,
    serialize_into: None,
});

/// A type of its own for one stream topic, not yet handed to Cyclone.
fn new_type(type_name: &CStr) -> *mut StreamType {
    let pool: &'static Pool = Box::leak(Box::new(Pool::new()));
    // SAFETY: a zeroed sertype is plain data; ddsi_sertype_init_flags fills every field
    // (flags 0: a keyed topic kind, as cdds_create_blob_topic(.., false) made)
    unsafe {
        let t = Box::into_raw(Box::new(StreamType { st: std::mem::zeroed(), pool }));
        ddsi_sertype_init_flags(&mut (*t).st, type_name.as_ptr(), &SERTYPE_OPS.0, &SERDATA_OPS.0, 0);
        t
    }
}

/// A topic as `cdds_create_blob_topic(dp, name, type_name, false)` makes it (the same type name
/// and CDR bytes on the wire), with a type of its own whose serialized samples come from a
/// free list: the topic and its pool. Err: Cyclone's return code.
pub fn topic(dp: dds_entity_t, name: &CStr, type_name: &CStr) -> Result<(dds_entity_t, &'static Pool), dds_return_t> {
    let t = new_type(type_name);
    // SAFETY: t is a fresh sertype with its one reference; on success Cyclone owns it (and
    // frees it through free_type), on failure it is still ours and its unref frees it
    unsafe {
        let pool = (*t).pool;
        let mut st = t as *mut ddsi_sertype;
        let topic = dds_create_topic_sertype(dp, name.as_ptr(), &mut st, null(), null(), null());
        if topic < 0 {
            ddsi_sertype_unref(t as *mut ddsi_sertype);
            return Err(topic);
        }
        Ok((topic, pool))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(tp: *const ddsi_sertype, bytes: &[u8]) -> *mut ddsi_serdata {
        let iov = [ddsrt_iovec_t { iov_base: bytes.as_ptr() as *mut c_void, iov_len: bytes.len() as _ }];
        // SAFETY: one iovec of bytes.len() bytes
        unsafe { from_ser_iov(tp, ddsi_serdata_kind_SDK_DATA, 1, iov.as_ptr(), bytes.len()) }
    }

    fn bytes_of(sd: *mut ddsi_serdata) -> Vec<u8> {
        // SAFETY: a live serdata of the pooled type; to_ser writes get_size bytes
        unsafe {
            let n = get_size(sd) as usize;
            let mut out = vec![0u8; n];
            to_ser(sd, 0, n, out.as_mut_ptr() as *mut c_void);
            out
        }
    }

    struct Type(*mut StreamType);

    impl Type {
        fn new() -> Type {
            Type(new_type(c"rapid::JointSample"))
        }
        fn tp(&self) -> *const ddsi_sertype {
            self.0 as *const ddsi_sertype
        }
        fn pool(&self) -> &'static Pool {
            // SAFETY: alive until drop
            unsafe { (*self.0).pool }
        }
    }

    impl Drop for Type {
        fn drop(&mut self) {
            // SAFETY: the test's own type, never registered: its last reference frees it
            unsafe { ddsi_sertype_unref(self.0 as *mut ddsi_sertype) }
        }
    }

    fn unref(sd: *mut ddsi_serdata) {
        // SAFETY: a serdata the test holds one reference to
        unsafe { ddsi_serdata_unref(sd) }
    }

    #[test]
    fn a_stream_of_samples_reuses_one_serdata_and_its_buffer() {
        let t = Type::new();
        let sample: Vec<u8> = (0..=255u8).cycle().take(781).collect();
        let mut first = null_mut();
        for i in 0..100 {
            let sd = write(t.tp(), &sample);
            if i == 0 {
                first = sd;
            }
            assert_eq!(sd, first); // the same serdata every time
            assert_eq!(bytes_of(sd), sample);
            // SAFETY: a live serdata; a fresh one has one reference and the pooled ops
            unsafe {
                assert_eq!((*sd).refc.v, 1);
                assert!(std::ptr::eq((*sd).ops, &SERDATA_OPS.0));
                assert_eq!((*sd).type_, t.tp());
            }
            unref(sd);
        }
        let s = t.pool().stats();
        assert_eq!((s.made, s.reused, s.kept, s.dropped, s.grown, s.out), (1, 99, 100, 0, 1, 0));
        assert_eq!(s.largest, 784); // rounded up to 4
    }

    #[test]
    fn buffers_grow_only_past_the_largest_sample_and_pad_with_zeros() {
        let t = Type::new();
        unref(write(t.tp(), &[7u8; 100]));
        let sd = write(t.tp(), &[1u8; 10]); // smaller: no growth, the padding zeroed
        // SAFETY: a live Pooled
        unsafe {
            assert_eq!(((*(sd as *const Pooled)).cap, get_size(sd)), (100, 10));
            let mut padded = [9u8; 12];
            to_ser(sd, 0, 12, padded.as_mut_ptr() as *mut c_void);
            assert_eq!(padded, [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0]);
        }
        unref(sd);
        unref(write(t.tp(), &[2u8; 201]));
        let s = t.pool().stats();
        assert_eq!((s.made, s.grown, s.largest), (1, 2, 204));
    }

    #[test]
    fn the_free_list_is_bounded_and_held_serdatas_are_counted_out() {
        let t = Type::new();
        let held: Vec<_> = (0..SLOTS + 3).map(|i| write(t.tp(), &[i as u8; 64])).collect();
        assert_eq!(t.pool().stats().out, (SLOTS + 3) as u64);
        for (i, sd) in held.iter().enumerate() {
            assert_eq!(bytes_of(*sd), vec![i as u8; 64]); // each its own bytes
        }
        for sd in held {
            unref(sd);
        }
        let s = t.pool().stats();
        assert_eq!((s.made, s.kept, s.dropped, s.out), ((SLOTS + 3) as u64, SLOTS as u64, 3, 0));
        let again: Vec<_> = (0..SLOTS).map(|_| write(t.tp(), &[0u8; 64])).collect();
        assert_eq!(t.pool().stats().made, (SLOTS + 3) as u64); // all from the list
        again.into_iter().for_each(unref);
    }

    #[test]
    fn a_reference_from_to_ser_ref_keeps_the_serdata_off_the_list_until_unref() {
        let t = Type::new();
        let sd = write(t.tp(), b"\x00\x01\x00\x00abcd");
        let mut iov = ddsrt_iovec_t { iov_base: null_mut(), iov_len: 0 };
        // SAFETY: a live serdata; the reference taken is dropped below
        let r = unsafe { to_ser_ref(sd, 4, 4, &mut iov) };
        assert_eq!(r, sd);
        unref(sd); // the writer's reference gone, the transmit path's still held
        assert_eq!(t.pool().stats().out, 1);
        // SAFETY: iov points into the serdata the reference keeps
        assert_eq!(unsafe { std::slice::from_raw_parts(iov.iov_base as *const u8, iov.iov_len as usize) }, b"abcd");
        // SAFETY: the reference to_ser_ref took
        unsafe { to_ser_unref(r, &iov) };
        assert_eq!(t.pool().stats().out, 0);
    }

    #[test]
    fn untyped_serdatas_and_those_outliving_their_type_are_freed_not_kept() {
        let t = Type::new();
        let sd = write(t.tp(), &[3u8; 16]);
        // SAFETY: a live serdata
        let u = unsafe { to_untyped(sd) };
        // SAFETY: the untyped one just made
        unsafe { assert!((*u).type_.is_null() && get_size(u) == 0 && std::ptr::eq((*u).ops, &SERDATA_OPS.0)) };
        unref(u);
        let pool = t.pool();
        assert_eq!(pool.stats().kept, 0);
        drop(t); // the type freed while sd is alive: the list closed
        unref(sd);
        let s = pool.stats();
        assert_eq!((s.kept, s.dropped, s.out), (0, 1, 0));
    }

    #[test]
    fn received_fragments_are_joined_overlapping_or_not_and_a_gap_is_refused() {
        // one message: the Rmsg header, then 40 bytes of packet; payload at offset 8 in it
        let mut msg = vec![0u64; (std::mem::size_of::<Rmsg>() + 48) / 8];
        let base = msg.as_mut_ptr() as *mut u8;
        let sample: Vec<u8> = (100..130u8).collect();
        // SAFETY: within msg
        unsafe { std::ptr::copy_nonoverlapping(sample.as_ptr(), base.add(std::mem::size_of::<Rmsg>() + 8), 30) };
        let rmsg = base as *const Rmsg;
        // fragment k holds the sample's bytes [min, maxp1), at payload_zoff 8 + min
        let frag = |min: u32, maxp1: u32, next: *const Rdata| Rdata { rmsg, nextfrag: next, min, maxp1, submsg_zoff: 0, payload_zoff: 8 + min as u16 };
        let c = frag(20, 30, null());
        let b = frag(8, 24, &c); // overlaps c
        let a = frag(0, 12, &b); // overlaps b
        let t = Type::new();
        // SAFETY: a chain as Cyclone's, into a fresh serdata
        let sd = unsafe { from_ser(t.tp(), ddsi_serdata_kind_SDK_DATA, &a as *const Rdata as *const ddsi_rdata, 30) };
        assert!(!sd.is_null());
        assert_eq!(bytes_of(sd), sample);
        unref(sd);
        let gap_end = frag(20, 30, null());
        let gap = frag(0, 12, &gap_end);
        // SAFETY: as above
        let sd = unsafe { from_ser(t.tp(), ddsi_serdata_kind_SDK_DATA, &gap as *const Rdata as *const ddsi_rdata, 30) };
        assert!(sd.is_null());
        assert_eq!(t.pool().stats().out, 0); // the refused one went back
    }
}
