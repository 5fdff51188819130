//! All Subgroup Combinations (Algorithm 2, ASC): every way to split a set into two subgroups,
//! enumerated lazily (one split at a time, never all in memory).

use serde::{Deserialize, Serialize};

use crate::error::{Result, RneError};

/// A split of the index set `0..n` into two subgroups; both lists are sorted ascending and
/// together hold every index exactly once.
#[derive(Debug, Clone, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Bipartition {
    /// The first subgroup (size `m`).
    pub first: Vec<usize>,
    /// The second subgroup (size `n - m`).
    pub second: Vec<usize>,
}

impl Bipartition {
    /// The split whose first subgroup is `first` (indices into `0..n`, any order); both lists
    /// come out sorted ascending.
    ///
    /// # Errors
    /// [`RneError::InvalidSplitIndex`] naming an index `>= n` or one given twice.
    pub fn from_first(n: usize, mut first: Vec<usize>) -> Result<Self> {
        first.sort_unstable();
        if let Some(&index) = first.last().filter(|&&i| i >= n) {
            return Err(RneError::InvalidSplitIndex {
                n,
                index,
                problem: "out of range",
            });
        }
        if let Some(w) = first.windows(2).find(|w| w[0] == w[1]) {
            return Err(RneError::InvalidSplitIndex {
                n,
                index: w[0],
                problem: "given twice",
            });
        }
        Ok(Self::from_sorted_first(n, first))
    }

    /// [`Bipartition::from_first`] for a `first` already known to be ascending, without
    /// repeats and within `0..n`.
    pub(crate) fn from_sorted_first(n: usize, first: Vec<usize>) -> Self {
        debug_assert!(first.windows(2).all(|w| w[0] < w[1]) && first.last() < Some(&n));
        let second = complement(n, &first);
        Self { first, second }
    }
}

/// The indices of `0..n` not in the ascending list `first`, ascending.
fn complement(n: usize, first: &[usize]) -> Vec<usize> {
    let mut second = Vec::with_capacity(n.saturating_sub(first.len()));
    let mut next = first.iter().peekable();
    for i in 0..n {
        if next.peek() == Some(&&i) {
            next.next();
        } else {
            second.push(i);
        }
    }
    second
}

/// Lazy iterator over all `m`-subsets of `0..n` in lexicographic order, built by
/// [`combinations`]. Holds one subset (`m` indices) at a time.
#[derive(Debug, Clone)]
pub struct Combinations {
    n: usize,
    current: Vec<usize>,
    done: bool,
}

impl Iterator for Combinations {
    type Item = Vec<usize>;

    fn next(&mut self) -> Option<Vec<usize>> {
        if self.done {
            return None;
        }
        let out = self.current.clone();
        let (n, m) = (self.n, self.current.len());
        // Advance to the next subset: the rightmost position that can still be incremented.
        match (0..m).rev().find(|&i| self.current[i] < n - m + i) {
            Some(i) => {
                self.current[i] += 1;
                for k in i + 1..m {
                    self.current[k] = self.current[k - 1] + 1;
                }
            }
            None => self.done = true,
        }
        Some(out)
    }
}

/// All `m`-subsets of `0..n` in lexicographic order (the order in which Algorithm 2 emits
/// them: fix the first element, recurse on the rest), as a lazy iterator.
///
/// Yields `C(n, m)` subsets ([`split_count`] gives the count without enumerating), each sorted
/// ascending; one empty subset if `m == 0`. Memory: `O(m)` whatever `n` and `m`.
///
/// # Errors
/// [`RneError::InvalidSubgroupSize`] if `m > n`.
pub fn combinations(n: usize, m: usize) -> Result<Combinations> {
    if m > n {
        return Err(RneError::InvalidSubgroupSize { size: m, total: n });
    }
    Ok(Combinations {
        n,
        current: (0..m).collect(),
        done: false,
    })
}

/// `C(n, m)`, exact whenever it fits in a `u128` and saturating at `u128::MAX` otherwise
/// (never overflows or panics); 0 if `m > n`.
pub fn binomial(n: usize, m: usize) -> u128 {
    if m > n {
        return 0;
    }
    let m = m.min(n - m) as u128;
    let n = n as u128;
    let mut c: u128 = 1;
    for i in 0..m {
        // C(n, i + 1) = C(n, i) * (n - i) / (i + 1). With g = gcd(n - i, i + 1), (i + 1) / g
        // divides C(n, i), so no intermediate exceeds C(n, i + 1), which grows with i up to
        // m <= n / 2: saturating here means the result does not fit.
        let g = gcd(n - i, i + 1);
        c = match (c / ((i + 1) / g)).checked_mul((n - i) / g) {
            Some(next) => next,
            None => return u128::MAX,
        };
    }
    c
}

