//! XCDR1 (plain CDR) reader and writer used by the generated encode/decode code. The same
//! file in every crate rapidgen writes (its source: rapidgen's runtime/rust/rapid_support/src,
//! where it is edited); docs/rust-backend.md describes the rules.
//!
//! Decoding treats its input as hostile: every read is bounds-checked, every count is
//! checked against the type's bound and the bytes left before anything is allocated,
//! nesting is limited, and errors come back as `DecodeError`, never as a panic.

use ::core::fmt;

/// Byte order of a serialized sample (the encapsulation header records it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Endianness {
    Little,
    Big,
}

/// Bytes that are not a valid encoding of the type asked for.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DecodeError {
    /// Offset in the input (the encapsulation header included) where reading failed.
    pub offset: usize,
    pub message: ::std::string::String,
}

/// A value that has no encoding (a string or sequence over its bound, a string holding NUL,
/// a union whose discriminator does not select the variant holding it).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EncodeError {
    pub message: ::std::string::String,
}

impl fmt::Display for DecodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} at offset {}", self.message, self.offset)
    }
}

impl fmt::Display for EncodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl ::std::error::Error for DecodeError {}
impl ::std::error::Error for EncodeError {}

/// A generated struct, union or enum: its DDS type name and its XCDR1 body.
pub trait Cdr: Sized {
    /// The IDL scoped name, as registered with DDS (`rapid::Command`).
    const TYPE_NAME: &'static str;
    fn encode(&self, w: &mut Writer) -> ::core::result::Result<(), EncodeError>;
    fn decode(r: &mut Reader<'_>) -> ::core::result::Result<Self, DecodeError>;
    /// Reads a value over `self`, as `decode` reads it (the same checks, the same errors),
    /// reusing the capacity `self` holds: a struct's strings refilled, its sequences
    /// truncated or extended in place, nested structs in place, a union's branch in place
    /// when the discriminator selects the variant it holds (else replaced, as an enum is).
    /// On an error `self` holds a mix of old and new members: decode it again.
    fn decode_into(&mut self, r: &mut Reader<'_>) -> ::core::result::Result<(), DecodeError> {
        *self = Self::decode(r)?;
        Ok(())
    }
    /// Adds the bytes `encode` writes (alignment included) to `s`: `serialize` allocates
    /// its output once, at the exact size.
    fn size(&self, s: &mut Size);
    /// Whether the type has key members (`@key`, `//@key`, `#pragma keylist`).
    const KEYED: bool = false;
    /// Writes the key members, in key order (nothing for a type without keys).
    fn encode_key(&self, _w: &mut Writer) -> ::core::result::Result<(), EncodeError> {
        Ok(())
    }
    /// Bytes of the largest key encoding (`key_bytes`), 1048576 for a key without bound:
    /// RTPS takes a key of at most 16 bytes as its hash, a longer one's MD5.
    const KEY_MAX_SIZE: usize = 0;
    /// Reads the key members as `encode_key` writes them and writes them again (the key in
    /// the writer's byte order; see `transcode_key`).
    fn transcode_key(_r: &mut Reader<'_>, _w: &mut Writer) -> ::core::result::Result<(), DecodeError> {
        Ok(())
    }
}

/// Deepest nesting of structs and unions a decoder follows (recursive types).
pub const MAX_DEPTH: u32 = 100;
/// Most elements a sequence of zero-size elements may announce.
pub const MAX_EMPTY_ELEMENTS: usize = 65536;
const HEADER: usize = 4;

/// `value` with its 4-byte encapsulation header (CDR_LE or CDR_BE).
pub fn serialize<T: Cdr>(value: &T, order: Endianness) -> ::core::result::Result<::std::vec::Vec<u8>, EncodeError> {
    let mut s = Size { pos: 0 };
    value.size(&mut s);
    let mut w = Writer::with_capacity(order, s.pos);
    value.encode(&mut w)?;
    Ok(w.into_bytes())
}

/// `value` with its encapsulation header into `buf` (cleared first; its capacity reused, so
/// a kept buffer stops allocating once it fits the largest sample). On an error `buf`
/// holds a partial encoding.
pub fn serialize_into<T: Cdr>(value: &T, order: Endianness, buf: &mut ::std::vec::Vec<u8>) -> ::core::result::Result<(), EncodeError> {
    let mut s = Size { pos: 0 };
    value.size(&mut s);
    let mut out = ::core::mem::take(buf);
    out.clear();
    let _ = out.try_reserve_exact(s.pos.saturating_add(HEADER));
    out.extend_from_slice(&[0, u8::from(order == Endianness::Little), 0, 0]);
    let mut w = Writer { out, little: order == Endianness::Little, origin: HEADER };
    let done = value.encode(&mut w);
    *buf = w.out;
    done
}

/// The key members of `value` in big-endian CDR from offset 0 (no header): the input of
/// the RTPS key hash (used as is when it fits 16 bytes, else its MD5).
pub fn key_bytes<T: Cdr>(value: &T) -> ::core::result::Result<::std::vec::Vec<u8>, EncodeError> {
    let mut w = Writer { out: ::std::vec::Vec::new(), little: false, origin: 0 };
    value.encode_key(&mut w)?;
    Ok(w.out)
}

/// Key bytes of `T` (`encode_key` from offset 0, no header) from one byte order into the
/// other, checked like any decoded input: a serialized key in a DDS message (a dispose)
/// is written in the sample's byte order, its hash input is big-endian.
pub fn transcode_key<T: Cdr>(key: &[u8], from: Endianness, to: Endianness) -> ::core::result::Result<::std::vec::Vec<u8>, DecodeError> {
    let mut data = ::std::vec::Vec::with_capacity(HEADER + key.len());
    data.extend_from_slice(&[0; HEADER]);
    data.extend_from_slice(key);
    let mut r = Reader { data: &data, pos: HEADER, little: from == Endianness::Little, depth: 0 };
    let mut w = Writer { out: ::std::vec::Vec::new(), little: to == Endianness::Little, origin: 0 };
    let moved = |e: DecodeError| DecodeError { offset: e.offset.saturating_sub(HEADER), message: e.message };
    T::transcode_key(&mut r, &mut w).map_err(moved)?;
    if data.len() - r.pos > 3 {
        return Err(moved(r.error(format_args!("{} bytes after the key", data.len() - r.pos))));
    }
    Ok(w.out)
}

/// A value from its encapsulated bytes, in either byte order; at most 3 bytes (a writer's
/// final padding) may follow it.
pub fn deserialize<T: Cdr>(data: &[u8]) -> ::core::result::Result<T, DecodeError> {
    let mut r = reader(data)?;
    let value = T::decode(&mut r)?;
    if data.len() - r.pos > 3 {
        return Err(r.error(format_args!("{} bytes after the value", data.len() - r.pos)));
    }
    Ok(value)
}

/// As `deserialize`, over `value` (`Cdr::decode_into`: its capacity reused, the same
/// checks and errors; on an error `value` is a mix of old and new members).
pub fn deserialize_into<T: Cdr>(data: &[u8], value: &mut T) -> ::core::result::Result<(), DecodeError> {
    let mut r = reader(data)?;
    value.decode_into(&mut r)?;
    if data.len() - r.pos > 3 {
        return Err(r.error(format_args!("{} bytes after the value", data.len() - r.pos)));
    }
    Ok(())
}

/// A reader after the encapsulation header, its byte order from it.
fn reader(data: &[u8]) -> ::core::result::Result<Reader<'_>, DecodeError> {
    let little = match data {
        [0, 0, _, _, ..] => false,
        [0, 1, _, _, ..] => true,
        [_, _, _, _, ..] => return Err(DecodeError { offset: 0, message: "not a CDR_LE or CDR_BE encapsulation header".into() }),
        _ => return Err(DecodeError { offset: 0, message: "shorter than the encapsulation header".into() }),
    };
    Ok(Reader { data, pos: HEADER, little, depth: 0 })
}

