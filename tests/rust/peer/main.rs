//! Live interop peer on RustDDS through a generated crate (`gen`, feature `dds`: its
//! `dds` module is the whole RustDDS glue).
//!   peer pub DOMAIN SECONDS   publish each sample of stdin every 200 ms for SECONDS
//!   peer sub DOMAIN SECONDS   read until every topic of stdin delivered its sample
//! stdin: "topic type profile le_hex" lines (the sample is the decoded vector). The sub
//! prints "ok TOPIC" / "MISMATCH TOPIC" per topic (a mismatch's values as JSON on stderr,
//! with the IDL's names) and exits 0 when all are equal. RTPS stays on 127.0.0.1
//! (`with_only_networks`); RustDDS 0.15 has no Partition QoS: its endpoints are in the
//! default partition.

use std::net::IpAddr;
use std::time::{Duration, Instant};

use gen::cdr::deserialize;
use gen::dds::{self, rustdds};
use gen::TopicType;
use rustdds::{policy, DomainParticipant, DomainParticipantBuilder, Publisher, QosPolicyBuilder, Subscriber};

trait Endpoint {
    fn topic(&self) -> &str;
    fn write(&self);
    /// 0 nothing yet, 1 equal, 2 different
    fn take(&mut self) -> i32;
}

struct Writer<T: TopicType> {
    topic: String,
    w: dds::Writer<T>,
    value: T,
}

struct Reader<T: TopicType> {
    topic: String,
    r: dds::Reader<T>,
    value: T,
}

impl<T: TopicType> Endpoint for Writer<T> {
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

fn json<T: TopicType>(v: &T) -> String {
    serde_json::to_string(v).unwrap_or_else(|e| e.to_string())
}

impl<T: TopicType> Endpoint for Reader<T> {
    fn topic(&self) -> &str {
        &self.topic
    }
    fn write(&self) {}
    fn take(&mut self) -> i32 {
        let mut result = 0;
        while let Ok(Some(got)) = self.r.take_next() {
            result = if got == self.value { 1 } else { 2 };
            if result == 2 {
                eprintln!("{}: got {}\n  want {}", self.topic, json(&got), json(&self.value));
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
    fn visit<T: TopicType>(&mut self) {
        for (topic, _, bytes) in self.lines.iter().filter(|l| l.1 == T::TYPE_NAME) {
            let value: T = deserialize(bytes).expect("vector decodes");
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
            // an asset topic through the asset's table (refused for another type), the rest by name
            let t = if gen::asset::TOPICS.iter().any(|a| a.topic == topic) {
                dds::asset_topic::<T>(self.dp, topic, &qos).expect("asset topic")
            } else {
                dds::create_topic::<T>(self.dp, topic, &qos).expect("topic")
            };
            let ep: Box<dyn Endpoint> = if self.pub_mode {
                let w = dds::create_writer::<T>(self.publisher, &t, Some(qos)).expect("writer");
                Box::new(Writer { topic: topic.clone(), w, value })
            } else {
                let r = dds::create_reader::<T>(self.subscriber, &t, Some(qos)).expect("reader");
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