fn gcd(mut a: u128, mut b: u128) -> u128 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

/// How many splits [`two_way_splits`]`(n, m)` yields: `C(n, m)`, halved when `m = n - m > 0`
/// (each unordered split once); 0 if `m > n`; saturating at `u128::MAX`.
///
/// Examples: 10 for the paper's 6 carriers split 3/3, 462 for 12 robots split 6/6, 92,378 for
/// 20 split 10/10, 7.8e7 for 30 split 15/15, 1.6e13 for 48 split 24/24.
pub fn split_count(n: usize, m: usize) -> u128 {
    let c = binomial(n, m);
    if m <= n && m == n - m && n > 0 {
        c / 2
    } else {
        c
    }
}

/// Lazy iterator over the splits of [`two_way_splits`]; holds one split at a time.
#[derive(Debug, Clone)]
pub struct TwoWaySplits {
    n: usize,
    firsts: Combinations,
    symmetric: bool,
}

impl Iterator for TwoWaySplits {
    type Item = Bipartition;

    fn next(&mut self) -> Option<Bipartition> {
        let first = self.firsts.next()?;
        // With equal halves, the splits whose first subgroup contains index 0 come first in
        // lexicographic order; the rest are mirror images of them.
        if self.symmetric && first.first() != Some(&0) {
            self.firsts.done = true;
            return None;
        }
        let second = complement(self.n, &first);
        Some(Bipartition { first, second })
    }
}