/// A fixed-size number: its size (= alignment) and its bytes in either order, one at a
/// time or a run at once (sequences and arrays: one alignment, one bounds check, then a
/// loop over fixed-size chunks the optimizer turns into a copy or a byte swap).
pub trait Primitive: Copy {
    const SIZE: usize;
    fn put(self, out: &mut ::std::vec::Vec<u8>, little: bool);
    fn get(r: &mut Reader<'_>) -> ::core::result::Result<Self, DecodeError>;
    /// Appends the elements' bytes.
    fn put_all(v: &[Self], out: &mut ::std::vec::Vec<u8>, little: bool);
    /// `bytes` (a whole number of elements) as elements, into `v` (as many).
    fn get_all(bytes: &[u8], v: &mut [Self], little: bool);
    /// `bytes` (a whole number of elements) as a new vector.
    fn get_vec(bytes: &[u8], little: bool) -> ::std::vec::Vec<Self>;
    /// `bytes` (a whole number of elements) as `v`'s elements (its capacity reused).
    fn get_refill(bytes: &[u8], v: &mut ::std::vec::Vec<Self>, little: bool);
}

macro_rules! primitive {
    ($kind:ident: $($t:ty),*) => {$(
        impl Primitive for $t {
            const SIZE: usize = ::core::mem::size_of::<$t>();
            #[inline]
            fn put(self, out: &mut ::std::vec::Vec<u8>, little: bool) {
                out.extend_from_slice(&if little { self.to_le_bytes() } else { self.to_be_bytes() });
            }
            #[inline]
            fn get(r: &mut Reader<'_>) -> ::core::result::Result<Self, DecodeError> {
                r.align(Self::SIZE)?;
                let b = r.take::<{ ::core::mem::size_of::<$t>() }>()?;
                Ok(if r.little { <$t>::from_le_bytes(b) } else { <$t>::from_be_bytes(b) })
            }
            primitive!(@$kind $t);
        }
    )*};
    // one byte: no order, a plain copy
    (@byte $t:ty) => {
        fn put_all(v: &[Self], out: &mut ::std::vec::Vec<u8>, _little: bool) {
            out.extend(v.iter().map(|x| { let [b] = x.to_le_bytes(); b }));
        }
        fn get_all(bytes: &[u8], v: &mut [Self], _little: bool) {
            v.iter_mut().zip(bytes).for_each(|(x, &b)| *x = <$t>::from_le_bytes([b]));
        }
        fn get_vec(bytes: &[u8], _little: bool) -> ::std::vec::Vec<Self> {
            bytes.iter().map(|&b| <$t>::from_le_bytes([b])).collect()
        }
        fn get_refill(bytes: &[u8], v: &mut ::std::vec::Vec<Self>, _little: bool) {
            v.clear();
            v.extend(bytes.iter().map(|&b| <$t>::from_le_bytes([b])));
        }
    };
    // several bytes: the output zeroed once, then each element's bytes in place
    (@number $t:ty) => {
        fn put_all(v: &[Self], out: &mut ::std::vec::Vec<u8>, little: bool) {
            let start = out.len();
            out.resize(start + v.len() * Self::SIZE, 0);
            if let Some(dst) = out.get_mut(start..) {
                let pairs = dst.chunks_exact_mut(Self::SIZE).zip(v);
                if little {
                    pairs.for_each(|(d, x)| d.copy_from_slice(&x.to_le_bytes()));
                } else {
                    pairs.for_each(|(d, x)| d.copy_from_slice(&x.to_be_bytes()));
                }
            }
        }
        fn get_all(bytes: &[u8], v: &mut [Self], little: bool) {
            const N: usize = ::core::mem::size_of::<$t>();
            let pairs = bytes.chunks_exact(N).zip(v.iter_mut());
            if little {
                pairs.for_each(|(c, x)| *x = <$t>::from_le_bytes(c.try_into().unwrap_or([0; N])));
            } else {
                pairs.for_each(|(c, x)| *x = <$t>::from_be_bytes(c.try_into().unwrap_or([0; N])));
            }
        }
        fn get_vec(bytes: &[u8], little: bool) -> ::std::vec::Vec<Self> {
            const N: usize = ::core::mem::size_of::<$t>();
            let chunks = bytes.chunks_exact(N);
            if little {
                chunks.map(|c| <$t>::from_le_bytes(c.try_into().unwrap_or([0; N]))).collect()
            } else {
                chunks.map(|c| <$t>::from_be_bytes(c.try_into().unwrap_or([0; N]))).collect()
            }
        }
        fn get_refill(bytes: &[u8], v: &mut ::std::vec::Vec<Self>, little: bool) {
            const N: usize = ::core::mem::size_of::<$t>();
            v.clear();
            let chunks = bytes.chunks_exact(N);
            if little {
                v.extend(chunks.map(|c| <$t>::from_le_bytes(c.try_into().unwrap_or([0; N]))));
            } else {
                v.extend(chunks.map(|c| <$t>::from_be_bytes(c.try_into().unwrap_or([0; N]))));
            }
        }
    };
}
primitive!(byte: i8, u8);
primitive!(number: i16, u16, i32, u32, i64, u64, f32, f64);

/// The encoded size of a value, counted as `Writer` writes it (alignment from the end of
/// the encapsulation header); the generated `Cdr::size` calls these. Only a capacity
/// for `serialize`: the sums wrap rather than check (a wrapped size reserves too little
/// and the buffer grows, as without it).
pub struct Size {
    pos: usize,
}

impl Size {
    /// Sizes and alignments are 1, 2, 4 or 8.
    #[inline]
    fn align(&mut self, n: usize) {
        self.pos = self.pos.wrapping_add(n - 1) & !(n - 1);
    }

