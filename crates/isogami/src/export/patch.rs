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

use super::error::ExportError;
use super::outline::chain_loops;
use crate::api::{
    deploy, requested_sheet, sheet_geometry, sheet_of_trajectory, DeployRequest, Deployment,
    FrameSelection, SheetRequest,
};
use crate::cell::End;
use crate::contact::ContactSettings;
use crate::deploy::{
    frame_records_for, frame_report, plan_frames, DeploySettings, FrameReport, Progress,
};
use crate::finite::{FiniteSheet, Region, SheetMobility, SheetTile};
use crate::math::Real;
use crate::topology::Design;
use serde::Serialize;
use std::collections::HashMap;

/// Most rows and most columns of a patch (40 × 40 cells; a 40×40 patch of a 12-tile cell
/// holds 19 200 tiles, enough for any sheet a laser bed or a print bed takes).
pub const MAX_PATCH: usize = 40;

/// Smallest edge length or patch width in mm (a micrometre: below it the numbers written are
/// no size any machine makes, and a subnormal scale loses its digits).
pub const MIN_SIZE_MM: Real = 1e-3;

/// Largest edge length or patch width in mm (a kilometre: a 40×40 patch of it stays far from
/// overflow in every format).
pub const MAX_SIZE_MM: Real = 1e6;

/// Most states in [`Patch::states`].
pub const MAX_PATCH_FRAMES: usize = 100;

/// How the patch is scaled to millimetres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scale {
    /// The mean edge length L of the tiles, in mm.
    EdgeMm(Real),
    /// The width (x extent) of the patch at the asked state, in mm.
    WidthMm(Real),
}

/// Which state of the deployment to export.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum State {
    /// The accepted state with t nearest this value, in [0, 1] (0 closed, 1 the contact
    /// limit).
    T(Real),
    /// The state of largest area ratio: the sheet open as far as contact lets it (the last
    /// such state on a tie).
    Open,
}

/// What patch to make.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchRequest {
    /// Cells along w, 1..=[`MAX_PATCH`].
    pub rows: usize,
    /// Cells along u, 1..=[`MAX_PATCH`].
    pub cols: usize,
    /// Millimetres.
    pub scale: Scale,
    /// The state.
    pub state: State,
    /// Cut width relative to the mean edge length, the deployment's contact setting (see
    /// [`ContactSettings::kerf`]): it decides where contact ends the deployment.
    pub kerf: Real,
    /// States kept in [`Patch::states`] for animated formats, nearest to evenly spaced t,
    /// 2..=[`MAX_PATCH_FRAMES`].
    pub frames: usize,
    /// Write the rectangle's completion to a one-DOF sheet ([`crate::finite::complete`]),
    /// the default, refused when there is none; `false` writes the R×C rectangle as it is
    /// (floppy boundary and all, its DOF named by [`PatchMobility::warning`]).
    pub complete: bool,
}

impl Default for PatchRequest {
    /// 6×6 cells, 20 mm mean edge, closed, default kerf, 11 states, the rectangle's one-DOF
    /// completion.
    fn default() -> Self {
        PatchRequest {
            rows: 6,
            cols: 6,
            scale: Scale::EdgeMm(20.0),
            state: State::T(0.0),
            kerf: ContactSettings::default().kerf,
            frames: 11,
            complete: true,
        }
    }
}

impl PatchRequest {
    /// The scale's name and value in mm.
    fn scale_value(&self) -> (&'static str, Real) {
        match self.scale {
            Scale::EdgeMm(v) => ("edge length", v),
            Scale::WidthMm(v) => ("patch width", v),
        }
    }

