//! The RAPID asset runtime's protocol core for Rust: what an asset does with the commands it is
//! sent (intake and validation in soraCore's order, acks, the queue with every action, access
//! control, the command window, the restart journal), apart from any DDS layer, as the C++
//! runtime's core is (runtime/cpp). The Python runtime (runtime/rapid_runtime) is the
//! reference; the protocol specification's cases (runtime/spec) are replayed by all three
//! (tests/spec_cases.rs here).
//!
//! A DDS layer reads Commands into [`Cmd`]s for [`CommandManager::receive`] and writes what the
//! manager hands its [`Outbox`]; the asset's code implements [`Handlers`].

pub mod access;
pub mod args;
#[cfg(feature = "test-breaks")]
pub mod breaks;
pub mod command;
pub mod configs;
pub mod handlers;
pub mod intake;
pub mod journal;
pub mod manager;
pub mod stream;
pub mod tables;
pub mod text;
pub mod texts;
pub mod validate;
pub mod value;
pub mod vocabulary;

pub use command::Cmd;
pub use configs::Serials;
pub use handlers::{Context, Handlers, Outcome};
pub use journal::{Journal, JournalEntry, Recovered};
pub use manager::{CommandManager, Options, Outbox, Record};
pub use tables::{AccessRule, AccessSpec, CommandRef, CommandSpec, Param, Subsystem, SubsystemType, Tables};
pub use value::{DataType, Value};
pub use vocabulary::{AckStatus, Completion, QueueAction, RecordResult, RecordStatus};
