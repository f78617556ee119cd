//! Every golden vector through serde_json (the crate's `serde` feature): decoded, written
//! as JSON, read back equal, and re-encoded to exactly its bytes. Prints `json ID TEXT` per
//! vector (the test compares TEXT with the vector's value form), then `ok N`.

mod common;

use gen::cdr::{deserialize, serialize, Endianness};

struct Check<'a> {
    vectors: &'a [common::Vector],
    done: usize,
    failed: Vec<String>,
}

impl gen::TypeVisitor for Check<'_> {
    fn visit<T: gen::TopicType>(&mut self) {
        for v in self.vectors.iter().filter(|v| v.type_name == T::TYPE_NAME) {
            self.done += 1;
            let result = (|| -> Result<String, String> {
                let a: T = deserialize(&v.le).map_err(|e| format!("decode: {e}"))?;
                let text = serde_json::to_string(&a).map_err(|e| format!("to JSON: {e}"))?;
                let b: T = serde_json::from_str(&text).map_err(|e| format!("from JSON: {e}\n{text}"))?;
                if a != b {
                    return Err(format!("read back differently:\n{a:?}\n{b:?}"));
                }
                if serialize(&b, Endianness::Little).map_err(|e| format!("encode: {e}"))? != v.le {
                    return Err("re-encoding differs".into());
                }
                Ok(text)
            })();
            match result {
                Ok(text) => println!("json {} {text}", v.id),
                Err(e) => self.failed.push(format!("{}: {e}", v.id)),
            }
        }
    }
}

fn main() {
    let vectors = common::read_vectors();
    let mut check = Check { vectors: &vectors, done: 0, failed: Vec::new() };
    gen::visit_types(&mut check);
    for f in &check.failed {
        println!("FAIL {f}");
    }
    if !check.failed.is_empty() {
        std::process::exit(1);
    }
    println!("ok {}", check.done);
}
