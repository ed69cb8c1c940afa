//! Store errors: one variant per thing a user can be told, each a single line.

use thiserror::Error;

/// What can go wrong with the database.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum StoreError {
    /// A reading command was pointed at a file that does not exist.
    #[error("no such database")]
    NotFound,
    /// The path exists but is not a regular file.
    #[error("not a file")]
    NotAFile,
    /// The file exists but is not an SQLite database at all.
    #[error("not an isogami database (not an SQLite file, or its header is damaged)")]
    NotSqlite,
    /// An empty file, where a reading command needs a database.
    #[error("empty file, not an isogami database")]
    EmptyFile,
    /// An SQLite database that some other program made.
    #[error("not an isogami database (an SQLite file with {tables})")]
    Foreign {
        /// Its tables, e.g. "tables designs, users" or "no tables".
        tables: String,
    },
    /// An isogami database of another schema version.
    #[error(
        "made by isogami database schema version {found}, this isogami reads version \
         {expected}: re-run explore into a new file"
    )]
    SchemaVersion {
        /// Version in the file.
        found: i64,
        /// Version this build reads and writes.
        expected: i64,
    },
    /// A database of schema version 2, whose joint strings use the edge labels of isogami
    /// before issue 21 (they depended on the exact shape): never read with the current labels.
    #[error(
        "made by an isogami whose joint strings used shape-dependent edge labels (schema \
         version 2): translate it with `isogami db migrate --db <this file> --into <new file>`"
    )]
    OldEdgeLabels,
    /// A database of schema version 3, made before the catalogue stored the finite 6×6
    /// patch's figures (issue 22).
    #[error(
        "made before the catalogue stored finite-sheet figures (schema version 3): upgrade it \
         with `isogami db migrate --db <this file> --into <new file>`"
    )]
    NoFiniteColumns,
    /// A database of schema version 4, made before the catalogue stored each design's margins
    /// (shape tolerance and most open state, issue 40).
    #[error(
        "made before the catalogue stored shape tolerances and most open states (schema version \
         4): upgrade it with `isogami db migrate --db <this file> --into <new file>`"
    )]
    NoMarginColumns,
    /// The file is damaged: SQLite's integrity check failed, a row fails its checksum, or a
    /// stored value cannot be read.
    #[error("damaged database ({0}); restore it from a copy or re-run explore into a new file")]
    Damaged(String),
    /// `db migrate` of a database already of the current schema: nothing to do, and it can be
    /// used as it is.
    #[error(
        "already of schema version {version}, the current one: nothing to migrate; use it as \
         it is"
    )]
    AlreadyCurrent {
        /// The schema version it has (and the current one).
        version: i64,
    },
    /// A writer was killed in the middle of a commit; its rollback journal is still there.
    #[error(
        "an interrupted write left its rollback journal beside the file; run the same explore \
         (or merge --into) on it once to roll it back before reading"
    )]
    InterruptedWrite,
    /// Another process holds the writer lock.
    #[error(
        "another isogami process (explore or merge) is writing to this database; wait for it \
         to finish or use another file"
    )]
    Busy,
    /// SQLite kept reporting the file busy past the timeout.
    #[error("the database stayed locked by another process for too long; try again")]
    Locked,
    /// The file was made with other settings than the run that opens it (or than the target
    /// of a merge); the text names each differing setting, e.g. "max_edges 16 in the file, 20
    /// in this run".
    #[error("database was made with other settings ({0}); use a new file or the same settings")]
    SettingsMismatch(String),
    /// An exploration into a database planned for another shard or run.
    #[error(
        "the database holds {found}, not {wanted}: give explore the same --shard, families and \
         cells as the run that made it, or use a new file"
    )]
    OtherShard {
        /// What the database holds, e.g. `shard 1/4 (5 of a 20-unit run)`.
        found: String,
        /// What the run plans.
        wanted: String,
    },
    /// A stored report or linkage analysis is intact but does not match this build's types.
    #[error("stored {what} of {spec} cannot be read by this build: {message}")]
    StoredJson {
        /// Spec of the design.
        spec: String,
        /// "deployment report" or "linkage analysis".
        what: &'static str,
        /// The parser's message.
        message: String,
    },
    /// A record offered for writing cannot be stored faithfully.
    #[error("design {spec} cannot be stored: {problem}")]
    InvalidRecord {
        /// Spec of the design.
        spec: String,
        /// What is wrong with it.
        problem: String,
    },
    /// A user design whose spec is already in the database.
    #[error("design {0} is already in the database")]
    DuplicateSpec(String),
    /// An exploration request with a setting out of range.
    #[error(transparent)]
    InvalidSettings(#[from] isogami::error::SettingsError),
    /// The request cannot be planned (a requested cell the settings leave out).
    #[error(transparent)]
    Plan(#[from] isogami::explore::ExploreError),
    /// A query with a bad bound, limit or parameter slot.
    #[error("invalid query: {0}")]
    InvalidQuery(#[from] crate::query::QueryError),
    /// The file system refused (creating, locking, reading the header).
    #[error("{0}")]
    Io(#[from] std::io::Error),
    /// Any other SQLite failure (disk full, read-only directory, …).
    #[error("database error: {0}")]
    Sqlite(rusqlite::Error),
}

impl From<rusqlite::Error> for StoreError {
    /// Sorts SQLite failures into the variants a user can act on.
    fn from(e: rusqlite::Error) -> StoreError {
        use rusqlite::ffi::ErrorCode;
        if let rusqlite::Error::SqliteFailure(f, _) = &e {
            if f.extended_code == rusqlite::ffi::SQLITE_READONLY_ROLLBACK {
                return StoreError::InterruptedWrite;
            }
            match f.code {
                ErrorCode::DatabaseCorrupt => {
                    return StoreError::Damaged(one_line(&format!("SQLite: {e}")))
                }
                ErrorCode::NotADatabase => return StoreError::NotSqlite,
                ErrorCode::DatabaseBusy | ErrorCode::DatabaseLocked => return StoreError::Locked,
                _ => {}
            }
        }
        StoreError::Sqlite(e)
    }
}

/// Joins the lines of a message so that every error prints as one line.
pub(crate) fn one_line(text: &str) -> String {
    text.split(['\n', '\r'])
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ")
}

/// Result alias.
pub type StoreResult<T> = std::result::Result<T, StoreError>;
