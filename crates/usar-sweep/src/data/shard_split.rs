//! One shard of a sweep (`usar sweep ... --shard I/N`) and the split of a sweep's jobs into
//! shards.
//!
//! The split is deterministic and balanced: the jobs are taken in the canonical order of
//! [`job_list`] (trial-major, then cell, then method) and each goes to the shard
//! with the least simulated time so far (ties to the lowest index). With equal trial lengths
//! that is round robin, so shard sizes differ by at most one job; with cells of different
//! trial lengths (`--vary mission.duration_s=...`) it balances simulated seconds. Every split
//! `0/N .. (N-1)/N` of a sweep covers every job exactly once.

use std::fmt;
use std::str::FromStr;

use crate::data::jobs::{JobId, job_list};
use crate::journal::SweepHeader;

/// The most shards a sweep may be split into (a guard against typos such as `--shard 0/40000000`).
pub const MAX_SHARDS: usize = 100_000;

/// A shard argument that cannot be used.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ShardError {
    /// Not of the form `I/N` with two whole numbers.
    #[error(
        "--shard {0:?}: expected I/N, the shard index I (from 0) and the shard count N, e.g. 0/4"
    )]
    Syntax(String),
    /// `N` is 0 or above [`MAX_SHARDS`].
    #[error("--shard {index}/{count}: the shard count must be from 1 to {MAX_SHARDS}")]
    Count {
        /// The index given.
        index: usize,
        /// The count given.
        count: usize,
    },
    /// `I` is not below `N`.
    #[error("--shard {index}/{count}: the shard index must be from 0 to {}", count - 1)]
    Index {
        /// The index given.
        index: usize,
        /// The count given.
        count: usize,
    },
}

/// Shard `index` of `count` (0-based, like Slurm's `SLURM_ARRAY_TASK_ID` for `--array=0-(N-1)`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Shard {
    /// The shard's index, `0..count`.
    pub index: usize,
    /// How many shards the sweep is split into, `1..=MAX_SHARDS`.
    pub count: usize,
}

impl Shard {
    /// Shard `index` of `count`.
    ///
    /// # Errors
    /// `count` is 0 or above [`MAX_SHARDS`], or `index >= count`.
    pub fn new(index: usize, count: usize) -> Result<Self, ShardError> {
        if count == 0 || count > MAX_SHARDS {
            return Err(ShardError::Count { index, count });
        }
        if index >= count {
            return Err(ShardError::Index { index, count });
        }
        Ok(Self { index, count })
    }

    /// The shard's folder under `<out>/shards/`: `<I>-of-<N>`, `I` zero-padded to the width
    /// of `N - 1` so that the folders sort in shard order (`03-of-16`).
    pub fn dir_name(&self) -> String {
        let width = (self.count - 1).to_string().len();
        format!("{:0width$}-of-{}", self.index, self.count)
    }

    /// Parses a folder name written by [`Shard::dir_name`]; `None` for any other name.
    pub fn from_dir_name(name: &str) -> Option<Self> {
        let (i, n) = name.split_once("-of-")?;
        let shard = Self::new(i.parse().ok()?, n.parse().ok()?).ok()?;
        (shard.dir_name() == name).then_some(shard)
    }

