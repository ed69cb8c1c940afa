//! A finite patch of a design's sheet in millimetres: the geometry every export format is
//! written from.
//!
//! [`patch_at`] deploys the design once ([`FrameSelection::AllSteps`]), takes the accepted
//! state whose t is nearest the asked t (states are never interpolated, so every joint of
//! the patch is an exact solution of the constraints), and places the R×C cells of the
//! patch: cell `[i, j]` is the cell copy at `i·u + j·w`, i in `0..cols`, j in `0..rows`.
//! Polygons are counter-clockwise with y up; each set of polygons (the state, the closed
//! sheet, every state of [`Patch::states`]) is shifted so that its bounding box starts at
//! (0, 0).
//!
//! | part | file |
//! |---|---|
//! | what is asked: size, scale, state, completion, and their limits | `request` |
//! | the sheet to write and what it is as a finite mechanism | `mobility` |
//! | placing tiles, joints and the outline in millimetres | `place` |
//! | a graded sheet (issue 25) as a patch, and reading one from JSON | [`graded`] |

pub mod graded;
mod mobility;
mod place;
mod request;

pub use graded::{graded_patch, read_graded, GradedInput, GradedPatchRequest};
use mobility::finite_patch;
pub use mobility::{GradedMobility, PatchMobility};
use place::{all_finite, bounds, mm, outline, patch_joints, polygons_mm, split_loops, Placer};
pub use request::{
    PatchRequest, Scale, State, MAX_PATCH, MAX_PATCH_FRAMES, MAX_SIZE_MM, MIN_SIZE_MM,
};

use crate::api::{deploy, sheet_geometry, DeployRequest, FrameSelection};
use crate::contact::ContactSettings;
use crate::deploy::{
    frame_records_for, frame_report, plan_frames, DeploySettings, FrameReport, Progress,
};
use crate::export::error::ExportError;
use crate::finite::{FiniteSheet, SheetTile};
use crate::math::Real;
use crate::topology::Design;
use serde::Serialize;

/// A patch of the sheet in millimetres.
#[derive(Debug, Clone, Serialize)]
pub struct Patch {
    /// The design's spec string.
    pub design: String,
    /// Cells along w (a region or a graded sheet: the cells its tiles span).
    pub rows: usize,
    /// Cells along u (a region or a graded sheet: the cells its tiles span).
    pub cols: usize,
    /// Tiles in one cell.
    pub tiles_per_cell: usize,
    /// What the sheet is as a mechanism: its degrees of freedom with a free boundary, and
    /// what completion did.
    pub finite: PatchMobility,
    /// Kerf relative to the mean edge length (the deployment's setting; 0 for a graded
    /// sheet, whose path check looks for overlaps only).
    pub kerf: Real,
    /// Mean edge length of the tiles, mm.
    pub edge_mm: Real,
    /// Millimetres per tiling unit.
    pub mm_per_unit: Real,
    /// t of the exported state (a graded sheet: its opening, 0 closed, 1 optimised).
    pub t: Real,
    /// Area ratio det F of the exported state (a graded sheet: the area of its corners'
    /// convex hull over the closed sheet's).
    pub area_ratio: Real,
    /// Bounding box size [width, height] of the tiles at the state, mm.
    pub size_mm: [Real; 2],
    /// The tiles, ordered by cell (row by row: j, then i) then tile index: the completed
    /// sheet (tiles of the R×C rectangle, less the pruned ones, plus the ring tiles it
    /// added, whose cells may lie outside 0..cols × 0..rows), or the rectangle with `raw`.
    pub tiles: Vec<PatchTile>,
    /// Every joint whose two tiles are both in the patch.
    pub joints: Vec<PatchJoint>,
    /// The same tiles in the closed state (t = 0), by tile id: the sheet a laser cuts.
    pub closed_polygons_mm: Vec<Vec<[Real; 2]>>,
    /// Boundary loops of the closed patch (counter-clockwise, first vertex not repeated).
    pub outline_mm: Vec<Vec<[Real; 2]>>,
    /// The same loops as [tile id, vertex index] of the tile whose boundary edge starts at
    /// each outline vertex.
    pub outline_vertices: Vec<Vec<[usize; 2]>>,
    /// States nearest to evenly spaced t, closed first and contact limit last.
    pub states: Vec<PatchState>,
}

