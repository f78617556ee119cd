//! Encode / decode ns/op of the generated Rust codec (crate `rapid_types`, generated/rapid/rust)
//! for the values bench/cpp_codec/bench.cpp times, with its method: per case, best of 5
//! timed loops of the same iteration counts (the first loop doubles as the warm-up).
//! `std::hint::black_box` hides the value from the optimizer on the way in and the result on
//! the way out, so no loop is folded away.
//!
//!     rust_codec_bench [--scale N] [--dump DIR]
//!
//! `--scale N` divides every iteration count by N (a smoke run); `--dump DIR` writes each
//! case's encoded bytes to DIR/<case>.bin (bench/rust_codec.py checks them against the
//! reference encoder). Prints one tab-separated line per case: name, bytes, encode ns/op,
//! decode ns/op, and `ok` when the bytes decode back to an equal value. Exits 1 otherwise;
//! never fails on time.

use std::hint::black_box;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use rapid_types::cdr::{self, Cdr, Endianness};
use rapid_types::rapid;

fn ns_per_op(iters: u64, mut f: impl FnMut()) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..5 {
        let t0 = Instant::now();
        for _ in 0..iters {
            f();
        }
        best = best.min(t0.elapsed().as_nanos() as f64 / iters as f64);
    }
    best
}

/// Times one case; false when its bytes do not decode back to an equal value.
fn bench<T: Cdr + PartialEq>(name: &str, file: &str, value: &T, iters: u64, dump: &Option<PathBuf>) -> bool {
    let bytes = match cdr::serialize(value, Endianness::Little) {
        Ok(b) => b,
        Err(e) => {
            eprintln!("{name}: encode failed: {e}");
            return false;
        }
    };
    if let Some(dir) = dump {
        if let Err(e) = std::fs::write(dir.join(format!("{file}.bin")), &bytes) {
            eprintln!("{name}: cannot write {}: {e}", dir.display());
            return false;
        }
    }
    let same = matches!(cdr::deserialize::<T>(&bytes), Ok(back) if back == *value);
    // the API as an application calls it: serialize returns a new Vec (CDR_LE header
    // included), deserialize a new value; both dropped inside the loop
    let enc = ns_per_op(iters, || {
        let _ = black_box(cdr::serialize(black_box(value), Endianness::Little));
    });
    let dec = ns_per_op(iters, || {
        let _ = black_box(cdr::deserialize::<T>(black_box(&bytes)));
    });
    println!("{name}\t{}\t{enc:.1}\t{dec:.1}\t{}", bytes.len(), if same { "ok" } else { "differs" });
    same
}

fn header() -> rapid::Header {
    rapid::Header {
        src_name: "commander-01".into(),
        asset_name: "K10Red".into(),
        time_stamp: 1_700_000_000_000_000,
        ..Default::default()
    }
}

fn command() -> rapid::Command {
    rapid::Command {
        hdr: header(),
        cmd_name: "driveTo".into(),
        cmd_id: "17-commander-01-1700000000".into(),
        cmd_src: "commander-01".into(),
        subsys_name: "Locomotion".into(),
        arguments: vec![
            rapid::ParameterUnion::S("waypoint-7".into()),
            rapid::ParameterUnion::D(0.5),
            rapid::ParameterUnion::Vec3d([1.0, 2.0, 3.0]),
        ],
        cmd_action: rapid::QueueAction::QueueAppend,
        ..Default::default()
    }
}

fn joint_sample() -> rapid::JointSample {
    let ramp: Vec<f32> = (0..64).map(|i| 0.25 * i as f32).collect();
    rapid::JointSample {
        hdr: header(),
        angle_pos: ramp.clone(),
        angle_vel: ramp.clone(),
        angle_acc: ramp.clone(),
        current: ramp.clone(),
        torque: ramp.clone(),
        temperature: ramp,
        status: vec![1; 64],
        ..Default::default()
    }
}

fn image() -> rapid::ImageSensorSample {
    let mut v = rapid::ImageSensorSample {
        hdr: header(),
        mime_type: "image/x-raw-gray8".into(),
        data: (0..1_048_576usize).map(|i| i.wrapping_mul(31) as u8).collect(),
        ..Default::default()
    };
    v.meta.sensor_name = "panCamLeft".into();
    v.meta.width = 1024;
    v.meta.height = 1024;
    v
}

fn main() -> ExitCode {
    let mut scale = 1u64;
    let mut dump = None;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match (a.as_str(), args.next()) {
            ("--scale", Some(n)) if n.parse::<u64>().map_or(false, |n| n > 0) => scale = n.parse().unwrap_or(1),
            ("--dump", Some(d)) => dump = Some(PathBuf::from(d)),
            _ => {
                eprintln!("usage: rust_codec_bench [--scale N>0] [--dump DIR]");
                return ExitCode::from(2);
            }
        }
    }
    let n = |iters: u64| (iters / scale).max(1);
    // names and iteration counts as in bench/cpp_codec/bench.cpp
    let ok = [
        bench("Command (3 arguments)", "Command", &command(), n(200_000), &dump),
        bench("JointSample (64)", "JointSample", &joint_sample(), n(100_000), &dump),
        bench("ImageSensorSample 1MB", "ImageSensorSample", &image(), n(300), &dump),
    ];
    if ok.iter().all(|&b| b) {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
