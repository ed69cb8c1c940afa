//! The least-squares problem of a graded sheet: residuals and their exact sparse Jacobian.
//!
//! Unknowns: the closed positions of the nodes (2 per node), then the opened pose of every
//! tile (x, y, θ: the opened position of its first node and its rotation), then the rotation
//! of every tile in each state part of the way (their positions follow from the pins:
//! [`super::loops`]). Residual groups, each with its weight:
//!
//! - **joints**: the two opened positions of every pinned node coincide (2 rows per pin); in
//!   a state part of the way, the chain of tiles around every cycle of a basis of the pin
//!   graph's cycles closes (2 rows per cycle), which holds exactly when the pins can close;
//! - **opening**: the mean relative rotation across the pins (signed like the periodic
//!   sheet's) equals the periodic sheet's at the chosen state, so the opened state is as far
//!   along the motion as the design's own (1 row);
//!
//! Pins and opening hold in every *state*: the opened state and states part of the way
//! there (denser towards closed), all sharing the one set of closed shapes, the pins of a
//! state weighed more the less it has opened ([`Problem::state_weight`]). A single
//! opened state is not enough: a generic graded sheet that closes its pins there is rigid
//! (an isolated configuration); asking for the states between makes its shapes ones that
//! move. The remaining groups concern the last (opened) state or the closed shapes:
//! - **fit**: every outline point of the opened boundary lies on the target (radial error),
//!   and no other boundary corner lies outside it (one-sided); or, for a field target, every
//!   measured cell opens by the area ratio the field asks of it ([`super::field`]);
//! - **smoothness**: lattice neighbours (the same tile of the cell in adjacent cells) keep
//!   similar shapes (their edge vectors from the first corner agree);
//! - **prior**: a weak pull of the closed nodes to their start (fixes the gauge);
//! - **shape bounds** (one-sided): every corner keeps at least a fraction of its starting
//!   sine (a minimum angle, away from 0 and from a straight angle: convex stays convex,
//!   reflex stays reflex) and of its starting triangle's area (no slivers), and every edge a
//!   fraction of its starting length.

use super::contact::Contact;
use super::field::FieldCell;
use super::loops::Segment;
use super::model::GradedSheet;
use super::target::Outline;
use crate::math::{perp, rotation, DVec, Real, Vec2};

/// Relative weights of the residual groups and the shape bounds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Weights {
    /// Pins.
    pub joints: Real,
    /// Mean opening.
    pub opening: Real,
    /// Target fit (outline).
    pub fit: Real,
    /// Target fit (area-ratio field; its residual is a ratio, not a length).
    pub field: Real,
    /// Shape smoothness between lattice neighbours.
    pub smooth: Real,
    /// Pull to the start.
    pub prior: Real,
    /// Shape bounds.
    pub bounds: Real,
    /// Contacts: a corner of one tile inside another (see [`super::contact`]).
    pub contact: Real,
    /// Fraction of its starting area the triangle of every corner (its two edges) keeps.
    pub corner_fraction: Real,
    /// Fraction of its starting sine every corner keeps (0.3 keeps a right angle within
    /// 17.5° to 162.5°).
    pub angle_fraction: Real,
    /// Fraction of its starting length every edge keeps.
    pub edge_fraction: Real,
    /// Fraction of a state's mean opening every pin opens at least.
    pub pin_fraction: Real,
    /// A state part of the way weighs its pins by (opened state's opening / its own)^this:
    /// a pin gap is measured against how far the state has turned.
    pub state_exponent: Real,
}

impl Default for Weights {
    fn default() -> Self {
        Weights {
            joints: 30.0,
            opening: 30.0,
            fit: 3.0,
            field: 10.0,
            smooth: 0.3,
            prior: 1e-3,
            bounds: 30.0,
            contact: 30.0,
            corner_fraction: 0.15,
            angle_fraction: 0.3,
            edge_fraction: 0.15,
            pin_fraction: 0.2,
            state_exponent: 0.5,
        }
    }
}

/// Everything fixed while the unknowns move.
#[derive(Debug, Clone)]
pub struct Problem {
    /// Tile corners, as node indices.
    pub tiles: Vec<Vec<usize>>,
    /// Pins: (tile a, tile b, node).
    pub joints: Vec<(usize, usize, usize)>,
    /// Sign of each pin's relative rotation at the start.
    pub joint_signs: Vec<Real>,
    /// The two angular gaps around every pin between its tiles' corners (see [`PinGap`]).
    pub pin_gaps: Vec<PinGap>,
    /// Pairs of tiles sharing a closed node, kept apart in every state (see
    /// [`super::contact`]).
    pub contacts: Vec<Contact>,
    /// Per contact, the chain of tiles placing b's entry node in a's frame, and that node
    /// (the states part of the way; None: b is not reachable by pins from a).
    pub contact_routes: Vec<Option<(Vec<Segment>, usize)>>,
    /// A basis of short cycles of the pin graph: the loop closures of the states part of
    /// the way.
    pub loops: Vec<Vec<Segment>>,
    /// The mean signed relative rotation of each state, the opened state last.
    pub openings: Vec<Real>,
    /// Outline points (tile, node) fitted to the target.
    pub tips: Vec<(usize, usize)>,
    /// Other boundary corners (tile, node), kept inside.
    pub inside: Vec<(usize, usize)>,
    /// The target and its scale.
    pub outline: Outline,
    /// Scale of the outline (its radius at scale 1 times this).
    pub scale: Real,
    /// The fit blended from where the outline points started (see [`FitBlend`]); None: the
    /// target itself.
    pub fit_from: Option<FitBlend>,
    /// Lattice-neighbour tile pairs with the same corner count.
    pub neighbours: Vec<(usize, usize)>,
    /// Cells whose opened area ratio is fitted to a target field (empty: an outline target).
    pub field: Vec<FieldCell>,
    /// Starting node positions (prior).
    pub start: Vec<Vec2>,
    /// Starting corner sines, per tile per corner.
    pub corner_start: Vec<Vec<Real>>,
    /// Starting corner crosses (twice the corner's triangle), per tile per corner.
    pub corner_area_start: Vec<Vec<Real>>,
    /// Starting edge lengths, per tile per edge.
    pub edge_start: Vec<Vec<Real>>,
    /// Concave tiles' triangles: (nodes counter-clockwise, twice their starting area), a
    /// fixed ear-clipping triangulation of each tile with a reflex corner. Every triangle
    /// keeps a fraction of its area, so a concave tile stays a simple polygon turned the
    /// same way (its corners' bounds alone let a reflex corner pass through a far edge).
    pub triangles: Vec<([usize; 3], Real)>,
    /// Weights.
    pub weights: Weights,
    /// The largest area ratio the design's periodic sheet reaches along its path (None when
    /// the problem was not set up from a deployment).
    pub periodic_opening: Option<Real>,
    /// When false, only the pins, the opening and the one-sided rows of the pins' turning (its
    /// fraction of the mean, the angular gaps) count: the closing projection and the path
    /// check's.
    pub full: bool,
}

