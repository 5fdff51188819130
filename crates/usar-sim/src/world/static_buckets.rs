//! [`StaticBuckets`]: the walls and debris by the cells of a coarse uniform grid, so that the
//! contact gate's static test (`PhysicsScene::static_within`) looks only at the obstacles
//! near a robot instead of all of them.
//!
//! Not in the paper. A query yields every obstacle whose bounding box meets the query's
//! square (a superset of those within reach; an obstacle that spans several cells may come
//! more than once), and the callers' exact tests decide, so the answers are those of a scan
//! of every obstacle.

use parry2d::bounding_volume::Aabb;
use parry2d::math::Vector as Vec2;

/// Side of a bucket, metres (8): a robot's static reach is under a metre, so a query meets
/// one to four buckets, and a 1 km arena has about 16,000.
pub const STATIC_BUCKET_M: f32 = 8.0;

/// What a query adds to its half-side, metres (0.01): far above the rounding of a bucket's
/// coordinate, so that an obstacle whose box is within reach is never left out.
const QUERY_PAD_M: f32 = 0.01;

/// Most buckets along a side (4096): larger arenas get wider buckets.
const MAX_BUCKETS_PER_SIDE: usize = 4096;

/// Obstacle indices by bucket: `starts[c]..starts[c + 1]` are bucket `c`'s entries of
/// `items` (ascending obstacle index). Points and boxes outside the field fall into the
/// nearest border bucket (clamped, monotone), so a query outside the arena stays exact.
#[derive(Debug, Clone)]
pub struct StaticBuckets {
    cell_m: f32,
    nx: usize,
    ny: usize,
    starts: Vec<u32>,
    items: Vec<u32>,
}

impl StaticBuckets {
    /// The buckets of obstacles with bounding boxes `boxes` over `[0, width_m] x [0,
    /// height_m]` (metres; a non-finite or non-positive size gives one bucket).
    pub fn new(boxes: &[Aabb], width_m: f32, height_m: f32) -> Self {
        let finite = |v: f32| if v.is_finite() && v > 0.0 { v } else { 0.0 };
        let (w, h) = (finite(width_m), finite(height_m));
        let limit = MAX_BUCKETS_PER_SIDE as f32;
        let cell_m = STATIC_BUCKET_M.max(w / limit).max(h / limit);
        let side = |len: f32| ((len / cell_m).ceil() as usize).clamp(1, MAX_BUCKETS_PER_SIDE);
        let mut buckets = Self {
            cell_m,
            nx: side(w),
            ny: side(h),
            starts: Vec::new(),
            items: Vec::new(),
        };
        let mut lists = vec![Vec::new(); buckets.nx * buckets.ny];
        for (k, b) in boxes.iter().enumerate() {
            buckets.for_each_bucket(b.mins, b.maxs, |c| lists[c].push(k as u32));
        }
        buckets.starts.push(0);
        for list in &lists {
            buckets.items.extend_from_slice(list);
            buckets.starts.push(buckets.items.len() as u32);
        }
        buckets
    }

    /// Bucket coordinate of `v` along an axis of `n` buckets, clamped (NaN to 0).
    fn coord(&self, v: f32, n: usize) -> usize {
        let c = v / self.cell_m;
        if c >= n as f32 {
            n - 1
        } else if c >= 0.0 {
            c as usize
        } else {
            0
        }
    }

    /// Calls `f(bucket)` for every bucket the rectangle `[lo, hi]` meets.
    fn for_each_bucket(&self, lo: Vec2, hi: Vec2, mut f: impl FnMut(usize)) {
        let (x0, x1) = (self.coord(lo.x, self.nx), self.coord(hi.x, self.nx));
        let (y0, y1) = (self.coord(lo.y, self.ny), self.coord(hi.y, self.ny));
        for cy in y0..=y1 {
            for cx in x0..=x1 {
                f(cy * self.nx + cx);
            }
        }
    }

    /// The obstacles whose bounding boxes meet the bucket of point `p` (clamped into the
    /// field), in ascending index, each once: every obstacle whose box holds `p` is among them.
    pub fn at(&self, p: Vec2) -> impl Iterator<Item = usize> + '_ {
        let c = self.coord(p.y, self.ny) * self.nx + self.coord(p.x, self.nx);
        let (a, b) = (self.starts[c] as usize, self.starts[c + 1] as usize);
        self.items[a..b].iter().map(|&k| k as usize)
    }

    /// Whether `test(k)` holds for some obstacle `k` whose bounding box may lie within
    /// `reach_m` of `p` (every obstacle whose box meets the square of half-side `reach_m`
    /// around `p`, and perhaps others near it; some more than once). Stops at the first.
    pub fn any_near(&self, p: Vec2, reach_m: f32, mut test: impl FnMut(usize) -> bool) -> bool {
        let r = Vec2::splat(reach_m.max(0.0) + QUERY_PAD_M);
        let mut found = false;
        self.for_each_bucket(p - r, p + r, |c| {
            if !found {
                let (a, b) = (self.starts[c] as usize, self.starts[c + 1] as usize);
                found = self.items[a..b].iter().any(|&k| test(k as usize));
            }
        });
        found
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    fn square(x: f32, y: f32, half: f32) -> Aabb {
        Aabb::new(Vec2::new(x - half, y - half), Vec2::new(x + half, y + half))
    }

    proptest! {
        /// A query finds every box within reach of the point (by the box's distance), as a
        /// scan of all boxes does, anywhere in the field and outside it.
        #[test]
        fn finds_every_box_within_reach(
            boxes in prop::collection::vec((-20.0f32..220.0, -20.0f32..120.0, 0.0f32..30.0), 0..40),
            px in -30.0f32..230.0,
            py in -30.0f32..130.0,
            reach in 0.0f32..12.0,
        ) {
            let boxes: Vec<Aabb> = boxes.iter().map(|&(x, y, h)| square(x, y, h)).collect();
            let buckets = StaticBuckets::new(&boxes, 200.0, 100.0);
            let p = Vec2::new(px, py);
            let within = |b: &Aabb| {
                let dx = (b.mins.x - p.x).max(p.x - b.maxs.x).max(0.0);
                let dy = (b.mins.y - p.y).max(p.y - b.maxs.y).max(0.0);
                dx * dx + dy * dy <= reach * reach
            };
            for (k, b) in boxes.iter().enumerate() {
                if within(b) {
                    prop_assert!(buckets.any_near(p, reach, |j| j == k), "box {k} missed");
                }
            }
            let scan = boxes.iter().any(within);
            prop_assert_eq!(buckets.any_near(p, reach, |j| within(&boxes[j])), scan);
        }
    }

    /// A degenerate field is one bucket holding every box.
    #[test]
    fn a_degenerate_field_is_one_bucket() {
        let boxes = [square(5.0, 5.0, 1.0), square(-50.0, 900.0, 1.0)];
        let buckets = StaticBuckets::new(&boxes, f32::NAN, 0.0);
        assert_eq!((buckets.nx, buckets.ny), (1, 1));
        assert!(buckets.any_near(Vec2::new(1e6, -1e6), 0.0, |k| k == 1));
    }
}
