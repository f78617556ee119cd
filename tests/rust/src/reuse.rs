//! `decode_into` and `serialize_into` on kept values (what a 1 kHz stream does): a value
//! reused from a longer sample, then a shorter, then a longer one equals a fresh decode each
//! time; once it has held the longest, decoding into it allocates nothing (while sequences of
//! strings or structs keep their length: elements cut off are dropped, so growing back
//! allocates them again); so does encoding into a kept buffer; a union's string branch is
//! read in place when the variant stays, replaced when it changes; a hostile count is
//! refused with deserialize's error. Prints `ok`.

use gen::cdr::{deserialize, deserialize_into, serialize, serialize_into, Endianness};
use gen::rapid::{Command, JointSample, NamedFloatSequence, ParameterUnion};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

struct Counting;
static ALLOCS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCS.fetch_add(1, Relaxed);
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCS.fetch_add(1, Relaxed);
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static ALLOC: Counting = Counting;

/// A sample of `joints` joints and `aux` auxiliary float sequences, names `tag` long.
fn sample(joints: usize, aux: usize, tag: &str) -> JointSample {
    let mut s = JointSample::default();
    s.hdr.src_name = tag.into();
    s.hdr.asset_name = format!("{tag}-asset");
    s.hdr.time_stamp = joints as i64 * 1000;
    let v = |k: f32| (0..joints).map(|i| k * i as f32).collect::<Vec<f32>>();
    s.angle_pos = v(0.5);
    s.angle_vel = v(-0.25);
    s.angle_acc = v(0.125);
    s.current = v(2.0);
    s.torque = v(3.0);
    s.temperature = v(40.0);
    s.status = (0..joints as i32).collect();
    s.aux_float = (0..aux).map(|i| NamedFloatSequence { name: format!("{tag}{i}"), values: v(i as f32) }).collect();
    s
}

fn check(kept: &mut JointSample, bytes: &[u8], what: &str) {
    deserialize_into(bytes, kept).unwrap_or_else(|e| panic!("{what}: {e}"));
    let fresh: JointSample = deserialize(bytes).unwrap_or_else(|e| panic!("{what}: {e}"));
    assert_eq!(*kept, fresh, "{what}: reused value differs from a fresh decode");
}

fn main() {
    let long = serialize(&sample(64, 3, "longer-name"), Endianness::Little).expect("encode");
    let short = serialize(&sample(3, 1, "s"), Endianness::Big).expect("encode");
    let mut kept = JointSample::default();
    check(&mut kept, &long, "long");
    check(&mut kept, &short, "short after long");
    assert!(kept.angle_pos.capacity() >= 64 && kept.hdr.src_name.capacity() >= 11, "capacity kept");
    check(&mut kept, &long, "long after short");

    // a kept value that has held the longest sample: no allocation, for fewer joints and
    // shorter names either (as many auxFloat entries)
    check(&mut kept, &long, "long again");
    let fewer = serialize(&sample(3, 3, "s"), Endianness::Big).expect("encode");
    let before = ALLOCS.load(Relaxed);
    for _ in 0..100 {
        deserialize_into(&long, &mut kept).expect("long");
        deserialize_into(&fewer, &mut kept).expect("fewer");
    }
    deserialize_into(&long, &mut kept).expect("long");
    let decoding = ALLOCS.load(Relaxed) - before;

    // a kept buffer: no allocation once it holds the longest encoding, the same bytes
    let mut buf = Vec::new();
    serialize_into(&kept, Endianness::Little, &mut buf).expect("encode");
    assert_eq!(buf, long, "serialize_into differs from serialize");
    let small = sample(3, 1, "s");
    let before = ALLOCS.load(Relaxed);
    for _ in 0..100 {
        serialize_into(&small, Endianness::Big, &mut buf).expect("encode");
        serialize_into(&kept, Endianness::Little, &mut buf).expect("encode");
    }
    let encoding = ALLOCS.load(Relaxed) - before;
    serialize_into(&small, Endianness::Big, &mut buf).expect("encode");
    assert_eq!(buf, short, "serialize_into of the short one differs");
    assert_eq!((decoding, encoding), (0, 0), "allocations in 201 decodes, 200 encodes into kept values");

    // a hostile count (anglePos's, after the header's two strings, i64, two i32) is refused
    // as deserialize refuses it, into a kept value as into a fresh one
    let at = 4 + 4 + 12 + 4 + 18 + 2 + 8 + 4 + 4; // hdr: srcName, pad, assetName, pad to 8, ...
    let mut hostile = long.clone();
    let n = u32::from_le_bytes(hostile[at..at + 4].try_into().expect("4 bytes"));
    assert_eq!(n, 64, "the count of anglePos sits at offset {at}");
    hostile[at..at + 4].copy_from_slice(&0x7fff_fff0u32.to_le_bytes());
    let fresh = deserialize::<JointSample>(&hostile).expect_err("hostile count accepted");
    let before = ALLOCS.load(Relaxed);
    let into = deserialize_into(&hostile, &mut kept).expect_err("hostile count accepted into a kept value");
    assert!(ALLOCS.load(Relaxed) - before <= 2, "the refusal allocated more than its message");
    assert_eq!(into, fresh);
    assert!(into.message.contains("rapid::JointSample.anglePos"), "{into}");
    // and the kept value decodes the next good sample as a fresh one
    check(&mut kept, &short, "short after a refusal");

    // unions: arguments whose variants stay are read in place, changed ones replaced
    let command = |args: Vec<ParameterUnion>| {
        let c = Command { cmd_name: "move".into(), cmd_id: "id-1".into(), arguments: args, ..Command::default() };
        serialize(&c, Endianness::Little).expect("encode")
    };
    let strings = command(vec![ParameterUnion::S("a longer text".into()), ParameterUnion::D(1.5), ParameterUnion::S("b".into())]);
    let swapped = command(vec![ParameterUnion::D(2.5), ParameterUnion::S("c".into()), ParameterUnion::S("d".into())]);
    let mut kept = Command::default();
    for (bytes, what) in [(&strings, "strings"), (&swapped, "variants changed"), (&strings, "strings again")] {
        deserialize_into(bytes, &mut kept).unwrap_or_else(|e| panic!("{what}: {e}"));
        assert_eq!(kept, deserialize::<Command>(bytes).expect("decode"), "{what}");
    }
    let before = ALLOCS.load(Relaxed);
    for _ in 0..100 {
        deserialize_into(&strings, &mut kept).expect("strings");
    }
    assert_eq!(ALLOCS.load(Relaxed) - before, 0, "allocations decoding the same variants into a kept Command");
    println!("ok");
}
