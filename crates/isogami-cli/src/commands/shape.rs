//! `isogami shape`: shape-aware mobility of a design (the library's `shape_space`): generic or
//! special, the shape constraints that keep one degree of freedom, moving a parameter along
//! them, and the search of a rigid design's shapes for one that moves; or the classification
//! of every design in a database.

use crate::output::{emit, print_json, CliResult};
use isogami::api::resolve_design;
use isogami::catalog::CatalogSettings;
use isogami::shape_space::{
    classify, follow, rank_drop, search_neighbours, ShapeClass, ShapeMobility, ShapeSettings,
};
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
    /// that is rigid at its own shape); with --db, search the rigid neighbours (one joint
    /// added or moved) of every topology in the database and assess what is found.
    #[arg(long, conflicts_with = "set")]
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

/// Designs, or topologies, of one family by class.
#[derive(Serialize, Default, Clone, Copy)]
struct Count {
    generic: usize,
    special: usize,
    fixed_shape: usize,
    failed: usize,
}

impl Count {
    fn add(&mut self, class: Option<ShapeClass>) {
        match class {
            Some(ShapeClass::Generic) => self.generic += 1,
            Some(ShapeClass::Special) => self.special += 1,
            Some(ShapeClass::FixedShape) => self.fixed_shape += 1,
            None => self.failed += 1,
        }
    }

    fn sum(counts: impl Iterator<Item = Count>) -> Count {
        counts.fold(Count::default(), |a, c| Count {
            generic: a.generic + c.generic,
            special: a.special + c.special,
            fixed_shape: a.fixed_shape + c.fixed_shape,
            failed: a.failed + c.failed,
        })
    }
}

/// Per family: its designs and its topologies by class. A topology is generic when any of
/// its stored shapes is (it moves on an open set of shapes), special when none is but one
/// is special.
#[derive(Serialize, Default)]
struct FamilyCount {
    designs: Count,
    topologies: Count,
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
    // Per topology, the most mobile class over its shapes: generic, then special, then fixed
    // shape (a family without parameters), then failed.
    let rank = |c: Option<ShapeClass>| match c {
        Some(ShapeClass::Generic) => 3,
        Some(ShapeClass::Special) => 2,
        Some(ShapeClass::FixedShape) => 1,
        None => 0,
    };
    let mut topologies: BTreeMap<&str, (String, Option<ShapeClass>)> = BTreeMap::new();
    for c in &candidates {
        let family = c.design.family.to_string();
        let class = match classify(&c.design, settings) {
            Ok(m) => {
                let class = m.class;
                if class == ShapeClass::Special {
                    out.special.push(m);
                }
                Some(class)
            }
            Err(e) => {
                out.failures.push((c.design.to_string(), e.to_string()));
                None
            }
        };
        out.families
            .entry(family.clone())
            .or_default()
            .designs
            .add(class);
        let entry = topologies.entry(&c.topology).or_insert((family, class));
        if rank(class) > rank(entry.1) {
            entry.1 = class;
        }
    }
    for (family, class) in topologies.into_values() {
        out.families
            .entry(family)
            .or_default()
            .topologies
            .add(class);
    }
    if json {
        return print_json(&out);
    }
    let mut o = String::new();
    outln!(o, "{:<8} {:>26}   {:>26}", "", "designs", "topologies");
    let head = ["family", "generic", "special", "fixed", "failed"];
    outln!(
        o,
        "{:<8} {:>6} {:>6} {:>6} {:>6}   {:>6} {:>6} {:>6} {:>6}",
        head[0],
        head[1],
        head[2],
        head[3],
        head[4],
        head[1],
        head[2],
        head[3],
        head[4]
    );
    let row = |o: &mut String, name: &str, d: Count, t: Count| {
        outln!(
            o,
            "{name:<8} {:>6} {:>6} {:>6} {:>6}   {:>6} {:>6} {:>6} {:>6}",
            d.generic,
            d.special,
            d.fixed_shape,
            d.failed,
            t.generic,
            t.special,
            t.fixed_shape,
            t.failed
        );
    };
    for (f, c) in &out.families {
        row(&mut o, f, c.designs, c.topologies);
    }
    let designs = Count::sum(out.families.values().map(|c| c.designs));
    let topologies = Count::sum(out.families.values().map(|c| c.topologies));
    row(&mut o, "all", designs, topologies);
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

/// The rank-drop search on the rigid neighbours of every topology of a database.
fn rank_drop_db(path: &std::path::Path, settings: &ShapeSettings, json: bool) -> CliResult {
    let store =
        Store::open_read(path, Check::Quick).map_err(|e| format!("{}: {e}", path.display()))?;
    let candidates = store
        .candidates(&DesignQuery::default())
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let mut topologies: Vec<Design> = Vec::new();
    let mut seen = std::collections::BTreeSet::new();
    for c in &candidates {
        if seen.insert(c.topology.clone()) {
            topologies.push(design_of(&c.topology)?);
        }
    }
    let report = search_neighbours(&topologies, settings, &CatalogSettings::default());
    if json {
        return print_json(&report);
    }
    let mut o = String::new();
    let admitted = report.findings.iter().filter(|f| f.admitted).count();
    outln!(
        o,
        "{} topologies, {} rigid neighbours searched, {} rank-dropping shapes found, {} admitted",
        report.designs,
        report.rigid_neighbours,
        report.findings.len(),
        admitted
    );
    for f in &report.findings {
        let verdict = match (&f.max_expansion, &f.rejection) {
            (Some(e), _) => format!("admitted, opens to {e:.3}"),
            (None, Some(why)) => format!("not admitted: {why}"),
            (None, None) => "not admitted".to_string(),
        };
        outln!(o, "{}  ({verdict})", f.spec);
    }
    emit(&o)
}

/// Runs the shape-space analysis asked for.
pub fn run(args: Args) -> CliResult {
    let settings = ShapeSettings::default();
    if let Some(db) = &args.db {
        if args.rank_drop {
            return rank_drop_db(db, &settings, args.json);
        }
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
