//! Union-find over robot ids whose components are the collision lists.
//!
//! The smaller id is the root, and each component's members are linked in a cycle so they can
//! be listed without a scan of all robots.

/// The root of `i`'s component (path halving).
pub(super) fn find(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// Unites the components of `a` and `b`; `next` links each component's members in a cycle
/// (spliced here), so a component's members can be listed without a scan of all robots.
pub(super) fn union(
    parent: &mut [usize],
    size: &mut [usize],
    next: &mut [usize],
    a: usize,
    b: usize,
) -> bool {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra == rb {
        return false;
    }
    // Deterministic: the smaller id becomes the root.
    let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
    parent[hi] = lo;
    size[lo] += size[hi];
    next.swap(lo, hi);
    true
}
