//! A Verlet list for the broad phase: the pairs near one state, listed with a skin and
//! reused at the states a solver visits next, for as long as no other pair can have come
//! near.
//!
//! Listing every lattice translate within reach (`pairs`) costs a lattice enumeration per
//! pair of tiles, and a deployment step evaluates the energy, its derivatives and the
//! clearance at dozens of states close to each other. [`PairCache`] lists, at a state q₀, the
//! pairs whose bounding circles are within `margin + skin`; at a later state q it passes on,
//! of those, exactly the pairs a fresh listing at `margin` would give, provided that the
//! state moved little enough since q₀. Otherwise it lists again at q.
//!
//! Why the list stays complete. A pair (a, b, k) left out at q₀ has centre distance
//! D₀ > R + M, R = r_a + r_b ≤ 2·r_max its radii, M = margin + skin. From q₀ to q each
//! reference point moves by at most c = max|p_i − p_i⁰| and the copy's shift by
//! |k_u(u − u₀) + k_w(w − w₀)| ≤ ‖k‖·δ, δ = √(|u − u₀|² + |w − w₀|²). The offset is bounded by
//! the distance: D₀ ≥ σ₀‖k‖ − d_max (σ₀ the smallest singular value of [u₀ w₀], d_max a bound
//! on the distance of two reference points of the cell at q₀), so
//! D ≥ D₀ − 2c − ‖k‖δ ≥ D₀(1 − δ/σ₀) − 2c − d_max·δ/σ₀, which for δ < σ₀ (implied by the
//! condition below) is smallest at the smallest D₀:
//!
//!   D > R + M − [2c + (δ/σ₀)(2·r_max + M + d_max)].
//!
//! While the bracket (the drift) is at most [`SKIN_USE`] · (M − margin), every pair left out
//! is still more than R + margin + (1 − SKIN_USE)·(M − margin) apart: no fresh listing at q
//! could contain it, whatever its lattice translate. The lists are checked against fresh
//! listings along real trajectories and a far-sheared sheet (`verlet/tests.rs`).

use super::lattice::LatticeProblem;
use super::pairs::{for_each_near_pair, CandidatePair};
use super::placement::Placement;
use super::reach::Spread;
use crate::math::{Real, Vec2};

/// Skin added to the margin a list is made for (units of L). A larger skin lists more
/// pairs (each filtered at every use) but lists less often.
pub(crate) const SKIN: Real = 0.25;
/// Fraction of the skin the state may drift (see the module docs) before a list is redone;
/// the rest keeps unlisted pairs clear of the fresh listing's rounding slack.
pub(crate) const SKIN_USE: Real = 0.9;
/// Most lists kept at once (one per margin the solver asks for; the least recently used
/// goes).
const MAX_LISTS: usize = 4;

/// The pairs of one listing and the state they were listed at.
#[derive(Debug, Clone)]
struct List {
    /// The margin asked for when the list was made.
    margin: Real,
    /// The margin it was made at: `margin + SKIN`.
    listed: Real,
    /// Reference points and tiling vectors at listing.
    centres: Vec<Vec2>,
    u: Vec2,
    w: Vec2,
    /// σ₀ and d_max of the listing state (see the module docs).
    sigma: Real,
    dmax: Real,
    /// Every pair whose bounding circles were within `listed`, in listing order.
    pairs: Vec<Listed>,
    /// Queries answered so far (to pick the least recently used list).
    last_use: u64,
}

/// A listed pair with what its test at every use needs.
#[derive(Debug, Clone, Copy)]
struct Listed {
    pair: CandidatePair,
    /// The cell offset as reals.
    k: [Real; 2],
    /// r_a + r_b.
    radii: Real,
}

impl List {
    /// True when no pair left out of this list can be within `margin` at `placed`.
    fn covers(&self, placed: &Placement, rmax: Real, margin: Real) -> bool {
        if margin > self.listed || placed.tiles.len() != self.centres.len() {
            return false;
        }
        let c = placed
            .tiles
            .iter()
            .zip(&self.centres)
            .map(|(t, c0)| (t.centre - c0).norm_squared())
            .fold(0.0, Real::max)
            .sqrt();
        let delta =
            ((placed.u - self.u).norm_squared() + (placed.w - self.w).norm_squared()).sqrt();
        let drift = 2.0 * c + delta / self.sigma * (2.0 * rmax + self.listed + self.dmax);
        // False for NaN: a state that cannot be bounded is listed afresh.
        drift <= SKIN_USE * (self.listed - margin)
    }
}

