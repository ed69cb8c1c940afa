//! Specs written before issue 21 (isogami's edge labels then depended on the exact shape; see
//! `cell::legacy_edges`), translated to the current labels.

use super::design::{Design, JointChoice};
use super::error::DesignError;
use super::spec::parse_exact;
use crate::cell::legacy_edges;

impl Design {
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
}