/// One tile of the patch at the exported state.
#[derive(Debug, Clone, Serialize)]
pub struct PatchTile {
    /// Index in [`Patch::tiles`].
    pub id: usize,
    /// Tile index in the cell.
    pub tile: usize,
    /// Cell [i, j] (multiples of u and w).
    pub cell: [i32; 2],
    /// Vertices, counter-clockwise, mm.
    pub polygon_mm: Vec<[Real; 2]>,
    /// Area centroid, mm.
    pub centroid_mm: [Real; 2],
    /// Rotation from the closed state, radians (counter-clockwise; the deployment holds the
    /// cell's tile 0 fixed, so rotations are relative to it).
    pub rotation: Real,
}

/// A pin joint between two tiles of the patch.
#[derive(Debug, Clone, Serialize)]
pub struct PatchJoint {
    /// Tile id on the edge's first side.
    pub a: usize,
    /// Tile id on the other side.
    pub b: usize,
    /// Where the pin is at the exported state, mm (vertex `vertex_a` of tile `a`).
    pub point_mm: [Real; 2],
    /// Unique edge index in the cell (the spec's joint string order).
    pub edge: usize,
    /// Which end of the edge: `'a'` or `'b'`.
    pub end: char,
    /// Vertex index on tile `a`'s polygon.
    pub vertex_a: usize,
    /// Vertex index on tile `b`'s polygon.
    pub vertex_b: usize,
}

/// The patch at one state of the deployment.
#[derive(Debug, Clone, Serialize)]
pub struct PatchState {
    /// Normalised arc length.
    pub t: Real,
    /// Tile polygons by tile id, mm.
    pub polygons_mm: Vec<Vec<[Real; 2]>>,
}

/// The patch of `design` asked for by `request` (see the module docs for placement).
pub fn patch_at(design: &Design, request: &PatchRequest) -> Result<Patch, ExportError> {
    patch_at_with(design, request, &mut |_| true)
}

