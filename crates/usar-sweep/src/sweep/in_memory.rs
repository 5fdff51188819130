//! A sweep in memory: every trial of every method run as [`crate::sweep::run_sweep`] runs
//! them, with nothing written (no output folder, journal or lock), its results returned.

use std::time::Instant;

use usar_sim::mission::TrialResult;

use crate::data::config::SweepConfig;
use crate::data::jobs::job_list;
use crate::data::outcome::{CellOutcome, Failure};
use crate::error::SweepError;
use crate::executor::{Job, Runner, execute, threads_for};
use crate::journal::SweepHeader;
use crate::sweep::checks::check_config;
use crate::sweep::header::header_of;
use crate::sweep::plans::{cell_plans, job_of};
use crate::sweep::records::{Slots, collect};

/// What a sweep run in memory ([`run_in_memory`]) produced: the results and failures of
/// every trial, nothing on disk.
#[derive(Debug, Clone)]
pub struct SweepResults {
    /// The sweep's parameters and grid, as [`crate::sweep::run_sweep`] would journal them
    /// (methods in canonical upper-case names, in sweep order).
    pub header: SweepHeader,
    /// Per grid cell, in cell order (one cell without a grid): successful trials in
    /// [`CellOutcome::results`] and failed ones in [`CellOutcome::failures`], each sorted by
    /// method order then trial, the order of the rows of `trials.csv`. Every trial is counted
    /// in [`CellOutcome::ran`]; [`CellOutcome::reused`] is 0.
    pub cells: Vec<CellOutcome>,
    /// Worker threads used ([`sweep_threads`](crate::sweep::sweep_threads)).
    pub threads: usize,
    /// Wall-clock time of the trials, seconds.
    pub wall_s: f64,
}

impl SweepResults {
    /// Every successful trial: by cell, then method order, then trial.
    pub fn results(&self) -> impl Iterator<Item = &TrialResult> {
        self.cells.iter().flat_map(|c| &c.results)
    }

    /// Every failed trial: by cell, then method order, then trial (empty when all ran).
    pub fn failures(&self) -> impl Iterator<Item = &Failure> {
        self.cells.iter().flat_map(|c| &c.failures)
    }
}

