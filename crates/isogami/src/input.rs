//! What every front end reads from its user, bounded: files read by [`read_text`] (a regular
//! file, at most a stated size, UTF-8; never a device, FIFO or folder, which could block or
//! never end) and inputs echoed in one-line messages by [`clip_echo`] (a pasted megabyte
//! number or a 5,000-character path comes back cut to its first characters).

use std::io::Read;
use std::path::Path;
use thiserror::Error;

/// Longest SVG target outline file read (bytes).
pub use crate::graded::svg::MAX_SVG_BYTES;

/// Longest graded sheet file read (bytes): a 40×40-cell sheet with its path states is a few
/// megabytes.
pub const MAX_SHEET_BYTES: usize = 256 << 20;

/// Longest inverse-design target file read (bytes).
pub const MAX_TARGET_BYTES: usize = 1 << 20;

/// Longest run of non-blank characters a message echoes whole.
pub const MAX_ECHO: usize = 80;

/// Why a file could not be read.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum InputError {
    /// Not a regular file (a folder, device, FIFO or socket).
    #[error("{path}: is a {kind}, not a regular file")]
    NotAFile {
        /// The path, clipped.
        path: String,
        /// What it is instead.
        kind: &'static str,
    },
    /// Longer than the limit for this kind of input.
    #[error("{path}: {bytes} bytes, more than the {limit} read")]
    TooLarge {
        /// The path, clipped.
        path: String,
        /// Its size (at least this many bytes).
        bytes: u64,
        /// The limit, as text (`16 MiB`).
        limit: String,
    },
    /// Not UTF-8 text.
    #[error("{path}: is not UTF-8 text")]
    NotText {
        /// The path, clipped.
        path: String,
    },
    /// The operating system's error (missing, not permitted, …).
    #[error("{path}: cannot read it: {message}")]
    Io {
        /// The path, clipped.
        path: String,
        /// The system's words.
        message: String,
    },
}

/// The text of the regular file at `path` (symbolic links followed), refused when it is not
/// a regular file or is longer than `max_bytes`. Reads at most `max_bytes + 1` bytes, so a
/// file that grows while it is read is refused too.
pub fn read_text(path: &Path, max_bytes: usize) -> Result<String, InputError> {
    let shown = clip_echo(&path.display().to_string());
    let io = |e: std::io::Error| InputError::Io {
        path: shown.clone(),
        message: e.to_string(),
    };
    let meta = std::fs::metadata(path).map_err(io)?;
    if !meta.is_file() {
        return Err(InputError::NotAFile {
            path: shown,
            kind: file_kind(&meta),
        });
    }
    let too_large = |bytes: u64| InputError::TooLarge {
        path: shown.clone(),
        bytes,
        limit: byte_size(max_bytes),
    };
    if meta.len() > max_bytes as u64 {
        return Err(too_large(meta.len()));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    std::fs::File::open(path)
        .and_then(|f| f.take(max_bytes as u64 + 1).read_to_end(&mut bytes))
        .map_err(io)?;
    if bytes.len() > max_bytes {
        return Err(too_large(bytes.len() as u64));
    }
    String::from_utf8(bytes).map_err(|_| InputError::NotText {
        path: shown.clone(),
    })
}

/// What a file that is not a regular one is.
fn file_kind(meta: &std::fs::Metadata) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    let t = meta.file_type();
    if t.is_dir() {
        "folder"
    } else if t.is_fifo() {
        "FIFO"
    } else if t.is_char_device() {
        "character device"
    } else if t.is_block_device() {
        "block device"
    } else if t.is_socket() {
        "socket"
    } else {
        "special file"
    }
}

/// `n` bytes in words: `16 MiB`, `48 KiB`, `100 bytes`.
pub fn byte_size(n: usize) -> String {
    match n {
        n if n >= 1 << 20 && n % (1 << 20) == 0 => format!("{} MiB", n >> 20),
        n if n >= 1 << 10 && n % (1 << 10) == 0 => format!("{} KiB", n >> 10),
        n => format!("{n} bytes"),
    }
}

