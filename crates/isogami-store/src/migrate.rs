//! `isogami db migrate`: a database of schema version 2, 3 or 4 carried into a new file of
//! this version. A version-3 or version-4 file lacks only columns (the finite-sheet ones, the
//! margins): it is copied and they are filled (`migrate_columns.rs`). A version-2 file:
//!
//! Version 2 files name joints by the edge labels of isogami before issue 21, which depended
//! on the exact shape, and summarise deployments over their stored frames only; read with
//! the current labels, some of their specs would name other mechanisms. Migration never
//! does that. It writes a new file (the old one is only read):
//!
//! - the explored catalogue is explored again with the old file's settings, families and
//!   cells (the same plan), so every explored row is what the current code computes;
//! - every design a user saved (live editing, inverse design) is translated to the current
//!   labels at its exact old shape ([`Design::from_legacy_spec`]: the same physical joints,
//!   canonical numbers), deployed again with its method and kerf, and saved with its linkage
//!   analysis. One already in the new file (an explored design, or two old specs that differ
//!   only by float noise) is counted as merged, not stored twice.

use crate::error::{StoreError, StoreResult};
use crate::exploration::{explore_into, ExploreEvent, ExploreOutcome, ExploreRequest};
use crate::file::{inspect, FileState};
use crate::migrate_columns::{fill_columns, ColumnFill};
use crate::open::{integrity, reader_connection, Check, StoreWriter};
use crate::records::{DesignRecord, Origin};
use crate::schema::{
    APPLICATION_ID, BEFORE_FINITE_COLUMNS, BEFORE_MARGIN_COLUMNS, LABELS_BEFORE_ISSUE_21,
    SCHEMA_VERSION,
};
use isogami::api::{deploy, linkages, DeployRequest, FrameSelection};
use isogami::catalog::CatalogSettings;
use isogami::cell::CellDims;
use isogami::deploy::DeploymentReport;
use isogami::tiling::Family;
use isogami::topology::Design;
use rusqlite::{Connection, OptionalExtension};
use serde::Serialize;
use std::collections::BTreeSet;
use std::path::Path;
use std::sync::atomic::AtomicBool;

/// What a migration did.
#[derive(Debug, Clone, Serialize)]
pub struct MigrateOutcome {
    /// The old file's schema version (2, 3 or 4).
    pub from_version: i64,
    /// The exploration of the new file (the old file's plan); version 2 only.
    pub explored: Option<ExploreOutcome>,
    /// The columns added and filled; versions 3 and 4 only.
    pub columns: Option<ColumnFill>,
    /// User designs in the old file.
    pub user_designs: usize,
    /// Of these, saved into the new file.
    pub user_saved: usize,
    /// Of these, already in the new file under their current spec (merged).
    pub user_merged: usize,
    /// Of these, whose joint string changed in the translation.
    pub user_relabelled: usize,
    /// User designs that could not be carried over: (old spec, reason).
    pub user_failed: Vec<(String, String)>,
}