    #[inline]
    pub fn put<T: Primitive>(&mut self) {
        self.align(T::SIZE);
        self.pos = self.pos.wrapping_add(T::SIZE);
    }

    /// Booleans, octets: no alignment.
    #[inline]
    pub fn bytes(&mut self, n: usize) {
        self.pos = self.pos.wrapping_add(n);
    }

    #[inline]
    pub fn string(&mut self, s: &str) {
        self.put::<u32>();
        self.bytes(s.len().wrapping_add(1));
    }

    /// A sequence's count.
    #[inline]
    pub fn count(&mut self) {
        self.put::<u32>();
    }

    /// `n` primitives in a row (aligned once, none for 0).
    #[inline]
    pub fn prims<T: Primitive>(&mut self, n: usize) {
        if n != 0 {
            self.align(T::SIZE);
            self.pos = self.pos.wrapping_add(n.wrapping_mul(T::SIZE));
        }
    }
}

/// Writes XCDR1 after a 4-byte encapsulation header; alignment counts from its end.
pub struct Writer {
    out: ::std::vec::Vec<u8>,
    little: bool,
    origin: usize,
}

impl Writer {
    pub fn new(order: Endianness) -> Self {
        Self::with_capacity(order, 0)
    }

    /// A writer whose buffer holds `body` bytes after the header without growing (when
    /// the allocator grants them; else it grows as it goes).
    pub fn with_capacity(order: Endianness, body: usize) -> Self {
        let little = order == Endianness::Little;
        let mut out = ::std::vec::Vec::new();
        let _ = out.try_reserve_exact(body.saturating_add(HEADER));
        out.extend_from_slice(&[0, u8::from(little), 0, 0]);
        Writer { out, little, origin: HEADER }
    }

