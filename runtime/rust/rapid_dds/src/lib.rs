//! The RAPID asset runtime's DDS layer for Rust (issue 38, second stage), on Cyclone DDS's C
//! library through cyclors (docs/rust-backend.md, "Choosing the DDS stack"): a participant on
//! the asset's domain, commands read from the asset's partition into
//! [`rapid_runtime::CommandManager`], its acks, QueueState and AccessControlState written back,
//! the asset's configs published transient-local. Samples travel as their CDR bytes (cyclors'
//! blob topics), encoded and decoded by the generated codec.

#[cfg(feature = "alloc-count")]
pub mod alloc_count;
pub mod bridge;
#[cfg(feature = "test-breaks")]
pub mod breaks;
pub mod client;
pub mod cmd;
pub mod configs;
pub mod convert;
pub mod dds;
pub mod images;
pub mod keyed;
mod md5;
pub mod outbox;
pub mod pooled;
pub mod stream;
pub mod stream_sim;
pub mod tables_json;
pub mod telemetry;

pub use dds::{Participant, Reader, Topic, Writer};
pub use outbox::DdsOutbox;