/// Migrates the version-2, 3 or 4 database at `from` into a new database at `into`
/// (which must not exist yet), with `jobs` worker threads for the exploration or the
/// figures of the columns a version-3 or 4 file lacks. `progress` and `cancel` are the exploration's ([`explore_into`]);
/// a cancelled migration of a version-2 file leaves a resumable new file and no user design
/// copied yet (run it again). A version-3 or 4 file is upgraded in one go
/// ([`fill_columns`]: nothing is left at `into` when it fails).
pub fn migrate(
    from: &Path,
    into: &Path,
    jobs: usize,
    progress: &mut dyn FnMut(&ExploreEvent<'_>),
    cancel: &AtomicBool,
) -> StoreResult<MigrateOutcome> {
    let old = OldFile::open(from)?;
    if matches!(old.version, BEFORE_FINITE_COLUMNS | BEFORE_MARGIN_COLUMNS) {
        let fill = fill_columns(from, into, old.version, old.settings, jobs)?;
        return Ok(MigrateOutcome {
            from_version: old.version,
            explored: None,
            columns: Some(fill),
            user_designs: 0,
            user_saved: 0,
            user_merged: 0,
            user_relabelled: 0,
            user_failed: Vec::new(),
        });
    }
    let settings = old
        .settings
        .ok_or_else(|| StoreError::Damaged("its settings cannot be read".into()))?;
    let request = ExploreRequest {
        settings,
        families: old.families.iter().copied().collect(),
        cells: Some(old.cells.clone()),
        shard: None,
        jobs,
        parts: 1,
    };
    match inspect(into)? {
        FileState::Missing | FileState::Empty => {}
        FileState::Sqlite { .. } => {
            // A migration that was interrupted may be resumed into its own file.
            StoreWriter::open(into, None, Check::Quick)?;
        }
    }
    let explored = explore_into(into, &request, progress, cancel)?;
    let cancelled = explored.cancelled;
    let mut outcome = MigrateOutcome {
        from_version: old.version,
        user_designs: old.user_designs.len(),
        user_saved: 0,
        user_merged: 0,
        user_relabelled: 0,
        user_failed: Vec::new(),
        explored: Some(explored),
        columns: None,
    };
    if cancelled {
        return Ok(outcome);
    }
    let mut writer = StoreWriter::open(into, None, Check::Quick)?;
    for (spec, report) in &old.user_designs {
        match carry_user_design(&settings, spec, report) {
            Ok((record, relabelled)) => {
                outcome.user_relabelled += usize::from(relabelled);
                match writer.save_user_design(&record) {
                    Ok(()) => outcome.user_saved += 1,
                    Err(StoreError::DuplicateSpec(_)) => outcome.user_merged += 1,
                    Err(e) => return Err(e),
                }
            }
            Err(reason) => outcome.user_failed.push((spec.clone(), reason)),
        }
    }
    Ok(outcome)
}

/// One saved design of the old file in the current labels, deployed again; whether its joint
/// string changed.
fn carry_user_design(
    settings: &CatalogSettings,
    spec: &str,
    report: &str,
) -> Result<(DesignRecord, bool), String> {
    let design = Design::from_legacy_spec(spec).map_err(|e| e.to_string())?;
    let old_joints = spec.rsplit(':').next().unwrap_or_default();
    let relabelled = design.to_string().rsplit(':').next() != Some(old_joints);
    let old: DeploymentReport =
        serde_json::from_str(report).map_err(|e| format!("stored report: {e}"))?;
    let mut request: DeployRequest = settings.deploy_request();
    request.settings.method = old.method;
    request.settings.contact.kerf = old.kerf;
    request.frames = FrameSelection::Evenly(old.frames.len().max(2));
    let run = deploy(&design, &request, &mut |_| true).map_err(|e| e.to_string())?;
    let analysis = linkages(&design).ok();
    let topology = design.to_string();
    let record = DesignRecord::from_parts(
        &design,
        &topology,
        Origin::User,
        &run.report,
        analysis.as_ref(),
    )
    .map_err(|e| e.to_string())?;
    Ok((record, relabelled))
}

/// What migration reads from a version-2 or version-3 file.
struct OldFile {
    /// Its schema version.
    version: i64,
    /// The run's settings (None in a file of user designs only).
    settings: Option<CatalogSettings>,
    families: BTreeSet<Family>,
    cells: Vec<CellDims>,
    /// (spec, report JSON) of every user design.
    user_designs: Vec<(String, String)>,
}

impl OldFile {
    fn open(path: &Path) -> StoreResult<OldFile> {
        let wal = match inspect(path)? {
            FileState::Missing => return Err(StoreError::NotFound),
            FileState::Empty => return Err(StoreError::EmptyFile),
            FileState::Sqlite { wal } => wal,
        };
        let conn = reader_connection(path, wal)?;
        integrity(&conn, Check::Full)?;
        let app_id: i32 = conn.pragma_query_value(None, "application_id", |r| r.get(0))?;
        let meta = |key: &str| -> StoreResult<Option<String>> {
            Ok(conn
                .query_row("SELECT value FROM meta WHERE key = ?1", [key], |r| r.get(0))
                .optional()?)
        };
        let version: Option<i64> = meta("schema_version")
            .ok()
            .flatten()
            .and_then(|v| v.trim().parse().ok());
        let version = match version {
            _ if app_id != APPLICATION_ID => {
                return Err(StoreError::Damaged(
                    "not an isogami database of schema version 2, 3 or 4".into(),
                ))
            }
            Some(v @ (LABELS_BEFORE_ISSUE_21 | BEFORE_FINITE_COLUMNS | BEFORE_MARGIN_COLUMNS)) => v,
            Some(SCHEMA_VERSION) => {
                return Err(StoreError::AlreadyCurrent {
                    version: SCHEMA_VERSION,
                })
            }
            Some(found) => {
                return Err(StoreError::SchemaVersion {
                    found,
                    expected: BEFORE_MARGIN_COLUMNS,
                })
            }
            None => {
                return Err(StoreError::Damaged(
                    "the schema version cannot be read".into(),
                ))
            }
        };
        let settings = match meta("settings")? {
            None => None,
            Some(text) => Some(
                CatalogSettings::from_fingerprint(&text)
                    .ok_or_else(|| StoreError::Damaged("its settings cannot be read".into()))?,
            ),
        };
        let (families, cells) = units(&conn)?;
        let user_designs = conn
            .prepare(
                "SELECT d.spec, x.report FROM designs d JOIN design_data x ON x.design = d.id \
                 WHERE d.origin = 'user' ORDER BY d.id",
            )?
            .query_map([], |r| Ok((r.get(0)?, r.get(1)?)))?
            .collect::<Result<_, _>>()?;
        Ok(OldFile {
            version,
            settings,
            families,
            cells,
            user_designs,
        })
    }
}

/// The families and cells of the old file's work units.
fn units(conn: &Connection) -> StoreResult<(BTreeSet<Family>, Vec<CellDims>)> {
    let rows: Vec<(String, String)> = conn
        .prepare("SELECT DISTINCT family, cell FROM work_units")?
        .query_map([], |r| Ok((r.get(0)?, r.get(1)?)))?
        .collect::<Result<_, _>>()?;
    let (mut families, mut cells) = (BTreeSet::new(), Vec::new());
    for (f, c) in rows {
        let bad = |what: &str| StoreError::Damaged(format!("work unit with {what} '{f} {c}'"));
        families.insert(f.parse::<Family>().map_err(|_| bad("family"))?);
        let cell = c.parse::<CellDims>().map_err(|_| bad("cell"))?;
        if !cells.contains(&cell) {
            cells.push(cell);
        }
    }
    cells.sort_by_key(|d| (d.a(), d.b()));
    Ok((families, cells))
}