    pub fn into_bytes(self) -> ::std::vec::Vec<u8> {
        self.out
    }

    /// Alignments are 1, 2, 4 or 8.
    #[inline]
    fn align(&mut self, n: usize) {
        let pad = self.origin.wrapping_sub(self.out.len()) & (n - 1);
        if pad != 0 {
            self.out.resize(self.out.len() + pad, 0);
        }
    }

    #[inline]
    pub fn put<T: Primitive>(&mut self, v: T) {
        self.align(T::SIZE);
        v.put(&mut self.out, self.little);
    }

    #[inline]
    pub fn put_bool(&mut self, v: bool) {
        self.out.push(u8::from(v));
    }

    /// A collection's length, refused over `bound` (0: unbounded).
    #[inline]
    pub fn put_count(&mut self, n: usize, bound: usize, what: &str) -> ::core::result::Result<(), EncodeError> {
        match u32::try_from(n) {
            Ok(c) if bound == 0 || n <= bound => {
                self.put(c);
                Ok(())
            }
            _ => Err(count_error(n, bound, what)),
        }
    }

    /// A string: length with the NUL, UTF-8 bytes, NUL. `bound` counts bytes (0: unbounded).
    #[inline]
    pub fn put_string(&mut self, s: &str, bound: usize, what: &str) -> ::core::result::Result<(), EncodeError> {
        let b = s.as_bytes();
        if (bound != 0 && b.len() > bound) || b.contains(&0) {
            return Err(string_error(s, bound, what));
        }
        self.put_count(b.len() + 1, 0, what)?;
        self.out.extend_from_slice(b);
        self.out.push(0);
        Ok(())
    }