/// Verlet lists of candidate pairs for one contact model, kept by a solver beside the
/// (immutable, shared) model while it moves the state. See the module docs for when a list
/// is reused; a list is never used for a model with other extents.
#[derive(Debug, Clone, Default)]
pub(crate) struct PairCache {
    /// Extents of the model the lists were made for, and their largest.
    extents: Vec<Real>,
    rmax: Real,
    lists: Vec<List>,
    /// Queries answered and lists made, for tests and measurements.
    queries: u64,
    listings: u64,
}

impl PairCache {
    /// An empty cache.
    pub(crate) fn new() -> PairCache {
        PairCache::default()
    }

    /// Lists made so far (each a full lattice enumeration).
    #[cfg(test)]
    pub(crate) fn listings(&self) -> u64 {
        self.listings
    }

    /// Calls `f` with every pair whose bounding circles are within `margin` at `placed`: the
    /// pairs [`for_each_near_pair`] gives, from a list made at this or an earlier state.
    /// The order is the listing's (the lattice enumeration order at the listing state). Fails
    /// like a fresh listing on a degenerate lattice, and on too many lattice points only when
    /// it has to list afresh.
    pub(crate) fn for_each_near_pair(
        &mut self,
        placed: &Placement,
        extents: &[Real],
        margin: Real,
        mut f: impl FnMut(CandidatePair),
    ) -> Result<(), LatticeProblem> {
        placed.sigma_min()?;
        if !margin.is_finite() || extents.len() != placed.tiles.len() {
            return for_each_near_pair(placed, extents, margin, f);
        }
        if self.extents != extents {
            self.extents = extents.to_vec();
            self.rmax = extents.iter().copied().fold(0.0, Real::max);
            self.lists.clear();
        }
        self.queries += 1;
        let index = match self.covering(placed, margin) {
            Some(i) => i,
            None => self.list(placed, margin)?,
        };
        let list = &mut self.lists[index];
        list.last_use = self.queries;
        let (u, w) = (placed.u, placed.w);
        for listed in &list.pairs {
            let radius = listed.radii + margin;
            if radius < 0.0 {
                continue;
            }
            // The slack of `Lattice::for_each_within`, so that both give the same pairs.
            let r = radius * (1.0 + 1e-12) + 1e-12;
            let pair = listed.pair;
            let d = placed.tiles[pair.b].centre - placed.tiles[pair.a].centre
                + u * listed.k[0]
                + w * listed.k[1];
            if d.norm_squared() <= r * r {
                f(pair);
            }
        }
        Ok(())
    }

    /// The list with the fewest pairs that covers `margin` at `placed`, if any. Lists made
    /// for a much larger margin are not used: filtering them would cost more than listing.
    fn covering(&self, placed: &Placement, margin: Real) -> Option<usize> {
        self.lists
            .iter()
            .enumerate()
            .filter(|(_, l)| l.listed <= margin + 2.0 * SKIN && l.covers(placed, self.rmax, margin))
            .min_by(|(_, a), (_, b)| a.listed.total_cmp(&b.listed))
            .map(|(i, _)| i)
    }

    /// Lists the pairs within `margin + SKIN` at `placed`, replacing the list made for the
    /// same margin (or the least recently used one when there are too many); its index.
    fn list(&mut self, placed: &Placement, margin: Real) -> Result<usize, LatticeProblem> {
        let spread = Spread::of(placed, &self.extents).ok_or(LatticeProblem::Degenerate)?;
        let listed = margin + SKIN;
        let mut pairs = Vec::new();
        let extents = &self.extents;
        for_each_near_pair(placed, extents, listed, |pair| {
            pairs.push(Listed {
                pair,
                k: pair.offset.map(Real::from),
                radii: extents[pair.a] + extents[pair.b],
            })
        })?;
        self.listings += 1;
        let list = List {
            margin,
            listed,
            centres: placed.tiles.iter().map(|t| t.centre).collect(),
            u: placed.u,
            w: placed.w,
            sigma: spread.sigma,
            dmax: spread.dmax,
            pairs,
            last_use: self.queries,
        };
        let slot = self
            .lists
            .iter()
            .position(|l| l.margin == margin)
            .or_else(|| {
                (self.lists.len() >= MAX_LISTS).then(|| {
                    (0..self.lists.len())
                        .min_by_key(|&i| self.lists[i].last_use)
                        .unwrap_or(0)
                })
            });
        Ok(match slot {
            Some(i) => {
                self.lists[i] = list;
                i
            }
            None => {
                self.lists.push(list);
                self.lists.len() - 1
            }
        })
    }
}

#[cfg(test)]
mod tests;
