//! Comparing two split scores with a tie tolerance: the earlier candidate wins a tie.
//!
//! Shared by the exact enumeration ([`HierarchicalRne`](crate::grouping::HierarchicalRne)
//! and the two-way bisection) and by the heuristic split's swap search, so that every search
//! breaks ties the same way.

/// Relative tolerance under which two scores count as tied (the earlier candidate wins).
pub(crate) const TIE_TOLERANCE: f64 = 1e-12;

/// `true` if `candidate` beats `best` by more than the tie tolerance.
pub(crate) fn beats(candidate: f64, best: f64) -> bool {
    candidate > best + TIE_TOLERANCE * best.abs().max(1.0)
}
