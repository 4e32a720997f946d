//! Disjoint sets over `0..n` (union-find with path halving), the tool behind
//! components, welding and fan splitting. Each union makes the smaller root
//! the representative, so every set is named by its lowest element.

/// Disjoint sets over the integers `0..n`. `find` and `union` cost
/// O(alpha(n)) amortized (path halving; union by smaller index keeps the
/// lowest element as representative, as welding and component numbering
/// need).
#[derive(Debug, Clone, Default)]
pub struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    /// `n` singleton sets. `n` must fit in `u32` (mesh element counts do).
    pub fn new(n: usize) -> Self {
        Self { parent: (0..n as u32).collect() }
    }

    /// Makes this `n` singleton sets again, reusing the allocation.
    pub fn reset(&mut self, n: usize) {
        self.parent.clear();
        self.parent.extend(0..n as u32);
    }

    /// The representative (lowest element) of the set holding `i`.
    pub fn find(&mut self, mut i: u32) -> u32 {
        while self.parent[i as usize] != i {
            let p = self.parent[i as usize];
            self.parent[i as usize] = self.parent[p as usize];
            i = p;
        }
        i
    }

    /// Merges the sets of `a` and `b`; `true` when they were apart.
    pub fn union(&mut self, a: u32, b: u32) -> bool {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra == rb {
            return false;
        }
        self.parent[ra.max(rb) as usize] = ra.min(rb);
        true
    }

    /// Number of elements (not sets).
    pub fn len(&self) -> usize {
        self.parent.len()
    }

    /// `true` when there are no elements.
    pub fn is_empty(&self) -> bool {
        self.parent.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lowest_element_names_the_set() {
        let mut s = UnionFind::new(6);
        assert!(s.union(4, 2));
        assert!(s.union(5, 4));
        assert!(!s.union(2, 5));
        assert_eq!([s.find(5), s.find(4), s.find(2), s.find(3)], [2, 2, 2, 3]);
        assert_eq!(s.len(), 6);
    }
}
