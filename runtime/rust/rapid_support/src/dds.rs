//! RustDDS 0.15 glue (feature `dds`): every struct and union of the crate is a RustDDS
//! topic type (`rustdds::Keyed`, its key the key members' bytes, `KeyBytes`), written and
//! read by the crate's own XCDR1 codec through `CdrAdapter` (docs/rust-backend.md).
//!
//! - A type with key members (`T::KEYED`) travels on a WITH_KEY topic, the others on a
//!   NO_KEY topic (RustDDS refuses a reader of the other kind; Cyclone does not match a
//!   NO_KEY writer with its keyed reader). `create_topic`, `create_writer` and
//!   `create_reader` choose; `Writer` and `Reader` hold either kind.
//! - RustDDS 0.15 has no Partition QoS: its endpoints are in the default partition.
//! - `DomainParticipantBuilder::new(d).with_only_networks([127.0.0.1])` keeps RTPS on
//!   loopback.

use ::core::cmp::Ordering;
use ::core::fmt;
use ::core::hash::{Hash, Hasher};
use ::core::marker::PhantomData;

use ::rustdds::bytes::Bytes;
use ::rustdds::cdr_encoding_size::{CdrEncodingMaxSize, CdrEncodingSize};
use ::rustdds::dds::{CreateResult, ReadResult, WriteResult};
use ::rustdds::{no_key, with_key, DomainParticipant, Keyed, Publisher, QosPolicies, RepresentationIdentifier, Subscriber,
                Timestamp, Topic, TopicKind};

use crate::cdr::{self, Cdr, DecodeError, EncodeError, Endianness};
use crate::TopicType;

/// The RustDDS this module is written for (`=0.15.0`): use it through this path to be sure
/// to have the same.
pub use ::rustdds;

/// A writer of a keyed type (a WITH_KEY topic): one instance per key.
pub type KeyedWriter<T> = with_key::DataWriter<T, CdrAdapter<T>>;
/// A reader of a keyed type (a WITH_KEY topic).
pub type KeyedReader<T> = with_key::DataReader<T, CdrAdapter<T>>;
/// A writer of a type without key members (a NO_KEY topic).
pub type NoKeyWriter<T> = no_key::DataWriter<T, CdrAdapter<T>>;
/// A reader of a type without key members (a NO_KEY topic).
pub type NoKeyReader<T> = no_key::DataReader<T, CdrAdapter<T>>;

/// The key of a sample of `T`: its key members in big-endian CDR from offset 0
/// (`cdr::key_bytes`), the input of the RTPS key hash. RustDDS takes a key of at most 16
/// bytes (`T::KEY_MAX_SIZE`) as its hash and hashes a longer one with MD5, as RAPID's
/// string keys need. Empty for a type without key members.
pub struct KeyBytes<T> {
    bytes: ::std::vec::Vec<u8>,
    _type: PhantomData<fn() -> T>,
}

impl<T: Cdr> KeyBytes<T> {
    /// The key of `value`; empty when a key member has no encoding (a string over its
    /// bound): such a value cannot be written either, its encoding fails first.
    pub fn of(value: &T) -> Self {
        KeyBytes { bytes: cdr::key_bytes(value).unwrap_or_default(), _type: PhantomData }
    }

    /// A key from its big-endian bytes, checked to be a key of `T`.
    pub fn from_bytes(bytes: &[u8]) -> ::core::result::Result<Self, DecodeError> {
        let bytes = cdr::transcode_key::<T>(bytes, Endianness::Big, Endianness::Big)?;
        Ok(KeyBytes { bytes, _type: PhantomData })
    }
}

impl<T> KeyBytes<T> {
    pub fn as_bytes(&self) -> &[u8] {
        &self.bytes
    }
}

// The key's traits compare the bytes alone (a derive would ask the same of T).
impl<T> Clone for KeyBytes<T> {
    fn clone(&self) -> Self {
        KeyBytes { bytes: self.bytes.clone(), _type: PhantomData }
    }
}

impl<T> PartialEq for KeyBytes<T> {
    fn eq(&self, other: &Self) -> bool {
        self.bytes == other.bytes
    }
}

impl<T> Eq for KeyBytes<T> {}

