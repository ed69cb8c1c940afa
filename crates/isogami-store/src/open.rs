//! Opening a database: reading never writes, writing only creates new or empty files, and
//! every open checks that the file is an intact isogami database of this schema version.
//!
//! - [`Store::open_read`] opens read-only. Nothing is created or changed: no schema, no
//!   journal-mode switch, no files beside it (a WAL-mode file of another program, whose
//!   readers would need `-wal`/`-shm` files, is read as immutable when it has none).
//! - [`StoreWriter::open`] takes the writer lock, then creates the schema in a new or empty
//!   file, or opens an existing isogami database. Anything else (another program's SQLite
//!   file, a non-SQLite file, another schema version, a damaged file) is refused before a
//!   byte of it is written.
//!
//! Both run SQLite's `quick_check` ([`Check::Quick`]) or `integrity_check` plus every row's
//! checksum and every stored document's parse ([`Check::Full`]) before returning.

use crate::checksum;
use crate::error::{StoreError, StoreResult};
use crate::file::{beside, inspect, uri, FileState};
use crate::lock::WriterLock;
use crate::rows::meta_values;
use crate::schema::{
    APPLICATION_ID, BEFORE_FINITE_COLUMNS, BEFORE_MARGIN_COLUMNS, CREATE, FINITE_INDEXES,
    LABELS_BEFORE_ISSUE_21, MARGIN_INDEXES, SCHEMA_VERSION, TABLES,
};
use rusqlite::{params, Connection, OpenFlags, OptionalExtension};
use std::path::Path;
use std::time::Duration;

/// How much to check when opening.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Check {
    /// SQLite's `quick_check`: b-tree structure, page ownership, record formats, NOT NULL.
    /// Reads every page once. Does not see a changed byte inside a stored value.
    Quick,
    /// SQLite's `integrity_check` (quick_check plus index-against-table consistency), every
    /// row's checksum, and every stored report and linkage analysis parsed into the library's
    /// types.
    Full,
}

/// The run a writer opens the database for: its settings must match the file's (a new file
/// takes them).
#[derive(Debug, Clone, Copy)]
pub struct RunInfo<'a> {
    /// Version of the tool writing.
    pub tool_version: &'a str,
    /// Settings fingerprint (JSON).
    pub settings: &'a str,
}

/// A design database open for reading.
#[derive(Debug)]
pub struct Store {
    pub(crate) conn: Connection,
}

/// A design database open for writing by this process alone. Reads go through [`Store`]
/// (`Deref`).
#[derive(Debug)]
pub struct StoreWriter {
    pub(crate) store: Store,
    _lock: WriterLock,
}

impl std::ops::Deref for StoreWriter {
    type Target = Store;
    fn deref(&self) -> &Store {
        &self.store
    }
}

/// Busy timeouts: a reader waits for a writer's commit, a writer for readers to finish.
const READER_BUSY: Duration = Duration::from_secs(10);
const WRITER_BUSY: Duration = Duration::from_secs(60);

/// Page cache per connection, in KiB as SQLite's negative `cache_size` (the summary table and
/// its indexes of 10^4 designs take about 8 MB; the default cache is 2 MB).
const CACHE_KIB: i64 = -32 * 1024;

/// Connection for reading only, creating no files beside the database.
pub(crate) fn reader_connection(path: &Path, wal: bool) -> StoreResult<Connection> {
    let flags = OpenFlags::SQLITE_OPEN_READ_ONLY | OpenFlags::SQLITE_OPEN_NO_MUTEX;
    let conn = if wal && !beside(path, "-wal").exists() {
        // With no -wal file there is nothing beyond the main file to read; immutable mode
        // reads it without creating -wal/-shm files.
        Connection::open_with_flags(
            uri(path, "immutable=1")?,
            flags | OpenFlags::SQLITE_OPEN_URI,
        )?
    } else {
        Connection::open_with_flags(path, flags)?
    };
    conn.busy_timeout(READER_BUSY)?;
    conn.pragma_update(None, "query_only", true)?;
    conn.pragma_update(None, "cache_size", CACHE_KIB)?;
    Ok(conn)
}

/// A meta value, checksum verified.
pub(crate) fn meta(conn: &Connection, key: &str) -> StoreResult<Option<String>> {
    let row: Option<(String, i64)> = conn
        .query_row(
            "SELECT value, checksum FROM meta WHERE key = ?1",
            [key],
            |r| Ok((r.get(0)?, r.get(1)?)),
        )
        .optional()?;
    match row {
        None => Ok(None),
        Some((value, stored)) => {
            if checksum::of_values(&meta_values(key, &value)) != stored {
                return Err(StoreError::Damaged(format!(
                    "meta value '{key}' fails its checksum"
                )));
            }
            Ok(Some(value))
        }
    }
}

/// Writes a meta value with its checksum.
pub(crate) fn put_meta(conn: &Connection, key: &str, value: &str) -> StoreResult<()> {
    conn.execute(
        "INSERT OR REPLACE INTO meta(key, value, checksum) VALUES (?1, ?2, ?3)",
        params![key, value, checksum::of_values(&meta_values(key, value))],
    )?;
    Ok(())
}

