//! Writing a command's output files: all of them or none, and never replacing what is not a
//! regular file.
//!
//! A command collects its outputs in [`Outputs`] and writes them with [`Outputs::write`]:
//!
//! 1. every destination is checked before anything is written: a regular file or a new name
//!    in an existing folder is replaced atomically; a **symbolic link is followed** (its
//!    target is written, the link stays; a link to nothing is refused); a character device
//!    (`/dev/null`, a terminal) or a FIFO is written through; a folder, a block device or a
//!    socket is refused; two outputs naming the same file are refused;
//! 2. every replaced file is written to a temporary file beside it (folders the outputs need
//!    are made first); a failure removes the temporary files and the folders it made;
//! 3. then the temporary files are renamed into place together, and devices and FIFOs
//!    written last (what went into them cannot be taken back).
//!
//! So a refused or failed command leaves no half-written file and changes no file but its
//! own outputs.

use std::fs::{self, File, Metadata, OpenOptions};
use std::io::{ErrorKind, Write};
use std::os::unix::fs::FileTypeExt;
use std::path::{Path, PathBuf};

/// Files a command writes, with their contents.
#[derive(Debug, Default)]
pub struct Outputs {
    files: Vec<(PathBuf, Vec<u8>)>,
    folders: Vec<PathBuf>,
}

/// Where one output goes, once checked.
#[derive(Debug)]
enum Destination {
    /// A regular file (or a new name): replaced atomically.
    Replace(PathBuf),
    /// A character device or FIFO: written through.
    Through(PathBuf),
}

impl Destination {
    /// The path written.
    fn path(&self) -> &Path {
        match self {
            Destination::Replace(p) | Destination::Through(p) => p,
        }
    }
}

impl Outputs {
    /// No outputs yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a file to write.
    pub fn file(&mut self, path: &Path, contents: Vec<u8>) {
        self.files.push((path.to_path_buf(), contents));
    }

    /// Adds a folder to make (with its missing parents) before the files in it are written.
    pub fn folder(&mut self, path: &Path) {
        self.folders.push(path.to_path_buf());
    }

    /// Checks every destination as [`Outputs::write`] does, writing nothing. A command
    /// checks its output paths (contents still empty) before its work, so that a folder given
    /// for a file, a missing parent or two outputs naming one file is refused at once, not
    /// after minutes of computing.
    pub fn check(&self) -> Result<(), String> {
        self.destinations().map(drop)
    }

    /// Every output's checked destination (see the module documentation, step 1).
    fn destinations(&self) -> Result<Vec<(PathBuf, Destination)>, String> {
        for folder in &self.folders {
            check_folder(folder)?;
        }
        let mut destinations: Vec<(PathBuf, Destination)> = Vec::with_capacity(self.files.len());
        for (path, _) in &self.files {
            let d = destination(path, &self.folders)?;
            if destinations.iter().any(|(_, e)| e.path() == d.path()) {
                return Err(format!("{}: named twice among the outputs", path.display()));
            }
            destinations.push((path.clone(), d));
        }
        Ok(destinations)
    }

    /// Writes every output, or none (see the module documentation); the error is one line
    /// naming the path. Temporary files that a killed earlier run left beside a destination
    /// are removed first.
    pub fn write(self) -> Result<(), String> {
        let destinations = self.destinations()?;
        for (_, d) in &destinations {
            if let Destination::Replace(real) = d {
                remove_stale_temps(real);
            }
        }
        let made = make_folders(&self.folders)?;
        let mut temps: Vec<(PathBuf, PathBuf)> = Vec::new();
        let staged = (|| {
            for ((path, d), (_, contents)) in destinations.iter().zip(&self.files) {
                if let Destination::Replace(real) = d {
                    let temp = temp_beside(real, temps.len());
                    temps.push((temp.clone(), real.clone()));
                    write_temp(&temp, real, contents)
                        .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
                }
            }
            Ok::<(), String>(())
        })();
        if let Err(e) = staged {
            for (temp, _) in &temps {
                let _ = fs::remove_file(temp);
            }
            for folder in made.iter().rev() {
                let _ = fs::remove_dir(folder);
            }
            return Err(e);
        }
        for (temp, real) in &temps {
            if let Err(e) = fs::rename(temp, real) {
                let _ = fs::remove_file(temp);
                return Err(format!("cannot write {}: {e}", real.display()));
            }
        }
        for ((path, d), (_, contents)) in destinations.iter().zip(&self.files) {
            if let Destination::Through(real) = d {
                OpenOptions::new()
                    .write(true)
                    .open(real)
                    .and_then(|mut f| f.write_all(contents).and_then(|_| f.flush()))
                    .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
            }
        }
        Ok(())
    }
}

/// Writes one file (see [`Outputs`]).
pub fn write_file(path: &Path, contents: &[u8]) -> Result<(), String> {
    let mut out = Outputs::new();
    out.file(path, contents.to_vec());
    out.write()
}

/// Checks that `folder` is a folder or can be made: its nearest existing ancestor is one.
fn check_folder(folder: &Path) -> Result<(), String> {
    let mut at = folder;
    loop {
        match fs::metadata(at) {
            Ok(m) if m.is_dir() => return Ok(()),
            Ok(_) if at == folder => {
                return Err(format!(
                    "{}: is a file, expected a folder",
                    folder.display()
                ))
            }
            Ok(_) => {
                return Err(format!(
                    "cannot make folder {}: {} is not a folder",
                    folder.display(),
                    at.display()
                ))
            }
            Err(e) if e.kind() == ErrorKind::NotFound => match at.parent() {
                Some(p) if !p.as_os_str().is_empty() => at = p,
                _ => return Ok(()),
            },
            Err(e) => return Err(format!("{}: {e}", at.display())),
        }
    }
}

