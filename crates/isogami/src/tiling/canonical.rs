//! The one canonical form of shape parameters, so that equal shapes have equal specs.
//!
//! A parameter is rounded to [`CANONICAL_DIGITS`] significant decimal digits and kept as the
//! nearest double to that decimal; printed with Rust's shortest round-trip formatting it reads
//! back bit for bit and has at most 12 significant digits (`0.22533575274100004` and
//! `0.225335752741` are one shape, written `0.225335752741`). The library applies it wherever a
//! design is made — parsing a spec or JSON, the shape grid, following a shape constraint,
//! inverse refinement — so a shape reached by arithmetic and the same shape typed by a user
//! name one design. Twelve digits keep every shape the exploration and the refinements
//! distinguish (their steps are ≥ 1e-9 of a parameter's scale) and drop float noise (≤ 1e-15).

use crate::math::Real;

/// Significant decimal digits of a canonical shape parameter.
pub const CANONICAL_DIGITS: usize = 12;

/// `x` rounded to [`CANONICAL_DIGITS`] significant digits (−0 and 0 are 0; non-finite values
/// are returned unchanged, for the caller's validation to name). Idempotent.
pub fn canonical_param(x: Real) -> Real {
    if !x.is_finite() {
        return x;
    }
    if x == 0.0 {
        return 0.0;
    }
    let text = format!("{:.*e}", CANONICAL_DIGITS - 1, x);
    text.parse().unwrap_or(x)
}

/// Every parameter in its canonical form.
pub fn canonical_params(params: &[Real]) -> Vec<Real> {
    params.iter().map(|&p| canonical_param(p)).collect()
}

/// True when every parameter is already canonical.
pub fn is_canonical(params: &[Real]) -> bool {
    params
        .iter()
        .all(|&p| canonical_param(p).to_bits() == p.to_bits())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn float_noise_is_dropped_and_twelve_digits_kept() {
        assert_eq!(canonical_param(0.22533575274100004), 0.225335752741);
        assert_eq!(canonical_param(0.15033575274102148), 0.150335752741);
        assert_eq!(canonical_param(-0.0), 0.0);
        assert!(canonical_param(-0.0).is_sign_positive());
        assert_eq!(canonical_param(1.0 / 3.0).to_string(), "0.333333333333");
        assert_eq!(canonical_param(1e-9 + 0.5), 0.500000001);
        assert!(canonical_param(Real::NAN).is_nan());
    }

    #[test]
    fn canonical_values_print_with_at_most_twelve_digits_and_read_back() {
        let mut x: Real = 0.123_456_789_012_345_67;
        for _ in 0..2000 {
            x = (x * 7.31 + 0.173).fract() * if x > 0.5 { -3.7 } else { 1.9 };
            let c = canonical_param(x);
            assert_eq!(
                canonical_param(c).to_bits(),
                c.to_bits(),
                "idempotent at {x}"
            );
            let text = c.to_string();
            let digits = text.chars().filter(|ch| ch.is_ascii_digit()).count();
            let leading = text
                .trim_start_matches('-')
                .chars()
                .take_while(|&ch| ch == '0' || ch == '.')
                .filter(|&ch| ch == '0')
                .count();
            assert!(digits - leading <= CANONICAL_DIGITS, "{x} -> {text}");
            assert_eq!(text.parse::<Real>().unwrap().to_bits(), c.to_bits());
            assert!((c - x).abs() <= 5e-12 * x.abs());
        }
    }
}