/// [`patch_at`] with a progress callback for the deployment: called with the number of
/// accepted states, and asked on (with the last count) while the sheet is completed;
/// returning `false` stops the export (a cancelled error).
pub fn patch_at_with(
    design: &Design,
    request: &PatchRequest,
    progress: Progress<'_>,
) -> Result<Patch, ExportError> {
    request.validate()?;
    let cell = design.cell().map_err(crate::Error::from)?;
    let geometry = sheet_geometry(design)?;
    let deploy_request = DeployRequest {
        settings: DeploySettings {
            contact: ContactSettings::with_kerf(request.kerf),
            ..DeploySettings::default()
        },
        frames: FrameSelection::AllSteps,
    };
    let run = deploy(design, &deploy_request, &mut *progress)?;
    let states = run.trajectory.steps.len();
    let (sheet, finite) = crate::stop::watched(progress, states, |keep_going| {
        finite_patch(
            design,
            &cell,
            &run,
            request,
            deploy_request.settings,
            keep_going,
        )
    })?;
    let frames = &run.report.frames;
    let chosen = choose_frame(frames, request.state);
    let place = Placer::new(&geometry.tiles, &sheet.tiles);
    let at_state = place.polygons(&frames[chosen]);
    let (lo, hi) = bounds(&at_state);
    let mm_per_unit = match request.scale {
        Scale::EdgeMm(mm) => mm / geometry.length_scale,
        Scale::WidthMm(mm) => {
            let width = hi[0] - lo[0];
            if !(width.is_finite() && width > 0.0) {
                return Err(ExportError::Degenerate { what: "width" });
            }
            mm / width
        }
    };
    let to_mm = |polys: &[Vec<[Real; 2]>]| polygons_mm(polys, mm_per_unit);
    let n = geometry.tiles.len();
    let frame = &frames[chosen];
    let tiles: Vec<PatchTile> = to_mm(&at_state)
        .into_iter()
        .enumerate()
        .map(|(id, polygon_mm)| {
            let SheetTile { cell, tile } = place.tiles[id];
            let pose = frame.tiles[tile];
            let shift = place.shift(frame, cell);
            let centre = [pose.x + shift[0], pose.y + shift[1]];
            PatchTile {
                id,
                tile,
                cell,
                polygon_mm,
                centroid_mm: mm(centre, lo, mm_per_unit),
                rotation: pose.theta,
            }
        })
        .collect();
    let closed_polygons_mm = to_mm(&place.polygons(&frames[0]));
    // Exactly the frames asked for: with fewer accepted states, states inserted between them
    // the way `deploy --frame-count` inserts them (it wrote 90 of 100 frames silently).
    let picks = plan_frames(&run.trajectory, request.frames);
    let records = frame_records_for(
        &run.mechanism,
        &run.contact,
        &run.trajectory,
        &picks,
        &deploy_request.settings,
    )
    .map_err(crate::Error::from)?;
    let states: Vec<PatchState> = records
        .iter()
        .map(|r| frame_report(&run.mechanism, r))
        .map(|f| PatchState {
            t: f.t,
            polygons_mm: to_mm(&place.polygons(&f)),
        })
        .collect();
    let joints = patch_joints(&cell, &run.mechanism, &sheet, &tiles);
    let edge_mm = geometry.length_scale * mm_per_unit;
    let loops = outline(&cell, &place, &closed_polygons_mm, 1e-7 * edge_mm);
    let (outline_mm, outline_vertices) = split_loops(&loops);
    let numbers = all_finite(tiles.iter().map(|t| &t.polygon_mm))
        && all_finite(&closed_polygons_mm)
        && all_finite(states.iter().flat_map(|s| &s.polygons_mm));
    if !numbers {
        let (what, value) = request.scale_value();
        return Err(ExportError::BadSize { what, value });
    }
    let [cols, rows] = match request.region {
        None => [request.cols, request.rows],
        Some(_) => cells_spanned(&sheet),
    };
    Ok(Patch {
        design: design.to_string(),
        rows,
        cols,
        tiles_per_cell: n,
        finite,
        kerf: request.kerf,
        edge_mm,
        mm_per_unit,
        t: frame.t,
        area_ratio: frame.measures.area_ratio,
        size_mm: [(hi[0] - lo[0]) * mm_per_unit, (hi[1] - lo[1]) * mm_per_unit],
        tiles,
        joints,
        closed_polygons_mm,
        outline_mm,
        outline_vertices,
        states,
    })
}

/// Cells along u and along w that `sheet`'s tiles span.
fn cells_spanned(sheet: &FiniteSheet) -> [usize; 2] {
    [0, 1].map(|axis| {
        let along = sheet.tiles.iter().map(|t| i64::from(t.cell[axis]));
        match (along.clone().min(), along.max()) {
            (Some(lo), Some(hi)) => (hi - lo + 1) as usize,
            _ => 0,
        }
    })
}

/// Index of the frame asked for (frames are ordered by t, the closed state first).
fn choose_frame(frames: &[FrameReport], state: State) -> usize {
    let key = |k: usize| match state {
        State::T(t) => -(frames[k].t - t).abs(),
        State::Open => frames[k].measures.area_ratio,
        State::Limit => frames[k].t,
    };
    // The first of equally near states for t, the last of equally open ones.
    let mut best = 0;
    for k in 1..frames.len() {
        let better = match state {
            State::T(_) => key(k) > key(best),
            State::Open | State::Limit => key(k) >= key(best),
        };
        if better {
            best = k;
        }
    }
    best
}
