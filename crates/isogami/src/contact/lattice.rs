//! The periodic lattice spanned by the current tiling vectors u, w: which translates
//! k_u·u + k_w·w of a tile can lie within a given distance of a point, found exactly for any
//! lattice (however sheared the deployment has made it) on a Lagrange–Gauss reduced basis.

use crate::math::{cross, Real, Vec2};

/// Most lattice points one enumeration visits. A state whose tiles do not overlap has a cell
/// at least as large as its tiles, so a reach of a few edge lengths holds a few dozen points;
/// more than this means a degenerate (squashed or non-finite) lattice.
pub(crate) const MAX_POINTS: usize = 100_000;

/// The tiling vectors and a reduced basis of the lattice they span.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Lattice {
    /// Reduced basis: |b1| ≤ |b2| and |b1·b2| ≤ |b1|²/2.
    b1: Vec2,
    b2: Vec2,
    /// Cell offsets (k_u, k_w) of b1 and b2: b = k_u·u + k_w·w.
    c1: [i64; 2],
    c2: [i64; 2],
    /// |b1|, |b1|² and b1 × b2, used by every query.
    b1_len: Real,
    b1_sq: Real,
    area: Real,
    /// Smallest singular value of [u w]: |k_u·u + k_w·w| ≥ σ_min·|(k_u, k_w)|.
    pub(crate) sigma_min: Real,
}

/// Why a lattice query has no answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum LatticeProblem {
    /// u and w are parallel, zero or not finite.
    Degenerate,
    /// The query would visit more than [`MAX_POINTS`] points.
    TooManyPoints,
}

impl Lattice {
    /// The smallest singular value of [u w] (see `sigma_min`), or `Degenerate` when u and w
    /// do not span the plane: the check of [`Lattice::new`] without the basis reduction.
    pub(crate) fn smallest_singular_value(u: Vec2, w: Vec2) -> Result<Real, LatticeProblem> {
        let area = cross(&u, &w).abs();
        let frob2 = u.norm_squared() + w.norm_squared();
        if !(area.is_finite() && frob2.is_finite()) || area <= 1e-12 * frob2 {
            return Err(LatticeProblem::Degenerate);
        }
        // σ_max² + σ_min² = ‖[u w]‖_F², σ_max·σ_min = |det|.
        let sigma_max =
            (0.5 * (frob2 + (frob2 * frob2 - 4.0 * area * area).max(0.0).sqrt())).sqrt();
        Ok(area / sigma_max)
    }

    /// The lattice of u and w, or `Degenerate` when they do not span the plane.
    pub(crate) fn new(u: Vec2, w: Vec2) -> Result<Lattice, LatticeProblem> {
        let sigma_min = Lattice::smallest_singular_value(u, w)?;
        let (mut b1, mut b2, mut c1, mut c2) = (u, w, [1i64, 0], [0i64, 1]);
        for _ in 0..200 {
            if b1.norm_squared() > b2.norm_squared() {
                std::mem::swap(&mut b1, &mut b2);
                std::mem::swap(&mut c1, &mut c2);
            }
            let ratio = b1.dot(&b2) / b1.norm_squared();
            // Reduced once |b1·b2| ≤ |b1|²/2; testing the rounded ratio instead would cycle
            // between ±1 on an exact tie (a hexagonal lattice).
            if !ratio.is_finite() || ratio.abs() <= 0.5 * (1.0 + 1e-12) || ratio.abs() > 1e12 {
                break;
            }
            let mu = ratio.round();
            b2 -= b1 * mu;
            let m = mu as i64;
            c2 = [c2[0] - m * c1[0], c2[1] - m * c1[1]];
        }
        Ok(Lattice {
            b1,
            b2,
            c1,
            c2,
            b1_len: b1.norm(),
            b1_sq: b1.norm_squared(),
            area: cross(&b1, &b2),
            sigma_min,
        })
    }

    /// Calls `f` with every cell offset (k_u, k_w) such that |d + k_u·u + k_w·w| ≤ radius
    /// (plus a relative 1e-12, so that no point on the circle is lost to rounding).
    pub(crate) fn for_each_within(
        &self,
        d: Vec2,
        radius: Real,
        mut f: impl FnMut([i32; 2]),
    ) -> Result<(), LatticeProblem> {
        if !(radius.is_finite() && d.x.is_finite() && d.y.is_finite()) {
            return Err(LatticeProblem::Degenerate);
        }
        if radius < 0.0 {
            return Ok(());
        }
        let r = radius * (1.0 + 1e-12) + 1e-12;
        let (b1, b2) = (self.b1, self.b2);
        let (n1, area) = (self.b1_len, self.area);
        // The points d + j·b2 + i·b1 lie on lines parallel to b1, |area|/|b1| apart; a line
        // meets the disc only if its distance from the origin is at most r.
        let c = cross(&b1, &d);
        let (lo, hi) = ((-r * n1 - c) / area, (r * n1 - c) / area);
        let (j0, j1) = (lo.min(hi).ceil(), lo.max(hi).floor());
        let b1sq = self.b1_sq;
        let mut visited = 0usize;
        let mut j = j0;
        while j <= j1 {
            let e = d + b2 * j;
            let be = b1.dot(&e);
            let disc = be * be - b1sq * (e.norm_squared() - r * r);
            if disc >= 0.0 {
                let s = disc.sqrt();
                let (i0, i1) = (((-be - s) / b1sq).ceil(), ((-be + s) / b1sq).floor());
                let mut i = i0;
                while i <= i1 {
                    visited += 1;
                    if visited > MAX_POINTS {
                        return Err(LatticeProblem::TooManyPoints);
                    }
                    f(self.cell_offset(i as i64, j as i64)?);
                    i += 1.0;
                }
            }
            visited += 1;
            if visited > MAX_POINTS {
                return Err(LatticeProblem::TooManyPoints);
            }
            j += 1.0;
        }
        Ok(())
    }