    /// Primitives in a row (an array's, a sequence's after its count): one alignment, one
    /// copy (none of either for no element, as element by element).
    pub fn put_prims<T: Primitive>(&mut self, v: &[T]) {
        if !v.is_empty() {
            self.align(T::SIZE);
            T::put_all(v, &mut self.out, self.little);
        }
    }

    /// A sequence of primitives: count, then the elements at once.
    pub fn put_seq_prims<T: Primitive>(&mut self, v: &[T], bound: usize, what: &str) -> ::core::result::Result<(), EncodeError> {
        self.put_count(v.len(), bound, what)?;
        self.put_prims(v);
        Ok(())
    }

    /// Booleans in a row (one byte each, no alignment).
    pub fn put_bools(&mut self, v: &[bool]) {
        self.out.extend(v.iter().map(|&b| u8::from(b)));
    }

    /// A sequence of booleans: count, then the elements at once.
    pub fn put_seq_bools(&mut self, v: &[bool], bound: usize, what: &str) -> ::core::result::Result<(), EncodeError> {
        self.put_count(v.len(), bound, what)?;
        self.put_bools(v);
        Ok(())
    }

    /// A sequence: count, then each element.
    pub fn put_seq<T>(&mut self, v: &[T], bound: usize, what: &str,
                      mut each: impl FnMut(&mut Self, &T) -> ::core::result::Result<(), EncodeError>)
                      -> ::core::result::Result<(), EncodeError> {
        self.put_count(v.len(), bound, what)?;
        v.iter().try_for_each(|e| each(self, e))
    }

