//! The writer lock: one writing process per database.
//!
//! A writer (explore, merge) holds an exclusive OS file lock on `FILE.lock` for as long as it
//! has the database open, so a second writer is refused at once with a clear message instead of
//! failing mid-run on a unique constraint. Readers never take it. The lock is released by the
//! operating system when the process ends in any way (kill -9 included), so a stale lock file
//! never blocks a later run; a writer that ends normally removes the file.
//!
//! A separate lock file is used rather than the database itself so the lock cannot interfere
//! with SQLite's own byte-range locks (they interact with `flock` on some network file
//! systems).

use crate::error::{StoreError, StoreResult};
use crate::file::beside;
use std::fs::{File, OpenOptions, TryLockError};
use std::path::{Path, PathBuf};

/// Suffix of the lock file beside a database.
pub(crate) const LOCK_SUFFIX: &str = ".lock";

/// A held writer lock; released (and its file removed) on drop.
#[derive(Debug)]
pub(crate) struct WriterLock {
    path: PathBuf,
    file: Option<File>,
}

/// True when `file` is still the file at `path` (not unlinked and replaced meanwhile).
#[cfg(unix)]
fn still_at(file: &File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn still_at(_file: &File, path: &Path) -> bool {
    path.exists()
}

impl WriterLock {
    /// Takes the lock of the database at `db`, or fails at once with [`StoreError::Busy`].
    pub(crate) fn acquire(db: &Path) -> StoreResult<WriterLock> {
        let path = beside(db, LOCK_SUFFIX);
        // A holder removes the file before it unlocks; a process that opened the old file
        // meanwhile may then lock an unlinked file, so it checks and tries again.
        for _ in 0..100 {
            let file = OpenOptions::new()
                .read(true)
                .write(true)
                .create(true)
                .truncate(false)
                .open(&path)?;
            match file.try_lock() {
                Ok(()) => {}
                Err(TryLockError::WouldBlock) => return Err(StoreError::Busy),
                Err(TryLockError::Error(e)) => return Err(e.into()),
            }
            if still_at(&file, &path) {
                return Ok(WriterLock {
                    path,
                    file: Some(file),
                });
            }
        }
        Err(StoreError::Busy)
    }
}

impl Drop for WriterLock {
    fn drop(&mut self) {
        // Remove while still holding the lock, then unlock by closing.
        let _ = std::fs::remove_file(&self.path);
        drop(self.file.take());
    }
}