    /// Checks sizes, scale, state and frame count (the kerf is checked by the deployment).
    pub fn validate(&self) -> Result<(), ExportError> {
        let (rows, cols) = (self.rows, self.cols);
        if rows == 0 || cols == 0 {
            return Err(ExportError::EmptyPatch { rows, cols });
        }
        if rows > MAX_PATCH || cols > MAX_PATCH {
            return Err(ExportError::PatchTooLarge {
                rows,
                cols,
                max: MAX_PATCH,
            });
        }
        let (what, value) = self.scale_value();
        if !(MIN_SIZE_MM..=MAX_SIZE_MM).contains(&value) {
            return Err(ExportError::BadSize { what, value });
        }
        if let State::T(t) = self.state {
            if !(0.0..=1.0).contains(&t) {
                return Err(ExportError::StatePastTrajectory { t });
            }
        }
        if !(2..=MAX_PATCH_FRAMES).contains(&self.frames) {
            return Err(ExportError::FrameCount {
                count: self.frames,
                max: MAX_PATCH_FRAMES,
            });
        }
        Ok(())
    }
}

/// A patch of the sheet in millimetres.
#[derive(Debug, Clone, Serialize)]
pub struct Patch {
    /// The design's spec string.
    pub design: String,
    /// Cells along w.
    pub rows: usize,
    /// Cells along u.
    pub cols: usize,
    /// Tiles in one cell.
    pub tiles_per_cell: usize,
    /// What the sheet is as a mechanism: its degrees of freedom with a free boundary, and
    /// what completion did.
    pub finite: PatchMobility,
    /// Kerf relative to the mean edge length (the deployment's setting).
    pub kerf: Real,
    /// Mean edge length of the tiles, mm.
    pub edge_mm: Real,
    /// Millimetres per tiling unit.
    pub mm_per_unit: Real,
    /// t of the exported state.
    pub t: Real,
    /// Area ratio det F of the exported state.
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

/// The patch as a finite mechanism (see [`crate::finite`]), counted at the periodic state
/// nearest t = 0.3.
#[derive(Debug, Clone, Serialize)]
pub struct PatchMobility {
    /// True when the tiles are the completion of the rectangle.
    pub completed: bool,
    /// Degrees of freedom of the written sheet with a free boundary (1 when completed).
    pub dof: usize,
    /// Degrees of freedom of the raw R×C rectangle.
    pub raw_dof: usize,
    /// Tiles of the rectangle.
    pub requested_tiles: usize,
    /// Rectangle tiles left out by completion.
    pub removed_tiles: usize,
    /// Tiles outside the rectangle added by completion.
    pub added_tiles: usize,
    /// Area of the rectangle's tiles kept over the area of all of them.
    pub covered_fraction: Real,
}

impl PatchMobility {
    /// The record of the rectangle written as it is, with `dof` degrees of freedom.
    fn raw(dof: usize, tiles: usize) -> PatchMobility {
        PatchMobility {
            completed: false,
            dof,
            raw_dof: dof,
            requested_tiles: tiles,
            removed_tiles: 0,
            added_tiles: 0,
            covered_fraction: 1.0,
        }
    }