    /// An array's elements (no count).
    pub fn put_array<T>(&mut self, v: &[T],
                        mut each: impl FnMut(&mut Self, &T) -> ::core::result::Result<(), EncodeError>)
                        -> ::core::result::Result<(), EncodeError> {
        v.iter().try_for_each(|e| each(self, e))
    }
}

// The encoder's refusals, out of the hot paths.
#[cold]
fn count_error(n: usize, bound: usize, what: &str) -> EncodeError {
    let message = if bound != 0 && n > bound {
        format!("{what}: {n} elements, over the bound {bound}")
    } else {
        format!("{what}: {n} elements do not fit CDR")
    };
    EncodeError { message }
}

#[cold]
fn string_error(s: &str, bound: usize, what: &str) -> EncodeError {
    let message = if bound != 0 && s.len() > bound {
        format!("{what}: {} bytes, over the bound {bound}", s.len())
    } else {
        format!("{what}: a CDR string cannot hold NUL")
    };
    EncodeError { message }
}

// The decoder's refusals of counts and string lengths, out of the hot paths.
#[cold]
fn count_refused(at: usize, n: usize, bound: usize, what: &str) -> DecodeError {
    let message = if bound != 0 && n > bound {
        format!("{what}: {n} elements, over the bound {bound}")
    } else {
        format!("{what}: {n} elements, more than the bytes left hold")
    };
    DecodeError { offset: at, message }
}

#[cold]
fn string_refused(at: usize, n: usize, bound: usize, what: &str) -> DecodeError {
    let message = if n == 0 {
        format!("{what}: string length 0 (no NUL)")
    } else {
        format!("{what}: {} bytes, over the bound {bound}", n - 1)
    };
    DecodeError { offset: at, message }
}

/// Reads XCDR1 from untrusted bytes.
pub struct Reader<'a> {
    data: &'a [u8],
    pos: usize,
    little: bool,
    depth: u32,
}

impl<'a> Reader<'a> {
    /// An error at the current offset.
    #[cold]
    pub fn error(&self, message: fmt::Arguments<'_>) -> DecodeError {
        DecodeError { offset: self.pos, message: message.to_string() }
    }

    #[inline]
    fn left(&self) -> usize {
        self.data.len() - self.pos
    }

    /// Alignments are 1, 2, 4 or 8.
    #[inline]
    fn align(&mut self, n: usize) -> ::core::result::Result<(), DecodeError> {
        let pad = HEADER.wrapping_sub(self.pos) & (n - 1);
        if pad > self.left() {
            return Err(self.error(format_args!("truncated")));
        }
        self.pos += pad;
        Ok(())
    }

    #[inline]
    fn take<const N: usize>(&mut self) -> ::core::result::Result<[u8; N], DecodeError> {
        match self.data.get(self.pos..self.pos + N) {
            Some(s) => {
                let mut b = [0u8; N];
                b.copy_from_slice(s);
                self.pos += N;
                Ok(b)
            }
            None => Err(self.error(format_args!("truncated"))),
        }
    }

    #[inline]
    pub fn get<T: Primitive>(&mut self) -> ::core::result::Result<T, DecodeError> {
        T::get(self)
    }

    /// Refuses an encoding shorter than `bytes` from here (before building a fixed-size array).
    #[inline]
    pub fn need(&self, bytes: usize, what: &str) -> ::core::result::Result<(), DecodeError> {
        if bytes > self.left() {
            return Err(self.error(format_args!("{what}: truncated")));
        }
        Ok(())
    }

    #[inline]
    pub fn get_bool(&mut self) -> ::core::result::Result<bool, DecodeError> {
        match self.take::<1>()? {
            [0] => Ok(false),
            [1] => Ok(true),
            [b] => Err(DecodeError { offset: self.pos - 1, message: format!("{b} is not a boolean") }),
        }
    }

