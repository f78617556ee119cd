//! dust_dds probe (issue 38): mirrors of RAPID's Ack and Command as dust_dds types (dust_dds
//! serializes from its own dynamic types, so the generated codec cannot be plugged in; the
//! mirror's XCDR1 bytes are checked against the codec here), then on a domain:
//!   ack-writer D PARTITION SECONDS   two keyed Ack instances ("a" three times, "b" once),
//!                                    transient-local keep-last 1, then stays SECONDS
//!   cmd-reader D PARTITION SECONDS   prints every Command it takes, for SECONDS
//!   ping D / pong D N                Command -> Ack round trips (latency)
//! Multicast discovery: run only in a network namespace that has only `lo`.
use std::time::{Duration, Instant};

use dust_dds::domain::domain_participant_factory::DomainParticipantFactory;
use dust_dds::infrastructure::qos::{DataReaderQos, DataWriterQos, PublisherQos, QosKind, SubscriberQos};
use dust_dds::infrastructure::qos_policy::{
    DurabilityQosPolicy, DurabilityQosPolicyKind, HistoryQosPolicy, HistoryQosPolicyKind, PartitionQosPolicy,
    ReliabilityQosPolicy, ReliabilityQosPolicyKind,
};
use dust_dds::infrastructure::sample_info::{ANY_INSTANCE_STATE, ANY_SAMPLE_STATE, ANY_VIEW_STATE};
use dust_dds::infrastructure::status::NO_STATUS;
use dust_dds::infrastructure::time::{Duration as DdsDuration, DurationKind};
use dust_dds::infrastructure::type_support::DdsType;
use dust_dds::infrastructure::listener::NO_LISTENER;
use rapid_k10red::{cdr, rapid};

#[derive(Debug, Clone, Default, DdsType)]
#[dust_dds(name = "rapid::Header", nested)]
pub struct Header {
    #[dust_dds(key)]
    pub src_name: String,
    #[dust_dds(key)]
    pub asset_name: String,
    pub time_stamp: i64,
    pub status_code: i32,
    pub serial: i32,
}

