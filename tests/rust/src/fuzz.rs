//! A bounded fuzz loop: every truncation of every golden vector, bytes flipped, counts
//! raised, and random bytes go to the decoder of its type. A panic fails the run (exit
//! 101); so does an allocation the input cannot justify (a counting allocator keeps the
//! peak of live heap bytes during each decode). The body of each input also goes to the
//! type's key transcoder (`transcode_key`), under the same rules, and to `deserialize_into`
//! over one value per type kept across all its inputs (whatever the last left in it): the
//! same outcome as `deserialize` (the same error, or a value encoding to the same bytes),
//! under the same allocation rule. Prints `seeds N decoded N refused N over N differ N`.

mod common;

use gen::cdr::{deserialize, deserialize_into, serialize, transcode_key, Cdr, Endianness};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

struct Counting;
static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let now = LIVE.fetch_add(layout.size(), Relaxed) + layout.size();
        PEAK.fetch_max(now, Relaxed);
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size(), Relaxed);
        System.dealloc(ptr, layout)
    }
}

#[global_allocator]
static ALLOC: Counting = Counting;

/// Heap a decode may use: in proportion to the input, plus a constant for error text.
fn allowed(len: usize) -> usize {
    64 * len + 64 * 1024
}

struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

struct Fuzz<'a> {
    vectors: &'a [common::Vector],
    rounds: usize,
    rng: Rng,
    seeds: usize,
    decoded: usize,
    refused: usize,
    over: Vec<String>,
    differ: Vec<String>,
}

impl Fuzz<'_> {
    fn feed<T: Cdr>(&mut self, what: &str, data: &[u8], kept: &mut T) -> bool {
        let base = LIVE.load(Relaxed);
        PEAK.store(base, Relaxed);
        let fresh = deserialize::<T>(data);
        let ok = fresh.is_ok();
        let body = data.get(4..).unwrap_or_default();
        let _ = transcode_key::<T>(body, Endianness::Little, Endianness::Big);
        let _ = transcode_key::<T>(body, Endianness::Big, Endianness::Little);
        let used = PEAK.load(Relaxed) - base;
        if used > allowed(data.len()) {
            self.over.push(format!("{what}: {used} bytes for {} input bytes", data.len()));
        }
        // into the kept value: its heap (of earlier inputs) is already live, what it adds is counted
        let base = LIVE.load(Relaxed);
        PEAK.store(base, Relaxed);
        let into = deserialize_into(data, kept);
        let used = PEAK.load(Relaxed) - base;
        if used > allowed(data.len()) {
            self.over.push(format!("{what} (into): {used} bytes for {} input bytes", data.len()));
        }
        // compared by encoding (a NaN is not equal to itself)
        let same = match (&fresh, &into) {
            (Ok(f), Ok(())) => serialize(f, Endianness::Little).ok() == serialize(kept, Endianness::Little).ok(),
            (Err(a), Err(b)) => a == b,
            _ => false,
        };
        if !same {
            self.differ.push(format!("{what}: deserialize {:?}, deserialize_into {into:?}", fresh.as_ref().err()));
        }
        if ok {
            self.decoded += 1;
        } else {
            self.refused += 1;
        }
        ok
    }
}

impl gen::TypeVisitor for Fuzz<'_> {
    fn visit<T: gen::TopicType>(&mut self) {
        let vectors = self.vectors;
        let mut kept = T::default();
        for v in vectors.iter().filter(|v| v.type_name == T::TYPE_NAME) {
            for seed in [&v.le, &v.be] {
                self.seeds += 1;
                assert!(self.feed::<T>(&v.id, seed, &mut kept), "{}: the vector itself is refused", v.id);
                for cut in 0..seed.len() {
                    // a value cut short is always refused (at most 3 bytes of padding may follow one)
                    assert!(!self.feed::<T>(&v.id, &seed[..cut], &mut kept), "{}: accepted cut at {cut}", v.id);
                }
                for _ in 0..self.rounds {
                    let mut m = seed.clone();
                    match self.rng.below(3) {
                        0 => {
                            let i = 4 + self.rng.below(m.len() - 4);
                            if let Some(b) = m.get_mut(i) {
                                *b = self.rng.next() as u8;
                            }
                        }
                        1 => {
                            // a 4-byte length or count raised to something large
                            let i = 4 + self.rng.below(m.len().saturating_sub(7).max(1)) / 4 * 4;
                            let big = [0xff, 0x7f, (self.rng.next() as u8) | 1, 0x10][self.rng.below(4)];
                            for b in m.iter_mut().skip(i).take(4) {
                                *b = big;
                            }
                        }
                        _ => {
                            let n = self.rng.below(2 * m.len());
                            m.truncate(4);
                            m.extend((0..n).map(|_| self.rng.next() as u8));
                        }
                    }
                    self.feed::<T>(&v.id, &m, &mut kept);
                }
            }
        }
    }
}

fn main() {
    let rounds = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(200);
    let vectors = common::read_vectors();
    let mut fuzz = Fuzz { vectors: &vectors, rounds, rng: Rng(0x5eed), seeds: 0, decoded: 0, refused: 0, over: Vec::new(), differ: Vec::new() };
    gen::visit_types(&mut fuzz);
    for o in fuzz.over.iter().take(20) {
        println!("OVER {o}");
    }
    for d in fuzz.differ.iter().take(20) {
        println!("DIFFER {d}");
    }
    println!("seeds {} decoded {} refused {} over {} differ {}", fuzz.seeds, fuzz.decoded, fuzz.refused, fuzz.over.len(),
             fuzz.differ.len());
    if !fuzz.over.is_empty() || !fuzz.differ.is_empty() {
        std::process::exit(1);
    }
}