/// The `schema_version` of a `meta` table (None without that row; an error when the table
/// cannot be read, e.g. another program's `meta` table without these columns).
fn version_in_meta(conn: &Connection) -> rusqlite::Result<Option<String>> {
    conn.query_row(
        "SELECT value FROM meta WHERE key = 'schema_version'",
        [],
        |r| r.get::<_, String>(0),
    )
    .optional()
}

/// Tells an isogami database of this version from everything else. Reads only the header and
/// the schema.
fn identify(conn: &Connection) -> StoreResult<()> {
    let app_id: i32 = conn.pragma_query_value(None, "application_id", |r| r.get(0))?;
    let tables: Vec<String> = conn
        .prepare(
            "SELECT name FROM sqlite_master WHERE type = 'table' AND name NOT LIKE 'sqlite_%' \
             ORDER BY name",
        )?
        .query_map([], |r| r.get(0))?
        .collect::<Result<_, _>>()?;
    let has = |t: &str| tables.iter().any(|x| x == t);
    if app_id == APPLICATION_ID {
        let version = if has("meta") {
            version_in_meta(conn)?
        } else {
            None
        };
        let found: i64 = version
            .and_then(|v| v.trim().parse().ok())
            .ok_or_else(|| StoreError::Damaged("the schema version cannot be read".into()))?;
        if found == LABELS_BEFORE_ISSUE_21 {
            return Err(StoreError::OldEdgeLabels);
        }
        if found == BEFORE_FINITE_COLUMNS {
            return Err(StoreError::NoFiniteColumns);
        }
        if found == BEFORE_MARGIN_COLUMNS {
            return Err(StoreError::NoMarginColumns);
        }
        if found != SCHEMA_VERSION {
            return Err(StoreError::SchemaVersion {
                found,
                expected: SCHEMA_VERSION,
            });
        }
        if let Some(t) = TABLES.iter().find(|t| !has(t)) {
            return Err(StoreError::Damaged(format!("table {t} is missing")));
        }
        return Ok(());
    }
    // isogami before schema version 2 wrote no application id, only meta.schema_version.
    if has("meta") {
        if let Some(found) = version_in_meta(conn)
            .ok()
            .flatten()
            .and_then(|v| v.trim().parse::<i64>().ok())
        {
            if found == SCHEMA_VERSION {
                return Err(StoreError::Damaged(
                    "the file's application id is wrong".into(),
                ));
            }
            return Err(StoreError::SchemaVersion {
                found,
                expected: SCHEMA_VERSION,
            });
        }
    }
    let tables = match tables.len() {
        0 => "no tables".to_string(),
        n if n <= 5 => format!("tables {}", tables.join(", ")),
        n => format!("tables {}, … ({n} in all)", tables[..5].join(", ")),
    };
    Err(StoreError::Foreign { tables })
}

/// Runs SQLite's quick_check or integrity_check; the first problem it reports is the message.
pub(crate) fn integrity(conn: &Connection, check: Check) -> StoreResult<()> {
    let pragma = match check {
        Check::Quick => "quick_check",
        Check::Full => "integrity_check",
    };
    let mut stmt = conn.prepare(&format!("PRAGMA {pragma}(10)"))?;
    let rows: Vec<String> = stmt
        .query_map([], |r| r.get::<_, String>(0))?
        .collect::<Result<_, _>>()?;
    if rows.len() == 1 && rows[0] == "ok" {
        return Ok(());
    }
    // One row may hold several newline-separated problems under a "*** in database ***" line.
    let problems: Vec<&str> = rows
        .iter()
        .flat_map(|r| r.lines())
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with("***"))
        .collect();
    let first = problems.first().copied().unwrap_or("no answer");
    let more = match problems.len() {
        0 | 1 => String::new(),
        n => format!(" (and {} more problems)", n - 1),
    };
    Err(StoreError::Damaged(crate::error::one_line(&format!(
        "SQLite {pragma}: {first}{more}"
    ))))
}

/// Once SQLite's header check passed, SQLite failing to read the file means damage.
fn as_damage(e: StoreError) -> StoreError {
    match e {
        StoreError::NotSqlite => StoreError::Damaged("SQLite cannot read the file".into()),
        e => e,
    }
}

impl Store {
    /// Opens an existing isogami database for reading only; see the module documentation.
    pub fn open_read(path: &Path, check: Check) -> StoreResult<Store> {
        let wal = match inspect(path)? {
            FileState::Missing => return Err(StoreError::NotFound),
            FileState::Empty => return Err(StoreError::EmptyFile),
            FileState::Sqlite { wal } => wal,
        };
        let store = Store {
            conn: reader_connection(path, wal)?,
        };
        store.check_file(check).map_err(as_damage)?;
        Ok(store)
    }

