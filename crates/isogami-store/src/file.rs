//! What is at a path, found without SQLite touching it: nothing, an empty file, something
//! that is not SQLite, or an SQLite file (in rollback-journal or WAL mode).

use crate::error::{StoreError, StoreResult};
use std::ffi::OsString;
use std::io::Read;
use std::path::{Path, PathBuf};

/// The first 16 bytes of every SQLite database file.
const SQLITE_MAGIC: &[u8; 16] = b"SQLite format 3\0";

/// What a path holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum FileState {
    /// Nothing there.
    Missing,
    /// A file of zero bytes.
    Empty,
    /// A file with SQLite's header; `wal` when the header says write-ahead logging.
    Sqlite {
        /// WAL mode (header bytes 18 and 19 are 2).
        wal: bool,
    },
}

/// Looks at the path and the file's first 100 bytes (SQLite's header). A non-empty file
/// without SQLite's header is [`StoreError::NotSqlite`].
pub(crate) fn inspect(path: &Path) -> StoreResult<FileState> {
    let meta = match std::fs::metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(FileState::Missing),
        Err(e) => return Err(e.into()),
    };
    if !meta.is_file() {
        return Err(StoreError::NotAFile);
    }
    if meta.len() == 0 {
        return Ok(FileState::Empty);
    }
    let mut header = Vec::with_capacity(100);
    std::fs::File::open(path)?
        .take(100)
        .read_to_end(&mut header)?;
    if header.len() < 100 || &header[..16] != SQLITE_MAGIC {
        return Err(StoreError::NotSqlite);
    }
    Ok(FileState::Sqlite {
        wal: header[18] == 2 || header[19] == 2,
    })
}

/// `path` with `suffix` appended to its file name, as SQLite names its journal files.
pub(crate) fn beside(path: &Path, suffix: &str) -> PathBuf {
    let mut s: OsString = path.as_os_str().to_owned();
    s.push(suffix);
    PathBuf::from(s)
}

/// The files SQLite (or this crate) may create beside a database.
pub fn sidecar_paths(path: &Path) -> [PathBuf; 4] {
    [
        beside(path, "-journal"),
        beside(path, "-wal"),
        beside(path, "-shm"),
        beside(path, crate::lock::LOCK_SUFFIX),
    ]
}

/// An SQLite URI (`file:…?params`) for `path`, percent-encoding every byte that is not
/// unreserved so that `?`, `#` and `%` in file names stay part of the name.
pub(crate) fn uri(path: &Path, params: &str) -> StoreResult<String> {
    let abs = std::path::absolute(path)?;
    let raw = abs
        .to_str()
        .ok_or_else(|| std::io::Error::other("the database path is not valid UTF-8"))?;
    let mut out = String::from("file:");
    for b in raw.bytes() {
        if b.is_ascii_alphanumeric() || b"/-._~:".contains(&b) {
            out.push(char::from(b));
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out.push('?');
    out.push_str(params);
    Ok(out)
}
