//! The scalar IPC log barrier on an (unsigned, unsquared) distance d:
//! b(d) = −κ (d − d̂)² ln(d / d̂) for 0 < d < d̂, 0 for d ≥ d̂. It is C² at d̂ (b, b′, b″ all
//! vanish there), convex on (0, d̂) and tends to +∞ as d → 0.

use crate::math::Real;

/// b(d), b′(d), b″(d) of one barrier term.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BarrierValue {
    pub(crate) b: Real,
    pub(crate) db: Real,
    pub(crate) d2b: Real,
}

/// The barrier and its first two derivatives at distance `d > 0` (zero from d̂ on).
pub(crate) fn barrier(d: Real, dhat: Real, kappa: Real) -> BarrierValue {
    if d >= dhat {
        return BarrierValue {
            b: 0.0,
            db: 0.0,
            d2b: 0.0,
        };
    }
    let (g, l) = (d - dhat, (d / dhat).ln());
    BarrierValue {
        b: -kappa * g * g * l,
        db: -kappa * (2.0 * g * l + g * g / d),
        d2b: -kappa * (2.0 * l + 4.0 * g / d - g * g / (d * d)),
    }
}

/// b(d) alone (+∞ for d ≤ 0).
pub(crate) fn barrier_energy(d: Real, dhat: Real, kappa: Real) -> Real {
    if d <= 0.0 {
        return Real::INFINITY;
    }
    barrier(d, dhat, kappa).b
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_match_finite_differences() {
        let (dhat, kappa) = (0.005, 1.3);
        for k in 1..20 {
            let d = dhat * Real::from(k) / 20.0;
            let h = 1e-6 * d;
            let v = barrier(d, dhat, kappa);
            let (p, m) = (barrier(d + h, dhat, kappa), barrier(d - h, dhat, kappa));
            let fd1 = (p.b - m.b) / (2.0 * h);
            let fd2 = (p.db - m.db) / (2.0 * h);
            assert!((fd1 - v.db).abs() <= 1e-6 * v.db.abs().max(1e-12), "{d}");
            assert!((fd2 - v.d2b).abs() <= 1e-6 * v.d2b.abs().max(1e-9), "{d}");
            assert!(v.b > 0.0 && v.db < 0.0 && v.d2b > 0.0);
        }
        // Smooth hand-over at d̂ and a wall at 0.
        let at = barrier(dhat * (1.0 - 1e-9), dhat, kappa);
        assert!(at.b.abs() < 1e-20 && at.db.abs() < 1e-15 && at.d2b.abs() < 1e-6);
        assert_eq!(barrier_energy(0.0, dhat, kappa), Real::INFINITY);
        assert_eq!(barrier_energy(dhat, dhat, kappa), 0.0);
    }
}
