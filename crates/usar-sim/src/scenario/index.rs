//! A spatial index of axis-aligned boxes (parry2d-f64's [`Bvh`]) for validation's proximity
//! rules: "is anything within `margin` of this shape or point?" visits only the boxes near it,
//! so debris generation and the start and rescuee checks cost about O(n log n) rather than
//! O(n^2) (issue 11, class 3: 2,000 generated slabs took 18 s with pairwise tests).
//!
//! The index only prunes: a box that does not come within `margin` of the query box holds a
//! shape farther than `margin` from the query (a shape lies inside its box), so callers run the
//! same exact distance test on the candidates as they ran on every shape before, and make the
//! same decisions.

use parry2d_f64::bounding_volume::Aabb;
use parry2d_f64::math::Vector;
use parry2d_f64::partitioning::Bvh;

use super::model::PointM;

/// Boxes numbered in insertion order (0, 1, ...), queried by closed-box overlap.
pub(crate) struct BoxIndex {
    bvh: Bvh,
    len: u32,
}

impl BoxIndex {
    /// An empty index.
    pub(crate) fn new() -> Self {
        Self {
            bvh: Bvh::new(),
            len: 0,
        }
    }

    /// Adds the box `[lo, hi]` (world frame, metres) as number `self.len()`.
    pub(crate) fn push(&mut self, lo: &PointM, hi: &PointM) {
        self.bvh.insert(
            Aabb::new(Vector::new(lo.x, lo.y), Vector::new(hi.x, hi.y)),
            self.len,
        );
        self.len += 1;
    }

    /// Numbers of the boxes that meet `[lo - margin, hi + margin]` (boundary included), in
    /// ascending order (so the first rule-breaker found is the first in list order).
    pub(crate) fn near(&self, lo: &PointM, hi: &PointM, margin: f64) -> Vec<usize> {
        if self.len == 0 {
            return Vec::new();
        }
        let query = Aabb::new(
            Vector::new(lo.x - margin, lo.y - margin),
            Vector::new(hi.x + margin, hi.y + margin),
        );
        let mut out: Vec<usize> = self
            .bvh
            .intersect_aabb(&query)
            .map(|i| i as usize)
            .collect();
        out.sort_unstable();
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_exactly_the_boxes_within_the_margin_in_order() {
        let mut index = BoxIndex::new();
        assert!(
            index
                .near(&PointM::new(0.0, 0.0), &PointM::new(1.0, 1.0), 5.0)
                .is_empty()
        );
        for i in 0..100 {
            let x = f64::from(i) * 3.0;
            index.push(&PointM::new(x, 0.0), &PointM::new(x + 1.0, 1.0));
        }
        // Box 10 spans x in [30, 31]; a margin of 1.9 around [33.5, 34] reaches [31.6, 35.9]:
        // box 11 ([33, 34]) only; a margin of 2.5 touches box 10's edge (31) and box 12
        // ([36, 37]).
        let (lo, hi) = (PointM::new(33.5, 0.5), PointM::new(34.0, 0.5));
        assert_eq!(index.near(&lo, &hi, 1.9), vec![11]);
        assert_eq!(index.near(&lo, &hi, 2.5), vec![10, 11, 12]);
        assert!(index.near(&lo, &hi, 0.0) == vec![11]);
    }
}