/// Makes the folders that do not exist yet; returns those it made, parents first.
fn make_folders(folders: &[PathBuf]) -> Result<Vec<PathBuf>, String> {
    let mut made = Vec::new();
    for folder in folders {
        let mut missing = Vec::new();
        let mut at = folder.as_path();
        while !at.as_os_str().is_empty() && fs::symlink_metadata(at).is_err() {
            missing.push(at.to_path_buf());
            match at.parent() {
                Some(p) => at = p,
                None => break,
            }
        }
        for m in missing.into_iter().rev() {
            if let Err(e) = fs::create_dir(&m) {
                for f in made.iter().rev() {
                    let _ = fs::remove_dir(f);
                }
                return Err(format!("cannot make folder {}: {e}", m.display()));
            }
            made.push(m);
        }
    }
    Ok(made)
}

/// Where `path` is written: symbolic links followed, its kind checked.
fn destination(path: &Path, folders: &[PathBuf]) -> Result<Destination, String> {
    let shown = path.display();
    match fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() => {
            let real = fs::canonicalize(path).map_err(|_| {
                format!("{shown}: a symbolic link to nothing (give the file it should point at)")
            })?;
            let m = fs::metadata(&real).map_err(|e| format!("{shown}: {e}"))?;
            kind(path, real, &m)
        }
        Ok(m) => kind(path, path.to_path_buf(), &m),
        Err(e) if matches!(e.kind(), ErrorKind::NotFound | ErrorKind::NotADirectory) => {
            if path.file_name().is_none() {
                return Err(format!("{shown}: not a file path"));
            }
            let parent = path
                .parent()
                .filter(|p| !p.as_os_str().is_empty())
                .unwrap_or(Path::new("."));
            if folders.iter().any(|f| f == parent) {
                return Ok(Destination::Replace(path.to_path_buf()));
            }
            match fs::metadata(parent) {
                Ok(m) if m.is_dir() => Ok(Destination::Replace(path.to_path_buf())),
                Ok(_) => Err(format!(
                    "cannot write {shown}: {} is not a folder",
                    parent.display()
                )),
                Err(_) => Err(format!(
                    "cannot write {shown}: folder {} does not exist",
                    parent.display()
                )),
            }
        }
        Err(e) => Err(format!("{shown}: {e}")),
    }
}

/// The destination for an existing `real` path (shown as `path`).
fn kind(path: &Path, real: PathBuf, m: &Metadata) -> Result<Destination, String> {
    let t = m.file_type();
    let refuse = |what: &str| {
        Err(format!(
            "{}: is a {what}; not written (outputs go to files, character devices or FIFOs)",
            path.display()
        ))
    };
    if t.is_file() {
        Ok(Destination::Replace(real))
    } else if t.is_char_device() || t.is_fifo() {
        Ok(Destination::Through(real))
    } else if t.is_dir() {
        refuse("folder")
    } else if t.is_block_device() {
        refuse("block device")
    } else if t.is_socket() {
        refuse("socket")
    } else {
        refuse("special file")
    }
}

/// A temporary name beside `real`, unique in this process: `.NAME.tmpPID-K`.
fn temp_beside(real: &Path, k: usize) -> PathBuf {
    real.with_file_name(format!(
        ".{}.tmp{}-{k}",
        file_name(real),
        std::process::id()
    ))
}

/// The file name of `real` as text (`output` for none).
fn file_name(real: &Path) -> String {
    real.file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned())
}

/// Removes the temporary files ([`temp_beside`]) of `real` whose process is gone: a run
/// killed between writing and renaming them (SIGKILL cannot be caught) leaves them. A file
/// of a process that still runs is left alone, and so is everything not named so. Only
/// where `/proc` tells which processes run.
fn remove_stale_temps(real: &Path) {
    let proc = Path::new("/proc/self");
    if !proc.exists() {
        return;
    }
    let prefix = format!(".{}.tmp", file_name(real));
    let folder = match real.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let Ok(entries) = fs::read_dir(folder) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some((pid, k)) = name
            .strip_prefix(&prefix)
            .and_then(|rest| rest.split_once('-'))
        else {
            continue;
        };
        let ours = !pid.is_empty()
            && pid.bytes().all(|b| b.is_ascii_digit())
            && !k.is_empty()
            && k.bytes().all(|b| b.is_ascii_digit());
        let alive = Path::new("/proc").join(pid).exists();
        if ours && !alive && entry.file_type().is_ok_and(|t| t.is_file()) {
            let _ = fs::remove_file(entry.path());
        }
    }
}

/// Writes `contents` to the new file `temp`, with the permissions of the file it will
/// replace when there is one.
fn write_temp(temp: &Path, real: &Path, contents: &[u8]) -> std::io::Result<()> {
    let mut f = OpenOptions::new().write(true).create_new(true).open(temp)?;
    f.write_all(contents)?;
    f.sync_all()?;
    if let Ok(m) = fs::metadata(real) {
        fs::set_permissions(temp, m.permissions())?;
    }
    drop::<File>(f);
    Ok(())
}
