//! Live interop peer on RustDDS with a generated crate's types (`gen`) and codec.
//!   peer pub DOMAIN SECONDS   publish each sample of stdin every 200 ms for SECONDS
//!   peer sub DOMAIN SECONDS   read until every topic of stdin delivered its sample
//! stdin: "topic type profile le_hex" lines (the sample is the decoded vector). The sub
//! prints "ok TOPIC" / "MISMATCH TOPIC" per topic and exits 0 when all are equal.
//! RTPS stays on 127.0.0.1 (`with_only_networks`). RustDDS 0.15 has no Partition QoS:
//! its endpoints are in the default partition. Keyed RAPID types use WITH_KEY endpoints
//! (Cyclone does not match a NO_KEY writer with its keyed reader).

use std::marker::PhantomData;
use std::net::IpAddr;
use std::time::{Duration, Instant};

use gen::cdr::{deserialize, key_bytes, serialize, Cdr, Endianness};
use rustdds::bytes::Bytes;
use rustdds::cdr_encoding_size::{CdrEncodingMaxSize, CdrEncodingSize};
use rustdds::{no_key, policy, with_key, DomainParticipant, DomainParticipantBuilder, Key, Keyed, Publisher,
              QosPolicyBuilder, RepresentationIdentifier, Subscriber, TopicKind};

/// A sample of a generated type: RustDDS's `Keyed` on a foreign type needs a wrapper.
#[derive(Debug, Clone, PartialEq)]
struct Sample<T>(T);

/// The key members in big-endian CDR (`gen::cdr::key_bytes`); RustDDS hashes them with
/// MD5 (an unbounded key), as RAPID's string keys require.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash)]
struct KeyBytes(Vec<u8>);

impl serde::Serialize for KeyBytes {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeTuple;
        let mut t = s.serialize_tuple(self.0.len())?;
        for b in &self.0 {
            t.serialize_element(b)?;
        }
        t.end()
    }
}

impl CdrEncodingSize for KeyBytes {
    fn cdr_encoding_max_size() -> CdrEncodingMaxSize {
        CdrEncodingMaxSize::Unbounded
    }
}

impl Key for KeyBytes {}

impl<T: Cdr> Keyed for Sample<T> {
    type K = KeyBytes;
    fn key(&self) -> KeyBytes {
        KeyBytes(key_bytes(&self.0).unwrap_or_default())
    }
}

/// RustDDS <-> the generated codec (the 4-byte encapsulation header is RustDDS's business).
struct Adapter<T>(PhantomData<T>);

#[derive(Debug)]
struct AdaptError(String);

impl std::fmt::Display for AdaptError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for AdaptError {}

impl<T: Cdr> no_key::SerializerAdapter<Sample<T>> for Adapter<T> {
    type Error = AdaptError;
    fn output_encoding() -> RepresentationIdentifier {
        RepresentationIdentifier::CDR_LE
    }
    fn to_bytes(value: &Sample<T>) -> Result<Bytes, AdaptError> {
        let v = serialize(&value.0, Endianness::Little).map_err(|e| AdaptError(e.to_string()))?;
        Ok(Bytes::copy_from_slice(&v[4..]))
    }
}

impl<T: Cdr> with_key::SerializerAdapter<Sample<T>> for Adapter<T> {
    fn key_to_bytes(key: &KeyBytes) -> Result<Bytes, AdaptError> {
        Ok(Bytes::copy_from_slice(&key.0))
    }
}

impl<T: Cdr> no_key::DeserializerAdapter<Sample<T>> for Adapter<T> {
    type Error = AdaptError;
    type Decoded = Sample<T>;
    fn supported_encodings() -> &'static [RepresentationIdentifier] {
        &[RepresentationIdentifier::CDR_LE, RepresentationIdentifier::CDR_BE]
    }
    fn transform_decoded(decoded: Sample<T>) -> Sample<T> {
        decoded
    }
}

impl<T: Cdr> with_key::DeserializerAdapter<Sample<T>> for Adapter<T> {
    type DecodedKey = KeyBytes;
    fn transform_decoded_key(key: KeyBytes) -> KeyBytes {
        key
    }
}

struct Decoder<T>(PhantomData<T>);

impl<T> Clone for Decoder<T> {
    fn clone(&self) -> Self {
        Decoder(PhantomData)
    }
}

impl<'de, T: Cdr> no_key::Decode<'de, Sample<T>> for Decoder<T> {
    type Error = AdaptError;
    fn decode_bytes(self, input: &'de [u8], encoding: RepresentationIdentifier) -> Result<Sample<T>, AdaptError> {
        let little = encoding == RepresentationIdentifier::CDR_LE;
        let mut data = vec![0, u8::from(little), 0, 0];
        data.extend_from_slice(input);
        deserialize(&data).map(Sample).map_err(|e| AdaptError(e.to_string()))
    }
}

impl<'de, T: Cdr> with_key::Decode<'de, Sample<T>, KeyBytes> for Decoder<T> {
    fn decode_key_bytes(self, input: &'de [u8], _encoding: RepresentationIdentifier) -> Result<KeyBytes, AdaptError> {
        Ok(KeyBytes(input.to_vec()))
    }
}

impl<T: Cdr> no_key::DefaultDecoder<Sample<T>> for Adapter<T> {
    type Decoder = Decoder<T>;
    const DECODER: Decoder<T> = Decoder(PhantomData);
}

impl<T: Cdr> with_key::DefaultDecoder<Sample<T>> for Adapter<T> {
    type Decoder = Decoder<T>;
    const DECODER: Decoder<T> = Decoder(PhantomData);
}

