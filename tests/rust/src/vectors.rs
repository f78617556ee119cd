//! Every golden vector decodes from both byte orders to equal values, and re-encodes to
//! exactly its bytes in both orders; its key bytes go to little-endian and back unchanged
//! (`transcode_key`); `serialize` allocates its output once, exactly. Prints `ok N` (N
//! vectors checked).

mod common;

use gen::cdr::{deserialize, key_bytes, serialize, transcode_key, Cdr, Endianness, Writer};
use std::collections::HashSet;

struct Check<'a> {
    vectors: &'a [common::Vector],
    done: usize,
    failed: Vec<String>,
    seen: HashSet<String>,
}

impl gen::TypeVisitor for Check<'_> {
    fn visit<T: gen::TopicType>(&mut self) {
        self.seen.insert(T::TYPE_NAME.to_owned());
        for v in self.vectors.iter().filter(|v| v.type_name == T::TYPE_NAME) {
            self.done += 1;
            let result = (|| -> Result<(), String> {
                let a: T = deserialize(&v.le).map_err(|e| format!("decode LE: {e}"))?;
                let b: T = deserialize(&v.be).map_err(|e| format!("decode BE: {e}"))?;
                if a != b {
                    return Err(format!("LE and BE decode differently:\n{a:?}\n{b:?}"));
                }
                let le = serialize(&a, Endianness::Little).map_err(|e| format!("encode LE: {e}"))?;
                let be = serialize(&a, Endianness::Big).map_err(|e| format!("encode BE: {e}"))?;
                if le != v.le || be != v.be {
                    return Err(format!("re-encoding differs (LE {}, BE {})", le == v.le, be == v.be));
                }
                // `Cdr::size` is exact: serialize allocates once, at the final length
                if le.capacity() != le.len() || be.capacity() != be.len() {
                    return Err(format!("output capacity {} for {} bytes", le.capacity(), le.len()));
                }
                // bit-exact floats: a value cloned and re-encoded gives the same bytes again
                if serialize(&a.clone(), Endianness::Little).ok() != Some(le) {
                    return Err("clone encodes differently".into());
                }
                let key = key_bytes(&a).map_err(|e| format!("key: {e}"))?;
                if key.len() > T::KEY_MAX_SIZE || T::KEYED == key.is_empty() {
                    return Err(format!("{} key bytes, KEY_MAX_SIZE {}", key.len(), T::KEY_MAX_SIZE));
                }
                let little = transcode_key::<T>(&key, Endianness::Big, Endianness::Little).map_err(|e| format!("key BE: {e}"))?;
                let big = transcode_key::<T>(&little, Endianness::Little, Endianness::Big).map_err(|e| format!("key LE: {e}"))?;
                let mut w = Writer::new(Endianness::Little);
                a.encode_key(&mut w).map_err(|e| format!("key LE: {e}"))?;
                if big != key || little != w.into_bytes()[4..] {
                    return Err(format!("key transcoding: {key:02x?} -> {little:02x?} -> {big:02x?}"));
                }
                Ok(())
            })();
            if let Err(e) = result {
                self.failed.push(format!("{}: {e}", v.id));
            }
        }
    }
}

fn main() {
    let vectors = common::read_vectors();
    let mut check = Check { vectors: &vectors, done: 0, failed: Vec::new(), seen: HashSet::new() };
    gen::visit_types(&mut check);
    for v in &vectors {
        if !check.seen.contains(&v.type_name) {
            check.failed.push(format!("{}: type {} is not in the crate", v.id, v.type_name));
        }
    }
    for f in &check.failed {
        println!("FAIL {f}");
    }
    if !check.failed.is_empty() {
        std::process::exit(1);
    }
    println!("ok {}", check.done);
}
