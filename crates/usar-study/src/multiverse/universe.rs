//! Universes: one alternative per axis. The full factorial is numbered in mixed radix with
//! the first axis varying slowest (as `--vary` numbers a grid's cells): with axes of 3 and 2
//! alternatives, universe 0 takes `(0, 0)`, 1 `(0, 1)`, 2 `(1, 0)`, ..., 5 `(2, 1)`.
//! [`select`] gives every universe, or `--sample N` of them drawn without replacement by a
//! ChaCha8 generator seeded with `--sample-seed` (`rand::seq::index::sample`), in universe
//! order. A universe keeps its factorial index (and its folder name, [`Universe::id`]) in a
//! sample, so a universe is the same universe in every sample.
//!
//! [`shard_of`] deals the selected universes round robin to the shards of `--shard I/N`
//! ([`usar_sweep::shard::split`] with equal costs): fixed, balanced, covering each once.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use usar_sweep::settings::Setting;
use usar_sweep::shard::{Shard, split};

/// Most universes one multiverse runs (10,000): each holds a calibration and a sweep, so a
/// larger count is a mistake (a forgotten `--sample`) or several multiverses' work.
pub const MAX_UNIVERSES: usize = 10_000;

/// `--sample N --sample-seed S`: `n` universes drawn without replacement from the factorial.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Sample {
    /// How many (1 to the factorial's size and [`MAX_UNIVERSES`]).
    pub n: usize,
    /// Seed of the draw.
    pub seed: u64,
}

/// One universe: its index in the full factorial and its alternative per axis.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Universe {
    /// Index in the full factorial, `0..factorial size`.
    pub index: u64,
    /// The alternative taken on each axis (an index into its alternatives), in axis order.
    pub choices: Vec<usize>,
}

impl Universe {
    /// The universe's folder name in a factorial of `total` universes: `u` and the index,
    /// zero-padded to at least 3 digits and to the width of `total - 1` (`u007`, `u0123`).
    pub fn id(&self, total: u64) -> String {
        let width = total.saturating_sub(1).to_string().len().max(3);
        format!("u{:0width$}", self.index)
    }
}

/// Why the universes cannot be selected: one line naming the flag.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum UniverseError {
    /// The factorial does not fit in 64 bits.
    #[error("the axes make more than 2^64 universes; use fewer axes or alternatives")]
    Overflow,
    /// More universes than [`MAX_UNIVERSES`] would run.
    #[error(
        "the axes make {count} universes, more than the limit of {MAX_UNIVERSES} per \
         multiverse: draw some with {} N",
        Setting::Sample
    )]
    TooMany {
        /// Universes that would run.
        count: u64,
    },
    /// `--sample 0`.
    #[error("{} must be at least 1", Setting::Sample)]
    EmptySample,
    /// More shards than universes (`--shard I/N`, `usar slurm --shards N`): a shard without
    /// a universe would be one more job to run and wait for.
    #[error(
        "{option}: the multiverse runs {universes} universe(s), so at most {universes} shards \
         have work; split it into at most {universes}"
    )]
    TooManyShards {
        /// The flag as given (`--shard 0/5`, `--shards 5`).
        option: String,
        /// Universes the multiverse runs.
        universes: usize,
    },
    /// `--sample N` above the factorial's size.
    #[error(
        "{} {n}: the axes make only {total} universes (the full factorial); give at most \
         {total}, or leave {} out to run them all",
        Setting::Sample,
        Setting::Sample
    )]
    SampleTooLarge {
        /// The sample size asked for.
        n: usize,
        /// The factorial's size.
        total: u64,
    },
}

/// The size of the full factorial of axes with `sizes` alternatives each.
///
/// # Errors
/// [`UniverseError::Overflow`] past `u64::MAX`.
pub fn factorial_size(sizes: &[usize]) -> Result<u64, UniverseError> {
    sizes.iter().try_fold(1u64, |acc, &k| {
        acc.checked_mul(k as u64).ok_or(UniverseError::Overflow)
    })
}

/// The alternatives of universe `index` of the factorial of `sizes` (first axis slowest).
/// `index` is taken modulo the factorial's size.
pub fn choices_at(sizes: &[usize], index: u64) -> Vec<usize> {
    let mut rest = index;
    let mut out = vec![0; sizes.len()];
    for (slot, &k) in out.iter_mut().zip(sizes).rev() {
        let k = k.max(1) as u64;
        *slot = (rest % k) as usize;
        rest /= k;
    }
    out
}

/// The universes of the factorial of `sizes` a multiverse runs: all of them, or the sample,
/// in index order.
///
/// # Errors
/// A factorial past `u64::MAX`, more than [`MAX_UNIVERSES`] to run, an empty sample, or a
/// sample larger than the factorial.
pub fn select(sizes: &[usize], sample: Option<Sample>) -> Result<Vec<Universe>, UniverseError> {
    let total = factorial_size(sizes)?;
    let indices: Vec<u64> = match sample {
        None if total > MAX_UNIVERSES as u64 => {
            return Err(UniverseError::TooMany { count: total });
        }
        None => (0..total).collect(),
        Some(s) if s.n == 0 => return Err(UniverseError::EmptySample),
        Some(s) if s.n as u64 > total => {
            return Err(UniverseError::SampleTooLarge { n: s.n, total });
        }
        Some(s) if s.n > MAX_UNIVERSES => {
            return Err(UniverseError::TooMany { count: s.n as u64 });
        }
        Some(s) => {
            let length = usize::try_from(total).map_err(|_| UniverseError::Overflow)?;
            let mut rng = ChaCha8Rng::seed_from_u64(s.seed);
            let mut drawn: Vec<u64> = rand::seq::index::sample(&mut rng, length, s.n)
                .into_iter()
                .map(|i| i as u64)
                .collect();
            drawn.sort_unstable();
            drawn
        }
    };
    Ok(indices
        .into_iter()
        .map(|index| Universe {
            index,
            choices: choices_at(sizes, index),
        })
        .collect())
}

