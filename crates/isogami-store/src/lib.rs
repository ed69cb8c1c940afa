//! The design database: the only code in isogami that knows SQL.
//!
//! An embedded SQLite file holds the exploration's results: one row per finished work unit
//! (with per-stage counts and times), one row per kept design (summary columns for filtering
//! and sorting, plus the full deployment report and linkage analysis as JSON), and the tool
//! version and settings the run used, so any row can be regenerated. Every work unit is
//! written in one transaction: a run killed at any moment keeps exactly the units it had
//! committed, and a resumed run skips them. The schema carries a version; a file with
//! another version is refused rather than misread.
//!
//! Plain records in and out; this crate does not know how designs are found or deployed.

mod error;
mod merge;
mod records;
mod schema;
mod stats;
mod store;

pub use error::{StoreError, StoreResult};
pub use merge::MergeReport;
pub use records::{DesignRecord, StageCount, WorkUnitRecord};
pub use schema::SCHEMA_VERSION;
pub use stats::{DbStats, FamilyStats};
pub use store::Store;
