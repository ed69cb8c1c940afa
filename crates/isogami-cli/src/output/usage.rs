//! Usage errors as one line: clap's multi-line report (error, possible values, tip, usage,
//! "for more information") is folded into `error: <what> [; tip]; see 'isogami <cmd> --help'`
//! with exit code 2. `--help` and `--version` print as clap prints them, with exit code 0.

use crate::Cli;
use clap::error::ErrorKind;
use clap::CommandFactory;
use std::ffi::OsString;
use std::process::ExitCode;

/// Prints a parse failure (or the help / version clap reports through the same path) and
/// gives the exit code.
pub fn report(e: &clap::Error, args: &[OsString]) -> ExitCode {
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => match e.print() {
            Ok(()) => ExitCode::SUCCESS,
            Err(_) => ExitCode::from(2),
        },
        _ => {
            let path = command_path(args);
            eprintln!(
                "error: {}; see '{} --help'",
                isogami::input::clip_echo(&summary(e, &path)),
                path.join(" ")
            );
            ExitCode::from(2)
        }
    }
}

/// `text` on one line: line breaks become "; ", runs of blanks one space.
pub fn one_line(text: &str) -> String {
    text.lines()
        .map(|l| l.split_whitespace().collect::<Vec<_>>().join(" "))
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ")
}

/// The (sub)command the arguments name, e.g. `["isogami", "db", "stats"]`: the leading
/// non-option words that are subcommands.
fn command_path(args: &[OsString]) -> Vec<String> {
    let mut cmd = Cli::command();
    let mut path = vec![cmd.get_name().to_string()];
    for arg in args.iter().skip(1) {
        if cmd.get_subcommands().next().is_none() {
            break;
        }
        let Some(word) = arg.to_str() else { break };
        if word.starts_with('-') {
            continue;
        }
        let Some(sub) = cmd.find_subcommand(word).cloned() else {
            break;
        };
        path.push(sub.get_name().to_string());
        cmd = sub;
    }
    path
}

/// What went wrong, on one line, without clap's usage and "for more information" lines.
fn summary(e: &clap::Error, path: &[String]) -> String {
    if matches!(
        e.kind(),
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand | ErrorKind::MissingSubcommand
    ) {
        let mut cmd = Cli::command();
        for name in &path[1..] {
            match cmd.find_subcommand(name).cloned() {
                Some(sub) => cmd = sub,
                None => break,
            }
        }
        let names: Vec<String> = cmd
            .get_subcommands()
            .map(|s| s.get_name().to_string())
            .filter(|n| n != "help")
            .collect();
        return format!("a command is required (one of: {})", names.join(", "));
    }
    let rendered = e.render().to_string();
    let mut out = String::new();
    // Inside a list introduced by a line ending in ':' (e.g. the missing arguments).
    let mut listing = false;
    for line in rendered.lines().map(str::trim) {
        if line.starts_with("Usage:") || line.starts_with("For more information") {
            break;
        }
        if line.is_empty() {
            listing = false;
            continue;
        }
        let line = line.strip_prefix("error: ").unwrap_or(line);
        let sep = if out.is_empty() {
            ""
        } else if out.ends_with(':') || line.starts_with('[') {
            " "
        } else if listing && !line.starts_with("tip:") {
            ", "
        } else {
            "; "
        };
        listing = listing || out.ends_with(':');
        out.push_str(sep);
        out.push_str(line);
    }
    if out.is_empty() {
        one_line(&rendered)
    } else {
        out
    }
}
