//! `isogami db designs`: the catalogue from the command line — the browser's filters, sort and
//! lead (buildable designs first by default) over the store's query types, one row per design
//! with what says whether it can be made: its finite sheet, shape tolerance and buildability.

use crate::output::{emit, print_json, CliResult};
use isogami_store::query::{RangeFilter, Sort};
use isogami_store::{Check, DesignQuery, DesignSummary, Facet, Store};
use std::path::PathBuf;

/// Arguments of `db designs`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The database.
    #[arg(long, default_value = "isogami.db")]
    db: PathBuf,
    /// Only these families (repeat or comma-separate: IH1,IH28).
    #[arg(long, value_delimiter = ',')]
    family: Vec<String>,
    /// Only these cells (e.g. 2x1).
    #[arg(long, value_delimiter = ',')]
    cell: Vec<String>,
    /// Only these behaviour classes (e.g. isotropic_auxetic).
    #[arg(long, value_delimiter = ',')]
    behaviour: Vec<String>,
    /// A range on a measure, MEASURE:MIN:MAX with either bound empty (repeatable), e.g.
    /// finite_covered:0.9: or shape_tolerance:0.0025: (the measures of `/api/measures`).
    #[arg(long, allow_hyphen_values = true)]
    range: Vec<String>,
    /// Sort key, `-` first for largest first (spec, max_area_ratio, shape_tolerance, …: the
    /// sort keys of `/api/designs`).
    #[arg(long, allow_hyphen_values = true, default_value = "-max_area_ratio")]
    sort: String,
    /// `buildable` (default): buildable designs first — a one-DOF finite 6x6 sheet and a
    /// shape tolerance of at least 0.0025 L — then the rest, each in the sort's order; `all`:
    /// the sort's order alone.
    #[arg(long, default_value = "buildable")]
    lead: String,
    /// Rows to print.
    #[arg(long, default_value_t = 20)]
    limit: u32,
    /// Rows to skip.
    #[arg(long, default_value_t = 0)]
    offset: u64,
    /// Print JSON ({total, offset, rows}, the rows as `/api/designs` gives them, each with
    /// `buildable`).
    #[arg(long)]
    json: bool,
}

/// The query the arguments ask for, or a one-line refusal naming the bad argument.
fn query(args: &Args) -> Result<DesignQuery, String> {
    let mut q = DesignQuery::default();
    let facets = [
        (Facet::Family, &args.family, "--family"),
        (Facet::Cell, &args.cell, "--cell"),
        (Facet::Behaviour, &args.behaviour, "--behaviour"),
    ];
    for (facet, values, flag) in facets {
        for v in values {
            q.select(facet.value(v).map_err(|e| format!("{flag}: {e}"))?);
        }
    }
    for r in &args.range {
        let r: RangeFilter = r.parse().map_err(|e| format!("--range: {e}"))?;
        q.range(r.measure, r.min, r.max);
    }
    let s: Sort = args.sort.parse().map_err(|e| format!("--sort: {e}"))?;
    q.sort_by(s.key, s.descending);
    q.lead(&args.lead).map_err(|e| format!("--lead: {e}"))?;
    q.limit = args.limit;
    q.offset = args.offset;
    Ok(q)
}

/// A row with its buildability, as printed in JSON.
#[derive(serde::Serialize)]
struct Row<'a> {
    #[serde(flatten)]
    summary: &'a DesignSummary,
    buildable: bool,
}

/// Runs `db designs`.
pub fn run(args: Args) -> CliResult {
    let q = query(&args)?;
    let store = Store::open_read(&args.db, Check::Quick)
        .map_err(|e| format!("{}: {e}", args.db.display()))?;
    let page = store
        .page(&q)
        .map_err(|e| format!("{}: {e}", args.db.display()))?;
    if args.json {
        let rows: Vec<Row> = page
            .rows
            .iter()
            .map(|summary| Row {
                summary,
                buildable: summary.buildable(),
            })
            .collect();
        return print_json(&serde_json::json!({
            "total": page.total,
            "offset": page.offset,
            "rows": rows,
        }));
    }
    let mut o = String::new();
    outln!(
        o,
        "{} designs match; rows {}–{}{}",
        page.total,
        (page.offset + 1).min(page.total),
        page.offset + page.rows.len() as u64,
        if q.buildable_first {
            " (buildable designs first; --lead all for the sort alone)"
        } else {
            ""
        }
    );
    outln!(
        o,
        "{:<9} {:>6}  {:<13} {:<10} {:<24} spec",
        "buildable",
        "area",
        "sheet (6x6)",
        "shape",
        "behaviour"
    );
    for r in &page.rows {
        let sheet = match (r.finite_covered, r.finite_raw_dof) {
            (Some(c), _) => format!("{:.0} %", 100.0 * c),
            (None, Some(_)) => "no 1-DOF".to_string(),
            (None, None) => "-".to_string(),
        };
        let shape = match (r.shape_tolerance, r.open_t) {
            (Some(0.0), _) => "special".to_string(),
            (Some(t), _) => format!("±{:.2} mm", 20.0 * t),
            (None, Some(_)) => "fixed".to_string(),
            (None, None) => "-".to_string(),
        };
        outln!(
            o,
            "{:<9} {:>6.3}  {:<13} {:<10} {:<24} {}",
            if r.buildable() { "yes" } else { "no" },
            r.max_area_ratio,
            sheet,
            shape,
            r.behaviour
                .map_or("-".to_string(), |b| b.as_str().to_string()),
            r.spec
        );
    }
    outln!(
        o,
        "shape: the tolerance in mm at 20 mm edges that keeps 95 % of the opening (special: only \
         the exact shape opens; fixed: no shape parameters)"
    );
    emit(&o)
}
