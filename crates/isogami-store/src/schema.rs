//! The schema, version 1.

/// Version written into `meta.schema_version`; bump on any incompatible change.
pub const SCHEMA_VERSION: i64 = 1;

/// Tables. Designs are keyed by their spec string (exact round trip), work units by a
/// deterministic id such as `topology/IH28/2x1`.
pub(crate) const CREATE: &str = "
CREATE TABLE IF NOT EXISTS meta (
    key   TEXT PRIMARY KEY,
    value TEXT NOT NULL
);
CREATE TABLE IF NOT EXISTS work_units (
    id          TEXT PRIMARY KEY,
    family      TEXT NOT NULL,
    cell        TEXT NOT NULL,
    kind        TEXT NOT NULL,
    seconds     REAL NOT NULL,
    finished_at TEXT NOT NULL
);
CREATE TABLE IF NOT EXISTS stage_counts (
    work_unit TEXT NOT NULL REFERENCES work_units(id),
    position  INTEGER NOT NULL,
    stage     TEXT NOT NULL,
    count_in  INTEGER NOT NULL,
    count_out INTEGER NOT NULL,
    seconds   REAL NOT NULL,
    PRIMARY KEY (work_unit, stage)
);
CREATE TABLE IF NOT EXISTS designs (
    spec              TEXT PRIMARY KEY,
    work_unit         TEXT NOT NULL REFERENCES work_units(id),
    family            TEXT NOT NULL,
    params            TEXT NOT NULL,
    cell              TEXT NOT NULL,
    joints            TEXT NOT NULL,
    topology          TEXT NOT NULL,
    behaviour         TEXT,
    end_reason        TEXT NOT NULL,
    max_expansion     REAL NOT NULL,
    min_expansion     REAL NOT NULL,
    max_area_ratio    REAL NOT NULL,
    max_tile_rotation REAL NOT NULL,
    steps             INTEGER NOT NULL,
    linkage_signature TEXT,
    report            TEXT NOT NULL,
    linkages          TEXT
);
CREATE INDEX IF NOT EXISTS designs_family ON designs(family);
CREATE INDEX IF NOT EXISTS designs_behaviour ON designs(behaviour);
";