/// Runs every trial of every method of every cell of `cfg` in memory and returns the results:
/// the same trials as [`crate::sweep::run_sweep`] on a fresh output folder (trial `k` seeded
/// `trial_seed(base_seed, k)` for every method and cell, one pool of
/// [`sweep_threads`](crate::sweep::sweep_threads) threads, the same checks), so the
/// results are bit-identical to the ones it journals, on any thread count. Nothing is
/// written: `out_dir`, `resume` and `overwrite` are not used, no folder is locked.
///
/// A failed trial (an error or a panic, in the method or in a hook) does not stop the sweep:
/// it is listed in [`SweepResults::failures`] and warned about on stderr, as on disk. The
/// hooks are called as on disk; `on_journaled` is called as each trial's record is made
/// (nothing is journaled). `progress` shows a bar when the program has installed a
/// [`crate::progress::ProgressSink`] (the `usar` binary draws one on a terminal).
///
/// # Errors
/// Bad parameters ([`crate::sweep::check_config`], [`crate::sweep::header_of`]), a shard
/// (`cfg.shard`: a shard is a part of a sweep on disk), or a thread pool that cannot start.
pub fn run_in_memory(cfg: &SweepConfig) -> Result<SweepResults, SweepError> {
    if let Some(s) = &cfg.shard {
        return Err(SweepError::ShardInMemory {
            index: s.shard.index,
            count: s.shard.count,
        });
    }
    let header = header_of(cfg)?;
    check_config(cfg, &header)?;
    let plans = cell_plans(cfg, &header)?;
    let jobs: Vec<Job> = job_list(plans.len(), header.methods.len(), cfg.trials)
        .into_iter()
        .map(|id| job_of(cfg, &header, id))
        .collect();
    let (threads, inside_trials) = threads_for(cfg.threads, &plans, jobs.len());
    let runner = Runner {
        factory: &cfg.method_factory,
        hooks: &cfg.hooks,
        progress: cfg.progress,
        threads,
        inside_trials,
    };
    let start = Instant::now();
    let records = execute(&runner, &plans, &jobs, None)?;
    let wall_s = start.elapsed().as_secs_f64();
    let slots = Slots {
        methods: header.methods.clone(),
        cells: plans.len(),
        trials: cfg.trials,
    };
    let cells = collect(&slots, vec![None; slots.len()], records);
    Ok(SweepResults {
        header,
        cells,
        threads,
        wall_s,
    })
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::data::hooks::TrialObserverFactory;
    use crate::data::limits::max_threads;
    use crate::sweep::run_sweep;

    const PAPER: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/paper.ron");

    /// paper.ron, RNE and DIS x 2 trials x 20 s, `threads` threads, into `out` (on disk).
    fn config(threads: usize, out: &std::path::Path) -> SweepConfig {
        let scenario = usar_sim::scenario::load(PAPER).unwrap();
        SweepConfig {
            methods: vec!["rne".into(), "dis".into()],
            trials: 2,
            base_seed: 7,
            duration_s: Some(20.0),
            threads,
            out_dir: out.to_path_buf(),
            progress: false,
            ..SweepConfig::new(scenario, PAPER)
        }
    }

    fn ran(results: &SweepResults) -> Vec<TrialResult> {
        results.results().cloned().collect()
    }

    #[test]
    fn in_memory_results_are_run_sweeps_on_any_thread_count_and_write_nothing() {
        let tmp = tempfile::tempdir().unwrap();
        let unused = tmp.path().join("never written");
        let two = run_in_memory(&config(2, &unused)).unwrap();
        let one = run_in_memory(&config(1, &unused)).unwrap();
        assert!(
            !unused.exists(),
            "an in-memory sweep made its output folder"
        );
        assert_eq!((two.threads, one.threads), (2.min(max_threads()), 1));
        assert_eq!(two.failures().count(), 0);
        assert_eq!(ran(&two), ran(&one), "1 and 2 threads differ");
        // Order of trials.csv: method order, then trial; trial k seeded as on disk.
        let order: Vec<(String, u32, u64)> = two
            .results()
            .map(|r| (r.method.clone(), r.trial, r.seed))
            .collect();
        let seed = |k| usar_sim::mission::trial_seed(7, k);
        let want = [("RNE", 0), ("RNE", 1), ("DIS", 0), ("DIS", 1)]
            .map(|(m, k)| (m.to_string(), k, seed(k)));
        assert_eq!(order, want);
        assert_eq!(two.cells[0].ran, 4);

        let out = tmp.path().join("sweep");
        let disk = run_sweep(&config(2, &out)).unwrap();
        assert_eq!(ran(&two), disk.cells[0].results, "on disk, as run");
        assert_eq!(two.header, disk.header);
        drop(disk);
        // The same command again reads every result back from the journal.
        let again = run_sweep(&config(1, &out)).unwrap();
        assert_eq!((again.ran, again.reused), (0, 4));
        assert_eq!(ran(&two), again.cells[0].results, "on disk, read back");
    }

    #[test]
    fn a_failing_trial_is_returned_and_the_others_run() {
        let tmp = tempfile::tempdir().unwrap();
        let mut cfg = config(2, tmp.path());
        let observer: TrialObserverFactory = Arc::new(|key| {
            assert!(!(key.method == "DIS" && key.trial == 1), "injected failure");
            None
        });
        cfg.hooks.trial_observer = Some(observer);
        let got = run_in_memory(&cfg).unwrap();
        let failed: Vec<&Failure> = got.failures().collect();
        assert_eq!(failed.len(), 1);
        assert_eq!((failed[0].method.as_str(), failed[0].trial), ("DIS", 1));
        assert!(failed[0].message.contains("panicked: injected failure"));
        let kept: Vec<(&str, u32)> = got
            .results()
            .map(|r| (r.method.as_str(), r.trial))
            .collect();
        assert_eq!(kept, [("RNE", 0), ("RNE", 1), ("DIS", 0)]);
    }

    #[test]
    fn a_stopped_sweep_skips_the_trials_not_started() {
        let tmp = tempfile::tempdir().unwrap();
        let mut cfg = config(1, tmp.path());
        let stop = Arc::new(std::sync::atomic::AtomicBool::new(false));
        let flag = stop.clone();
        // Stopped once the first trial is recorded: on one thread, no other trial starts.
        cfg.hooks.on_journaled = Some(Arc::new(move |_, _| {
            flag.store(true, std::sync::atomic::Ordering::SeqCst);
        }));
        cfg.hooks.stop = Some(stop);
        let got = run_in_memory(&cfg).unwrap();
        assert_eq!(got.failures().count(), 0);
        let kept: Vec<(&str, u32)> = got
            .results()
            .map(|r| (r.method.as_str(), r.trial))
            .collect();
        assert_eq!(kept, [("RNE", 0)]);
    }

    #[test]
    fn bad_parameters_are_one_line_errors() {
        let tmp = tempfile::tempdir().unwrap();
        let cfg = SweepConfig {
            trials: 0,
            ..config(1, tmp.path())
        };
        let e = run_in_memory(&cfg).unwrap_err();
        assert_eq!(format!("{e:#}"), "trials must be at least 1");
    }
}
