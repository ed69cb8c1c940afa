//! The largest piece of a patch that its joints hold together. A rectangle of cells can hold
//! border tiles whose joints all lead out of the patch; cut (or printed) free they would fall
//! out of the sheet, so fabrication formats leave them off and say so in their metadata.

use crate::disjoint_sets::DisjointSets;

/// Ids of the tiles of the largest connected piece of the graph of `n` tiles joined by
/// `joints` (the piece holding the lowest tile id on a tie), ascending; empty when `n` is
/// zero. Joints must name tiles below `n`.
pub(crate) fn largest_piece(n: usize, joints: impl IntoIterator<Item = [usize; 2]>) -> Vec<usize> {
    let mut sets = DisjointSets::new(n);
    for [a, b] in joints {
        sets.union(a, b);
    }
    let root: Vec<usize> = (0..n).map(|i| sets.find(i)).collect();
    let mut size = vec![0usize; n];
    for &r in &root {
        size[r] += 1;
    }
    let Some(best) = (0..n).max_by(|&a, &b| size[root[a]].cmp(&size[root[b]]).then(b.cmp(&a)))
    else {
        return Vec::new();
    };
    (0..n).filter(|&t| root[t] == root[best]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_largest_piece_wins_and_ties_go_to_the_lowest_id() {
        assert_eq!(largest_piece(5, [[1, 2], [2, 4]]), vec![1, 2, 4]);
        assert_eq!(largest_piece(4, [[2, 3], [0, 1]]), vec![0, 1]);
        assert_eq!(largest_piece(3, []), vec![0]);
        assert!(largest_piece(0, []).is_empty());
    }
}
