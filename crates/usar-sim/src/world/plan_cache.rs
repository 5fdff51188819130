//! The planner's plan cache: smoothed plans (cell indices, start to goal) and failures by
//! (inflation, start cell, goal cell, goal kind), bounded in entries and in bytes.
//!
//! The grid never changes, so a cached answer is exactly what planning again would give: the
//! cache only saves time, and clearing it changes no path. When a new entry would take the
//! cache past [`PLAN_CACHE_CAPACITY`] entries or [`PLAN_CACHE_BYTES`] bytes, the cache is
//! cleared first (no eviction order to keep deterministic); a single plan larger than the byte
//! bound is not cached. A smoothed plan keeps the path's corners, a few dozen cells in the
//! shipped scenarios, but a path winding through thousands of debris pieces keeps thousands,
//! and nothing bounds them below the grid's cells: bounded by entries alone, 4,096 plans of
//! 10,000 corners would hold 160 MB.

use std::collections::HashMap;

use super::error::NavError;

/// Most entries the plan cache holds before it is cleared.
const PLAN_CACHE_CAPACITY: usize = 4096;

/// Most bytes the plan cache's entries hold (the entries' fixed size plus 4 bytes per cell of
/// their plans) before it is cleared: 64 MiB.
const PLAN_CACHE_BYTES: usize = 64 << 20;

/// Cache key: inflation (f32 bits), start cell, goal cell, whether the goal is shared.
pub(super) type PlanKey = (u32, u32, u32, bool);

/// A cached answer: the smoothed plan's cells, or why there is none.
pub(super) type Planned = Result<Vec<u32>, NavError>;

/// Plans by key within an entry and a byte bound (see the module docs).
#[derive(Debug, Clone)]
pub(super) struct PlanCache {
    plans: HashMap<PlanKey, Planned>,
    /// Bytes the entries hold ([`entry_bytes`] summed).
    bytes: usize,
    max_entries: usize,
    max_bytes: usize,
}

impl Default for PlanCache {
    fn default() -> Self {
        Self::new(PLAN_CACHE_CAPACITY, PLAN_CACHE_BYTES)
    }
}

/// Bytes an entry holds: its fixed size and its plan's cells.
fn entry_bytes(planned: &Planned) -> usize {
    let cells = planned.as_ref().map_or(0, Vec::capacity);
    size_of::<(PlanKey, Planned)>() + cells * size_of::<u32>()
}

impl PlanCache {
    /// An empty cache of at most `max_entries` entries holding at most `max_bytes` bytes.
    pub(super) fn new(max_entries: usize, max_bytes: usize) -> Self {
        Self {
            plans: HashMap::new(),
            bytes: 0,
            max_entries,
            max_bytes,
        }
    }

    /// The cached answer for `key`, if any.
    pub(super) fn get(&self, key: &PlanKey) -> Option<&Planned> {
        self.plans.get(key)
    }

    /// Caches `planned` for `key` (a key not cached yet), clearing the cache first when the
    /// entry would not fit beside the others; an entry over the byte bound alone is not kept.
    pub(super) fn insert(&mut self, key: PlanKey, mut planned: Planned) {
        if let Ok(cells) = &mut planned {
            cells.shrink_to_fit();
        }
        let bytes = entry_bytes(&planned);
        if bytes > self.max_bytes || self.max_entries == 0 {
            return;
        }
        if self.plans.len() >= self.max_entries || self.bytes + bytes > self.max_bytes {
            self.plans.clear();
            self.bytes = 0;
        }
        if let Some(old) = self.plans.insert(key, planned) {
            self.bytes -= entry_bytes(&old);
        }
        self.bytes += bytes;
    }

    /// Number of entries.
    #[cfg(test)]
    pub(super) fn len(&self) -> usize {
        self.plans.len()
    }

    /// Bytes the entries hold (fixed size plus 4 bytes per plan cell).
    pub(super) fn bytes(&self) -> usize {
        self.bytes
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan(cells: usize) -> Planned {
        Ok((0..cells as u32).collect())
    }

    #[test]
    fn the_cache_stays_within_its_entries_and_bytes() {
        let per_cell = size_of::<u32>();
        let fixed = size_of::<(PlanKey, Planned)>();
        let mut cache = PlanCache::new(3, 2 * fixed + 100 * per_cell);
        cache.insert((0, 0, 1, false), plan(60));
        cache.insert((0, 0, 2, false), plan(30));
        assert_eq!(cache.len(), 2);
        assert_eq!(cache.bytes(), 2 * fixed + 90 * per_cell);
        // 90 + 20 cells do not fit: cleared, then kept.
        cache.insert((0, 0, 3, false), plan(20));
        assert_eq!(cache.len(), 1);
        assert!(cache.get(&(0, 0, 1, false)).is_none());
        assert_eq!(cache.get(&(0, 0, 3, false)), Some(&plan(20)));
        cache.insert((0, 0, 4, false), Err(NavError::NoPath));
        cache.insert((0, 0, 5, false), Err(NavError::NoPath));
        assert_eq!(cache.len(), 3);
        cache.insert((0, 0, 7, false), Err(NavError::NoPath));
        assert_eq!(cache.len(), 1, "a fourth entry cleared the three");
        // Larger than the bound alone: not kept, the rest stays.
        cache.insert((0, 0, 6, false), plan(200));
        assert_eq!(cache.len(), 1);
        assert!(cache.get(&(0, 0, 6, false)).is_none());
        assert!(cache.bytes() <= 2 * fixed + 100 * per_cell);
    }
}
