//! The schema, version 5: tables, indexes and the marks that identify an isogami file.
//!
//! - `meta`: schema version, tool version and the settings of the run, each row with a
//!   checksum; a shard database made by `explore --shard` also has the key `shard` (JSON: its
//!   index, the shard count, the whole run's unit count and digest, its own units). Databases
//!   without that key (whole runs, or shards made before it existed) read as before, so it
//!   needed no new schema version.
//! - `work_units` and `stage_counts`: one row per finished work unit (checksum over the unit
//!   and its stage rows) and its per-stage counts.
//! - `designs`: one row per design with every column a catalogue filters, sorts, facets or
//!   plots by (since version 4 the finite 6×6 patch's raw DOF and completed covered
//!   fraction; since version 5 the margins: most open state, end of the path's area ratio,
//!   shape tolerance and the opening kept at the fabrication tolerance), and a checksum over the row. Explored designs name their work unit; designs
//!   saved by a user (live editing) have origin `user` and no work unit.
//! - `design_data`: the full deployment report and linkage analysis as JSON, one row per
//!   design, kept apart so that list queries scan a dense table; checksum over the spec and
//!   both documents.
//!
//! - `unit_memory` (optional): a work unit's peak resident memory, one row per unit that has
//!   it, with a checksum. Writers create it when missing, so databases made before it existed
//!   read as before (their units have no figure) and needed no new schema version.
//!
//! - `motion_classes` (optional): per topology, the representative of its class of topologies
//!   that move alike across cells and families (`motions.rs`), with a checksum; recomputed by
//!   writers, absent in files made before it existed.
//!
//! - `cell_twins` (optional): the spec of each explored design found again on another cell of
//!   its family (same shape, same path) and the spec of the design it is stored with, which
//!   keeps the only `designs` row (`twins.rs`), with a checksum; recomputed by writers.
//!
//! - `unit_parts` (optional): parts of work units split with `explore --unit-parts`, waiting
//!   for their siblings (`parts.rs`): the library's part outcome as JSON with its seconds and
//!   peak memory, and a checksum. Empty once every split unit is complete.
//!
//! The file is marked with SQLite's `application_id` so that other programs' databases are
//! told apart before anything is read, and uses a rollback journal (not WAL) so that readers
//! never create files beside it.

/// Version written into `meta.schema_version`; bump on any incompatible change. Version 1
/// (issue 2) had no checksums, no user designs and one table for summaries and JSON.
/// Version 2 had the same tables as 3, but its specs name joints by the edge labels of
/// isogami before issue 21, which depended on the exact shape, and its reports summarise the
/// stored frames only; `isogami db migrate` carries such a file into the current version.
/// Version 3 lacked the finite-sheet columns of `designs` (`finite_raw_dof`,
/// `finite_covered`, issue 22); `isogami db migrate` copies such a file and computes them.
/// Version 4 lacked the margin columns (`open_t`, `end_area_ratio`, `shape_tolerance`,
/// `fabrication_kept`, issue 40); `isogami db migrate` copies such a file and computes them.
pub const SCHEMA_VERSION: i64 = 5;

/// The schema version without the margin columns.
pub(crate) const BEFORE_MARGIN_COLUMNS: i64 = 4;

/// The schema version without the finite-sheet columns.
pub(crate) const BEFORE_FINITE_COLUMNS: i64 = 3;

/// The schema version whose joint strings use the old, shape-dependent edge labels.
pub(crate) const LABELS_BEFORE_ISSUE_21: i64 = 2;

/// `PRAGMA application_id` of an isogami database: "ISOG".
pub(crate) const APPLICATION_ID: i32 = 0x4953_4F47;

/// Tables every isogami database has.
pub(crate) const TABLES: [&str; 5] = [
    "meta",
    "work_units",
    "stage_counts",
    "designs",
    "design_data",
];

/// The optional tables (see the module docs); a writer creates them when missing.
pub(crate) const OPTIONAL_TABLES: &str = "
CREATE TABLE IF NOT EXISTS unit_memory (
    work_unit      TEXT PRIMARY KEY REFERENCES work_units(id),
    peak_rss_bytes INTEGER NOT NULL,
    checksum       INTEGER NOT NULL
);
CREATE TABLE IF NOT EXISTS motion_classes (
    topology       TEXT PRIMARY KEY,
    representative TEXT NOT NULL,
    checksum       INTEGER NOT NULL
);
CREATE INDEX IF NOT EXISTS motion_classes_representative ON motion_classes(representative);
CREATE INDEX IF NOT EXISTS designs_topology ON designs(topology);
CREATE TABLE IF NOT EXISTS cell_twins (
    spec     TEXT PRIMARY KEY,
    kept     TEXT NOT NULL,
    checksum INTEGER NOT NULL
);
CREATE INDEX IF NOT EXISTS cell_twins_kept ON cell_twins(kept);
CREATE TABLE IF NOT EXISTS unit_parts (
    work_unit      TEXT NOT NULL,
    part           INTEGER NOT NULL,
    parts          INTEGER NOT NULL,
    seconds        REAL NOT NULL,
    peak_rss_bytes INTEGER,
    data           TEXT NOT NULL,
    checksum       INTEGER NOT NULL,
    PRIMARY KEY (work_unit, part)
);
";

/// Shape parameter columns p0…p5 (isohedral families have at most six parameters).
pub(crate) const PARAM_SLOTS: usize = 6;