trait Endpoint {
    fn topic(&self) -> &str;
    fn write(&self);
    /// 0 nothing yet, 1 equal, 2 different
    fn take(&mut self) -> i32;
}

struct Writer<T: Cdr + Clone + 'static> {
    topic: String,
    w: with_key::DataWriter<Sample<T>, Adapter<T>>,
    value: Sample<T>,
}

struct Reader<T: Cdr + PartialEq + 'static> {
    topic: String,
    r: with_key::DataReader<Sample<T>, Adapter<T>>,
    value: Sample<T>,
}

impl<T: Cdr + Clone + 'static> Endpoint for Writer<T> {
    fn topic(&self) -> &str {
        &self.topic
    }
    fn write(&self) {
        let _ = self.w.write(self.value.clone(), None);
    }
    fn take(&mut self) -> i32 {
        0
    }
}

impl<T: Cdr + PartialEq + std::fmt::Debug + 'static> Endpoint for Reader<T> {
    fn topic(&self) -> &str {
        &self.topic
    }
    fn write(&self) {}
    fn take(&mut self) -> i32 {
        let mut result = 0;
        while let Ok(Some(s)) = self.r.take_next_sample() {
            let Some(got) = s.into_value().value() else { continue }; // a dispose carries no value
            result = if got == self.value { 1 } else { 2 };
            if result == 2 {
                eprintln!("{}: got {:?}", self.topic, got);
                break;
            }
        }
        result
    }
}

struct Make<'a> {
    dp: &'a DomainParticipant,
    publisher: &'a Publisher,
    subscriber: &'a Subscriber,
    pub_mode: bool,
    lines: &'a [(String, String, Vec<u8>)],
    out: Vec<Box<dyn Endpoint>>,
}

impl gen::TypeVisitor for Make<'_> {
    fn visit<T>(&mut self)
    where
        T: Cdr + std::fmt::Debug + Clone + PartialEq + Default + 'static,
    {
        for (topic, type_name, bytes) in self.lines.iter().filter(|l| l.1 == T::TYPE_NAME) {
            let value = Sample::<T>(deserialize(bytes).expect("vector decodes"));
            let kind = if T::KEYED { TopicKind::WithKey } else { TopicKind::NoKey };
            // the writer offers the most (reliable, transient-local), the reader asks the
            // least: they match every RAPID profile on the other side
            let qos = if self.pub_mode {
                QosPolicyBuilder::new()
                    .reliable(rustdds::Duration::from_millis(100))
                    .durability(policy::Durability::TransientLocal)
                    .history(policy::History::KeepLast { depth: 1 })
                    .build()
            } else {
                QosPolicyBuilder::new().best_effort().durability(policy::Durability::Volatile)
                    .history(policy::History::KeepLast { depth: 16 }).build()
            };
            let t = self.dp.create_topic(topic.clone(), type_name.clone(), &qos, kind).expect("topic");
            let ep: Box<dyn Endpoint> = if self.pub_mode {
                let w = self.publisher.create_datawriter::<Sample<T>, Adapter<T>>(&t, Some(qos)).expect("writer");
                Box::new(Writer { topic: topic.clone(), w, value })
            } else {
                let r = self.subscriber.create_datareader::<Sample<T>, Adapter<T>>(&t, Some(qos)).expect("reader");
                Box::new(Reader { topic: topic.clone(), r, value })
            };
            self.out.push(ep);
        }
    }
}

fn unhex(s: &str) -> Vec<u8> {
    (0..s.len() / 2).map(|i| u8::from_str_radix(&s[2 * i..2 * i + 2], 16).expect("hex")).collect()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (pub_mode, domain, seconds) = (args[1] == "pub", args[2].parse::<u16>().unwrap(), args[3].parse::<f64>().unwrap());
    let mut text = String::new();
    std::io::Read::read_to_string(&mut std::io::stdin(), &mut text).unwrap();
    let lines: Vec<(String, String, Vec<u8>)> = text
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            (f[0].to_owned(), f[1].to_owned(), unhex(f[3]))
        })
        .collect();
    let dp = DomainParticipantBuilder::new(domain)
        .with_only_networks([IpAddr::from([127, 0, 0, 1])])
        .build()
        .expect("participant");
    let qos = QosPolicyBuilder::new().build();
    let publisher = dp.create_publisher(&qos).unwrap();
    let subscriber = dp.create_subscriber(&qos).unwrap();
    let mut make = Make { dp: &dp, publisher: &publisher, subscriber: &subscriber, pub_mode, lines: &lines, out: Vec::new() };
    gen::visit_types(&mut make);
    let mut eps = make.out;
    assert_eq!(eps.len(), lines.len(), "a topic's type is not in the crate");
    let end = Instant::now() + Duration::from_secs_f64(seconds);
    let mut done = std::collections::HashSet::new();
    let mut bad = false;
    while Instant::now() < end {
        for ep in eps.iter_mut() {
            if pub_mode {
                ep.write();
            } else if !done.contains(ep.topic()) {
                match ep.take() {
                    1 => println!("ok {}", ep.topic()),
                    2 => {
                        println!("MISMATCH {}", ep.topic());
                        bad = true;
                    }
                    _ => continue,
                }
                done.insert(ep.topic().to_owned());
            }
        }
        if !pub_mode && done.len() == eps.len() {
            std::process::exit(i32::from(bad));
        }
        std::thread::sleep(Duration::from_millis(if pub_mode { 200 } else { 20 }));
    }
    std::process::exit(if pub_mode { 0 } else { 1 });
}