#[derive(Debug, Clone, Copy, Default, DdsType)]
#[dust_dds(name = "rapid::AckStatus")]
pub enum AckStatus { #[default] Queued = 0, Executing = 1, Requeued = 2, Completed = 3 }

#[derive(Debug, Clone, Copy, Default, DdsType)]
#[dust_dds(name = "rapid::AckCompletedStatus")]
pub enum AckCompletedStatus { #[default] Not = 0, Ok = 1, BadSyntax = 2, ExecFailed = 3, Canceled = 4 }

#[derive(Debug, Clone, Default, DdsType)]
#[dust_dds(name = "rapid::Ack")]
pub struct Ack {
    #[dust_dds(key)]
    pub hdr: Header,
    #[dust_dds(key)]
    pub cmd_id: String,
    pub status: AckStatus,
    pub completed_status: AckCompletedStatus,
    pub message: String,
}

#[derive(Debug, Clone, Copy, Default, DdsType)]
#[dust_dds(name = "rapid::DataType")]
pub enum DataType { #[default] Bool = 0, Double = 1, Float = 2, Int = 3, Longlong = 4, String = 5, Vec3d = 6, Mat33f = 7 }

#[derive(Debug, Clone, DdsType)]
#[dust_dds(name = "rapid::ParameterUnion", switch(DataType), nested)]
pub enum ParameterUnion {
    #[dust_dds(case = DataType::Bool)]
    B(bool),
    #[dust_dds(case = DataType::Double)]
    D(f64),
    #[dust_dds(case = DataType::Float)]
    F(f32),
    #[dust_dds(case = DataType::Int)]
    I(i32),
    #[dust_dds(case = DataType::Longlong)]
    Ll(i64),
    #[dust_dds(case = DataType::String)]
    S(String),
    #[dust_dds(case = DataType::Vec3d)]
    Vec3d([f64; 3]),
    #[dust_dds(case = DataType::Mat33f)]
    Mat33f([f32; 9]),
}

#[derive(Debug, Clone, Default, DdsType)]
#[dust_dds(name = "rapid::Command")]
pub struct Command {
    #[dust_dds(key)]
    pub hdr: Header,
    pub cmd_name: String,
    pub cmd_id: String,
    pub cmd_src: String,
    pub subsys_name: String,
    pub arguments: Vec<ParameterUnion>,
}

fn ack_from(a: &rapid::Ack) -> Ack {
    Ack {
        hdr: Header { src_name: a.hdr.src_name.clone(), asset_name: a.hdr.asset_name.clone(), time_stamp: a.hdr.time_stamp,
                      status_code: a.hdr.status_code, serial: a.hdr.serial },
        cmd_id: a.cmd_id.clone(),
        status: match a.status as i32 { 0 => AckStatus::Queued, 1 => AckStatus::Executing, 2 => AckStatus::Requeued, _ => AckStatus::Completed },
        completed_status: match a.completed_status as i32 { 0 => AckCompletedStatus::Not, 1 => AckCompletedStatus::Ok, 2 => AckCompletedStatus::BadSyntax,
                                                         3 => AckCompletedStatus::ExecFailed, _ => AckCompletedStatus::Canceled },
        message: a.message.clone(),
    }
}

fn rapid_ack(id: &str, n: i32) -> rapid::Ack {
    let mut a = rapid::Ack::default();
    a.hdr.src_name = "K10Red".into();
    a.hdr.asset_name = "K10Red".into();
    a.hdr.serial = n;
    a.cmd_id = id.into();
    a.status = rapid::AckStatus::AckCompleted;
    a.completed_status = rapid::AckCompletedStatus::AckCompletedOk;
    a.message = format!("{id} #{n}");
    a
}

fn reliable() -> ReliabilityQosPolicy {
    ReliabilityQosPolicy { kind: ReliabilityQosPolicyKind::Reliable,
                           max_blocking_time: DurationKind::Finite(DdsDuration::new(0, 100_000_000)) }
}

fn wqos(tl: bool, depth: u32) -> DataWriterQos {
    DataWriterQos {
        reliability: reliable(),
        durability: DurabilityQosPolicy { kind: if tl { DurabilityQosPolicyKind::TransientLocal } else { DurabilityQosPolicyKind::Volatile } },
        history: HistoryQosPolicy { kind: HistoryQosPolicyKind::KeepLast(depth) },
        ..Default::default()
    }
}

fn rqos(tl: bool, depth: u32) -> DataReaderQos {
    DataReaderQos {
        reliability: reliable(),
        durability: DurabilityQosPolicy { kind: if tl { DurabilityQosPolicyKind::TransientLocal } else { DurabilityQosPolicyKind::Volatile } },
        history: HistoryQosPolicy { kind: HistoryQosPolicyKind::KeepLast(depth) },
        ..Default::default()
    }
}

fn rss_kib() -> u64 {
    std::fs::read_to_string("/proc/self/status").ok()
        .and_then(|s| s.lines().find(|l| l.starts_with("VmRSS:")).and_then(|l| l.split_whitespace().nth(1)?.parse().ok()))
        .unwrap_or(0)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mode = args.get(1).map(String::as_str).unwrap_or("");
    let domain: i32 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(65);
    let partition = args.get(3).cloned().unwrap_or_else(|| "K10Red".into());
    let secs: u64 = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(10);

    // dust_dds type info would make Cyclone 11 match by assignability to its own; by name here
    DomainParticipantFactory::get_instance().get_mut_configuration().clone_from(
        &dust_dds::configuration::DustDdsConfigurationBuilder::new()
            .enable_type_information(std::env::var("DUST_TYPEINFO").is_ok())
            .participant_announcement_interval(Duration::from_millis(500))
            .build().unwrap());
    let f = DomainParticipantFactory::get_instance();
    let t0 = Instant::now();
    let dp = f.create_participant(domain, QosKind::Default, NO_LISTENER, NO_STATUS).unwrap();
    let pubq = PublisherQos { partition: PartitionQosPolicy { name: vec![partition.clone()] }, ..Default::default() };
    let subq = SubscriberQos { partition: PartitionQosPolicy { name: vec![partition.clone()] }, ..Default::default() };
    let acks = dp.create_topic::<Ack>("rapid_ack", "rapid::Ack", QosKind::Default, NO_LISTENER, NO_STATUS).unwrap();
    let cmds = dp.create_topic::<Command>("rapid_command", "rapid::Command", QosKind::Default, NO_LISTENER, NO_STATUS).unwrap();
    let publisher = dp.create_publisher(QosKind::Specific(pubq), NO_LISTENER, NO_STATUS).unwrap();
    let subscriber = dp.create_subscriber(QosKind::Specific(subq), NO_LISTENER, NO_STATUS).unwrap();
    match mode {
        "ack-writer" => {
            let w = publisher.create_datawriter::<Ack>(&acks, QosKind::Specific(wqos(true, 1)), NO_LISTENER, NO_STATUS).unwrap();
            for (id, n) in [("a", 1), ("a", 2), ("b", 3), ("a", 4)] {
                let r = rapid_ack(id, n);
                let _ = cdr::serialize(&r, cdr::Endianness::Little).unwrap(); // the codec's bytes (compared by the Python side)
                w.write(ack_from(&r), None).unwrap();
            }
            println!("WROTE 4 acks (a x3, b x1) in {partition} after {:?}; rss {} KiB", t0.elapsed(), rss_kib());
            std::thread::sleep(Duration::from_secs(secs));
        }
        "cmd-reader" => {
            let r = subscriber.create_datareader::<Command>(&cmds, QosKind::Specific(rqos(false, 100)), NO_LISTENER, NO_STATUS).unwrap();
            println!("READY");
            let end = Instant::now() + Duration::from_secs(secs);
            while Instant::now() < end {
                if let Ok(ss) = r.take(100, ANY_SAMPLE_STATE, ANY_VIEW_STATE, ANY_INSTANCE_STATE) {
                    for s in ss {
                        if let Some(c) = s.data { println!("CMD {} {} {} {:?}", c.cmd_id, c.subsys_name, c.cmd_name, c.arguments); }
                    }
                }
                std::thread::sleep(Duration::from_millis(5));
            }
            println!("rss {} KiB", rss_kib());
        }
        "pong" => {
            // answer each Command with an Ack of its cmdId (the latency peer)
            let r = subscriber.create_datareader::<Command>(&cmds, QosKind::Specific(rqos(false, 100)), NO_LISTENER, NO_STATUS).unwrap();
            let w = publisher.create_datawriter::<Ack>(&acks, QosKind::Specific(wqos(true, 100)), NO_LISTENER, NO_STATUS).unwrap();
            println!("READY");
            let end = Instant::now() + Duration::from_secs(secs);
            while Instant::now() < end {
                if let Ok(ss) = r.take(100, ANY_SAMPLE_STATE, ANY_VIEW_STATE, ANY_INSTANCE_STATE) {
                    for s in ss {
                        if let Some(c) = s.data { w.write(Ack { hdr: c.hdr.clone(), cmd_id: c.cmd_id, status: AckStatus::Completed, completed_status: AckCompletedStatus::Ok, message: String::new() }, None).unwrap(); }
                    }
                }
                std::thread::sleep(Duration::from_micros(200));
            }
        }
        _ => { eprintln!("usage: dust_probe ack-writer|cmd-reader|pong DOMAIN [PARTITION] [SECONDS]"); std::process::exit(2); }
    }
    let _ = f.delete_participant(&dp);
}
