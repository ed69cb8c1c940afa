//! A family at concrete shape parameters, validated.

use super::error::{Culprit, ShapeProblem, TilingError};
use super::family::Family;
use crate::geometry::{is_simple_problem, signed_area};
use crate::math::{cross, vec2, Mat2, Real, Vec2};

/// Relative tolerance (times the prototile's diameter) below which an edge is degenerate or
/// two edges touch.
const SHAPE_REL_TOL: Real = 1e-6;

/// A 2D affine map x ↦ m·x + t.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Affine {
    /// Linear part.
    pub m: Mat2,
    /// Translation.
    pub t: Vec2,
}

impl Affine {
    /// Applies the map to a point.
    pub fn apply(&self, p: &Vec2) -> Vec2 {
        self.m * p + self.t
    }

    /// True when the map reverses orientation (a reflection).
    pub fn reflects(&self) -> bool {
        self.m.determinant() < 0.0
    }

    fn from_glam(m: &glam::DMat3) -> Affine {
        Affine {
            m: Mat2::new(m.x_axis.x, m.y_axis.x, m.x_axis.y, m.y_axis.y),
            t: vec2(m.z_axis.x, m.z_axis.y),
        }
    }
}

/// An isohedral tiling at concrete, validated shape parameters.
#[derive(Debug, Clone)]
pub struct Tiling {
    family: Family,
    params: Vec<Real>,
    prototile: Vec<Vec2>,
    aspects: Vec<Affine>,
    t1: Vec2,
    t2: Vec2,
}

/// The raw geometry for some parameters, before validation.
fn raw(family: Family, params: &[Real]) -> (Vec<Vec2>, Vec<Affine>, Vec2, Vec2) {
    let mut t = family.tactile();
    let mut p = [0.0; 6];
    t.parameters(&mut p);
    p[..params.len()].copy_from_slice(params);
    t.set_parameters(&p);
    let proto = t.vertices().iter().map(|v| vec2(v.x, v.y)).collect();
    let aspects = (0..t.num_aspects())
        .map(|i| Affine::from_glam(t.aspect_transform(i)))
        .collect();
    (
        proto,
        aspects,
        vec2(t.t1().x, t.t1().y),
        vec2(t.t2().x, t.t2().y),
    )
}

/// What is wrong with the tile at these parameters, if anything.
fn shape_problem(family: Family, params: &[Real], default_sign: Real) -> Option<ShapeProblem> {
    let (proto, aspects, t1, t2) = raw(family, params);
    let diameter = proto
        .iter()
        .flat_map(|a| proto.iter().map(move |b| (a - b).norm()))
        .fold(0.0, Real::max);
    if !diameter.is_finite() || diameter == 0.0 {
        return Some(ShapeProblem::Degenerate);
    }
    if let Some(p) = is_simple_problem(&proto, SHAPE_REL_TOL * diameter) {
        return Some(ShapeProblem::NotSimple(p));
    }
    let area = signed_area(&proto);
    if area.signum() != default_sign {
        return Some(ShapeProblem::Inverted);
    }
    let lattice = cross(&t1, &t2).abs();
    let covered = area.abs() * aspects.len() as Real;
    if (covered - lattice).abs() > 1e-9 * lattice.max(covered) {
        return Some(ShapeProblem::Overlap { covered, lattice });
    }
    None
}

impl Tiling {
    /// The family at its default parameters.
    pub fn default_for(family: Family) -> Tiling {
        Tiling::new(family, &family.default_params()).expect("default parameters are valid")
    }

    /// The family at `params`, refusing parameters that give a non-simple, degenerate,
    /// inverted or overlapping tile; the error names the responsible parameter(s).
    pub fn new(family: Family, params: &[Real]) -> Result<Tiling, TilingError> {
        let expected = family.param_count();
        if params.len() != expected {
            return Err(TilingError::ParamCount {
                family,
                expected,
                got: params.len(),
            });
        }
        if let Some((index, &value)) = params.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(TilingError::ParamNotFinite { index, value });
        }
        let defaults = family.default_params();
        let (dproto, ..) = raw(family, &defaults);
        let default_sign = signed_area(&dproto).signum();
        if let Some(problem) = shape_problem(family, params, default_sign) {
            return Err(TilingError::InvalidShape {
                family,
                params: params.to_vec(),
                culprit: culprit(family, params, &defaults, default_sign),
                problem,
            });
        }
        let (prototile, aspects, t1, t2) = raw(family, params);
        Ok(Tiling {
            family,
            params: params.to_vec(),
            prototile,
            aspects,
            t1,
            t2,
        })
    }

    /// The family.
    pub fn family(&self) -> Family {
        self.family
    }

    /// The shape parameters.
    pub fn params(&self) -> &[Real] {
        &self.params
    }

    /// Prototile vertices in the family's order (orientation as the tables give it).
    pub fn prototile(&self) -> &[Vec2] {
        &self.prototile
    }

    /// Aspect transforms of the minimal translational cell.
    pub fn aspects(&self) -> &[Affine] {
        &self.aspects
    }

    /// First translation vector.
    pub fn t1(&self) -> Vec2 {
        self.t1
    }

    /// Second translation vector.
    pub fn t2(&self) -> Vec2 {
        self.t2
    }
}

/// Parameters joined by commas, each in Rust's shortest round-trip form.
pub(crate) fn format_params(params: &[Real]) -> String {
    params
        .iter()
        .map(|p| format!("{p}"))
        .collect::<Vec<_>>()
        .join(",")
}

/// Names the parameter(s) whose change from the default alone breaks the tile; when none
/// does alone, names all changed parameters "together".
fn culprit(family: Family, params: &[Real], defaults: &[Real], sign: Real) -> Culprit {
    let changed: Vec<usize> = (0..params.len())
        .filter(|&i| params[i] != defaults[i])
        .collect();
    let alone: Vec<usize> = changed
        .iter()
        .copied()
        .filter(|&i| {
            let mut p = defaults.to_vec();
            p[i] = params[i];
            shape_problem(family, &p, sign).is_some()
        })
        .collect();
    let pairs = |ix: &[usize]| ix.iter().map(|&i| (i, params[i])).collect();
    match (alone.len(), changed.len()) {
        (0, 0) => Culprit::Defaults,
        (0, _) => Culprit::Together(pairs(&changed)),
        _ => Culprit::Alone(pairs(&alone)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_default_is_valid() {
        for f in Family::all() {
            let t = Tiling::new(f, &f.default_params());
            assert!(t.is_ok(), "{f}: {:?}", t.err());
        }
    }

    #[test]
    fn bad_parameters_are_named() {
        let f: Family = "IH28".parse().unwrap();
        let mut p = f.default_params();
        let e = Tiling::new(f, &p[..p.len() - 1]).unwrap_err();
        assert!(
            matches!(e, TilingError::ParamCount { expected, got, .. } if got + 1 == expected),
            "{e}"
        );
        p[0] = Real::NAN;
        let e = Tiling::new(f, &p).unwrap_err();
        assert!(
            matches!(e, TilingError::ParamNotFinite { index: 0, value } if value.is_nan()),
            "{e}"
        );
    }
}