/// A fit part of the way from where every outline point started to the target: point k is
/// asked to lie at (1 − λ)·r₀ₖ + λ·s·ρ(φ) from the centre (the tips exactly, the other
/// boundary corners at most), r₀ₖ its distance at the start. At λ = 0 the start meets it.
#[derive(Debug, Clone, PartialEq)]
pub struct FitBlend {
    /// How far towards the target, in [0, 1].
    pub lambda: Real,
    /// r₀ of every tip, in the order of [`Problem::tips`].
    pub tips: Vec<Real>,
    /// r₀ of every other boundary corner, in the order of [`Problem::inside`].
    pub inside: Vec<Real>,
}

/// The residuals and their Jacobian rows. Sparse rows are stored flat (row r's entries are
/// `entries[starts[r]..starts[r + 1]]`); the few *dense* rows (a mean over every pin of a
/// state) are kept apart, so that the solver can add them as a low-rank term instead of
/// filling the normal equations with a dense block.
#[derive(Debug, Clone)]
pub struct Rows {
    /// Values of the sparse rows.
    pub values: Vec<Real>,
    starts: Vec<usize>,
    entries: Vec<(usize, Real)>,
    /// Values of the dense rows.
    pub dense_values: Vec<Real>,
    /// Entries of the dense rows: (column, value).
    pub dense_entries: Vec<Vec<(usize, Real)>>,
}

impl Default for Rows {
    fn default() -> Self {
        Rows {
            values: Vec::new(),
            starts: vec![0],
            entries: Vec::new(),
            dense_values: Vec::new(),
            dense_entries: Vec::new(),
        }
    }
}

#[cfg(test)]
impl Rows {
    /// The Jacobian as a dense matrix over `columns` unknowns and the residuals, the sparse
    /// rows first, then the dense ones.
    pub fn to_dense(&self, columns: usize) -> (crate::math::DMat, DVec) {
        let count = self.values.len();
        let mut j = crate::math::DMat::zeros(count + self.dense_values.len(), columns);
        for r in 0..j.nrows() {
            let entries = if r < count {
                self.row(r)
            } else {
                &self.dense_entries[r - count]
            };
            for &(c, v) in entries {
                j[(r, c)] += v;
            }
        }
        let values = self.values.iter().chain(&self.dense_values).copied();
        let values = DVec::from_iterator(j.nrows(), values);
        (j, values)
    }
}

impl Rows {
    pub(super) fn push(&mut self, value: Real, entries: impl IntoIterator<Item = (usize, Real)>) {
        self.values.push(value);
        self.entries.extend(entries);
        self.starts.push(self.entries.len());
    }

    fn push_dense(&mut self, value: Real, entries: Vec<(usize, Real)>) {
        self.dense_values.push(value);
        self.dense_entries.push(entries);
    }

    /// Entries (column, value) of sparse row `r`.
    pub fn row(&self, r: usize) -> &[(usize, Real)] {
        &self.entries[self.starts[r]..self.starts[r + 1]]
    }

    /// ½‖r‖² over every row.
    pub fn cost(&self) -> Real {
        0.5 * self
            .values
            .iter()
            .chain(&self.dense_values)
            .map(|v| v * v)
            .sum::<Real>()
    }
}

/// Entries sorted by column, duplicates summed (chain rows repeat node columns; merged,
/// the normal equations' assembly, quadratic in a row's length, does less).
pub(super) fn merged(mut e: Vec<(usize, Real)>) -> Vec<(usize, Real)> {
    e.sort_unstable_by_key(|x| x.0);
    let mut out: Vec<(usize, Real)> = Vec::with_capacity(e.len());
    for (c, v) in e {
        match out.last_mut() {
            Some(last) if last.0 == c => last.1 += v,
            _ => out.push((c, v)),
        }
    }
    out
}

/// The Jacobian of a point placed by a chain of tiles: 2 rows of any length.
pub(super) struct ChainJacobian {
    rows: [Vec<(usize, Real)>; 2],
}

impl ChainJacobian {
    pub(super) fn row(&self, r: usize) -> &[(usize, Real)] {
        &self.rows[r]
    }

    /// The Jacobian of this chain's point plus `next`'s (a chain continued).
    pub(super) fn then(&self, next: ChainJacobian) -> ChainJacobian {
        let [x, y] = next.rows;
        let join = |mut head: Vec<(usize, Real)>, tail: Vec<(usize, Real)>| {
            head.extend(tail);
            head
        };
        ChainJacobian {
            rows: [join(self.rows[0].clone(), x), join(self.rows[1].clone(), y)],
        }
    }
}

impl From<CornerJacobian> for ChainJacobian {
    fn from(j: CornerJacobian) -> Self {
        ChainJacobian {
            rows: [j.row(0).to_vec(), j.row(1).to_vec()],
        }
    }
}

/// The Jacobian of an opened corner: 2 rows of 2 to 6 entries.
pub(super) struct CornerJacobian {
    entries: [[(usize, Real); 6]; 2],
    len: usize,
}

impl CornerJacobian {
    pub(super) fn row(&self, r: usize) -> &[(usize, Real)] {
        &self.entries[r][..self.len]
    }
}

