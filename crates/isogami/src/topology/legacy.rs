//! Specs written before issue 21 (isogami's edge labels then depended on the exact shape; see
//! `cell::legacy_edges`), translated to the current labels.

use super::design::{Design, JointChoice};
use super::error::DesignError;
use super::spec::parse_exact;
use crate::cell::legacy_edges;
use serde::Serialize;

/// Which edge labels a spec's joint string is in. A spec carries no mark of it: the same text
/// can name two different mechanisms, so the reader must say which labels it was written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpecLabels {
    /// Today's labels (the same at every shape of the family): every spec isogami writes
    /// since issue 21, and every spec in a database of schema version 3 or later.
    Current,
    /// The labels of isogami before issue 21, which depended on the exact shape.
    BeforeRelabelling,
}

/// A spec read in the labels it was written in, as a design in today's labels.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MigratedSpec {
    /// The design in today's labels, its parameters canonical.
    #[serde(serialize_with = "as_spec")]
    pub design: Design,
    /// The design the same text names when read in the other labels, when that is another
    /// design: the text is ambiguous, and only its writer knows which one it meant.
    #[serde(
        serialize_with = "as_opt_spec",
        skip_serializing_if = "Option::is_none"
    )]
    pub other_reading: Option<Design>,
}

fn as_spec<S: serde::Serializer>(d: &Design, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&d.to_string())
}

fn as_opt_spec<S: serde::Serializer>(d: &Option<Design>, s: S) -> Result<S::Ok, S::Error> {
    match d {
        Some(d) => s.serialize_str(&d.to_string()),
        None => s.serialize_none(),
    }
}

impl Design {
    /// Reads `text` (a name, JSON or a spec) in the edge labels `labels` and returns the design
    /// in today's labels, with the other labels' reading when it differs. Reading a current
    /// spec as [`SpecLabels::Current`] gives it back unchanged (canonical numbers), so carrying
    /// specs over is idempotent: a spec translated once is current.
    pub fn migrate_spec(text: &str, labels: SpecLabels) -> Result<MigratedSpec, DesignError> {
        let current = || -> Result<Design, DesignError> {
            let d = Design::resolve(text)?;
            Ok(Design::new(d.family, &d.params, d.dims, d.joints))
        };
        let (design, other) = match labels {
            SpecLabels::Current => (current()?, Design::from_legacy_spec(text).ok()),
            SpecLabels::BeforeRelabelling => (Design::from_legacy_spec(text)?, current().ok()),
        };
        Ok(MigratedSpec {
            other_reading: other.filter(|o| o != &design),
            design,
        })
    }

