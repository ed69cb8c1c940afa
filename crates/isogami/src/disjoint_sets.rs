//! Disjoint sets (union–find) over `0..n`: which tiles a sheet's joints hold together, which
//! (tile, vertex) slots a graded sheet's cell edges make one node. Plain index arithmetic,
//! with path halving; the union keeps the smaller index as the root.

/// A partition of `0..n` into disjoint sets.
#[derive(Debug, Clone)]
pub(crate) struct DisjointSets {
    parent: Vec<usize>,
}

impl DisjointSets {
    /// `n` singletons.
    pub(crate) fn new(n: usize) -> Self {
        DisjointSets {
            parent: (0..n).collect(),
        }
    }

    /// The root of `i`'s set.
    pub(crate) fn find(&mut self, mut i: usize) -> usize {
        while self.parent[i] != i {
            self.parent[i] = self.parent[self.parent[i]];
            i = self.parent[i];
        }
        i
    }

    /// Joins the sets of `a` and `b`.
    pub(crate) fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.parent[ra.max(rb)] = ra.min(rb);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unions_join_sets_and_nothing_else() {
        let mut s = DisjointSets::new(6);
        s.union(4, 1);
        s.union(1, 5);
        s.union(2, 3);
        assert_eq!(s.find(5), s.find(4));
        assert_eq!(s.find(3), s.find(2));
        assert_ne!(s.find(0), s.find(1));
        assert_ne!(s.find(2), s.find(1));
        assert_eq!(s.find(4), 1, "the smaller index is the root");
    }
}