    /// A warning for a sheet that is not one mechanism with one DOF, naming its DOF.
    pub fn warning(&self) -> Option<String> {
        (self.dof != 1).then(|| {
            format!(
                "this raw patch has {} degrees of freedom with a free boundary (its boundary \
                 tiles flop), not the design's one; the completed sheet (the default export) \
                 opens with one",
                self.dof
            )
        })
    }
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
/// accepted states; returning `false` stops the export (a cancelled error).
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
    let run = deploy(design, &deploy_request, progress)?;
    let (sheet, finite) = finite_patch(design, &cell, &run, request, deploy_request.settings)?;
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
    let to_mm = |polys: &[Vec<[Real; 2]>]| -> Vec<Vec<[Real; 2]>> {
        let (lo, _) = bounds(polys);
        polys
            .iter()
            .map(|p| p.iter().map(|v| mm(*v, lo, mm_per_unit)).collect())
            .collect()
    };
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
    let outline_mm = loops
        .iter()
        .map(|l| l.iter().map(|(p, _)| *p).collect())
        .collect();
    let outline_vertices = loops
        .iter()
        .map(|l| l.iter().map(|(_, v)| *v).collect())
        .collect();
    let all_numbers = |p: &Vec<[Real; 2]>| p.iter().flatten().all(|x| x.is_finite());
    let all_finite = tiles.iter().all(|t| all_numbers(&t.polygon_mm))
        && closed_polygons_mm.iter().all(all_numbers)
        && states
            .iter()
            .all(|s: &PatchState| s.polygons_mm.iter().all(all_numbers));
    if !all_finite {
        let (what, value) = request.scale_value();
        return Err(ExportError::BadSize { what, value });
    }
    Ok(Patch {
        design: design.to_string(),
        rows: request.rows,
        cols: request.cols,
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

/// The sheet to write — the R×C rectangle's completion, or the rectangle itself with `raw`
/// — and what it is as a mechanism, from the deployment already made.
fn finite_patch(
    design: &Design,
    cell: &crate::cell::UnitCell,
    run: &Deployment,
    request: &PatchRequest,
    settings: DeploySettings,
) -> Result<(FiniteSheet, PatchMobility), ExportError> {
    let sheet_request = SheetRequest {
        region: Region::Cells {
            rows: request.rows,
            cols: request.cols,
        },
        complete: request.complete,
        settings,
        ..SheetRequest::default()
    };
    let mech = &run.mechanism;
    let requested = requested_sheet(cell, mech, &sheet_request)?;
    if run.trajectory.steps.len() < 2 {
        // A design locked by contact has no opened state: its raw rectangle, counted closed.
        if request.complete {
            let reason = "the periodic sheet does not open (locked by contact)".into();
            return Err(
                crate::Error::from(crate::finite::FiniteError::NoOneDofSheet { reason }).into(),
            );
        }
        let poses = requested.poses(mech, &mech.rest);
        let m: SheetMobility =
            crate::finite::sheet_mobility(&requested, mech, &poses, None, settings.mobility)
                .map_err(crate::Error::from)?;
        let info = PatchMobility::raw(m.dof, requested.len());
        return Ok((requested, info));
    }
    let analysis = sheet_of_trajectory(
        design,
        cell,
        mech,
        &run.trajectory,
        &sheet_request,
        requested,
    )?;
    let info = match &analysis.completion {
        Some(c) => PatchMobility {
            completed: true,
            dof: c.mobility.dof,
            raw_dof: analysis.raw_mobility.dof,
            requested_tiles: c.report.requested,
            removed_tiles: c.report.removed.len(),
            added_tiles: c.report.added.len(),
            covered_fraction: c.report.covered_fraction,
        },
        None => PatchMobility::raw(analysis.raw_mobility.dof, analysis.raw.len()),
    };
    Ok((analysis.sheet().clone(), info))
}

/// Index of the frame asked for (frames are ordered by t, the closed state first).
fn choose_frame(frames: &[FrameReport], state: State) -> usize {
    let key = |k: usize| match state {
        State::T(t) => -(frames[k].t - t).abs(),
        State::Open => frames[k].measures.area_ratio,
    };
    // The first of equally near states for t, the last of equally open ones.
    let mut best = 0;
    for k in 1..frames.len() {
        let better = match state {
            State::T(_) => key(k) > key(best),
            State::Open => key(k) >= key(best),
        };
        if better {
            best = k;
        }
    }
    best
}

/// Places the cell's tile shapes by a frame's poses at the sheet's tiles.
struct Placer<'a> {
    shapes: &'a [Vec<[Real; 2]>],
    tiles: &'a [SheetTile],
    index: HashMap<SheetTile, usize>,
}

impl<'a> Placer<'a> {
    fn new(shapes: &'a [Vec<[Real; 2]>], tiles: &'a [SheetTile]) -> Self {
        let index = tiles.iter().enumerate().map(|(i, t)| (*t, i)).collect();
        Placer {
            shapes,
            tiles,
            index,
        }
    }

    /// Tile id of tile `tile` in `cell`, if it is in the sheet.
    fn id(&self, cell: [i32; 2], tile: usize) -> Option<usize> {
        self.index.get(&SheetTile { cell, tile }).copied()
    }

    /// Translation of `cell` at a frame (tiling units).
    fn shift(&self, frame: &FrameReport, cell: [i32; 2]) -> [Real; 2] {
        let (i, j) = (Real::from(cell[0]), Real::from(cell[1]));
        [
            i * frame.u[0] + j * frame.w[0],
            i * frame.u[1] + j * frame.w[1],
        ]
    }

    /// Every tile polygon of the sheet at a frame, by tile id (tiling units).
    fn polygons(&self, frame: &FrameReport) -> Vec<Vec<[Real; 2]>> {
        self.tiles
            .iter()
            .map(|t| {
                let s = self.shift(frame, t.cell);
                let pose = &frame.tiles[t.tile];
                let (sin, cos) = pose.theta.sin_cos();
                self.shapes[t.tile]
                    .iter()
                    .map(|p| {
                        [
                            pose.x + cos * p[0] - sin * p[1] + s[0],
                            pose.y + sin * p[0] + cos * p[1] + s[1],
                        ]
                    })
                    .collect()
            })
            .collect()
    }
}

/// Lower and upper corners of the bounding box of polygons.
fn bounds(polys: &[Vec<[Real; 2]>]) -> ([Real; 2], [Real; 2]) {
    let (mut lo, mut hi) = ([Real::INFINITY; 2], [Real::NEG_INFINITY; 2]);
    for v in polys.iter().flatten() {
        for d in 0..2 {
            lo[d] = lo[d].min(v[d]);
            hi[d] = hi[d].max(v[d]);
        }
    }
    (lo, hi)
}

fn mm(v: [Real; 2], lo: [Real; 2], scale: Real) -> [Real; 2] {
    [(v[0] - lo[0]) * scale, (v[1] - lo[1]) * scale]
}

/// Every joint of the sheet, with its pin's place at the exported state.
fn patch_joints(
    cell: &crate::cell::UnitCell,
    mech: &crate::kinematics::Mechanism,
    sheet: &FiniteSheet,
    tiles: &[PatchTile],
) -> Vec<PatchJoint> {
    sheet
        .joints
        .iter()
        .map(|j| {
            let joint = &mech.joints[j.joint];
            let vertex_a = cell.endpoint_index_on_a(joint.edge, joint.end);
            PatchJoint {
                a: j.a,
                b: j.b,
                point_mm: tiles[j.a].polygon_mm[vertex_a],
                edge: joint.edge,
                end: if joint.end == End::A { 'a' } else { 'b' },
                vertex_a,
                vertex_b: cell.endpoint_index_on_b(joint.edge, joint.end),
            }
        })
        .collect()
}

/// Boundary loops of the closed patch: tile edges whose neighbour is outside the patch.
fn outline(
    cell: &crate::cell::UnitCell,
    place: &Placer<'_>,
    closed: &[Vec<[Real; 2]>],
    tol: Real,
) -> Vec<Vec<([Real; 2], [usize; 2])>> {
    let mut edges = Vec::new();
    for (id, poly) in closed.iter().enumerate() {
        let SheetTile { cell: c, tile } = place.tiles[id];
        for k in 0..poly.len() {
            let e = &cell.edges[cell.tile_edges[tile][k]];
            let (other, offset) = if e.tile_a == tile && e.edge_a == k {
                (e.tile_b, e.offset)
            } else {
                (e.tile_a, [-e.offset[0], -e.offset[1]])
            };
            if place
                .id([c[0] + offset[0], c[1] + offset[1]], other)
                .is_none()
            {
                edges.push(([poly[k], poly[(k + 1) % poly.len()]], [id, k]));
            }
        }
    }
    chain_loops(&edges, tol)
}