    /// Reads a spec written by isogami before issue 21 and returns the design with the same
    /// physical joints in the current labels, its parameters canonical. The old labels are
    /// rebuilt at the spec's exact parameters (before rounding), as the old code built them.
    pub fn from_legacy_spec(text: &str) -> Result<Design, DesignError> {
        let old = parse_exact(text)?;
        let map = legacy_edges(&old.tiling()?, old.dims)?;
        if old.joints.len() != map.len() {
            return Err(DesignError::JointCount {
                given: old.joints.len(),
                family: old.family,
                dims: old.dims,
                edges: map.len(),
            });
        }
        let mut joints = vec![JointChoice::None; map.len()];
        for (choice, e) in old.joints.iter().zip(&map) {
            joints[e.edge] = match (*choice, e.swapped) {
                (JointChoice::A, true) => JointChoice::B,
                (JointChoice::B, true) => JointChoice::A,
                (c, _) => c,
            };
        }
        Ok(Design::new(old.family, &old.params, old.dims, joints))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specs_away_from_jumps_translate_to_themselves_with_canonical_numbers() {
        for (old, new) in [
            ("rotating-squares", None),
            (
                "IH23:0.155769230769,0.35,0.22533575274100004,0.35:1x1:aa-a-",
                Some("IH23:0.155769230769,0.35,0.225335752741,0.35:1x1:aa-a-"),
            ),
            (
                "IH28:0.6,0.35:1x1:a--a-b-bbb",
                Some("IH28:0.6,0.35:1x1:a--a-b-bbb"),
            ),
        ] {
            let Some(new) = new else { continue };
            assert_eq!(Design::from_legacy_spec(old).unwrap().to_string(), new);
        }
    }

    #[test]
    fn the_ih9_spec_above_the_old_jump_names_its_old_joints() {
        // At p1 = 0.500000001 the old builder placed tile 1 one lattice step away, so old
        // edge 1 joined tile 0 to tile 1; below it, the same string meant tile 0 to tile 3.
        let below = "IH9:0.12239750492,0.499999999,0.225335752741:2x1:---abb--a-bb";
        let above = "IH9:0.12239750492,0.500000001,0.225335752741:2x1:---abb--a-bb";
        assert_eq!(
            Design::from_legacy_spec(below).unwrap().to_string(),
            below,
            "below the jump the old labels are the current ones"
        );
        let moved = Design::from_legacy_spec(above).unwrap();
        assert_ne!(moved.to_string(), above, "above it they are not");
        assert_eq!(moved.joint_count(), 6);
        moved.cell().unwrap();
    }

    /// The current spec: read as current it stays itself (and names its legacy
    /// reading); only --legacy turns it into that other design.
    #[test]
    fn a_current_spec_passes_through_and_its_legacy_reading_is_named() {
        let spec = "IH2:0.04739750492,0.35,0.150335752741,0.150335752741:2x1:---a-b--abaa";
        let m = Design::migrate_spec(spec, SpecLabels::Current).unwrap();
        assert_eq!(m.design.to_string(), spec);
        let other = m.other_reading.expect("ambiguous");
        assert_eq!(other, Design::from_legacy_spec(spec).unwrap());
        assert_ne!(other.to_string(), spec);
        let old = Design::migrate_spec(spec, SpecLabels::BeforeRelabelling).unwrap();
        assert_eq!(old.design, other);
        assert_eq!(old.other_reading.unwrap().to_string(), spec);
    }

    /// Over random joint strings on every family's 1×1 and 2×1 cells at every shape of the
    /// exploration's grid (seeded): reading as current is the identity on current specs, so migrating twice
    /// equals once, whatever the legacy reading would have been.
    #[test]
    fn migrating_current_specs_changes_none_and_is_idempotent() {
        use crate::cell::CellDims;
        use crate::test_rng::TestRng;
        use crate::tiling::Family;
        let mut rng = TestRng::new(21);
        let choices = [JointChoice::None, JointChoice::A, JointChoice::B];
        let mut ambiguous = 0;
        for family in Family::all() {
            let shapes = crate::tiling::shape_grid(family, 3, 0.3, 12);
            for (dims, params) in [CellDims::new(1, 1).unwrap(), CellDims::new(2, 1).unwrap()]
                .into_iter()
                .flat_map(|d| shapes.iter().map(move |p| (d, p.clone())))
            {
                let Ok(tiling) = crate::tiling::Tiling::new(family, &params) else {
                    continue;
                };
                let Ok(cell) = crate::cell::UnitCell::new(&tiling, dims) else {
                    continue;
                };
                let joints = (0..cell.edges.len())
                    .map(|_| choices[(rng.next_u64() % 3) as usize])
                    .collect();
                let spec = Design::new(family, &params, dims, joints).to_string();
                let once = Design::migrate_spec(&spec, SpecLabels::Current).unwrap();
                assert_eq!(
                    once.design.to_string(),
                    spec,
                    "a current spec passes through"
                );
                let twice =
                    Design::migrate_spec(&once.design.to_string(), SpecLabels::Current).unwrap();
                assert_eq!(twice.design, once.design);
                ambiguous += usize::from(once.other_reading.is_some());
            }
        }
        assert!(
            ambiguous > 0,
            "some texts read differently in the old labels"
        );
    }
}
