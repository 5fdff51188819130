//! A monotone bucket queue (Dial's algorithm) for Dijkstra's algorithm with small integer edge
//! costs: the open set of [`super::distance_field::DistanceField`].
//!
//! Keys are non-negative integers; every key pushed lies within `max_step` of the key last
//! popped (as in Dijkstra's algorithm, where a push is the popped cost plus one edge cost of at
//! most `max_step`). The keys in the queue then fall into a window of `max_step + 1` values, and
//! one bucket per value, used circularly, holds them: a push is `O(1)`, and the pops of a whole
//! search cost `O(pops + largest key)` together. Items of equal key come out in no particular
//! order (last pushed first); Dijkstra's settled costs do not depend on it.
//!
//! Reference: R. B. Dial, "Algorithm 360: shortest-path forest with topological ordering",
//! Communications of the ACM 12(11), 1969.

/// A min-queue of `(key, item)` for monotone searches (see the module docs).
#[derive(Debug, Clone)]
pub struct BucketQueue {
    /// `buckets[k % buckets.len()]` holds the items of key `k`, for keys in
    /// `current..=current + max_step`.
    buckets: Vec<Vec<u32>>,
    /// The smallest key the queue can hold: the key last popped (0 at first).
    current: u32,
    len: usize,
}

impl BucketQueue {
    /// An empty queue whose pushes are at most `max_step` above the last popped key (0 before
    /// the first pop).
    pub fn new(max_step: u32) -> Self {
        Self {
            buckets: vec![Vec::new(); max_step as usize + 1],
            current: 0,
            len: 0,
        }
    }

    /// Adds `item` with `key`. Keys must lie in `last popped ..= last popped + max_step`
    /// (checked in debug builds; outside it the pop order would be wrong).
    pub fn push(&mut self, key: u32, item: u32) {
        let span = self.buckets.len() as u32;
        debug_assert!(
            key >= self.current && key - self.current < span,
            "key {key} outside the window {}..{}",
            self.current,
            u64::from(self.current) + u64::from(span)
        );
        self.buckets[(key % span) as usize].push(item);
        self.len += 1;
    }

    /// Removes and returns an item of the smallest key, with the key; `None` when empty.
    pub fn pop(&mut self) -> Option<(u32, u32)> {
        if self.len == 0 {
            return None;
        }
        let span = self.buckets.len() as u32;
        loop {
            if let Some(item) = self.buckets[(self.current % span) as usize].pop() {
                self.len -= 1;
                return Some((self.current, item));
            }
            self.current += 1;
        }
    }

    /// Heap memory the queue holds, bytes: the bucket list and every bucket's capacity (a
    /// bucket keeps the largest capacity it grew to). `O(max_step)`.
    pub fn heap_bytes(&self) -> usize {
        let items: usize = self.buckets.iter().map(Vec::capacity).sum();
        self.buckets.capacity() * size_of::<Vec<u32>>() + items * size_of::<u32>()
    }

    /// Number of items in the queue.
    #[cfg(test)]
    fn len(&self) -> usize {
        self.len
    }

    /// Whether the queue is empty.
    #[cfg(test)]
    fn is_empty(&self) -> bool {
        self.len == 0
    }
}

#[cfg(test)]
mod tests {
    use std::cmp::Reverse;
    use std::collections::BinaryHeap;

    use proptest::prelude::*;

    use super::*;

    #[test]
    fn pops_in_key_order_across_the_circular_window() {
        let mut q = BucketQueue::new(3);
        q.push(0, 7);
        assert_eq!(q.pop(), Some((0, 7)));
        q.push(3, 1);
        q.push(1, 2);
        q.push(3, 3);
        assert_eq!(q.len(), 3);
        assert_eq!(q.pop(), Some((1, 2)));
        q.push(4, 4); // bucket 0 again, after key 0 was popped
        assert_eq!(q.pop().map(|(k, _)| k), Some(3));
        assert_eq!(q.pop().map(|(k, _)| k), Some(3));
        assert_eq!(q.pop(), Some((4, 4)));
        assert_eq!(q.pop(), None);
        assert!(q.is_empty());
    }

    proptest! {
        /// A monotone sequence of pushes and pops gives the same keys, in the same order, as a
        /// binary heap (items of equal key may come out in another order).
        #[test]
        fn pops_the_keys_a_binary_heap_pops(
            ops in prop::collection::vec((0u32..=1414, 0u32..5), 1..400),
        ) {
            let mut q = BucketQueue::new(1414);
            let mut heap = BinaryHeap::new();
            let mut last = 0u32;
            for (i, &(step, pops)) in ops.iter().enumerate() {
                q.push(last + step, i as u32);
                heap.push(Reverse((last + step, i as u32)));
                for _ in 0..pops {
                    let got = q.pop().map(|(k, _)| k);
                    let want = heap.pop().map(|Reverse((k, _))| k);
                    prop_assert_eq!(got, want);
                    if let Some(k) = got {
                        last = k;
                    }
                }
                prop_assert_eq!(q.len(), heap.len());
            }
            while let Some(Reverse((k, _))) = heap.pop() {
                prop_assert_eq!(q.pop().map(|(k, _)| k), Some(k));
            }
            prop_assert!(q.is_empty());
        }
    }
}