/// Algorithm 2 (ASC), generalised to unequal sizes: every split of `0..n` into a first
/// subgroup of size `m` and a second of size `n - m`, each split **once**, as a lazy iterator.
///
/// * `m != n - m`: the subgroups are distinguishable by size; all `C(n, m)` splits, first
///   subgroups in lexicographic order.
/// * `m == n - m`: `{A, B}` and `{B, A}` are the same split, so only the `C(n, m) / 2` splits
///   whose first subgroup contains index 0 are emitted (still in lexicographic order).
///   For `n = 0` one split `(∅, ∅)` is returned.
///
/// Size: [`split_count`]`(n, m)` splits (10 for the paper's 6 carriers split 3/3, 92,378 for
/// 20 robots split 10/10, 1.6e13 for 48 split 24/24), produced one at a time in `O(n)` memory.
/// The hierarchical grouping scores them all only while the count is within
/// [`HierarchicalRne::exact_split_limit`](crate::grouping::HierarchicalRne::exact_split_limit).
///
/// # Errors
/// [`RneError::InvalidSubgroupSize`] if `m > n`.
///
/// # Reference
/// `ASC(A, m) = { (S, A \ S) : S ⊆ A, |S| = m }` modulo swapping when `|S| = |A \ S|`;
/// paper Algorithm 2 and Sec. V (`C_x^{x/2}` combinations).
pub fn two_way_splits(n: usize, m: usize) -> Result<TwoWaySplits> {
    let firsts = combinations(n, m)?;
    Ok(TwoWaySplits {
        n,
        firsts,
        symmetric: m == n - m && n > 0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn combinations_counts_and_order() {
        assert_eq!(
            combinations(4, 2).unwrap().collect::<Vec<_>>(),
            vec![
                vec![0, 1],
                vec![0, 2],
                vec![0, 3],
                vec![1, 2],
                vec![1, 3],
                vec![2, 3]
            ]
        );
        assert_eq!(
            combinations(3, 0).unwrap().collect::<Vec<_>>(),
            vec![Vec::<usize>::new()]
        );
        assert_eq!(
            combinations(3, 3).unwrap().collect::<Vec<_>>(),
            vec![vec![0, 1, 2]]
        );
        assert_eq!(combinations(10, 5).unwrap().count(), 252);
        assert!(combinations(2, 3).is_err());
    }

    #[test]
    fn equal_halves_emitted_once() {
        let s: Vec<_> = two_way_splits(4, 2).unwrap().collect();
        assert_eq!(s.len(), 3);
        assert_eq!(
            s[0],
            Bipartition {
                first: vec![0, 1],
                second: vec![2, 3]
            }
        );
        assert_eq!(two_way_splits(6, 3).unwrap().count(), 10);
        assert_eq!(two_way_splits(2, 1).unwrap().count(), 1);
    }

    #[test]
    fn unequal_sizes_emit_all() {
        let s: Vec<_> = two_way_splits(5, 2).unwrap().collect();
        assert_eq!(s.len(), 10);
        assert!(s.iter().all(|b| b.first.len() == 2 && b.second.len() == 3));
        assert_eq!(
            two_way_splits(3, 0).unwrap().collect::<Vec<_>>(),
            vec![Bipartition {
                first: vec![],
                second: vec![0, 1, 2]
            }]
        );
    }

    #[test]
    fn every_split_is_a_partition_and_unique() {
        for n in 0..8 {
            for m in 0..=n {
                let s: Vec<_> = two_way_splits(n, m).unwrap().collect();
                assert_eq!(s.len() as u128, split_count(n, m), "n = {n}, m = {m}");
                let mut seen = std::collections::HashSet::new();
                for b in &s {
                    let mut all: Vec<usize> = b.first.iter().chain(&b.second).copied().collect();
                    all.sort_unstable();
                    assert_eq!(all, (0..n).collect::<Vec<_>>());
                    let mut key = [b.first.clone(), b.second.clone()];
                    key.sort();
                    assert!(seen.insert(key), "duplicate split {b:?}");
                }
            }
        }
    }

    #[test]
    fn counts_are_exact_and_saturate() {
        assert_eq!(binomial(48, 24), 32_247_603_683_100);
        assert_eq!(split_count(48, 24), 16_123_801_841_550);
        assert_eq!(split_count(20, 10), 92_378);
        assert_eq!(split_count(6, 3), 10);
        assert_eq!(split_count(0, 0), 1);
        assert_eq!(split_count(2, 3), 0);
        assert_eq!(binomial(1000, 500), u128::MAX);
        assert_eq!(binomial(1000, 1), 1000);
        // Exact up to the largest value that fits: no intermediate overflows first.
        assert_eq!(
            binomial(128, 64),
            23_951_146_041_928_082_866_135_587_776_380_551_750
        );
        assert_eq!(
            binomial(131, 65),
            188_694_833_082_770_476_622_296_176_145_946_360_850
        );
        assert_eq!(binomial(132, 66), u128::MAX);
        assert_eq!(binomial(usize::MAX, 1), usize::MAX as u128);
        assert_eq!(binomial(usize::MAX, usize::MAX - 1), usize::MAX as u128);
        // Pascal's rule wherever the sum fits.
        for n in 1..140 {
            for k in 1..n {
                let (a, b) = (binomial(n - 1, k - 1), binomial(n - 1, k));
                if let Some(sum) = a.checked_add(b).filter(|&s| s < u128::MAX) {
                    assert_eq!(binomial(n, k), sum, "C({n}, {k})");
                }
            }
        }
        // Huge sizes neither overflow nor panic.
        assert_eq!(split_count(usize::MAX, usize::MAX / 2 + 1), u128::MAX);
        assert!(two_way_splits(usize::MAX, 0).is_ok());
    }

    #[test]
    fn huge_enumerations_are_lazy() {
        // C(48, 24) splits cannot be held in memory; taking a few must be instant.
        let first: Vec<_> = two_way_splits(48, 24).unwrap().take(3).collect();
        assert_eq!(first[0].first, (0..24).collect::<Vec<_>>());
        assert_eq!(first[2].first.last(), Some(&25));
    }

    #[test]
    fn from_first_builds_a_partition_or_names_the_bad_index() {
        assert_eq!(
            Bipartition::from_first(5, vec![3, 1]).unwrap(),
            Bipartition {
                first: vec![1, 3],
                second: vec![0, 2, 4]
            }
        );
        assert_eq!(
            Bipartition::from_first(3, vec![5, 1])
                .unwrap_err()
                .to_string(),
            "split of 0..3: index 5 is out of range"
        );
        assert_eq!(
            Bipartition::from_first(3, vec![1, 2, 1])
                .unwrap_err()
                .to_string(),
            "split of 0..3: index 1 is given twice"
        );
    }
}