    /// Enters a struct or union; refuses nesting deeper than MAX_DEPTH.
    #[inline]
    pub fn enter(&mut self) -> ::core::result::Result<(), DecodeError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(self.error(format_args!("nested deeper than {MAX_DEPTH}")));
        }
        Ok(())
    }

    #[inline]
    pub fn leave(&mut self) {
        self.depth -= 1;
    }

    /// A collection's count: at most `bound` (0: unbounded), and no more than the bytes
    /// left can hold at `min_size` bytes per element (MAX_EMPTY_ELEMENTS when 0).
    #[inline]
    pub fn get_count(&mut self, bound: usize, min_size: usize, what: &str) -> ::core::result::Result<usize, DecodeError> {
        let at = self.pos;
        let n = usize::try_from(self.get::<u32>()?).unwrap_or(usize::MAX);
        let fits = n <= self.left().checked_div(min_size).unwrap_or(MAX_EMPTY_ELEMENTS);
        if (bound == 0 || n <= bound) && fits {
            Ok(n)
        } else {
            Err(count_refused(at, n, bound, what))
        }
    }

    /// A NUL-terminated UTF-8 string of at most `bound` bytes (0: unbounded).
    #[inline]
    pub fn get_string(&mut self, bound: usize, what: &str) -> ::core::result::Result<::std::string::String, DecodeError> {
        Ok(self.string(bound, what)?.to_owned())
    }

    /// As `get_string`, into `s` (cleared and refilled: its capacity reused).
    #[inline]
    pub fn get_string_into(&mut self, s: &mut ::std::string::String, bound: usize, what: &str) -> ::core::result::Result<(), DecodeError> {
        let text = self.string(bound, what)?;
        s.clear();
        s.push_str(text);
        Ok(())
    }

    /// The checked text of a string in the input.
    #[inline]
    fn string(&mut self, bound: usize, what: &str) -> ::core::result::Result<&'a str, DecodeError> {
        let data: &'a [u8] = self.data;
        let at = self.pos;
        let n = self.get_count(0, 1, what)?;
        if n == 0 || (bound != 0 && n - 1 > bound) {
            return Err(string_refused(at, n, bound, what));
        }
        // get_count checked that the n bytes are there, n > 0
        let (text, nul) = match data.get(self.pos..).and_then(|d| d.get(..n)).and_then(|b| b.split_last()) {
            Some((nul, text)) => (text, *nul),
            None => return Err(self.error(format_args!("{what}: truncated"))),
        };
        if nul != 0 || text.contains(&0) {
            return Err(self.error(format_args!("{what}: string not NUL-terminated or holding NUL")));
        }
        let s = ::core::str::from_utf8(text).map_err(|_| self.error(format_args!("{what}: string is not UTF-8")))?;
        self.pos += n;
        Ok(s)
    }

    /// The next `n` elements of `size` bytes (aligned to `size` unless `n` is 0), checked
    /// against the bytes left.
    fn run(&mut self, n: usize, size: usize, what: &str) -> ::core::result::Result<&'a [u8], DecodeError> {
        if n == 0 {
            return Ok(&[]);
        }
        self.align(size)?;
        let data: &'a [u8] = self.data;
        match n.checked_mul(size).and_then(|len| data.get(self.pos..).and_then(|rest| rest.get(..len))) {
            Some(bytes) => {
                self.pos += bytes.len();
                Ok(bytes)
            }
            None => Err(self.error(format_args!("{what}: truncated"))),
        }
    }

    /// An array of primitives into `v`: one alignment and bounds check, then a copy.
    pub fn get_prims<T: Primitive>(&mut self, v: &mut [T], what: &str) -> ::core::result::Result<(), DecodeError> {
        let bytes = self.run(v.len(), T::SIZE, what)?;
        T::get_all(bytes, v, self.little);
        Ok(())
    }

    /// A sequence of primitives: the count (checked as in `get_seq`), then the elements
    /// at once, allocated only once all their bytes are known to be there.
    pub fn get_seq_prims<T: Primitive>(&mut self, bound: usize, what: &str) -> ::core::result::Result<::std::vec::Vec<T>, DecodeError> {
        let n = self.get_count(bound, T::SIZE, what)?;
        let bytes = self.run(n, T::SIZE, what)?;
        Ok(T::get_vec(bytes, self.little))
    }

    /// As `get_seq_prims`, into `v` (its capacity reused).
    pub fn get_seq_prims_into<T: Primitive>(&mut self, v: &mut ::std::vec::Vec<T>, bound: usize, what: &str) -> ::core::result::Result<(), DecodeError> {
        let n = self.get_count(bound, T::SIZE, what)?;
        let bytes = self.run(n, T::SIZE, what)?;
        T::get_refill(bytes, v, self.little);
        Ok(())
    }

    /// Validated booleans (bytes 0 or 1), the first other byte refused at its offset.
    fn bools(&mut self, n: usize, what: &str) -> ::core::result::Result<&'a [u8], DecodeError> {
        let at = self.pos;
        let bytes = self.run(n, 1, what)?;
        match bytes.iter().position(|&b| b > 1) {
            None => Ok(bytes),
            Some(i) => {
                let b = bytes.get(i).copied().unwrap_or_default();
                Err(DecodeError { offset: at + i, message: format!("{b} is not a boolean") })
            }
        }
    }

    /// An array of booleans into `v`.
    pub fn get_bools(&mut self, v: &mut [bool], what: &str) -> ::core::result::Result<(), DecodeError> {
        let bytes = self.bools(v.len(), what)?;
        v.iter_mut().zip(bytes).for_each(|(x, &b)| *x = b != 0);
        Ok(())
    }

    /// A sequence of booleans (count checked as in `get_seq`).
    pub fn get_seq_bools(&mut self, bound: usize, what: &str) -> ::core::result::Result<::std::vec::Vec<bool>, DecodeError> {
        let n = self.get_count(bound, 1, what)?;
        Ok(self.bools(n, what)?.iter().map(|&b| b != 0).collect())
    }

    /// As `get_seq_bools`, into `v` (its capacity reused).
    pub fn get_seq_bools_into(&mut self, v: &mut ::std::vec::Vec<bool>, bound: usize, what: &str) -> ::core::result::Result<(), DecodeError> {
        let n = self.get_count(bound, 1, what)?;
        let bytes = self.bools(n, what)?;
        v.clear();
        v.extend(bytes.iter().map(|&b| b != 0));
        Ok(())
    }

    /// A sequence: count (checked before allocating), then each element.
    pub fn get_seq<T>(&mut self, bound: usize, min_size: usize, what: &str,
                      mut each: impl FnMut(&mut Self) -> ::core::result::Result<T, DecodeError>)
                      -> ::core::result::Result<::std::vec::Vec<T>, DecodeError> {
        let n = self.get_count(bound, min_size, what)?;
        let mut v = ::std::vec::Vec::with_capacity(n);
        for _ in 0..n {
            v.push(each(self)?);
        }
        Ok(v)
    }

    /// As `get_seq`, into `v`: the count checked as there, then the elements `v` keeps read
    /// over with `into`, those past its length with `each` (reserved only once the count
    /// is checked), those past the count dropped.
    pub fn get_seq_into<T>(&mut self, v: &mut ::std::vec::Vec<T>, bound: usize, min_size: usize, what: &str,
                           mut into: impl FnMut(&mut Self, &mut T) -> ::core::result::Result<(), DecodeError>,
                           mut each: impl FnMut(&mut Self) -> ::core::result::Result<T, DecodeError>)
                           -> ::core::result::Result<(), DecodeError> {
        let n = self.get_count(bound, min_size, what)?;
        v.truncate(n);
        for e in v.iter_mut() {
            into(self, e)?;
        }
        v.reserve_exact(n - v.len());
        while v.len() < n {
            v.push(each(self)?);
        }
        Ok(())
    }

    /// An array's elements read over those of `v`.
    pub fn get_array_into<T>(&mut self, v: &mut [T],
                             mut into: impl FnMut(&mut Self, &mut T) -> ::core::result::Result<(), DecodeError>)
                             -> ::core::result::Result<(), DecodeError> {
        v.iter_mut().try_for_each(|e| into(self, e))
    }

    /// An array's elements into `v` (already holding N defaults: a fixed size the type,
    /// not the input, decides).
    pub fn get_array<T>(&mut self, v: &mut [T],
                        mut each: impl FnMut(&mut Self) -> ::core::result::Result<T, DecodeError>)
                        -> ::core::result::Result<(), DecodeError> {
        for e in v.iter_mut() {
            *e = each(self)?;
        }
        Ok(())
    }
}
