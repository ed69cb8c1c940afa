//! `isogami export`: a patch of a design in millimetres, or a graded sheet (`--sheet`, the
//! file `isogami graded` writes), written in one format.
//!
//! Arguments are read in two stages: the raw flags, then a validated [`PatchRequest`] and
//! options that the library's one export entry point ([`export_design`]) checks again; every
//! file is built in memory first and then written to a temporary name and renamed, so a bad
//! value or a failure leaves no file behind. The formats and their names come from the
//! library ([`Format`]).

use crate::output::{emit, write_atomic, CliResult, Outputs};
use isogami::api::resolve_design;
use isogami::contact::ContactSettings;
use isogami::export::{
    export_design, export_graded, read_graded, ExportError, ExportFiles, ExportOptions, Format,
    GradedPatchRequest, PatchRequest, Scale, SettingsGroup, State, MAX_PATCH,
};
use isogami::finite::{FiniteError, Region};
use isogami::input::{read_text, MAX_SHEET_BYTES};
use isogami::stop::NEVER;
use std::path::{Path, PathBuf};

/// The `--format` values: the library's formats by name, each with its description.
fn format_parser() -> impl clap::builder::TypedValueParser<Value = Format> {
    use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
    PossibleValuesParser::new(
        Format::ALL.map(|f| PossibleValue::new(f.name()).help(f.description())),
    )
    .try_map(|name| name.parse::<Format>())
}

/// Arguments of `export`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The design: a name (rotating-squares), a spec string, or design JSON.
    #[arg(
        long,
        allow_hyphen_values = true,
        required_unless_present = "sheet",
        conflicts_with = "sheet"
    )]
    design: Option<String>,
    /// A graded sheet instead of a design: the JSON file `isogami graded --out` writes (or a
    /// bare graded sheet). Written closed for laser formats; --t is its opening (0 closed,
    /// 1 or `open` the optimised state) and --frames keeps that many of its path's states.
    #[arg(long)]
    sheet: Option<PathBuf>,
    /// Output format.
    #[arg(long, value_parser = format_parser())]
    format: Format,
    /// Output file (a folder for kirigami-sim, created when missing).
    #[arg(long)]
    out: PathBuf,
    /// Patch size ROWSxCOLS in cells (rows along w, columns along u), each 1..=40.
    #[arg(long, default_value = "6x6", conflicts_with = "sheet")]
    patch: String,
    /// Another region instead of the patch, read as `isogami sheet --region` reads it: RxC
    /// cells, or in mm (at --edge-mm) rect:W,H, disc:R, polygon:x,y;x,y;… centred on cell
    /// [0, 0]. Completed like the patch (or written as it is with --raw).
    #[arg(long, conflicts_with_all = ["sheet", "patch", "width_mm"])]
    region: Option<Region>,
    /// Mean tile edge length in mm [default: 20].
    #[arg(long, allow_hyphen_values = true, conflicts_with = "width_mm")]
    edge_mm: Option<f64>,
    /// Width of the patch at the exported state in mm (instead of --edge-mm).
    #[arg(long, allow_hyphen_values = true)]
    width_mm: Option<f64>,
    /// State: t in [0, 1] (the nearest accepted state; 0 closed), `open` (the most open
    /// state: largest area ratio, often mid-path) or `limit` (where the path ends, at the
    /// contact limit). With --sheet: the opening in [0, 1] (the state of nearest opening; 0
    /// closed) or `open`/`limit` (the optimised state).
    #[arg(long, default_value = "0", allow_hyphen_values = true)]
    t: String,
    /// Cut width relative to the mean edge length, for the deployment's contact model.
    #[arg(
        long,
        default_value_t = ContactSettings::default().kerf,
        allow_hyphen_values = true,
        conflicts_with = "sheet"
    )]
    kerf: f64,
    /// Deployment states written as frames by animated formats (FOLD), 2..=100.
    #[arg(long, default_value_t = PatchRequest::default().frames)]
    frames: usize,
    /// Write the ROWSxCOLS rectangle as it is, floppy boundary and all (a warning names its
    /// degrees of freedom). Without it the rectangle's completion is written: a sheet with
    /// exactly the design's one motion (tiles held by fewer than two pins or flopping at the
    /// boundary pruned, the ring of tiles that closes open linkage loops added), or the
    /// export is refused with the reason when there is none; `isogami sheet` shows what
    /// completion does.
    #[arg(long, conflicts_with = "sheet")]
    raw: bool,
    /// The default (write the completion); kept for scripts written when it was opt-in.
    #[arg(long, hide = true, conflicts_with = "raw")]
    complete: bool,
    #[command(flatten)]
    laser: super::laser_args::LaserArgs,
    #[command(flatten)]
    print: super::print_args::PrintArgs,
}

