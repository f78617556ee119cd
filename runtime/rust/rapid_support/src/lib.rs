//! The fixed modules of every generated RAPID Rust crate, compiled here as a crate of their
//! own so that they are checked as code (`cargo clippy --all-features -- -D warnings`;
//! tests/rust/test_support_crate.py runs the default features, the generated crates' tests
//! every feature). rapidgen copies `cdr.rs`, `serde_arrays.rs` and `dds.rs` into each crate
//! it writes (rapidgen/backends/support.py): a types crate depends on nothing. This file is
//! not copied; it stands in for a generated crate's root (`TopicType`).

pub mod cdr;
#[cfg(feature = "dds")]
// a generated crate invokes `keyed!` (which uses `Keyed`) with its types after the module's text
#[allow(unused_macros, unused_imports)]
pub mod dds;
#[cfg(feature = "serde")]
pub mod serde_arrays;

/// A generated crate's topic type (lib.rs.j2), as `dds` needs it.
#[cfg(feature = "dds")]
pub trait TopicType:
    cdr::Cdr + ::core::fmt::Debug + ::core::clone::Clone + ::core::cmp::PartialEq + ::core::default::Default + 'static
    + ::serde::Serialize + ::serde::de::DeserializeOwned + ::rustdds::Keyed<K = dds::KeyBytes<Self>>
{
}
