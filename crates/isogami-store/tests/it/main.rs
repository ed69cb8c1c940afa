//! The integration tests of `isogami-store`, one test binary: every file here is a module (one
//! link instead of one per file; `cargo test -p isogami-store --test it MODULE::` runs one).

mod common;
mod exploration;
mod migrate;
mod motions;
mod query;
mod roundtrip;
mod safety;
mod shards;
mod twins;
mod unit_memory;
