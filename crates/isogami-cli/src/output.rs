//! Printing and file writing shared by the commands, and the output boundary: every JSON
//! value a command prints or writes goes through [`json_text`] (no NaN, infinity or `null`
//! standing in for a number), and every text it prints through [`emit`] (no formatted NaN or
//! infinity). A violation is a one-line error (exit code 2) instead of output.

mod files;
mod finite;
mod text;
pub mod usage;

pub use files::Outputs;
pub use finite::check_finite;
use serde::Serialize;
use std::io::Write;
use std::path::Path;

/// A command's failure, printed as one line.
pub type CliResult = Result<(), String>;

/// `value` as pretty JSON, after checking that every number in it is finite (serde_json
/// would write NaN and infinities as `null`).
pub fn json_text<T: Serialize + ?Sized>(value: &T) -> Result<String, String> {
    check_finite(value)
        .map_err(|e| format!("refusing to write JSON with a non-finite number: {e}"))?;
    serde_json::to_string_pretty(value).map_err(|e| format!("JSON output: {e}"))
}

/// Prints a value as pretty JSON on stdout (checked by [`json_text`]).
pub fn print_json<T: Serialize + ?Sized>(value: &T) -> CliResult {
    write_stdout(&(json_text(value)? + "\n"))
}

/// Writes `contents` to `path`: a regular file is replaced atomically, a symbolic link
/// followed, a device or FIFO written through (see [`Outputs`]); a failure never leaves a
/// partial file.
pub fn write_atomic(path: &Path, contents: &[u8]) -> CliResult {
    files::write_file(path, contents)
}

/// Parses a comma-separated parameter list.
pub fn parse_params(text: &str) -> Result<Vec<f64>, String> {
    if text.trim().is_empty() {
        return Ok(Vec::new());
    }
    text.split(',')
        .enumerate()
        .map(|(i, p)| {
            p.trim()
                .parse::<f64>()
                .map_err(|_| format!("--params: v{i} '{}' is not a number", p.trim()))
        })
        .collect()
}

/// Appends a formatted line to a `String` buffer.
macro_rules! outln {
    ($buf:expr, $($arg:tt)*) => {{
        use std::fmt::Write as _;
        let _ = writeln!($buf, $($arg)*);
    }};
}

/// Writes a finished text to stdout; a closed pipe (`| head`) is not an error. A text
/// holding a formatted NaN or infinity is refused whole (nothing is printed).
pub fn emit(text: &str) -> CliResult {
    check_text(text)?;
    write_stdout(text)
}

/// Refuses a text holding a formatted NaN or infinity (the check [`emit`] makes).
pub fn check_text(text: &str) -> CliResult {
    match text::find_non_finite(text) {
        Some((line, word)) => Err(format!(
            "refusing to print a non-finite number ('{word}' in output line {line})"
        )),
        None => Ok(()),
    }
}

/// Writes `text` to stdout as it is; a closed pipe (`| head`) is not an error.
fn write_stdout(text: &str) -> CliResult {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(e) => Err(format!("cannot write to stdout: {e}")),
    }
}