/// Builds the patch and writes the file(s).
pub fn run(args: Args) -> CliResult {
    let request = request(&args)?;
    let options = options(&args)?;
    // The destination before the work: a sheet can take minutes.
    check_out(&args.out, args.format.extension().is_none())?;
    let (patch, files) = match (&args.sheet, &args.design) {
        (Some(path), _) => {
            let graded = GradedPatchRequest {
                scale: request.scale,
                state: request.state,
                frames: request.frames,
            };
            let text = read_text(path, MAX_SHEET_BYTES).map_err(|e| format!("--sheet {e}"))?;
            let input =
                read_graded(&text).map_err(|e| format!("--sheet {}: {e}", path.display()))?;
            export_graded(
                &input.sheet,
                input.path.as_ref(),
                &graded,
                args.format,
                &options,
                NEVER,
            )
            .map_err(|e| format!("--sheet {}: {e}", path.display()))?
        }
        (None, design) => {
            let design = design.as_deref().ok_or("--design or --sheet is required")?;
            let design = resolve_design(design).map_err(|e| e.to_string())?;
            export_design(&design, &request, args.format, &options, &mut |_| true).map_err(|e| {
                match e {
                    ExportError::Library(isogami::Error::Finite(FiniteError::NoOneDofSheet {
                        ..
                    })) => format!("{e}; --raw exports the rectangle as it is"),
                    e => e.to_string(),
                }
            })?
        }
    };
    write_files(&args.out, &files)?;
    let f = &patch.finite;
    let sheet = if let Some(g) = &f.graded {
        format!(
            "graded sheet, {} DOF at {:.0} % open",
            g.dof.map_or("uncounted".into(), |d| d.to_string()),
            100.0 * g.counted_at
        )
    } else if f.completed {
        format!(
            "one-DOF completion: {} of {} requested tiles kept, {} added, {:.1} % covered",
            f.requested_tiles - f.removed_tiles,
            f.requested_tiles,
            f.added_tiles,
            100.0 * f.covered_fraction
        )
    } else {
        format!(
            "raw {}, {} DOF",
            if args.region.is_some() {
                "region"
            } else {
                "rectangle"
            },
            f.dof
        )
    };
    emit(&format!(
        "wrote {} ({} tiles, {} joints, t = {:.4}, {:.1} x {:.1} mm; {sheet})\n",
        args.out.display(),
        patch.tiles.len(),
        patch.joints.len(),
        patch.t,
        patch.size_mm[0],
        patch.size_mm[1]
    ))?;
    if let Some(w) = f.warning() {
        eprintln!("warning: {w}");
    }
    Ok(())
}

/// The format's own settings group, read from its flags and checked (the other groups'
/// flags are ignored).
fn options(args: &Args) -> Result<ExportOptions, String> {
    let mut options = ExportOptions::default();
    match args.format.settings_group() {
        SettingsGroup::Laser => options.laser = args.laser.settings()?,
        SettingsGroup::Print => {
            options.print = args
                .print
                .settings(args.laser.hinge_mm, args.laser.thickness_mm)?
        }
        SettingsGroup::None => {}
    }
    options.validate(args.format).map_err(|e| e.to_string())?;
    Ok(options)
}

/// Checks `--out` as a file or, for a folder format, a folder, writing nothing.
fn check_out(out: &Path, folder: bool) -> CliResult {
    let mut outputs = Outputs::new();
    if folder {
        if out.exists() && !out.is_dir() {
            return Err(format!(
                "--out {}: is a file, expected a folder",
                out.display()
            ));
        }
        outputs.folder(out);
    } else {
        if out.is_dir() {
            return Err(format!(
                "--out {}: is a folder, expected a file",
                out.display()
            ));
        }
        outputs.file(out, Vec::new());
    }
    outputs.check()
}

fn write_files(out: &Path, files: &ExportFiles) -> CliResult {
    check_out(out, matches!(files, ExportFiles::Folder(_)))?;
    match files {
        ExportFiles::One(bytes) => write_atomic(out, bytes),
        ExportFiles::Folder(named) => {
            // All the folder's files, or none.
            let mut outputs = Outputs::new();
            outputs.folder(out);
            for (name, bytes) in named {
                outputs.file(&out.join(name), bytes.clone());
            }
            outputs.write()
        }
    }
}

/// The validated request of the raw flags.
fn request(args: &Args) -> Result<PatchRequest, String> {
    let (rows, cols) = parse_patch(&args.patch)?;
    let scale = match (args.edge_mm, args.width_mm) {
        (_, Some(w)) => Scale::WidthMm(w),
        (Some(e), None) => Scale::EdgeMm(e),
        (None, None) => Scale::EdgeMm(20.0),
    };
    let state: State = args.t.parse().map_err(|e| format!("--{e}"))?;
    let request = PatchRequest {
        rows,
        cols,
        scale,
        state,
        kerf: args.kerf,
        frames: args.frames,
        complete: !args.raw,
        region: args.region.clone(),
    };
    request.validate().map_err(|e| e.to_string())?;
    Ok(request)
}

/// `ROWSxCOLS`.
fn parse_patch(text: &str) -> Result<(usize, usize), String> {
    let bad = || format!("--patch '{text}': expected ROWSxCOLS, each 1..={MAX_PATCH}, e.g. 6x6");
    let (r, c) = text.trim().split_once(['x', 'X']).ok_or_else(bad)?;
    let r = r.trim().parse::<usize>().map_err(|_| bad())?;
    let c = c.trim().parse::<usize>().map_err(|_| bad())?;
    Ok((r, c))
}
