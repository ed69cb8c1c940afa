//! The design database: the only code in isogami that knows SQL.
//!
//! An embedded SQLite file holds the exploration's results and the designs users save: one
//! row per finished work unit (with per-stage counts and times), one row per design (every
//! column a catalogue filters, sorts, facets or plots by) with its full deployment report and
//! linkage analysis as JSON beside it, and the tool version and settings of the run, so any
//! row can be regenerated.
//!
//! Safety, in order of what can go wrong:
//! - **Reading never writes.** [`Store::open_read`] opens read-only and creates nothing
//!   beside the file (the database uses a rollback journal, not WAL).
//! - **Only new or empty files are created.** [`StoreWriter::open`] refuses another program's
//!   SQLite file, a non-SQLite file and another schema version, leaving them byte-for-byte
//!   unchanged.
//! - **Damage is refused.** Every open runs SQLite's `quick_check` (or the full
//!   `integrity_check`); every row carries a CRC-32 over its values, verified whenever it is
//!   read, which catches changed bytes inside stored values that SQLite's checks cannot see.
//!   Stored reports and linkage analyses are parsed back into the library's types.
//! - **One writer.** A writer holds an OS lock on `FILE.lock` (released when the process
//!   ends in any way); a second writer is refused at once.
//! - **Atomic work units.** Every work unit is one transaction: a run killed at any moment
//!   keeps exactly the units it had committed, and a resumed run skips them.
//!
//! What is not detected: an index entry changed so that it still points at a valid row is
//! seen only by [`Check::Full`] (SQLite's integrity_check), not by `quick_check`; facet
//! counts and scatter points aggregate inside SQLite and are not checksum-verified row by
//! row; a file truncated to zero bytes is indistinguishable from a new empty file.
//!
//! Plain records in and out; this crate does not know how designs are found or deployed. It
//! builds its records from the library's plain data types (`CatalogEntry`,
//! `DeploymentReport`, `LinkageAnalysis`). It also holds the exploration driver
//! ([`explore_into`]): the library plans and runs work units, this crate schedules them on a
//! thread pool and commits each one, so every front end runs an exploration the same way.

mod candidates;
mod checksum;
mod dictionary;
mod error;
mod exploration;
mod file;
mod from_catalog;
mod inverse_results;
mod lock;
mod merge;
mod migrate;
mod migrate_columns;
mod motion_groups;
mod motions;
mod open;
mod parts;
mod peak_memory;
pub mod query;
mod read;
mod records;
mod rows;
mod schema;
mod settings_diff;
mod shard;
mod stats;
mod twins;
mod verify;
mod write;

pub use dictionary::{FieldDoc, DICTIONARY};
pub use error::{StoreError, StoreResult};
pub use exploration::{
    explore_into, ExploreEvent, ExploreOutcome, ExploreRequest, UnitFailure, MAX_JOBS,
};
pub use file::sidecar_paths;
pub use from_catalog::POISSON_OPEN_FRACTION;
pub use inverse_results::SavedDesign;
pub use merge::MergeReport;
pub use migrate::{migrate, MigrateOutcome};
pub use migrate_columns::ColumnFill;
pub use motion_groups::{BehaviourCount, MotionGroup, MotionGroups, MotionMember, Span};
pub use motions::{MotionClass, MotionCounts, MotionVariant};
pub use open::{Check, RunInfo, Store, StoreWriter};
pub use parts::StoredPart;
pub use query::{DesignQuery, Facet, FacetCount, FacetValue, Measure, Page, SortKey};
pub use records::{
    DesignRecord, DesignSummary, Origin, StageCount, StoredDesign, UnitRecords, WorkUnitRecord,
};
pub use schema::SCHEMA_VERSION;
pub use shard::{check_shard_set, ShardRecord, ShardSetError, ShardStatus};
pub use stats::{DbStats, FamilyStats, FiniteCounts, MarginCounts, UnitSummary};