/// One of the two angular gaps around a pin between its two tiles' corners, in the closed
/// sheet: counter-clockwise from the edge `node → from` (one tile's last edge at the node) to
/// the edge `node → to` (the other's first). When tile b turns by Δθ relative to tile a the
/// gap becomes gap + sign·Δθ, which must stay ≥ 0: otherwise the two tiles overlap around
/// their pin (the pin opened past the room its corners leave).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PinGap {
    /// Index of the pin in [`Problem::joints`].
    pub joint: usize,
    /// Node at the far end of the gap's first edge.
    pub from: usize,
    /// Node at the far end of its second edge.
    pub to: usize,
    /// +1 for the gap from a's corner to b's, −1 for the one from b's to a's.
    pub sign: Real,
    /// The gap at the start, in [0, 2π).
    pub start: Real,
    /// atan2 of the start, the branch the gap is followed from.
    pub start_raw: Real,
}

/// The angle wrapped to (−π, π].
pub fn wrap_angle(a: Real) -> Real {
    let w = (a + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
    if w <= -std::f64::consts::PI {
        w + std::f64::consts::TAU
    } else {
        w
    }
}

/// Factor on the pins' and the opening's weights in a closing projection, against the
/// turning rows': the balance of the fit's last stage, which ends with them 1,000 times their
/// base weight. Weighed alike, a turning row the fit left a hair violated held the pins of a
/// 400-tile sheet 1.7e-5 open in the projection (7.9e-7 with this factor; the next state of
/// the path, 1.8e-7 either way).
pub const PROJECTION_STIFFNESS: Real = 1000.0;

/// Corners whose starting sine is below this are straight (a vertex on a straight side):
/// no bound keeps their angle.
pub const SINE_FLOOR: Real = 1e-6;

/// Column of node `n`'s x.
fn node_col(n: usize) -> usize {
    2 * n
}

impl Problem {
    /// Number of unknowns for `nodes` nodes.
    pub fn unknowns(&self, nodes: usize) -> usize {
        let t = self.tiles.len();
        2 * nodes + 3 * t + t * (self.openings.len() - 1)
    }

    /// Number of nodes of unknowns `z`.
    fn nodes_of(&self, z: &DVec) -> usize {
        let t = self.tiles.len();
        (z.len() - 3 * t - t * (self.openings.len() - 1)) / 2
    }

    /// Column of tile `i`'s x in the opened state (y and θ follow).
    fn pose_col(&self, nodes: usize, i: usize) -> usize {
        2 * nodes + 3 * i
    }

    /// Column of tile `i`'s rotation in state `s` (the opened state's full poses come first,
    /// then every state part of the way's rotations).
    pub(super) fn theta_col(&self, nodes: usize, s: usize, i: usize) -> usize {
        let t = self.tiles.len();
        if s == self.openings.len() - 1 {
            2 * nodes + 3 * i + 2
        } else {
            2 * nodes + 3 * t + t * s + i
        }
    }

    /// The point reached along `segments` (tile t, entered at node `from` and left at `to`,
    /// adds R(θ_t)(X_to − X_from)) in state `state`, and its derivative entries.
    pub(super) fn chain(
        &self,
        z: &DVec,
        nodes: usize,
        state: usize,
        segments: impl IntoIterator<Item = Segment>,
    ) -> (Vec2, ChainJacobian) {
        let x = |k: usize| Vec2::new(z[node_col(k)], z[node_col(k) + 1]);
        let mut p = Vec2::zeros();
        let mut jac = ChainJacobian {
            rows: [Vec::with_capacity(15), Vec::with_capacity(15)],
        };
        for seg in segments {
            if seg.from == seg.to {
                continue;
            }
            let tc = self.theta_col(nodes, state, seg.tile);
            let r = rotation(z[tc]);
            let rd = r * (x(seg.to) - x(seg.from));
            p += rd;
            let dth = perp(&rd);
            for (row, entries) in jac.rows.iter_mut().enumerate() {
                entries.push((tc, dth[row]));
                entries.push((node_col(seg.to), r[(row, 0)]));
                entries.push((node_col(seg.to) + 1, r[(row, 1)]));
                entries.push((node_col(seg.from), -r[(row, 0)]));
                entries.push((node_col(seg.from) + 1, -r[(row, 1)]));
            }
        }
        (p, jac)
    }

    /// The point [`Self::chain`] reaches, without its derivative.
    pub(super) fn chain_point(
        &self,
        z: &DVec,
        nodes: usize,
        state: usize,
        segments: impl IntoIterator<Item = Segment>,
    ) -> Vec2 {
        let x = |k: usize| Vec2::new(z[node_col(k)], z[node_col(k) + 1]);
        segments
            .into_iter()
            .filter(|seg| seg.from != seg.to)
            .map(|seg| {
                rotation(z[self.theta_col(nodes, state, seg.tile)]) * (x(seg.to) - x(seg.from))
            })
            .sum()
    }

    /// Loop closures of state `state` (part of the way): around every cycle of
    /// [`Self::loops`], the tiles' chain returns to its start (2 rows per cycle).
    fn push_loops(&self, z: &DVec, nodes: usize, state: usize, out: &mut Rows) {
        let w = self.weights.joints * self.state_weight(state);
        for cycle in &self.loops {
            let (p, jac) = self.chain(z, nodes, state, cycle.iter().copied());
            for row in 0..2 {
                out.push(
                    w * p[row],
                    merged(jac.row(row).iter().map(|&(c, v)| (c, w * v)).collect()),
                );
            }
        }
    }

    /// The unknowns of a sheet: its nodes, its opened poses, then the rotations of its
    /// states part of the way (its `path`).
    pub fn pack(sheet: &GradedSheet) -> DVec {
        let n = sheet.nodes.len();
        let states: Vec<&Vec<super::model::OpenedPose>> = sheet
            .path
            .iter()
            .chain(std::iter::once(&sheet.opened))
            .collect();
        let t = sheet.tiles.len();
        let mut z = DVec::zeros(2 * n + 3 * t + t * (states.len() - 1));
        for (k, p) in sheet.nodes.iter().enumerate() {
            z[2 * k] = p[0];
            z[2 * k + 1] = p[1];
        }
        let mut at = 2 * n;
        for pose in &sheet.opened {
            z[at] = pose.x;
            z[at + 1] = pose.y;
            z[at + 2] = pose.theta;
            at += 3;
        }
        // States part of the way: rotations only.
        for poses in &sheet.path {
            for pose in poses {
                z[at] = pose.theta;
                at += 1;
            }
        }
        z
    }

    /// Writes unknowns back into a sheet (as many states as it has).
    pub fn unpack(sheet: &mut GradedSheet, z: &DVec) {
        let n = sheet.nodes.len();
        for (k, p) in sheet.nodes.iter_mut().enumerate() {
            *p = [z[2 * k], z[2 * k + 1]];
        }
        let mut at = 2 * n;
        for pose in sheet.opened.iter_mut() {
            pose.x = z[at];
            pose.y = z[at + 1];
            pose.theta = z[at + 2];
            at += 3;
        }
        if sheet.path.is_empty() {
            return;
        }
        // States part of the way: the rotations, then the positions that close the pins best
        // (see [`super::loops::place`]).
        let joints: Vec<(usize, usize, usize)> =
            sheet.joints.iter().map(|j| (j.a, j.b, j.node)).collect();
        let nodes: Vec<Vec2> = (0..n).map(|k| sheet.node(k)).collect();
        let firsts: Vec<usize> = sheet.tiles.iter().map(|t| t.nodes[0]).collect();
        for poses in sheet.path.iter_mut() {
            let thetas: Vec<Real> = (0..poses.len()).map(|i| z[at + i]).collect();
            at += poses.len();
            let mut positions: Vec<Vec2> = poses.iter().map(|p| Vec2::new(p.x, p.y)).collect();
            super::loops::place(&firsts, &joints, &nodes, &thetas, &mut positions);
            for ((pose, theta), p) in poses.iter_mut().zip(thetas).zip(positions) {
                *pose = super::model::OpenedPose {
                    x: p.x,
                    y: p.y,
                    theta,
                };
            }
        }
    }

    /// Opened position of node `n` as a corner of tile `i`, and its derivative entries.
    pub(super) fn corner(
        &self,
        z: &DVec,
        nodes: usize,
        state: usize,
        i: usize,
        n: usize,
    ) -> (Vec2, CornerJacobian) {
        debug_assert_eq!(
            state,
            self.openings.len() - 1,
            "full poses in the opened state only"
        );
        let f = self.tiles[i][0];
        let pc = self.pose_col(nodes, i);
        let th = z[pc + 2];
        let r = rotation(th);
        let x = |k: usize| Vec2::new(z[node_col(k)], z[node_col(k) + 1]);
        let d = x(n) - x(f);
        let rd = r * d;
        let p = Vec2::new(z[pc], z[pc + 1]) + rd;
        let dth = perp(&rd);
        let mut jac = CornerJacobian {
            entries: [[(0, 0.0); 6]; 2],
            len: if n != f { 6 } else { 2 },
        };
        for (row, entries) in jac.entries.iter_mut().enumerate() {
            entries[0] = (pc + row, 1.0);
            entries[1] = (pc + 2, dth[row]);
            // ∂p/∂X_n = R, ∂p/∂X_f = −R
            entries[2] = (node_col(n), r[(row, 0)]);
            entries[3] = (node_col(n) + 1, r[(row, 1)]);
            entries[4] = (node_col(f), -r[(row, 0)]);
            entries[5] = (node_col(f) + 1, -r[(row, 1)]);
        }
        (p, jac)
    }

    /// Every residual and its Jacobian rows at `z`.
    pub fn rows(&self, z: &DVec) -> Rows {
        self.rows_of(z, false)
    }

    /// Every row that can occur, one-sided ones included whether active or not: the sparsity
    /// pattern of the normal equations (the values mean nothing).
    pub fn structure(&self, z: &DVec) -> Rows {
        self.rows_of(z, true)
    }

    /// The problem of a closing projection (the optimisation's last step and the path
    /// check's): the pins, the opening and the one-sided rows of the pins' turning only (its
    /// fraction of the mean, the angular gaps), the pins and the opening weighed `stiffness`
    /// times their fit weight against the turning rows (see [`PROJECTION_STIFFNESS`]).
    pub fn projection(&self, stiffness: Real) -> Problem {
        let mut p = Problem {
            full: false,
            ..self.clone()
        };
        p.weights.joints *= stiffness;
        p.weights.opening *= stiffness;
        p
    }

    /// Factor on the pin weight of state `state`: (the opened state's opening / this
    /// state's)^[`Weights::state_exponent`], 1 for the opened state. A state near the closed
    /// tiling turns its tiles little, so a pin gap there matters more than the same gap well
    /// open; weighed alike, the fit left the states nearest closed with pins 1e-4 open and
    /// tiles overlapping at the sheet's corners (400 tiles, a disc), and the sheet lost its
    /// motion there (measured: the exponent 0.5 closes them, 1 over-stiffens the fit).
    pub fn state_weight(&self, state: usize) -> Real {
        let last = self.openings.len() - 1;
        let (opened, here) = (self.openings[last], self.openings[state]);
        if state == last || here == 0.0 {
            1.0
        } else {
            (opened / here).abs().powf(self.weights.state_exponent)
        }
    }

    /// The pin rows of every state alone, in the order [`Self::rows`] has them.
    pub fn pin_rows(&self, z: &DVec) -> Rows {
        let states = self.openings.len();
        let nodes = self.nodes_of(z);
        let mut out = Rows::default();
        for state in 0..states {
            if state == states - 1 {
                self.push_pins(z, nodes, state, &mut out);
            } else {
                self.push_loops(z, nodes, state, &mut out);
            }
        }
        out
    }

    /// The two opened positions of every pinned node coincide (2 rows per pin).
    fn push_pins(&self, z: &DVec, nodes: usize, state: usize, out: &mut Rows) {
        let wj = self.weights.joints * self.state_weight(state);
        for &(a, b, n) in &self.joints {
            let (pa, ja) = self.corner(z, nodes, state, a, n);
            let (pb, jb) = self.corner(z, nodes, state, b, n);
            for row in 0..2 {
                let e = ja.row(row).iter().map(|&(c, v)| (c, wj * v));
                let e = e.chain(jb.row(row).iter().map(|&(c, v)| (c, -wj * v)));
                out.push(wj * (pa[row] - pb[row]), e);
            }
        }
    }

    fn rows_of(&self, z: &DVec, every: bool) -> Rows {
        let states = self.openings.len();
        let nodes = self.nodes_of(z);
        let last = states - 1;
        let w = self.weights;
        let mut out = Rows::default();
        let x = |k: usize| Vec2::new(z[node_col(k)], z[node_col(k) + 1]);
        for (state, &opening) in self.openings.iter().enumerate() {
            if state == last {
                self.push_pins(z, nodes, state, &mut out);
            } else {
                self.push_loops(z, nodes, state, &mut out);
            }
            // Mean opening.
            if !self.joints.is_empty() {
                let m = self.joints.len() as Real;
                let mut value = -opening;
                let mut e = Vec::with_capacity(2 * self.joints.len());
                for (&(a, b, _), &s) in self.joints.iter().zip(&self.joint_signs) {
                    let ca = self.theta_col(nodes, state, a);
                    let cb = self.theta_col(nodes, state, b);
                    value += s * (z[cb] - z[ca]) / m;
                    e.push((cb, w.opening * s / m));
                    e.push((ca, -w.opening * s / m));
                }
                out.push_dense(w.opening * value, e);
            }
            // Every pin opens the way the periodic sheet's does, by at least a fraction of the
            // state's mean (one-sided): a pin turning back would push its two tiles into each
            // other.
            for (&(a, b, _), &s) in self.joints.iter().zip(&self.joint_signs) {
                if s == 0.0 {
                    continue;
                }
                let floor = w.pin_fraction * opening;
                let ca = self.theta_col(nodes, state, a);
                let cb = self.theta_col(nodes, state, b);
                let value = floor - s * (z[cb] - z[ca]);
                if every || value > 0.0 {
                    out.push(w.bounds * value, [(cb, -w.bounds * s), (ca, w.bounds * s)]);
                }
            }
            // The two tiles of a pin never turn into each other around it: each angular gap
            // between their corners stays open (one-sided).
            for gap in &self.pin_gaps {
                let (a, b, n) = self.joints[gap.joint];
                let (v, u) = (x(gap.from) - x(n), x(gap.to) - x(n));
                let (lv, lu) = (v.norm_squared(), u.norm_squared());
                if lv == 0.0 || lu == 0.0 {
                    continue;
                }
                let raw = crate::math::cross(&v, &u).atan2(v.dot(&u));
                let closed_gap = gap.start + wrap_angle(raw - gap.start_raw);
                let ca = self.theta_col(nodes, state, a);
                let cb = self.theta_col(nodes, state, b);
                let value = -(closed_gap + gap.sign * (z[cb] - z[ca]));
                if every || value > 0.0 {
                    // ∂arg(u)/∂u = perp(u)/|u|², ∂arg(v)/∂v likewise, gap = arg u − arg v.
                    let du = Vec2::new(-u.y, u.x) / lu;
                    let dv = -Vec2::new(-v.y, v.x) / lv;
                    let dn = -(du + dv);
                    let k = -w.bounds;
                    out.push(
                        w.bounds * value,
                        [
                            (node_col(gap.to), k * du.x),
                            (node_col(gap.to) + 1, k * du.y),
                            (node_col(gap.from), k * dv.x),
                            (node_col(gap.from) + 1, k * dv.y),
                            (node_col(n), k * dn.x),
                            (node_col(n) + 1, k * dn.y),
                            (cb, k * gap.sign),
                            (ca, -k * gap.sign),
                        ],
                    );
                }
            }
            if self.full {
                self.contact_rows(z, nodes, state, every, &mut out);
            }
        }
        if !self.full {
            return out;
        }
        // Target fit: radial error |p| − s·ρ(p); blended, |p| − ((1 − λ)·r₀ + λ·s·ρ(p)).
        let fit = |i: usize, n: usize, from: Option<Real>, one_sided: bool, out: &mut Rows| {
            let (p, jp) = self.corner(z, nodes, last, i, n);
            let r = p.norm().max(1e-300);
            let (rho, drho) = self.outline.radius(p);
            let (value, g) = match (from, &self.fit_from) {
                (Some(r0), Some(b)) => (
                    r - ((1.0 - b.lambda) * r0 + b.lambda * self.scale * rho),
                    p / r - drho * (b.lambda * self.scale),
                ),
                _ => (r - self.scale * rho, p / r - drho * self.scale),
            };
            if one_sided && value <= 0.0 && !every {
                return;
            }
            let e = (0..2).flat_map(|row| {
                jp.row(row)
                    .iter()
                    .map(move |&(c, v)| (c, w.fit * g[row] * v))
            });
            out.push(w.fit * value, e);
        };
        let from = |k: usize, tips: bool| {
            self.fit_from
                .as_ref()
                .map(|b| if tips { b.tips[k] } else { b.inside[k] })
        };
        for (k, &(i, n)) in self.tips.iter().enumerate() {
            fit(i, n, from(k, true), false, &mut out);
        }
        for (k, &(i, n)) in self.inside.iter().enumerate() {
            fit(i, n, from(k, false), true, &mut out);
        }
        // Area-ratio field: (opened area − target × closed area) / starting closed area.
        for cell in &self.field {
            let closed: Vec<Vec2> = cell.corners.iter().map(|&(_, n)| x(n)).collect();
            let opened: Vec<(Vec2, CornerJacobian)> = cell
                .corners
                .iter()
                .map(|&(i, n)| self.corner(z, nodes, last, i, n))
                .collect();
            let points: Vec<Vec2> = opened.iter().map(|o| o.0).collect();
            let a_open = crate::geometry::signed_area(&points);
            let a_closed = crate::geometry::signed_area(&closed);
            let k = w.field / cell.start_area;
            let value = k * (a_open - cell.target * a_closed);
            // ∂A/∂p_j = ½ (p_{j+1}.y − p_{j−1}.y, p_{j−1}.x − p_{j+1}.x)
            let grad = |p: &[Vec2], j: usize| {
                let (next, prev) = (p[(j + 1) % 4], p[(j + 3) % 4]);
                Vec2::new(next.y - prev.y, prev.x - next.x) * 0.5
            };
            let mut e = Vec::with_capacity(32);
            for (j, (_, jacobian)) in opened.iter().enumerate() {
                let g = grad(&points, j);
                for row in 0..2 {
                    e.extend(jacobian.row(row).iter().map(|&(c, v)| (c, k * g[row] * v)));
                }
                let g = grad(&closed, j) * (-k * cell.target);
                let n = cell.corners[j].1;
                e.push((node_col(n), g.x));
                e.push((node_col(n) + 1, g.y));
            }
            out.push(value, e);
        }
        // Smoothness between lattice neighbours.
        for &(a, b) in &self.neighbours {
            let (ta, tb) = (&self.tiles[a], &self.tiles[b]);
            for v in 1..ta.len() {
                for d in 0..2 {
                    let value = (x(ta[v])[d] - x(ta[0])[d]) - (x(tb[v])[d] - x(tb[0])[d]);
                    out.push(
                        w.smooth * value,
                        [
                            (node_col(ta[v]) + d, w.smooth),
                            (node_col(ta[0]) + d, -w.smooth),
                            (node_col(tb[v]) + d, -w.smooth),
                            (node_col(tb[0]) + d, w.smooth),
                        ],
                    );
                }
            }
        }
        // Prior.
        for (k, s) in self.start.iter().enumerate() {
            for d in 0..2 {
                out.push(w.prior * (x(k)[d] - s[d]), [(node_col(k) + d, w.prior)]);
            }
        }
        // Shape bounds.
        for (i, t) in self.tiles.iter().enumerate() {
            let m = t.len();
            for v in 0..m {
                let (ip, ia, inx) = (t[(v + m - 1) % m], t[v], t[(v + 1) % m]);
                let s0 = self.corner_start[i][v];
                if s0.abs() > SINE_FLOOR {
                    let o = s0.signum();
                    let (a, b) = (x(inx) - x(ia), x(ip) - x(ia));
                    let (la, lb) = (a.norm(), b.norm());
                    // c = cross(next − at, prev − at) = |a||b| sin: twice the corner's
                    // triangle. ∂c/∂next = (b.y, −b.x); ∂c/∂prev = (−a.y, a.x).
                    let c = crate::math::cross(&a, &b);
                    let (dcn, dcp) = (Vec2::new(b.y, -b.x), Vec2::new(-a.y, a.x));
                    let c0 = self.corner_area_start[i][v];
                    let bound = |value: Real, dn: Vec2, dp: Vec2, out: &mut Rows| {
                        if every || value > 0.0 {
                            let k = -o * w.bounds;
                            let rows = [(inx, dn), (ip, dp), (ia, -(dn + dp))];
                            push_three_nodes(out, w.bounds * value, rows.map(|(n, g)| (n, g * k)));
                        }
                    };
                    // The corner's triangle keeps a fraction of its area: tiles do not
                    // collapse to slivers.
                    bound(w.corner_fraction * c0.abs() - o * c, dcn, dcp, &mut out);
                    // Its sine keeps a fraction of its value: a minimum angle, away from 0
                    // and from a straight angle.
                    if la > 1e-300 && lb > 1e-300 {
                        let sine = c / (la * lb);
                        // ∂|a|/∂next = â, ∂|b|/∂prev = b̂
                        let dn = dcn / (la * lb) - a * (sine / (la * la));
                        let dp = dcp / (la * lb) - b * (sine / (lb * lb));
                        bound(w.angle_fraction * s0.abs() - o * sine, dn, dp, &mut out);
                    }
                }
                let e = x(inx) - x(ia);
                let len = e.norm();
                let value = w.edge_fraction * self.edge_start[i][v] - len;
                if (every || value > 0.0) && len > 1e-300 {
                    let g = e / len * (-w.bounds);
                    out.push(
                        w.bounds * value,
                        [
                            (node_col(inx), g.x),
                            (node_col(inx) + 1, g.y),
                            (node_col(ia), -g.x),
                            (node_col(ia) + 1, -g.y),
                        ],
                    );
                }
            }
        }
        // Concave tiles: every triangle of their fixed triangulation keeps a fraction of its
        // area. c = cross(b − a, c − a); ∂c/∂b = (c−a).perp, ∂c/∂c = −(b−a).perp.
        for &([ia, ib, ic], c0) in &self.triangles {
            let (pa, pb, pc) = (x(ia), x(ib), x(ic));
            let (ab, ac) = (pb - pa, pc - pa);
            let value = w.corner_fraction * c0 - crate::math::cross(&ab, &ac);
            if every || value > 0.0 {
                let db = Vec2::new(ac.y, -ac.x);
                let dc = Vec2::new(-ab.y, ab.x);
                let rows = [(ia, -(db + dc)), (ib, db), (ic, dc)];
                push_three_nodes(
                    &mut out,
                    w.bounds * value,
                    rows.map(|(n, g)| (n, g * -w.bounds)),
                );
            }
        }
        out
    }
}

/// Pushes a row over three nodes' columns: `entries` are (node, gradient of the row).
fn push_three_nodes(out: &mut Rows, value: Real, entries: [(usize, Vec2); 3]) {
    out.push(
        value,
        entries
            .into_iter()
            .flat_map(|(n, g)| [(node_col(n), g.x), (node_col(n) + 1, g.y)]),
    );
}

/// The triangles of every tile of `tiles` (node lists over `start`) with a reflex corner
/// (starting sine below −[`SINE_FLOOR`]): a fixed ear-clipping triangulation, each triangle
/// with twice its starting area (see [`Problem::triangles`]).
pub fn reflex_triangles(
    tiles: &[Vec<usize>],
    start: &[Vec2],
    sines: &[Vec<Real>],
) -> Vec<([usize; 3], Real)> {
    let mut out = Vec::new();
    for (t, s) in tiles.iter().zip(sines) {
        if !s.iter().any(|&v| v < -SINE_FLOOR) {
            continue;
        }
        let poly: Vec<Vec2> = t.iter().map(|&n| start[n]).collect();
        let Some(tris) = crate::geometry::triangulate(&poly) else {
            continue;
        };
        for [a, b, c] in tris {
            let c0 = crate::math::cross(&(poly[b] - poly[a]), &(poly[c] - poly[a]));
            if c0 > 0.0 {
                out.push(([t[a], t[b], t[c]], c0));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::{setup, GradedRequest};
    use super::*;

    /// Every Jacobian entry matches central differences of the residuals, on a perturbed
    /// start where the one-sided terms are active.
    #[test]
    fn the_jacobian_matches_finite_differences() {
        let outline = GradedRequest {
            design: "rotating-squares".into(),
            rows: 2,
            cols: 2,
            outline: Outline::Ellipse { a: 1.5, b: 1.0 },
            ..GradedRequest::default()
        };
        let field = GradedRequest {
            rows: 3,
            states: 2,
            field: Some(crate::graded::parse_field("field:1.3,1.8,30").unwrap()),
            ..outline.clone()
        };
        let pushed = GradedRequest {
            states: 2,
            ..outline.clone()
        };
        // A concave tile (a 221° reflex corner): its triangles' rows.
        let concave = GradedRequest {
            design: super::super::CONCAVE_DESIGN.into(),
            ..outline.clone()
        };
        assert!(!setup(&concave).unwrap().1.triangles.is_empty());
        for request in [outline, field, concave] {
            jacobian_matches_finite_differences(&request, false);
        }
        // A blended fit (the fall-back's): tips part of the way from their start, the other
        // boundary corners held to 90 % of theirs, so that their rows are active.
        let (sheet, mut problem) = setup(&pushed).unwrap();
        let r0 = |points: &[(usize, usize)], f: Real| -> Vec<Real> {
            points
                .iter()
                .map(|&(i, n)| f * sheet.opened_corner(i, n).norm())
                .collect()
        };
        problem.fit_from = Some(FitBlend {
            lambda: 0.4,
            tips: r0(&problem.tips, 1.0),
            inside: r0(&problem.inside, 0.9),
        });
        problem.full = true;
        let z = Problem::pack(&sheet);
        let mut without = problem.clone();
        without.inside.clear();
        assert!(problem.rows(&z).values.len() > without.rows(&z).values.len());
        jacobian_at(&problem, &z);
        // Contact rows active: a tile pushed into its neighbour in the opened state.
        jacobian_matches_finite_differences(&pushed, true);
        // Contact rows active in a state part of the way (rotations only), along
        // pin paths of one hop and longer.
        jacobian_matches_finite_differences_turned(&pushed);
    }

    /// Every tile of the states part of the way turned so that contact rows (of
    /// pinned and unpinned pairs) are active there; then the finite-difference comparison.
    fn jacobian_matches_finite_differences_turned(request: &GradedRequest) {
        let (sheet, problem) = setup(request).unwrap();
        assert!(!sheet.path.is_empty());
        let z0 = Problem::pack(&sheet);
        assert_eq!(z0.len(), problem.unknowns(sheet.nodes.len()));
        assert_eq!(active_contacts(&problem, &z0), 0);
        // Pack and unpack round trip: the poses part of the way come back (pins closed).
        let mut back = sheet.clone();
        for pose in back.path.iter_mut().flatten() {
            pose.x += 0.3;
            pose.y -= 0.2;
        }
        Problem::unpack(&mut back, &z0);
        for (p, q) in back.path.iter().flatten().zip(sheet.path.iter().flatten()) {
            let shift = (
                back.path[0][0].x - sheet.path[0][0].x,
                back.path[0][0].y - sheet.path[0][0].y,
            );
            assert!((p.x - q.x - shift.0).abs() < 1e-9 && (p.y - q.y - shift.1).abs() < 1e-9);
        }
        // Turn tiles until contacts are active part of the way, of both kinds.
        let mut seed = 11u64;
        let mut z = z0.clone();
        let first = 2 * sheet.nodes.len() + 3 * sheet.tiles.len();
        for k in first..z.len() {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            z[k] += 1.2 * ((seed >> 11) as Real / (1u64 << 53) as Real - 0.5);
        }
        let count = |pinned: bool| {
            let mut p = problem.clone();
            let keep: Vec<bool> = p
                .contacts
                .iter()
                .map(|c| c.pin.is_some() == pinned)
                .collect();
            let mut k = 0;
            p.contacts.retain(|_| {
                k += 1;
                keep[k - 1]
            });
            let mut k = 0;
            p.contact_routes.retain(|_| {
                k += 1;
                keep[k - 1]
            });
            active_contacts(&p, &z)
        };
        let (pinned, unpinned) = (count(true), count(false));
        assert!(
            pinned > 0 && unpinned > 0,
            "active: pinned {pinned}, unpinned {unpinned}"
        );
        assert!(
            problem
                .contact_routes
                .iter()
                .flatten()
                .any(|r| r.0.len() > 1),
            "a route of more than one hop"
        );
        jacobian_at(&problem, &z);
    }

    /// Moves the opened pose of the second tile of the first unpinned contact pair halfway
    /// towards the first tile's; returns the pair.
    fn push_into_neighbour(sheet: &mut GradedSheet, problem: &Problem) -> (usize, usize) {
        let c = problem
            .contacts
            .iter()
            .find(|c| c.pin.is_none())
            .expect("an unpinned pair");
        let centre = |p: Vec<Vec2>| p.iter().sum::<Vec2>() / p.len() as Real;
        let shift = (centre(sheet.opened_polygon(c.a)) - centre(sheet.opened_polygon(c.b))) * 0.5;
        sheet.opened[c.b].x += shift.x;
        sheet.opened[c.b].y += shift.y;
        (c.a, c.b)
    }

    /// How many contact rows are active at `z`.
    fn active_contacts(problem: &Problem, z: &DVec) -> usize {
        let mut without = problem.clone();
        without.contacts.clear();
        problem.rows(z).values.len() - without.rows(z).values.len()
    }

    fn jacobian_matches_finite_differences(request: &GradedRequest, push_in: bool) {
        let (mut sheet, mut problem) = setup(request).unwrap();
        assert!(request.field.is_none() || !problem.field.is_empty());
        if push_in {
            push_into_neighbour(&mut sheet, &problem);
            let z = Problem::pack(&sheet);
            assert!(
                active_contacts(&problem, &z) > 0,
                "no contact row is active"
            );
        }
        // Strong shape bounds so that some are active after the perturbation.
        problem.weights.corner_fraction = 0.99;
        problem.weights.angle_fraction = 0.99;
        problem.weights.edge_fraction = 0.99;
        let mut z = Problem::pack(&sheet);
        let mut seed = 7u64;
        for v in z.iter_mut() {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            *v += 0.02 * ((seed >> 11) as Real / (1u64 << 53) as Real - 0.5);
        }
        jacobian_at(&problem, &z);
    }

    fn jacobian_at(problem: &Problem, z: &DVec) {
        let z = z.clone();
        let h = 1e-6;
        let (jacobian, values) = problem.rows(&z).to_dense(z.len());
        // Sparse rows, then dense rows, as in `to_dense`.
        let values_at = |z: &DVec| -> Vec<Real> {
            let rows = problem.rows(z);
            rows.values
                .iter()
                .chain(&rows.dense_values)
                .copied()
                .collect()
        };
        for c in 0..z.len() {
            let (mut zp, mut zm) = (z.clone(), z.clone());
            zp[c] += h;
            zm[c] -= h;
            let (vp, vm) = (values_at(&zp), values_at(&zm));
            // One-sided rows switching on or off between the two points change the row
            // count: such a column is skipped (it sits on a kink).
            if vp.len() != values.len() || vm.len() != values.len() {
                continue;
            }
            for r in 0..values.len() {
                let fd = (vp[r] - vm[r]) / (2.0 * h);
                let exact = jacobian[(r, c)];
                assert!(
                    (fd - exact).abs() < 1e-5 * (1.0 + fd.abs()),
                    "row {r} column {c}: finite difference {fd}, exact {exact}"
                );
            }
        }
    }

    /// A state part of the way weighs its pins by (opened opening / its own)^0.5: more the
    /// less it has opened, the opened state by 1; the pin rows carry the factor.
    #[test]
    fn states_nearer_closed_weigh_their_pins_more() {
        let request = GradedRequest {
            design: "rotating-squares".into(),
            rows: 2,
            cols: 2,
            states: 4,
            ..GradedRequest::default()
        };
        let (sheet, mut problem) = setup(&request).unwrap();
        let last = problem.openings.len() - 1;
        assert_eq!(problem.state_weight(last), 1.0);
        for s in 0..last {
            let expected = (problem.openings[last] / problem.openings[s]).sqrt();
            assert!((problem.state_weight(s) - expected).abs() < 1e-12);
            assert!(problem.state_weight(s) > problem.state_weight(s + 1));
        }
        // Every tile of every state moved: pins open everywhere.
        let mut z = Problem::pack(&sheet);
        let nodes = 2 * sheet.nodes.len();
        for (k, v) in z.iter_mut().enumerate().skip(nodes) {
            *v += 1e-3 * ((k * 37 % 11) as Real / 11.0 - 0.5);
        }
        let weighed = problem.rows(&z);
        let first = problem.state_weight(0);
        problem.weights.state_exponent = 0.0;
        let plain = problem.rows(&z);
        // State 0's block starts with its loop closures.
        assert!(!problem.loops.is_empty());
        for r in 0..2 * problem.loops.len() {
            let ratio = weighed.values[r] / plain.values[r];
            assert!((ratio - first).abs() < 1e-9 * ratio, "{ratio} vs {first}");
        }
    }

    /// Two tiles that meet in the closed sheet, pushed into each other in the opened state:
    /// contact rows become active and the independent overlap test agrees that the pair
    /// overlaps; the unpushed start (a periodic state) has none active.
    #[test]
    fn a_tile_pushed_into_its_neighbour_is_a_contact() {
        let request = GradedRequest {
            design: "rotating-squares".into(),
            rows: 2,
            cols: 2,
            states: 1,
            ..GradedRequest::default()
        };
        let (mut sheet, problem) = setup(&request).unwrap();
        assert_eq!(active_contacts(&problem, &Problem::pack(&sheet)), 0);
        let (a, b) = push_into_neighbour(&mut sheet, &problem);
        assert!(active_contacts(&problem, &Problem::pack(&sheet)) > 0);
        assert!(crate::geometry::interiors_overlap(
            &sheet.opened_polygon(a),
            &sheet.opened_polygon(b),
            crate::graded::deploy::OVERLAP_TOLERANCE
        ));
    }

    /// The pin gaps are the room around each pin: at the ungraded opened start (a periodic
    /// state, no overlap) no gap row is active; turning one tile of a pin past a gap makes
    /// that gap's row active and the two tiles overlap (the independent overlap test agrees).
    #[test]
    fn a_pin_turned_past_its_gap_is_an_overlap() {
        let request = GradedRequest {
            design: "rotating-squares".into(),
            rows: 2,
            cols: 2,
            states: 1,
            ..GradedRequest::default()
        };
        let (sheet, problem) = setup(&request).unwrap();
        let z = Problem::pack(&sheet);
        let active = |z: &DVec| problem.rows(z).values.len();
        let at_rest = active(&z);
        assert!(!problem.pin_gaps.is_empty());
        for gap in problem.pin_gaps.iter().step_by(3) {
            let (a, b, _) = problem.joints[gap.joint];
            if b == 0 || a == 0 {
                continue;
            }
            // Turn tile b about the pin's node, past the gap by 0.2 rad.
            let mut turned = sheet.clone();
            let (ta, tb) = (turned.opened[a].theta, turned.opened[b].theta);
            let now = gap.start + gap.sign * (tb - ta);
            let delta = -gap.sign * (now + 0.2);
            let pin = turned.opened_corner(b, problem.joints[gap.joint].2);
            let pose = &mut turned.opened[b];
            let r = rotation(delta);
            let first = Vec2::new(pose.x, pose.y);
            let moved = pin + r * (first - pin);
            pose.x = moved.x;
            pose.y = moved.y;
            pose.theta += delta;
            let zt = Problem::pack(&turned);
            assert!(active(&zt) > at_rest, "gap {gap:?}: no row became active");
            let overlap = crate::graded::deploy::overlap(&turned);
            assert!(
                overlap.is_some(),
                "gap {gap:?}: turned past it, yet no overlap"
            );
        }
    }
}
