//! Candidate tile pairs: the 3×3 block of cells, plus tiles farther out that touch a tile of
//! the centre cell; each physical pair once.

/// Tile `a` of the centre cell against tile `b` of the cell at `offset` = (k_u, k_w).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct CandidatePair {
    /// Tile of the centre cell.
    pub a: usize,
    /// Tile of the neighbouring (or centre) cell.
    pub b: usize,
    /// Cell offset of tile `b`'s copy: in {−1, 0, 1}² for the 3×3 block, up to
    /// [`SEARCH_RING`] for the extra touching pairs.
    pub offset: [i32; 2],
}

/// How many rings of cells around the centre are searched for touching tiles.
pub const SEARCH_RING: i32 = 3;

/// The pairs (a, 0)–(b, o) with o ∈ {−1,0,1}², plus those with o farther out (up to
/// [`SEARCH_RING`]) for which `touches(a, b, o)`; never a tile against itself; each physical
/// pair once: (a, 0)–(b, o) is the translate of (b, 0)–(a, −o), so only the triple with
/// a < b, or a == b and o lexicographically positive, is kept.
pub(crate) fn candidate_pairs(
    tiles: usize,
    mut touches: impl FnMut(usize, usize, [i32; 2]) -> bool,
) -> Vec<CandidatePair> {
    let mut out = Vec::new();
    for a in 0..tiles {
        for b in a..tiles {
            for ku in -SEARCH_RING..=SEARCH_RING {
                for kw in -SEARCH_RING..=SEARCH_RING {
                    if a == b && (ku, kw) <= (0, 0) {
                        continue;
                    }
                    let block = ku.abs() <= 1 && kw.abs() <= 1;
                    if block || touches(a, b, [ku, kw]) {
                        out.push(CandidatePair {
                            a,
                            b,
                            offset: [ku, kw],
                        });
                    }
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    #[test]
    fn every_physical_pair_of_the_block_once() {
        for n in 1..5 {
            let pairs = candidate_pairs(n, |_, _, _| false);
            // Ordered combinations 9n², minus n self-pairs, halved.
            assert_eq!(pairs.len(), (9 * n * n - n) / 2);
            let set: HashSet<_> = pairs.iter().map(|p| (p.a, p.b, p.offset)).collect();
            assert_eq!(set.len(), pairs.len());
            for p in &pairs {
                assert!(!(p.a == p.b && p.offset == [0, 0]));
                assert!(p.offset.iter().all(|k| k.abs() <= 1));
                let mirror = (p.b, p.a, [-p.offset[0], -p.offset[1]]);
                assert!(!set.contains(&mirror), "{p:?} and its mirror both kept");
            }
        }
    }

    #[test]
    fn touching_pairs_beyond_the_block_are_added_once() {
        // Tile 0 touches tile 1 two cells along u (and so tile 1 touches tile 0 at −2u).
        let touches = |a: usize, b: usize, o: [i32; 2]| {
            (a, b, o) == (0, 1, [2, 0]) || (a, b, o) == (1, 0, [-2, 0])
        };
        let pairs = candidate_pairs(2, touches);
        assert_eq!(pairs.len(), (9 * 4 - 2) / 2 + 1);
        assert!(pairs.contains(&CandidatePair {
            a: 0,
            b: 1,
            offset: [2, 0]
        }));
    }
}
