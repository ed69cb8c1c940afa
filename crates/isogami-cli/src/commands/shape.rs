//! `isogami shape`: shape-aware mobility of a design (the library's `shape_space`): generic or
//! special, the shape constraints that keep one degree of freedom, moving a parameter along
//! them, and the search of a rigid design's shapes for one that moves; or the classification
//! of every design in a database.

use crate::output::{emit, print_json, CliResult};
use isogami::api::resolve_design;
use isogami::shape_space::{classify, follow, rank_drop, ShapeClass, ShapeMobility, ShapeSettings};
use isogami::topology::Design;
use isogami_store::{Check, DesignQuery, Store};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// Arguments of `shape`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The design: a name, a spec string, or design JSON.
    #[arg(long, allow_hyphen_values = true, required_unless_present = "db")]
    design: Option<String>,
    /// Move shape parameter I (0-based) to VALUE, adjusting the others so the design keeps one
    /// degree of freedom: I=VALUE.
    #[arg(long, allow_hyphen_values = true, conflicts_with = "db")]
    set: Option<String>,
    /// Search the design's shapes for one with exactly one degree of freedom (for a design
    /// that is rigid at its own shape).
    #[arg(long, conflicts_with_all = ["db", "set"])]
    rank_drop: bool,
    /// Classify every design of this database instead (a table per family).
    #[arg(long, conflicts_with = "design")]
    db: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

fn design_of(text: &str) -> Result<Design, String> {
    resolve_design(text).map_err(|e| e.to_string())
}

fn set_of(text: &str) -> Result<(usize, f64), String> {
    let bad = || {
        format!(
            "--set '{}': expected I=VALUE, e.g. 0=0.25",
            text.escape_debug()
        )
    };
    let (i, v) = text.split_once('=').ok_or_else(bad)?;
    Ok((
        i.trim().parse().map_err(|_| bad())?,
        v.trim().parse().map_err(|_| bad())?,
    ))
}

fn mobility_text(m: &ShapeMobility) -> String {
    let mut o = String::new();
    outln!(o, "design          {}", m.design);
    outln!(o, "class           {}", class_name(m.class));
    outln!(
        o,
        "nearby shapes   {} of {} keep one DOF",
        m.samples_one_dof,
        m.samples
    );
    outln!(o, "self-stresses   {}", m.self_stresses);
    for (k, n) in m.constraints.iter().enumerate() {
        let n: Vec<String> = n.iter().map(|x| format!("{x:+.4}")).collect();
        outln!(o, "constraint {k}    n·δp = 0 with n = ({})", n.join(", "));
    }
    if !m.pinned.is_empty() {
        let p: Vec<String> = m.pinned.iter().map(|i| i.to_string()).collect();
        outln!(o, "pinned          parameter(s) {}", p.join(", "));
    }
    o
}

fn class_name(c: ShapeClass) -> &'static str {
    match c {
        ShapeClass::FixedShape => "fixed shape (no shape parameters)",
        ShapeClass::Generic => "generic: one DOF at every nearby shape",
        ShapeClass::Special => "special: one DOF only on a subset of shapes",
    }
}

#[derive(Serialize, Default)]
struct FamilyCount {
    generic: usize,
    special: usize,
    fixed_shape: usize,
    failed: usize,
}

#[derive(Serialize)]
struct DbOut {
    families: BTreeMap<String, FamilyCount>,
    special: Vec<ShapeMobility>,
    failures: Vec<(String, String)>,
}

fn classify_db(path: &std::path::Path, settings: &ShapeSettings, json: bool) -> CliResult {
    let store =
        Store::open_read(path, Check::Quick).map_err(|e| format!("{}: {e}", path.display()))?;
    let candidates = store
        .candidates(&DesignQuery::default())
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let mut out = DbOut {
        families: BTreeMap::new(),
        special: Vec::new(),
        failures: Vec::new(),
    };
    for c in &candidates {
        let count = out.families.entry(c.design.family.to_string()).or_default();
        match classify(&c.design, settings) {
            Ok(m) => {
                match m.class {
                    ShapeClass::Generic => count.generic += 1,
                    ShapeClass::Special => count.special += 1,
                    ShapeClass::FixedShape => count.fixed_shape += 1,
                }
                if m.class == ShapeClass::Special {
                    out.special.push(m);
                }
            }
            Err(e) => {
                count.failed += 1;
                out.failures.push((c.design.to_string(), e.to_string()));
            }
        }
    }
    if json {
        return print_json(&out);
    }
    let mut o = String::new();
    outln!(
        o,
        "{:<8} {:>8} {:>8} {:>12} {:>7}",
        "family",
        "generic",
        "special",
        "fixed shape",
        "failed"
    );
    let mut total = FamilyCount::default();
    for (f, c) in &out.families {
        outln!(
            o,
            "{f:<8} {:>8} {:>8} {:>12} {:>7}",
            c.generic,
            c.special,
            c.fixed_shape,
            c.failed
        );
        total.generic += c.generic;
        total.special += c.special;
        total.fixed_shape += c.fixed_shape;
        total.failed += c.failed;
    }
    outln!(
        o,
        "{:<8} {:>8} {:>8} {:>12} {:>7}",
        "all",
        total.generic,
        total.special,
        total.fixed_shape,
        total.failed
    );
    for m in &out.special {
        outln!(
            o,
            "special  {} ({} constraint(s))",
            m.design,
            m.constraints.len()
        );
    }
    for (d, e) in &out.failures {
        outln!(o, "failed   {d}: {e}");
    }
    emit(&o)
}

/// Runs the shape-space analysis asked for.
pub fn run(args: Args) -> CliResult {
    let settings = ShapeSettings::default();
    if let Some(db) = &args.db {
        return classify_db(db, &settings, args.json);
    }
    let design = design_of(args.design.as_deref().unwrap_or_default())?;
    if args.rank_drop {
        let found = rank_drop(&design, &settings).map_err(|e| e.to_string())?;
        if args.json {
            return print_json(&found);
        }
        return match found {
            Some(r) => emit(&format!(
                "one DOF at {}\nσ from {:.3e} to {:.3e} in {} shapes\n",
                r.spec, r.start_sigma, r.sigma, r.evaluations
            )),
            None => emit("no shape with one DOF found within the search box\n"),
        };
    }
    if let Some(set) = &args.set {
        let (i, v) = set_of(set)?;
        let moved = follow(&design, i, v, &settings).map_err(|e| e.to_string())?;
        if args.json {
            return print_json(&moved);
        }
        let adj: Vec<String> = moved.adjusted.iter().map(|x| format!("{x:+.4}")).collect();
        return emit(&format!(
            "{}\nclass {}, {} continuation step(s), parameters moved by ({}) scales\n",
            moved.spec,
            class_name(moved.class),
            moved.steps,
            adj.join(", ")
        ));
    }
    let m = classify(&design, &settings).map_err(|e| e.to_string())?;
    if args.json {
        return print_json(&m);
    }
    emit(&mobility_text(&m))
}
