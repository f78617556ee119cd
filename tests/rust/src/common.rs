//! Shared by the test programs: the golden-vector lines on stdin and hex.

use std::io::Read;

/// One golden vector: id, DDS type name, XCDR1 little- and big-endian bytes.
pub struct Vector {
    pub id: String,
    pub type_name: String,
    pub le: Vec<u8>,
    pub be: Vec<u8>,
}

fn unhex(s: &str) -> Vec<u8> {
    (0..s.len() / 2).map(|i| u8::from_str_radix(&s[2 * i..2 * i + 2], 16).expect("hex")).collect()
}

/// `id type le_hex be_hex` per line, from stdin.
pub fn read_vectors() -> Vec<Vector> {
    let mut text = String::new();
    std::io::stdin().read_to_string(&mut text).expect("stdin");
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            Vector { id: f[0].to_owned(), type_name: f[1].to_owned(), le: unhex(f[2]), be: unhex(f[3]) }
        })
        .collect()
}