impl<T> PartialOrd for KeyBytes<T> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl<T> Ord for KeyBytes<T> {
    fn cmp(&self, other: &Self) -> Ordering {
        self.bytes.cmp(&other.bytes)
    }
}

impl<T> Hash for KeyBytes<T> {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.bytes.hash(state);
    }
}

impl<T> fmt::Debug for KeyBytes<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_tuple("KeyBytes").field(&self.bytes).finish()
    }
}

/// The bytes as they are (no length): RustDDS hashes what this writes.
impl<T> ::serde::Serialize for KeyBytes<T> {
    fn serialize<S: ::serde::Serializer>(&self, s: S) -> ::core::result::Result<S::Ok, S::Error> {
        use ::serde::ser::SerializeTuple;
        let mut t = s.serialize_tuple(self.bytes.len())?;
        for b in &self.bytes {
            t.serialize_element(b)?;
        }
        t.end()
    }
}

impl<T: Cdr> CdrEncodingSize for KeyBytes<T> {
    fn cdr_encoding_max_size() -> CdrEncodingMaxSize {
        if T::KEY_MAX_SIZE <= 16 {
            CdrEncodingMaxSize::Bytes(T::KEY_MAX_SIZE)
        } else {
            CdrEncodingMaxSize::Unbounded
        }
    }
}

impl<T: Cdr> ::rustdds::Key for KeyBytes<T> {}

macro_rules! keyed {
    ($($t:ty),* $(,)?) => {$(
        impl Keyed for $t {
            type K = KeyBytes<$t>;
            fn key(&self) -> KeyBytes<$t> {
                KeyBytes::of(self)
            }
        }
    )*};
}

/// RustDDS's serializer and deserializer adapters for `T`, forwarding to the codec:
/// samples go out as CDR_LE, either byte order comes in (RustDDS keeps the 4-byte
/// encapsulation header apart from the body).
pub struct CdrAdapter<T>(PhantomData<fn() -> T>);

impl<T: Cdr> no_key::SerializerAdapter<T> for CdrAdapter<T> {
    type Error = EncodeError;

    fn output_encoding() -> RepresentationIdentifier {
        RepresentationIdentifier::CDR_LE
    }

    fn to_bytes(value: &T) -> ::core::result::Result<Bytes, EncodeError> {
        Ok(Bytes::from(cdr::serialize(value, Endianness::Little)?).slice(4..))
    }
}

impl<T: TopicType> with_key::SerializerAdapter<T> for CdrAdapter<T> {
    /// A serialized key (a dispose) is in the samples' byte order.
    fn key_to_bytes(key: &KeyBytes<T>) -> ::core::result::Result<Bytes, EncodeError> {
        cdr::transcode_key::<T>(key.as_bytes(), Endianness::Big, Endianness::Little)
            .map(Bytes::from)
            .map_err(|e| EncodeError { message: e.to_string() })
    }
}

impl<T: Cdr> no_key::DeserializerAdapter<T> for CdrAdapter<T> {
    type Error = DecodeError;
    type Decoded = T;

    fn supported_encodings() -> &'static [RepresentationIdentifier] {
        &[RepresentationIdentifier::CDR_LE, RepresentationIdentifier::CDR_BE]
    }

    fn transform_decoded(decoded: T) -> T {
        decoded
    }
}

impl<T: TopicType> with_key::DeserializerAdapter<T> for CdrAdapter<T> {
    type DecodedKey = KeyBytes<T>;

    fn transform_decoded_key(key: KeyBytes<T>) -> KeyBytes<T> {
        key
    }
}

impl<T: Cdr> no_key::DefaultDecoder<T> for CdrAdapter<T> {
    type Decoder = CdrDecoder<T>;
    const DECODER: CdrDecoder<T> = CdrDecoder(PhantomData);
}

impl<T: TopicType> with_key::DefaultDecoder<T> for CdrAdapter<T> {
    type Decoder = CdrDecoder<T>;
    const DECODER: CdrDecoder<T> = CdrDecoder(PhantomData);
}

/// Decodes a sample body (or a serialized key) of `T` with the codec: untrusted bytes give
/// a `DecodeError`, never a panic.
pub struct CdrDecoder<T>(PhantomData<fn() -> T>);

impl<T> Clone for CdrDecoder<T> {
    fn clone(&self) -> Self {
        CdrDecoder(PhantomData)
    }
}

