//! Every golden vector decodes from both byte orders to equal values, and re-encodes to
//! exactly its bytes in both orders; its key bytes go to little-endian and back unchanged
//! (`transcode_key`); `serialize` allocates its output once, exactly. One value and one
//! buffer per type are kept across its vectors (forwards, then backwards: longer values
//! followed by shorter ones and the reverse): `deserialize_into` it equals `deserialize`,
//! `serialize_into` it gives `serialize`'s bytes. Prints `ok N` (N vectors checked).

mod common;

use gen::cdr::{deserialize, deserialize_into, key_bytes, serialize, serialize_into, transcode_key, Cdr, Endianness, Writer};
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
        let mut kept = T::default();
        let mut buf = Vec::new();
        let of_type: Vec<&common::Vector> = self.vectors.iter().filter(|v| v.type_name == T::TYPE_NAME).collect();
        for v in of_type.iter().chain(of_type.iter().rev()) {
            for (bytes, order) in [(&v.le, Endianness::Little), (&v.be, Endianness::Big)] {
                let fresh = deserialize::<T>(bytes);
                let into = deserialize_into(bytes, &mut kept);
                if into.is_err() || fresh.as_ref().ok() != Some(&kept) {
                    self.failed.push(format!("{}: decode into a kept value: {into:?}\n{kept:?}\n{fresh:?}", v.id));
                }
                let encoded = serialize_into(&kept, order, &mut buf);
                if encoded.is_err() || buf != **bytes {
                    self.failed.push(format!("{}: serialize_into a kept buffer differs: {encoded:?}", v.id));
                }
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