/// `message` with every run of more than [`MAX_ECHO`] non-blank characters cut to its first
/// 60 and a note of its length: `1111…(1000000 characters)`. Shorter runs, and so every
/// message of the library's own words, come back unchanged.
pub fn clip_echo(message: &str) -> String {
    let mut out = String::with_capacity(message.len().min(4 * MAX_ECHO));
    let mut rest = message;
    while !rest.is_empty() {
        let blank = rest
            .find(|c: char| !c.is_whitespace())
            .unwrap_or(rest.len());
        out.push_str(&rest[..blank]);
        rest = &rest[blank..];
        let word_end = rest.find(char::is_whitespace).unwrap_or(rest.len());
        let word = &rest[..word_end];
        let count = word.chars().count();
        if count > MAX_ECHO {
            out.extend(word.chars().take(60));
            out.push_str(&format!("…({count} characters)"));
        } else {
            out.push_str(word);
        }
        rest = &rest[word_end..];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    fn temp_dir() -> tempfile::TempDir {
        tempfile::tempdir().unwrap()
    }

    /// Issue 42: `--target @/dev/zero` read until memory ran out, and a FIFO with no writer
    /// blocked forever; both are refused before a byte is read, as is a folder.
    #[test]
    fn devices_fifos_and_folders_are_refused_unread() {
        let dir = temp_dir();
        let fifo = dir.path().join("pipe.svg");
        let status = std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap();
        assert!(status.success());
        for (path, kind) in [
            (Path::new("/dev/zero"), "character device"),
            (fifo.as_path(), "FIFO"),
            (dir.path(), "folder"),
        ] {
            let e = read_text(path, 1 << 20).unwrap_err();
            assert!(
                matches!(&e, InputError::NotAFile { kind: k, .. } if *k == kind),
                "{e}"
            );
            assert_eq!(e.to_string().lines().count(), 1);
        }
    }

    /// A file over the limit is refused with its size; one at the limit is read whole.
    #[test]
    fn sizes_are_bounded() {
        let dir = temp_dir();
        let path = dir.path().join("a.svg");
        std::fs::File::create(&path)
            .unwrap()
            .write_all(&[b'x'; 1025])
            .unwrap();
        let e = read_text(&path, 1024).unwrap_err();
        assert_eq!(
            e.to_string(),
            format!("{}: 1025 bytes, more than the 1 KiB read", path.display())
        );
        assert_eq!(read_text(&path, 1025).unwrap().len(), 1025);
        std::fs::write(&path, [0xff, 0xfe]).unwrap();
        assert!(matches!(
            read_text(&path, 1024),
            Err(InputError::NotText { .. })
        ));
        let missing = read_text(&dir.path().join("no.svg"), 10).unwrap_err();
        assert!(matches!(missing, InputError::Io { .. }), "{missing}");
    }

    /// Long runs are cut, short words and blanks kept, for any length and any characters.
    #[test]
    fn echoes_are_clipped() {
        let number = "1".repeat(1_000_000);
        let clipped = clip_echo(&format!("--t: '{number}' is not a number"));
        assert_eq!(
            clipped,
            format!(
                "--t: '{}…(1000002 characters) is not a number",
                "1".repeat(59)
            )
        );
        let path = format!("/{}", "é/".repeat(2_500));
        let clipped = clip_echo(&format!("cannot write {path}: no such folder"));
        assert!(clipped.chars().count() < 140, "{clipped}");
        // The path and its colon are one run of 5,002 characters.
        assert!(
            clipped.ends_with("…(5002 characters) no such folder"),
            "{clipped}"
        );
        let plain = "bad region: '3y3' is not a region:  write RxC";
        assert_eq!(clip_echo(plain), plain);
        let limit = "x".repeat(MAX_ECHO);
        assert_eq!(clip_echo(&limit), limit);
    }
}
