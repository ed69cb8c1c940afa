//! Distinct motions across cells and families (issue 13, item 5): the exploration keeps one
//! design per motion within a cell, but the same mechanism appears again in other cells of a
//! family (a×b and its b×a twin) and in other families whose default shapes give congruent
//! sheets. This groups topologies whose first-order motions match.
//!
//! A topology's motion key is [`motion_invariant`] of its closed state's motion at its own
//! (default) shape: independent of the fixed tile, tile and edge order, sign and scale of the
//! motion and isometries of the sheet, so it is comparable between any two topologies with
//! the same number of unique edges. Topologies with different edge counts are never matched:
//! a bigger cell that only repeats a smaller cell's motion is already dropped within its family
//! (`dedup::repeats`), and two different cells' edge multisets can agree only by such a
//! repeat. Designs sampled at other shapes belong to their topology's class: the class is the
//! motion the topology was found with.
//!
//! Classes are formed greedily in the order the topologies are given (callers sort them by
//! spec, so the result does not depend on which unit or shard found what): each topology
//! joins the first earlier representative it matches to [`MOTION_TOL`], else it represents a
//! new class. Plain data in and out; the analyses run in parallel on the current rayon pool.

use super::dedup::{motion_invariant, MotionIndex, MotionInvariant, MOTION_TOL};
use crate::kinematics::Mechanism;
use crate::mobility::{analyze, MobilitySettings};
use crate::topology::Design;
use rayon::prelude::*;

/// The motion key of `topology` (see the module docs), or None when it does not have exactly
/// one degree of freedom at its shape or cannot be built.
pub fn topology_motion(topology: &Design, settings: MobilitySettings) -> Option<MotionInvariant> {
    let cell = topology.cell().ok()?;
    let mech = Mechanism::new(&cell, &topology.joints).ok()?;
    let mob = analyze(&mech, &mech.rest, settings).ok()?;
    if mob.dof != 1 {
        return None;
    }
    let v = &mob.motion.as_ref()?.vector;
    let key = motion_invariant(&cell, &mech, v);
    key.values.iter().all(|x| x.is_finite()).then_some(key)
}

/// For each topology, the index of its class's representative (the first topology of the
/// class in the order given; a representative points at itself), or None when it has no
/// motion key.
pub fn motion_classes(topologies: &[Design], settings: MobilitySettings) -> Vec<Option<usize>> {
    let keys: Vec<Option<MotionInvariant>> = topologies
        .par_iter()
        .map(|t| topology_motion(t, settings))
        .collect();
    group(&keys)
}

/// Greedy grouping of keys in order (see the module docs).
pub fn group(keys: &[Option<MotionInvariant>]) -> Vec<Option<usize>> {
    let mut index = MotionIndex::new();
    let mut owners: Vec<usize> = Vec::new();
    keys.iter()
        .enumerate()
        .map(|(i, key)| {
            let key = key.as_ref()?;
            Some(match index.find(key, MOTION_TOL) {
                Some(id) => owners[id],
                None => {
                    index.insert(key.clone());
                    owners.push(i);
                    i
                }
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(values: &[f64]) -> Option<MotionInvariant> {
        Some(MotionInvariant {
            values: values.to_vec(),
        })
    }

    #[test]
    fn keys_group_to_their_first_match_and_lengths_never_mix() {
        let keys = vec![
            key(&[0.1, 0.2, 0.3]),
            key(&[0.5, 0.5, 0.5]),
            None,
            key(&[0.1, 0.2, 0.3 + 1e-9]),
            key(&[0.1, 0.2, 0.3, 0.0]),
            key(&[0.1, 0.2, 0.3 + 1e-3]),
        ];
        assert_eq!(
            group(&keys),
            vec![Some(0), Some(1), None, Some(0), Some(4), Some(5)]
        );
    }
}
