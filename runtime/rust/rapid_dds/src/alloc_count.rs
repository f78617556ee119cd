//! Heap allocations counted per thread, for the setpoint bench only (bench/rust_setpoint.py;
//! feature `alloc-count`, off in every other build). Two counters:
//!
//! - [`rust_allocs`]: Rust's own allocations (the codec, the runtime, the callback), through
//!   [`Counting`], which the bench's program installs with `#[global_allocator]`;
//! - [`all_allocs`]: every malloc of the thread, Cyclone DDS's C library included: malloc and
//!   friends defined here take the place of glibc's for the whole program (as the C++ bench's
//!   bench/setpoint/alloc_count.cpp), each counts, then calls glibc's own. Rust's allocations
//!   reach malloc too, so this count includes the first;
//! - [`process_allocs`]: every malloc of every thread (Cyclone's own threads included: its
//!   receive, event and discovery threads), to see what the per-thread counts miss.
//!
//! The per-thread counters are thread-locals without destructors (plain TLS: reading or
//! bumping one never allocates); the process's is one atomic.
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::ffi::c_void;
use std::sync::atomic::{AtomicU64, Ordering};

thread_local! {
    static RUST: Cell<u64> = const { Cell::new(0) };
    static ALL: Cell<u64> = const { Cell::new(0) };
}

static PROCESS: AtomicU64 = AtomicU64::new(0);

fn bump(c: &'static std::thread::LocalKey<Cell<u64>>) {
    let _ = c.try_with(|c| c.set(c.get() + 1));
}

/// A malloc of any kind: this thread's count and the process's.
fn bump_all() {
    bump(&ALL);
    PROCESS.fetch_add(1, Ordering::Relaxed);
}

/// Rust allocations on this thread so far (with `#[global_allocator] static A: Counting`).
pub fn rust_allocs() -> u64 {
    RUST.try_with(|c| c.get()).unwrap_or(0)
}

/// Every malloc, calloc, realloc and aligned allocation on this thread so far.
pub fn all_allocs() -> u64 {
    ALL.try_with(|c| c.get()).unwrap_or(0)
}

/// Every malloc, calloc, realloc and aligned allocation of the process so far (all threads).
pub fn process_allocs() -> u64 {
    PROCESS.load(Ordering::Relaxed)
}

/// The system allocator, counting each allocation and reallocation on the calling thread.
pub struct Counting;

// SAFETY: forwards every call to System unchanged
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        bump(&RUST);
        // SAFETY: the caller's layout, as GlobalAlloc::alloc requires
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        bump(&RUST);
        // SAFETY: as alloc
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        bump(&RUST);
        // SAFETY: ptr came from this allocator (System underneath) with layout
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as realloc
        unsafe { System.dealloc(ptr, layout) }
    }
}

extern "C" {
    fn __libc_malloc(n: usize) -> *mut c_void;
    fn __libc_calloc(n: usize, size: usize) -> *mut c_void;
    fn __libc_realloc(p: *mut c_void, n: usize) -> *mut c_void;
    fn __libc_memalign(align: usize, n: usize) -> *mut c_void;
}

/// # Safety
/// malloc's contract (glibc's own does the work).
#[no_mangle]
pub unsafe extern "C" fn malloc(n: usize) -> *mut c_void {
    bump_all();
    // SAFETY: glibc's own malloc, the caller's contract unchanged
    unsafe { __libc_malloc(n) }
}

/// # Safety
/// calloc's contract.
#[no_mangle]
pub unsafe extern "C" fn calloc(n: usize, size: usize) -> *mut c_void {
    bump_all();
    // SAFETY: as malloc
    unsafe { __libc_calloc(n, size) }
}

/// # Safety
/// realloc's contract.
#[no_mangle]
pub unsafe extern "C" fn realloc(p: *mut c_void, n: usize) -> *mut c_void {
    bump_all();
    // SAFETY: p came from this malloc family (glibc's underneath)
    unsafe { __libc_realloc(p, n) }
}

/// # Safety
/// memalign's contract.
#[no_mangle]
pub unsafe extern "C" fn memalign(align: usize, n: usize) -> *mut c_void {
    bump_all();
    // SAFETY: as malloc
    unsafe { __libc_memalign(align, n) }
}

/// # Safety
/// aligned_alloc's contract.
#[no_mangle]
pub unsafe extern "C" fn aligned_alloc(align: usize, n: usize) -> *mut c_void {
    bump_all();
    // SAFETY: as malloc
    unsafe { __libc_memalign(align, n) }
}

/// # Safety
/// posix_memalign's contract.
#[no_mangle]
pub unsafe extern "C" fn posix_memalign(out: *mut *mut c_void, align: usize, n: usize) -> i32 {
    bump_all();
    // SAFETY: as malloc
    let p = unsafe { __libc_memalign(align, n) };
    if p.is_null() {
        return 12; // ENOMEM
    }
    // SAFETY: out is the caller's pointer to fill (posix_memalign's contract)
    unsafe { *out = p };
    0
}