    /// The jobs of the sweep with `header` that this shard runs, in [`job_list`] order.
    pub fn jobs(&self, header: &SweepHeader) -> Vec<JobId> {
        let jobs = sweep_jobs(header);
        let owners = split(&job_costs_ms(header, &jobs), self.count);
        jobs.into_iter()
            .zip(owners)
            .filter(|&(_, owner)| owner == self.index)
            .map(|(job, _)| job)
            .collect()
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl FromStr for Shard {
    type Err = ShardError;

    /// Parses `I/N` (spaces around the numbers are allowed).
    fn from_str(s: &str) -> Result<Self, ShardError> {
        let syntax = || ShardError::Syntax(s.to_string());
        let (i, n) = s.split_once('/').ok_or_else(syntax)?;
        let index = i.trim().parse().map_err(|_| syntax())?;
        let count = n.trim().parse().map_err(|_| syntax())?;
        Self::new(index, count)
    }
}

/// Every job of the sweep with `header`, in [`job_list`] order.
pub fn sweep_jobs(header: &SweepHeader) -> Vec<JobId> {
    job_list(header.grid.cells.len(), header.methods.len(), header.trials)
}

/// The cost of each job for the split: its cell's trial length in whole milliseconds of
/// simulated time (integers, so that the split is exact on every machine).
pub fn job_costs_ms(header: &SweepHeader, jobs: &[JobId]) -> Vec<u64> {
    jobs.iter()
        .map(|j| {
            (header.grid.cells[j.cell].duration_s * 1000.0)
                .round()
                .max(1.0) as u64
        })
        .collect()
}

/// The shard (`0..count`) of each job of a list with costs `costs_ms`: each job, in list
/// order, goes to the shard with the least cost so far, ties to the lowest index. With equal
/// costs this is round robin (job `j` to shard `j % count`). `count` must be at least 1
/// (0 is treated as 1).
pub fn split(costs_ms: &[u64], count: usize) -> Vec<usize> {
    let mut load = vec![0u64; count.max(1)];
    costs_ms
        .iter()
        .map(|&c| {
            let (shard, _) = load
                .iter()
                .enumerate()
                .min_by_key(|&(i, &l)| (l, i))
                .unwrap_or((0, &0));
            load[shard] += c;
            shard
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn parses_and_prints_i_of_n() {
        assert_eq!("2/4".parse(), Ok(Shard { index: 2, count: 4 }));
        assert_eq!(" 0 / 1 ".parse(), Ok(Shard { index: 0, count: 1 }));
        assert_eq!(Shard::new(3, 4).map(|s| s.to_string()), Ok("3/4".into()));
        assert!(matches!(
            "4/4".parse::<Shard>(),
            Err(ShardError::Index { .. })
        ));
        assert!(matches!(
            "0/0".parse::<Shard>(),
            Err(ShardError::Count { .. })
        ));
        assert!(matches!("1-4".parse::<Shard>(), Err(ShardError::Syntax(_))));
        assert!(matches!(
            "-1/4".parse::<Shard>(),
            Err(ShardError::Syntax(_))
        ));
        assert_eq!(
            ShardError::Index { index: 4, count: 4 }.to_string(),
            "--shard 4/4: the shard index must be from 0 to 3"
        );
    }

    #[test]
    fn folder_names_sort_and_read_back() {
        let names: Vec<String> = (0..12)
            .map(|i| Shard::new(i, 12).map(|s| s.dir_name()).unwrap_or_default())
            .collect();
        assert_eq!(names[3], "03-of-12");
        let mut sorted = names.clone();
        sorted.sort();
        assert_eq!(sorted, names);
        assert_eq!(Shard::from_dir_name("03-of-12"), Shard::new(3, 12).ok());
        assert_eq!(Shard::from_dir_name("3-of-12"), None);
        assert_eq!(Shard::from_dir_name("12-of-12"), None);
        assert_eq!(Shard::new(0, 1).map(|s| s.dir_name()), Ok("0-of-1".into()));
    }

    #[test]
    fn equal_costs_are_dealt_round_robin() {
        assert_eq!(split(&[5; 7], 3), [0, 1, 2, 0, 1, 2, 0]);
        // Long jobs are balanced by cost, not count.
        assert_eq!(split(&[10, 20, 10, 20], 2), [0, 1, 0, 0]);
    }

    proptest! {
        /// Every split covers every job once, and no shard's cost exceeds another's by more
        /// than the costliest job.
        #[test]
        fn every_split_covers_every_job_once(
            costs in prop::collection::vec(1u64..1_000, 0..200),
            count in 1usize..40,
        ) {
            let owners = split(&costs, count);
            prop_assert_eq!(owners.len(), costs.len());
            prop_assert!(owners.iter().all(|&s| s < count));
            let mut load = vec![0u64; count];
            for (c, s) in costs.iter().zip(&owners) {
                load[*s] += c;
            }
            let max_job = costs.iter().copied().max().unwrap_or(0);
            let (lo, hi) = (load.iter().min().copied(), load.iter().max().copied());
            prop_assert!(hi.unwrap_or(0) - lo.unwrap_or(0) <= max_job);
        }
    }
}