/// Tables and indexes, created in one transaction in a new or empty file. Every facet and
/// every sortable measure has an index; a column that may be missing has a second index on
/// `(column IS NULL, column)`, whose order is ascending with missing values last.
pub(crate) const CREATE: &str = "
CREATE TABLE meta (
    key      TEXT PRIMARY KEY,
    value    TEXT NOT NULL,
    checksum INTEGER NOT NULL
);
CREATE TABLE work_units (
    id          TEXT PRIMARY KEY,
    family      TEXT NOT NULL,
    cell        TEXT NOT NULL,
    kind        TEXT NOT NULL,
    seconds     REAL NOT NULL,
    finished_at TEXT NOT NULL,
    checksum    INTEGER NOT NULL
);
CREATE TABLE stage_counts (
    work_unit TEXT NOT NULL REFERENCES work_units(id),
    position  INTEGER NOT NULL,
    stage     TEXT NOT NULL,
    count_in  INTEGER NOT NULL,
    count_out INTEGER NOT NULL,
    seconds   REAL NOT NULL,
    PRIMARY KEY (work_unit, position)
);
CREATE TABLE designs (
    id                INTEGER PRIMARY KEY,
    spec              TEXT NOT NULL,
    origin            TEXT NOT NULL CHECK (origin IN ('explored', 'user')),
    work_unit         TEXT REFERENCES work_units(id),
    family            INTEGER NOT NULL,
    cell              TEXT NOT NULL,
    cell_a            INTEGER NOT NULL,
    cell_b            INTEGER NOT NULL,
    tile_count        INTEGER NOT NULL,
    joints            TEXT NOT NULL,
    topology          TEXT NOT NULL,
    param_count       INTEGER NOT NULL,
    p0 REAL, p1 REAL, p2 REAL, p3 REAL, p4 REAL, p5 REAL,
    behaviour         TEXT,
    linkage_signature TEXT,
    end_reason        TEXT NOT NULL,
    method            TEXT NOT NULL,
    dof               INTEGER NOT NULL,
    kerf              REAL NOT NULL,
    max_expansion     REAL NOT NULL,
    min_expansion     REAL NOT NULL,
    max_area_ratio    REAL NOT NULL,
    max_tile_rotation REAL NOT NULL,
    poisson_min       REAL,
    poisson_max       REAL,
    steps             INTEGER NOT NULL,
    finite_raw_dof    INTEGER,
    finite_covered    REAL,
    open_t            REAL,
    end_area_ratio    REAL,
    shape_tolerance   REAL,
    fabrication_kept  REAL,
    checksum          INTEGER NOT NULL,
    CHECK ((origin = 'explored') = (work_unit IS NOT NULL))
);
CREATE TABLE design_data (
    design   INTEGER PRIMARY KEY REFERENCES designs(id),
    report   TEXT NOT NULL,
    linkages TEXT,
    checksum INTEGER NOT NULL
);
CREATE UNIQUE INDEX designs_spec ON designs(spec);
CREATE INDEX designs_work_unit ON designs(work_unit);
CREATE INDEX designs_family ON designs(family);
CREATE INDEX designs_cell ON designs(cell);
CREATE INDEX designs_tile_count ON designs(tile_count);
CREATE INDEX designs_behaviour ON designs(behaviour);
CREATE INDEX designs_linkage ON designs(linkage_signature);
CREATE INDEX designs_end_reason ON designs(end_reason);
CREATE INDEX designs_origin ON designs(origin);
CREATE INDEX designs_max_expansion ON designs(max_expansion);
CREATE INDEX designs_min_expansion ON designs(min_expansion);
CREATE INDEX designs_area_ratio ON designs(max_area_ratio);
CREATE INDEX designs_tile_rotation ON designs(max_tile_rotation);
CREATE INDEX designs_poisson_min ON designs(poisson_min);
CREATE INDEX designs_poisson_max ON designs(poisson_max);
CREATE INDEX designs_steps ON designs(steps);
CREATE INDEX designs_behaviour_nulls_last ON designs(behaviour IS NULL, behaviour);
CREATE INDEX designs_linkage_nulls_last ON designs(linkage_signature IS NULL, linkage_signature);
CREATE INDEX designs_poisson_min_nulls_last ON designs(poisson_min IS NULL, poisson_min);
CREATE INDEX designs_poisson_max_nulls_last ON designs(poisson_max IS NULL, poisson_max);
";

/// The finite-sheet columns' indexes (schema version 4), in [`CREATE`] and made by the
/// migration from version 3.
pub(crate) const FINITE_INDEXES: &str = "
CREATE INDEX designs_finite_raw_dof ON designs(finite_raw_dof);
CREATE INDEX designs_finite_covered ON designs(finite_covered);
CREATE INDEX designs_finite_raw_dof_nulls_last ON designs(finite_raw_dof IS NULL, finite_raw_dof);
CREATE INDEX designs_finite_covered_nulls_last ON designs(finite_covered IS NULL, finite_covered);
";

/// The margin columns' indexes (schema version 5), made with [`CREATE`] and by the migration
/// from version 4 or 3.
pub(crate) const MARGIN_INDEXES: &str = "
CREATE INDEX designs_open_t ON designs(open_t);
CREATE INDEX designs_end_area_ratio ON designs(end_area_ratio);
CREATE INDEX designs_shape_tolerance ON designs(shape_tolerance);
CREATE INDEX designs_fabrication_kept ON designs(fabrication_kept);
CREATE INDEX designs_open_t_nulls_last ON designs(open_t IS NULL, open_t);
CREATE INDEX designs_end_area_ratio_nulls_last ON designs(end_area_ratio IS NULL, end_area_ratio);
CREATE INDEX designs_shape_tolerance_nulls_last ON designs(shape_tolerance IS NULL, shape_tolerance);
CREATE INDEX designs_fabrication_kept_nulls_last ON designs(fabrication_kept IS NULL, fabrication_kept);
";
