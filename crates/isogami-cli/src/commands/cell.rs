//! `isogami cell`.

use crate::output::{emit, parse_params, print_json, write_atomic, CliResult};
use isogami::cell::{CellDims, End, UnitCell};
use isogami::render::cell_svg;
use isogami::tiling::{Family, Tiling};
use std::path::PathBuf;

/// Arguments of `cell`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Tiling family, e.g. IH28.
    #[arg(long)]
    family: String,
    /// Shape parameters, comma separated (default: the family's defaults).
    #[arg(long, allow_hyphen_values = true)]
    params: Option<String>,
    /// Supercell size AxB (1..4 each).
    #[arg(long, default_value = "1x1")]
    cell: String,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Write an SVG of the closed sheet over 3×3 cells.
    #[arg(long)]
    svg: Option<PathBuf>,
}

#[derive(serde::Serialize)]
struct EdgeOut {
    index: usize,
    tile_a: usize,
    edge_a: usize,
    tile_b: usize,
    edge_b: usize,
    offset: [i32; 2],
    a: [f64; 2],
    b: [f64; 2],
}

#[derive(serde::Serialize)]
struct CellOut<'a> {
    family: String,
    params: &'a [f64],
    cell: String,
    u: [f64; 2],
    w: [f64; 2],
    tiles: &'a [isogami::cell::Tile],
    edges: Vec<EdgeOut>,
    mean_edge_length: f64,
}

/// Builds the cell and prints or writes it.
pub fn run(args: Args) -> CliResult {
    let family: Family = args.family.parse().map_err(|e| format!("{e}"))?;
    let params = match &args.params {
        Some(p) => parse_params(p)?,
        None => family.default_params(),
    };
    let dims: CellDims = args.cell.parse().map_err(|e| format!("{e}"))?;
    let tiling = Tiling::new(family, &params).map_err(|e| e.to_string())?;
    let cell = UnitCell::new(&tiling, dims).map_err(|e| e.to_string())?;
    if let Some(path) = &args.svg {
        write_atomic(path, cell_svg(&cell, None).as_bytes())?;
    }
    let pt = |v: isogami::math::Vec2| [v.x, v.y];
    let out = CellOut {
        family: family.name(),
        params: &cell.params,
        cell: dims.to_string(),
        u: pt(cell.u),
        w: pt(cell.w),
        tiles: &cell.tiles,
        edges: (0..cell.edges.len())
            .map(|k| {
                let e = cell.edges[k];
                EdgeOut {
                    index: k,
                    tile_a: e.tile_a,
                    edge_a: e.edge_a,
                    tile_b: e.tile_b,
                    edge_b: e.edge_b,
                    offset: e.offset,
                    a: pt(cell.endpoint(k, End::A)),
                    b: pt(cell.endpoint(k, End::B)),
                }
            })
            .collect(),
        mean_edge_length: cell.mean_edge_length(),
    };
    if args.json {
        return print_json(&out);
    }
    let mut o = String::new();
    outln!(
        o,
        "{} params [{}] cell {}: {} tiles, {} unique edges",
        out.family,
        params
            .iter()
            .map(|p| p.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        out.cell,
        cell.tiles.len(),
        cell.edges.len()
    );
    outln!(
        o,
        "u = ({:.6}, {:.6})  w = ({:.6}, {:.6})",
        out.u[0],
        out.u[1],
        out.w[0],
        out.w[1]
    );
    for (i, t) in cell.tiles.iter().enumerate() {
        let pts: Vec<String> = t
            .polygon
            .iter()
            .map(|p| format!("({:.4}, {:.4})", p.x, p.y))
            .collect();
        outln!(o, "tile {i} (aspect {}): {}", t.aspect, pts.join(" "));
    }
    for e in &out.edges {
        outln!(
        o,
            "edge {:>2}: tile {} edge {} | tile {} edge {} in cell ({:>2}, {:>2})  A=({:.4}, {:.4}) B=({:.4}, {:.4})",
            e.index, e.tile_a, e.edge_a, e.tile_b, e.edge_b, e.offset[0], e.offset[1], e.a[0], e.a[1], e.b[0], e.b[1]
        );
    }
    if let Some(p) = &args.svg {
        outln!(o, "wrote {}", p.display());
    }
    emit(&o)
}
