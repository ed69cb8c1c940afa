//! What each shape parameter of a family does to its tile, in words for a slider label
//! (issue 24 item 4): derived from the prototile itself, not written by hand. At the
//! family's default shape each parameter is moved a little and the tile's intrinsic shape is
//! compared — its interior angles and its edge lengths relative to the mean edge — so the
//! words hold whatever the family's coordinates or the tile's placement: "v1: opens the
//! angles at corners 0 and 2, closes 1; lengthens edge 1 against 0 and 2". Corners and edges
//! are numbered as tile 0 of every cell of the family numbers its vertices (the prototile's
//! order, reversed when the family's first aspect mirrors it, as `cell` places it; edge k runs
//! from corner k to corner k + 1), so a page can label tile 0's corners and the words apply.

use super::family::Family;
use super::shape::Tiling;
use crate::geometry::signed_area;
use crate::math::{cross, Real, Vec2};
use serde::Serialize;

/// What one shape parameter does to the tile at the family's default shape.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParamEffect {
    /// Parameter index (v0…v5).
    pub index: usize,
    /// One line for a slider label, e.g. "opens the angle at corner 2, closes 0 and 1;
    /// lengthens edges 1 and 2 against 0".
    pub description: String,
    /// Corners whose interior angle grows as the parameter grows.
    pub opens: Vec<usize>,
    /// Corners whose interior angle shrinks.
    pub closes: Vec<usize>,
    /// Edges that grow relative to the mean edge.
    pub lengthens: Vec<usize>,
    /// Edges that shrink relative to the mean edge.
    pub shortens: Vec<usize>,
}

/// Share of the largest change below which a corner or edge counts as unchanged.
const SIGNIFICANT: Real = 0.05;
/// Smallest change (degrees per unit parameter scale, or relative length per unit scale)
/// that counts at all: below it the parameter does nothing to the tile's shape.
const FLOOR: Real = 1e-6;

/// Tile 0 of a cell at this tiling: the prototile under the first aspect, its vertex order
/// reversed when that makes it counter-clockwise (as `cell::build` places it).
fn tile0(t: &Tiling) -> Vec<Vec2> {
    let poly: Vec<Vec2> = t
        .prototile()
        .iter()
        .map(|p| t.aspects()[0].apply(p))
        .collect();
    let n = poly.len();
    if signed_area(&poly) < 0.0 {
        (0..n).map(|i| poly[(n - i) % n]).collect()
    } else {
        poly
    }
}

/// Interior angles (degrees) and edge lengths relative to the mean edge of a polygon.
fn intrinsic(poly: &[Vec2]) -> (Vec<Real>, Vec<Real>) {
    let n = poly.len();
    let lens: Vec<Real> = (0..n)
        .map(|k| (poly[(k + 1) % n] - poly[k]).norm())
        .collect();
    let mean = lens.iter().sum::<Real>() / n as Real;
    let orient = signed_area(poly).signum();
    let angles = (0..n)
        .map(|k| {
            let prev = poly[(k + n - 1) % n] - poly[k];
            let next = poly[(k + 1) % n] - poly[k];
            let a = (cross(&next, &prev) * orient)
                .atan2(next.dot(&prev))
                .to_degrees();
            if a < 0.0 {
                a + 360.0
            } else {
                a
            }
        })
        .collect();
    (angles, lens.iter().map(|l| l / mean).collect())
}

/// Indices whose change is significant, split by sign: (growing, shrinking).
fn split(changes: &[Real]) -> (Vec<usize>, Vec<usize>) {
    let largest = changes.iter().fold(0.0, |m: Real, c| m.max(c.abs()));
    if largest < FLOOR {
        return (Vec::new(), Vec::new());
    }
    let cut = SIGNIFICANT * largest;
    let grow = (0..changes.len()).filter(|&k| changes[k] > cut).collect();
    let shrink = (0..changes.len()).filter(|&k| changes[k] < -cut).collect();
    (grow, shrink)
}

/// "0", "0 and 2", "0, 1 and 3".
fn list(ix: &[usize]) -> String {
    let words: Vec<String> = ix.iter().map(|i| i.to_string()).collect();
    match words.len() {
        0 => String::new(),
        1 => words[0].clone(),
        n => format!("{} and {}", words[..n - 1].join(", "), words[n - 1]),
    }
}

fn plural(n: usize, one: &'static str, many: &'static str) -> &'static str {
    if n == 1 {
        one
    } else {
        many
    }
}

/// The sentence for one parameter's effect.
fn sentence(opens: &[usize], closes: &[usize], lengthens: &[usize], shortens: &[usize]) -> String {
    let mut parts = Vec::new();
    match (opens.is_empty(), closes.is_empty()) {
        (true, true) => {}
        (false, true) => parts.push(format!(
            "opens the {} at {} {}",
            plural(opens.len(), "angle", "angles"),
            plural(opens.len(), "corner", "corners"),
            list(opens)
        )),
        (true, false) => parts.push(format!(
            "closes the {} at {} {}",
            plural(closes.len(), "angle", "angles"),
            plural(closes.len(), "corner", "corners"),
            list(closes)
        )),
        (false, false) => parts.push(format!(
            "opens the {} at {} {}, closes {}",
            plural(opens.len(), "angle", "angles"),
            plural(opens.len(), "corner", "corners"),
            list(opens),
            list(closes)
        )),
    }
    match (lengthens.is_empty(), shortens.is_empty()) {
        (true, true) => {}
        (false, true) => parts.push(format!(
            "lengthens {} {}",
            plural(lengthens.len(), "edge", "edges"),
            list(lengthens)
        )),
        (true, false) => parts.push(format!(
            "shortens {} {}",
            plural(shortens.len(), "edge", "edges"),
            list(shortens)
        )),
        (false, false) => parts.push(format!(
            "lengthens {} {} against {}",
            plural(lengthens.len(), "edge", "edges"),
            list(lengthens),
            list(shortens)
        )),
    }
    if parts.is_empty() {
        // Angles and edge ratios unchanged: only the tile's size or placement moves.
        "scales or moves the tile without changing its shape".into()
    } else {
        parts.join("; ")
    }
}

