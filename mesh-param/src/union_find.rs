//! Disjoint sets over `u32` indices (union by smaller root, path halving),
//! shared by the seam and chart code. Amortized O(alpha(n)) per operation.

/// The root of `i`'s set, halving the path on the way.
pub(crate) fn find(parent: &mut [u32], mut i: u32) -> u32 {
    while parent[i as usize] != i {
        let p = parent[i as usize];
        parent[i as usize] = parent[p as usize];
        i = p;
    }
    i
}

/// Joins the sets of `a` and `b` under the smaller root; `true` when they
/// were apart.
pub(crate) fn union(parent: &mut [u32], a: u32, b: u32) -> bool {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        parent[ra.max(rb) as usize] = ra.min(rb);
    }
    ra != rb
}