/// Refuses a split into more shards than the `universes` a multiverse runs; `option` names
/// the flag (`--shard 0/5`, `--shards 5`).
///
/// # Errors
/// [`UniverseError::TooManyShards`] when `shards > universes`.
pub fn check_shards(option: &str, shards: usize, universes: usize) -> Result<(), UniverseError> {
    if shards > universes {
        return Err(UniverseError::TooManyShards {
            option: option.to_string(),
            universes,
        });
    }
    Ok(())
}

/// The positions (into `count` selected universes) that `shard` runs: universe `j` goes to
/// shard `j % N`.
pub fn shard_of(count: usize, shard: Shard) -> Vec<usize> {
    split(&vec![1; count], shard.count)
        .into_iter()
        .enumerate()
        .filter(|&(_, owner)| owner == shard.index)
        .map(|(j, _)| j)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_factorial_is_numbered_first_axis_slowest() {
        let all = select(&[3, 2], None).unwrap();
        let choices: Vec<Vec<usize>> = all.iter().map(|u| u.choices.clone()).collect();
        assert_eq!(
            choices,
            [[0, 0], [0, 1], [1, 0], [1, 1], [2, 0], [2, 1]].map(|c| c.to_vec())
        );
        assert_eq!(all[5].index, 5);
        assert_eq!(choices_at(&[2, 3, 4], 23), [1, 2, 3]);
        assert_eq!(choices_at(&[2, 3, 4], 4 * 3 + 4 + 1), [1, 1, 1]);
        assert_eq!(factorial_size(&[]).unwrap(), 1);
        assert_eq!(select(&[], None).unwrap().len(), 1);
    }

    #[test]
    fn ids_are_padded_to_the_factorial() {
        let u = |index| Universe {
            index,
            choices: Vec::new(),
        };
        assert_eq!(u(7).id(8), "u007");
        assert_eq!(u(7).id(1000), "u007");
        assert_eq!(u(7).id(1001), "u0007");
        assert_eq!(u(0).id(1), "u000");
    }

    #[test]
    fn a_sample_is_seeded_distinct_sorted_and_within_the_factorial() {
        let sizes = [3, 3, 2, 2, 5];
        let s = |n, seed| select(&sizes, Some(Sample { n, seed })).unwrap();
        let a = s(20, 7);
        assert_eq!(a.len(), 20);
        assert_eq!(a, s(20, 7), "same seed, same sample");
        assert_ne!(a, s(20, 8), "another seed, another sample");
        assert!(a.windows(2).all(|w| w[0].index < w[1].index));
        assert!(a.iter().all(|u| u.index < 180));
        for u in &a {
            assert_eq!(u.choices, choices_at(&sizes, u.index));
        }
        // The whole factorial as a sample is every universe.
        let all: Vec<u64> = s(180, 1).iter().map(|u| u.index).collect();
        assert_eq!(all, (0..180).collect::<Vec<_>>());
    }

    #[test]
    fn bad_counts_are_refused_in_one_line() {
        let e = select(&[2, 2], Some(Sample { n: 5, seed: 0 })).unwrap_err();
        assert_eq!(
            e.to_string(),
            "--sample 5: the axes make only 4 universes (the full factorial); give at most 4, \
             or leave --sample out to run them all"
        );
        assert_eq!(
            select(&[2], Some(Sample { n: 0, seed: 0 })).unwrap_err(),
            UniverseError::EmptySample
        );
        assert_eq!(
            select(&[100, 101], None).unwrap_err(),
            UniverseError::TooMany { count: 10_100 }
        );
        // A large factorial is fine with a sample.
        assert_eq!(
            select(&[1000; 5], Some(Sample { n: 3, seed: 1 }))
                .unwrap()
                .len(),
            3
        );
        assert_eq!(
            select(&[usize::MAX, 3], Some(Sample { n: 3, seed: 1 })).unwrap_err(),
            UniverseError::Overflow
        );
        assert!(check_shards("--shards 4", 4, 4).is_ok());
        assert_eq!(
            check_shards("--shard 0/5", 5, 4).unwrap_err().to_string(),
            "--shard 0/5: the multiverse runs 4 universe(s), so at most 4 shards have work; \
             split it into at most 4"
        );
    }

    #[test]
    fn shards_cover_every_universe_once_and_balance() {
        for n in 1..=7 {
            let mut seen = Vec::new();
            for i in 0..n {
                let own = shard_of(10, Shard::new(i, n).unwrap());
                assert!(
                    own.len() == 10 / n || own.len() == 10 / n + 1,
                    "{n}: {own:?}"
                );
                seen.extend(own);
            }
            seen.sort_unstable();
            assert_eq!(seen, (0..10).collect::<Vec<_>>());
        }
    }
}