fn order(encoding: RepresentationIdentifier) -> Endianness {
    if encoding == RepresentationIdentifier::CDR_LE {
        Endianness::Little
    } else {
        Endianness::Big
    }
}

impl<'de, T: Cdr> no_key::Decode<'de, T> for CdrDecoder<T> {
    type Error = DecodeError;

    fn decode_bytes(self, input: &'de [u8], encoding: RepresentationIdentifier) -> ::core::result::Result<T, DecodeError> {
        // the codec reads the encapsulation header too (a copy: a cheap one beside decoding)
        let mut data = ::std::vec::Vec::with_capacity(4 + input.len());
        data.extend_from_slice(&[0, u8::from(order(encoding) == Endianness::Little), 0, 0]);
        data.extend_from_slice(input);
        cdr::deserialize(&data)
    }
}

impl<'de, T: TopicType> with_key::Decode<'de, T, KeyBytes<T>> for CdrDecoder<T> {
    fn decode_key_bytes(self, input: &'de [u8], encoding: RepresentationIdentifier)
                        -> ::core::result::Result<KeyBytes<T>, DecodeError> {
        let bytes = cdr::transcode_key::<T>(input, order(encoding), Endianness::Big)?;
        Ok(KeyBytes { bytes, _type: PhantomData })
    }
}

/// WITH_KEY for a type with key members, else NO_KEY.
pub fn topic_kind<T: Cdr>() -> TopicKind {
    if T::KEYED {
        TopicKind::WithKey
    } else {
        TopicKind::NoKey
    }
}

/// The topic `name` carrying `T`: its DDS type name `T::TYPE_NAME`, its kind `topic_kind::<T>()`.
pub fn create_topic<T: TopicType>(dp: &DomainParticipant, name: &str, qos: &QosPolicies) -> CreateResult<Topic> {
    dp.create_topic(name.to_owned(), T::TYPE_NAME.to_owned(), qos, topic_kind::<T>())
}

/// A writer of either kind.
pub enum Writer<T: TopicType> {
    Keyed(KeyedWriter<T>),
    NoKey(NoKeyWriter<T>),
}

impl<T: TopicType> Writer<T> {
    pub fn write(&self, value: T, source_timestamp: Option<Timestamp>) -> WriteResult<(), T> {
        match self {
            Writer::Keyed(w) => w.write(value, source_timestamp),
            Writer::NoKey(w) => w.write(value, source_timestamp),
        }
    }
}

/// A reader of either kind.
pub enum Reader<T: TopicType> {
    Keyed(KeyedReader<T>),
    NoKey(NoKeyReader<T>),
}

impl<T: TopicType> Reader<T> {
    /// The next sample not yet taken; a keyed reader passes over disposes (they carry no value).
    pub fn take_next(&mut self) -> ReadResult<Option<T>> {
        match self {
            Reader::Keyed(r) => loop {
                match r.take_next_sample()? {
                    Some(s) => {
                        if let Some(v) = s.into_value().value() {
                            return Ok(Some(v));
                        }
                    }
                    None => return Ok(None),
                }
            },
            Reader::NoKey(r) => Ok(r.take_next_sample()?.map(|s| s.into_value())),
        }
    }
}

/// A writer of `T` on `topic` (of `T`'s kind, see `create_topic`).
pub fn create_writer<T: TopicType>(publisher: &Publisher, topic: &Topic, qos: Option<QosPolicies>) -> CreateResult<Writer<T>> {
    Ok(if T::KEYED {
        Writer::Keyed(publisher.create_datawriter::<T, CdrAdapter<T>>(topic, qos)?)
    } else {
        Writer::NoKey(publisher.create_datawriter_no_key::<T, CdrAdapter<T>>(topic, qos)?)
    })
}

/// A reader of `T` on `topic` (of `T`'s kind, see `create_topic`).
pub fn create_reader<T: TopicType>(subscriber: &Subscriber, topic: &Topic, qos: Option<QosPolicies>) -> CreateResult<Reader<T>> {
    Ok(if T::KEYED {
        Reader::Keyed(subscriber.create_datareader::<T, CdrAdapter<T>>(topic, qos)?)
    } else {
        Reader::NoKey(subscriber.create_datareader_no_key::<T, CdrAdapter<T>>(topic, qos)?)
    })
}