    /// Integrity, identity and (for [`Check::Full`]) every row.
    fn check_file(&self, check: Check) -> StoreResult<()> {
        integrity(&self.conn, check)?;
        identify(&self.conn)?;
        for key in [
            "schema_version",
            "settings",
            "tool_version",
            crate::shard::SHARD_KEY,
        ] {
            meta(&self.conn, key)?;
        }
        if check == Check::Full {
            self.verify_rows()?;
        }
        Ok(())
    }

    /// Settings JSON the database was made with.
    pub fn settings(&self) -> StoreResult<Option<String>> {
        meta(&self.conn, "settings")
    }

    /// Tool version that made the database.
    pub fn tool_version(&self) -> StoreResult<Option<String>> {
        meta(&self.conn, "tool_version")
    }
}

/// Creates the schema in a new or empty file, all in one transaction: a creation that fails
/// part-way leaves the file as it was.
fn create_schema(conn: &mut Connection) -> StoreResult<()> {
    let tx = conn.transaction_with_behavior(rusqlite::TransactionBehavior::Immediate)?;
    tx.execute_batch(CREATE)?;
    tx.execute_batch(FINITE_INDEXES)?;
    tx.execute_batch(MARGIN_INDEXES)?;
    tx.pragma_update(None, "application_id", APPLICATION_ID)?;
    put_meta(&tx, "schema_version", &SCHEMA_VERSION.to_string())?;
    tx.commit()?;
    Ok(())
}

/// Identifies the file before a writer opens it. A file whose last writer was interrupted is
/// identified from its main file alone (immutable mode ignores the journal): the writer may
/// then roll the journal back, but only in an isogami database.
fn precheck(path: &Path, wal: bool) -> StoreResult<()> {
    // Setting up the reader already reads the schema, so the interrupted write can show there.
    match reader_connection(path, wal).and_then(|c| identify(&c)) {
        Err(StoreError::InterruptedWrite) => {
            let flags = OpenFlags::SQLITE_OPEN_READ_ONLY
                | OpenFlags::SQLITE_OPEN_NO_MUTEX
                | OpenFlags::SQLITE_OPEN_URI;
            let conn = Connection::open_with_flags(uri(path, "immutable=1")?, flags)?;
            identify(&conn).map_err(as_damage)
        }
        other => other.map_err(as_damage),
    }
}

impl StoreWriter {
    /// Opens the database at `path` for writing by this process alone, creating it when the
    /// path is new or an empty file. With `run`, the file's settings must equal the run's (a
    /// file without settings takes them); without, settings are left to the caller (merging).
    pub fn open(path: &Path, run: Option<RunInfo<'_>>, check: Check) -> StoreResult<StoreWriter> {
        // Refuse what is not ours before creating anything beside it.
        if let FileState::Sqlite { wal } = inspect(path)? {
            precheck(path, wal)?;
        }
        let lock = WriterLock::acquire(path)?;
        let flags = OpenFlags::SQLITE_OPEN_READ_WRITE | OpenFlags::SQLITE_OPEN_NO_MUTEX;
        let conn = match inspect(path)? {
            state @ (FileState::Missing | FileState::Empty) => {
                let mut conn =
                    Connection::open_with_flags(path, flags | OpenFlags::SQLITE_OPEN_CREATE)?;
                conn.busy_timeout(WRITER_BUSY)?;
                if let Err(e) = create_schema(&mut conn) {
                    drop(conn);
                    if state == FileState::Missing {
                        let _ = std::fs::remove_file(path);
                    }
                    return Err(e);
                }
                conn
            }
            FileState::Sqlite { wal } => {
                precheck(path, wal)?;
                let conn = Connection::open_with_flags(path, flags)?;
                conn.busy_timeout(WRITER_BUSY)?;
                if wal {
                    // Back to a rollback journal, so readers never need files beside it.
                    conn.pragma_update(None, "journal_mode", "DELETE")?;
                }
                conn
            }
        };
        conn.pragma_update(None, "foreign_keys", true)?;
        conn.pragma_update(None, "cache_size", CACHE_KIB)?;
        let writer = StoreWriter {
            store: Store { conn },
            _lock: lock,
        };
        writer.check_file(check).map_err(as_damage)?;
        writer.conn.execute_batch(crate::schema::OPTIONAL_TABLES)?;
        if let Some(run) = run {
            match writer.settings()? {
                None => {
                    put_meta(&writer.conn, "settings", run.settings)?;
                    put_meta(&writer.conn, "tool_version", run.tool_version)?;
                }
                Some(s) if s == run.settings => {}
                Some(s) => {
                    return Err(StoreError::SettingsMismatch(
                        crate::settings_diff::settings_difference(
                            &s,
                            "the file",
                            run.settings,
                            "this run",
                        ),
                    ))
                }
            }
        }
        Ok(writer)
    }
}

/// Whether the file has the (optional) table `name`: files made before it existed lack it.
pub(crate) fn has_table(conn: &rusqlite::Connection, name: &str) -> StoreResult<bool> {
    Ok(conn.query_row(
        "SELECT count(*) > 0 FROM sqlite_master WHERE type = 'table' AND name = ?1",
        [name],
        |r| r.get(0),
    )?)
}