/// What each shape parameter of `family` does to the tile, at the default shape (central
/// differences of the interior angles and relative edge lengths, a step of 1e-4 of the
/// parameter's scale max(|default|, 0.25)).
pub fn param_effects(family: Family) -> Vec<ParamEffect> {
    let defaults = family.default_params();
    (0..defaults.len())
        .map(|k| {
            let h = 1e-4 * defaults[k].abs().max(0.25);
            let at = |x: Real| {
                let mut p = defaults.clone();
                p[k] = x;
                Tiling::new(family, &p).ok().map(|t| intrinsic(&tile0(&t)))
            };
            let (da, dl) = match (at(defaults[k] + h), at(defaults[k] - h)) {
                (Some((a1, l1)), Some((a0, l0))) => (
                    a1.iter()
                        .zip(&a0)
                        .map(|(x, y)| (x - y) / (2.0 * h))
                        .collect::<Vec<_>>(),
                    l1.iter()
                        .zip(&l0)
                        .map(|(x, y)| (x - y) / (2.0 * h))
                        .collect::<Vec<_>>(),
                ),
                _ => (Vec::new(), Vec::new()),
            };
            let (opens, closes) = split(&da);
            let (lengthens, shortens) = split(&dl);
            ParamEffect {
                index: k,
                description: sentence(&opens, &closes, &lengthens, &shortens),
                opens,
                closes,
                lengthens,
                shortens,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_parameter_of_every_family_is_described() {
        for f in Family::all() {
            let effects = param_effects(f);
            assert_eq!(effects.len(), f.param_count(), "{f}");
            for e in &effects {
                assert!(!e.description.is_empty(), "{f} v{}", e.index);
                let n = tile0(&Tiling::default_for(f)).len();
                for &c in e
                    .opens
                    .iter()
                    .chain(&e.closes)
                    .chain(&e.lengthens)
                    .chain(&e.shortens)
                {
                    assert!(c < n, "{f} v{}: index {c} of {n}", e.index);
                }
            }
        }
    }

    /// The words agree with what a larger move of the parameter does to the tile: a corner
    /// said to open has a larger angle after the move, one said to close a smaller one.
    #[test]
    fn the_words_match_a_finite_move() {
        for f in Family::all() {
            let defaults = f.default_params();
            let (a0, l0) = intrinsic(&tile0(&Tiling::default_for(f)));
            for e in param_effects(f) {
                let mut p = defaults.clone();
                p[e.index] += 1e-3 * defaults[e.index].abs().max(0.25);
                let Ok(t) = Tiling::new(f, &p) else { continue };
                let (a1, l1) = intrinsic(&tile0(&t));
                for &c in &e.opens {
                    assert!(a1[c] > a0[c], "{f} v{}: corner {c} should open", e.index);
                }
                for &c in &e.closes {
                    assert!(a1[c] < a0[c], "{f} v{}: corner {c} should close", e.index);
                }
                for &c in &e.lengthens {
                    assert!(l1[c] > l0[c], "{f} v{}: edge {c} should lengthen", e.index);
                }
                for &c in &e.shortens {
                    assert!(l1[c] < l0[c], "{f} v{}: edge {c} should shorten", e.index);
                }
            }
        }
    }

    #[test]
    fn sentences_read_as_english() {
        assert_eq!(
            sentence(&[2], &[0, 1], &[1, 2], &[0]),
            "opens the angle at corner 2, closes 0 and 1; lengthens edges 1 and 2 against 0"
        );
        assert_eq!(
            sentence(&[], &[3], &[], &[]),
            "closes the angle at corner 3"
        );
        assert_eq!(
            sentence(&[], &[], &[], &[]),
            "scales or moves the tile without changing its shape"
        );
    }

    /// The numbering is the cell's: tile 0 of a built cell has the same vertices in the same
    /// order, up to a translation.
    #[test]
    fn corners_are_numbered_as_tile_0_of_a_cell() {
        use crate::cell::{CellDims, UnitCell};
        for f in Family::all() {
            let t = Tiling::default_for(f);
            let mine = tile0(&t);
            let cell = UnitCell::new(&t, CellDims::new(1, 1).unwrap()).unwrap();
            let theirs = &cell.tiles[0].polygon;
            assert_eq!(mine.len(), theirs.len(), "{f}");
            let shift = theirs[0] - mine[0];
            for (a, b) in mine.iter().zip(theirs) {
                assert!((a + shift - b).norm() < 1e-9, "{f}: {a:?} vs {b:?}");
            }
        }
    }
}
