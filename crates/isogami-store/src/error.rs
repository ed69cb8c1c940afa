//! Store errors.

use thiserror::Error;

/// What can go wrong with the database.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum StoreError {
    /// SQLite failed (locked, corrupt, disk full, …).
    #[error("database error: {0}")]
    Sqlite(#[from] rusqlite::Error),
    /// The file was written by another schema version.
    #[error(
        "database schema version {found}, this isogami needs {expected}: explore into a new file"
    )]
    SchemaVersion {
        /// Version in the file.
        found: i64,
        /// Version this build writes.
        expected: i64,
    },
    /// The file was made with other settings than the run that opens it.
    #[error("database was made with other settings ({0}); use a new file or the same settings")]
    SettingsMismatch(String),
    /// A stored JSON value that cannot be read.
    #[error("stored JSON: {0}")]
    Json(#[from] serde_json::Error),
}

/// Result alias.
pub type StoreResult<T> = std::result::Result<T, StoreError>;