    /// The cell offset of reduced coordinates (i, j).
    fn cell_offset(&self, i: i64, j: i64) -> Result<[i32; 2], LatticeProblem> {
        let ku = i * self.c1[0] + j * self.c2[0];
        let kw = i * self.c1[1] + j * self.c2[1];
        match (i32::try_from(ku), i32::try_from(kw)) {
            (Ok(a), Ok(b)) => Ok([a, b]),
            _ => Err(LatticeProblem::TooManyPoints),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    /// Brute force over every offset with ‖k‖ ≤ (|d| + r)/σ_min, σ_min from nalgebra's SVD:
    /// no point outside that block can be within r of −d.
    fn brute(u: Vec2, w: Vec2, d: Vec2, r: Real) -> Vec<[i32; 2]> {
        let m = nalgebra::Matrix2::from_columns(&[u, w]);
        let sigma = m.singular_values().min();
        let span = ((d.norm() + r) / sigma).ceil() as i32 + 1;
        let mut out = Vec::new();
        for a in -span..=span {
            for b in -span..=span {
                if (d + u * Real::from(a) + w * Real::from(b)).norm() <= r {
                    out.push([a, b]);
                }
            }
        }
        out.sort();
        out
    }

    fn listed(l: &Lattice, d: Vec2, r: Real) -> Vec<[i32; 2]> {
        let mut out = Vec::new();
        l.for_each_within(d, r, |k| out.push(k)).unwrap();
        out.sort();
        out
    }

    #[test]
    fn agrees_with_brute_force_on_sheared_and_skewed_lattices() {
        let cases = [
            (vec2(1.0, 0.0), vec2(0.0, 1.0)),
            (vec2(2.0, 0.0), vec2(0.5, 0.3)),
            // Heavily sheared: w = 7u + small. The reduced basis is short.
            (vec2(1.0, 0.1), vec2(7.02, 0.95)),
            (vec2(-0.3, 2.0), vec2(5.0, -33.0)),
            (vec2(0.05, 0.0), vec2(0.0, 3.0)),
        ];
        let mut seed = 7u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        for (u, w) in cases {
            let l = Lattice::new(u, w).unwrap();
            for _ in 0..40 {
                let d = vec2(3.0 * rnd(), 3.0 * rnd());
                let r = 2.5 * (rnd() + 1.0);
                assert_eq!(listed(&l, d, r), brute(u, w, d, r), "{u:?} {w:?} {d:?} {r}");
            }
        }
    }

    #[test]
    fn reduction_stops_on_a_hexagonal_tie() {
        // b1·b2 = |b1|²/2 exactly: a tie that must not ping-pong between ±1.
        for w in [
            vec2(1.0, 3.0f64.sqrt()),
            vec2(5.0, 3.0f64.sqrt()),
            vec2(-3.0, 3.0f64.sqrt()),
        ] {
            let l = Lattice::new(vec2(2.0, 0.0), w).unwrap();
            assert!(
                l.b1.norm() <= 2.0 + 1e-12 && l.b2.norm() <= 2.0 + 1e-12,
                "{w:?}"
            );
            assert!(l.b1.dot(&l.b2).abs() <= 0.5 * l.b1.norm_squared() * (1.0 + 1e-9));
            // The basis still spans the same lattice: its offsets are unimodular.
            let det = l.c1[0] * l.c2[1] - l.c1[1] * l.c2[0];
            assert_eq!(det.abs(), 1, "{w:?}");
        }
    }

    #[test]
    fn singular_values_bound_translates() {
        let (u, w) = (vec2(1.0, 0.1), vec2(7.02, 0.95));
        let l = Lattice::new(u, w).unwrap();
        for a in -20..=20 {
            for b in -20..=20 {
                let v = u * Real::from(a) + w * Real::from(b);
                let k = Real::from(a * a + b * b).sqrt();
                assert!(v.norm() >= l.sigma_min * k * (1.0 - 1e-12));
            }
        }
    }

    #[test]
    fn degenerate_lattices_are_refused() {
        assert_eq!(
            Lattice::new(vec2(1.0, 0.0), vec2(2.0, 0.0)).err(),
            Some(LatticeProblem::Degenerate)
        );
        assert!(Lattice::new(vec2(Real::NAN, 0.0), vec2(0.0, 1.0)).is_err());
        let l = Lattice::new(vec2(1.0, 0.0), vec2(0.0, 1.0)).unwrap();
        assert_eq!(
            l.for_each_within(vec2(0.0, 0.0), 1e4, |_| {}),
            Err(LatticeProblem::TooManyPoints)
        );
        assert!(l
            .for_each_within(vec2(Real::NAN, 0.0), 1.0, |_| {})
            .is_err());
        let mut n = 0;
        l.for_each_within(vec2(0.0, 0.0), -1.0, |_| n += 1).unwrap();
        assert_eq!(n, 0);
    }
}
