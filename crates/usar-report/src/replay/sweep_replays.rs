//! Replays of chosen trials of a sweep (`usar sweep --replay METHOD:TRIAL,...`): recorded by
//! the sweep's own per-trial observer ([`usar_sweep::sweep::SweepHooks::trial_observer`]) while
//! the trial runs, and written as `replay-<method>-<trial>.html` into the folder of the
//! trial's cell (the output folder itself without a grid).
//!
//! A requested trial that this run does not run (it is already in the journal: `--resume`, or
//! the same command run again) is run once more after the sweep, alone, only for its replay:
//! trials are deterministic, so it is the same trial (the journal is not touched). A trial
//! that failed gets no replay.

use std::path::PathBuf;
use std::sync::{Arc, Mutex, PoisonError};

use usar_sim::mission::{Simulation, StepObserver};

use super::error::ReplayError;
use super::page::write_replay;
use super::recorder::ReplayRecorder;
use super::trial::record_trial;
use usar_sweep::sweep::{
    SweepConfig, SweepOutcome, TrialContext, TrialKey, TrialObserverFactory, trust_model,
};

/// One trial to replay: a method (its display name) and a trial index.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ReplayRequest {
    /// The method's display name, as the sweep's results spell it (`RNE`, `hp_sort`).
    pub method: String,
    /// The trial index.
    pub trial: u32,
}

impl ReplayRequest {
    /// The page's file name: `replay-<method, lower case>-<trial>.html` (`replay-rne-0.html`).
    pub fn file_name(&self) -> String {
        format!(
            "replay-{}-{}.html",
            self.method.to_ascii_lowercase(),
            self.trial
        )
    }
}

/// Parses `--replay` values (`METHOD:TRIAL`, comma-separated, repeatable) against the
/// sweep's methods (display names, as [`usar_sweep::sweep::canonical_method`] gives them) and
/// trial count; `canonical` maps a name as typed (as the factory takes it, e.g. `rne` or
/// `hp_sort`) to its display name. Duplicates are dropped.
///
/// # Errors
/// [`ReplayError::Spec`] naming the first item that is not `METHOD:TRIAL`, names a method the
/// sweep does not run, or a trial outside `0..trials`.
pub fn parse_replay_list(
    specs: &[String],
    methods: &[String],
    trials: u32,
    canonical: &dyn Fn(&str) -> Option<String>,
) -> Result<Vec<ReplayRequest>, ReplayError> {
    let mut out: Vec<ReplayRequest> = Vec::new();
    for item in specs.iter().flat_map(|s| s.split(',')) {
        let item = item.trim();
        if item.is_empty() {
            continue;
        }
        let bad = |why: String| ReplayError::Spec(format!("--replay {item:?}: {why}"));
        let (m, k) = item
            .rsplit_once(':')
            .ok_or_else(|| bad("expected METHOD:TRIAL, e.g. rne:0".into()))?;
        let k: u32 = k
            .trim()
            .parse()
            .map_err(|_| bad(format!("{:?} is not a trial index", k.trim())))?;
        let method = canonical(m.trim())
            .filter(|c| methods.contains(c))
            .ok_or_else(|| {
                bad(format!(
                    "the sweep runs no method {:?} (its methods: {})",
                    m.trim(),
                    methods.join(", ")
                ))
            })?;
        if k >= trials {
            let runs = match trials {
                0 => "no trial".to_string(),
                1 => "trial 0 only".to_string(),
                n => format!("trials 0 to {}", n - 1),
            };
            return Err(bad(format!(
                "trial {k} is out of range (the sweep runs {runs})"
            )));
        }
        let r = ReplayRequest { method, trial: k };
        if !out.contains(&r) {
            out.push(r);
        }
    }
    Ok(out)
}

/// A replay page written for a sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct WrittenReplay {
    /// Grid cell index (0 without a grid).
    pub cell: usize,
    /// Which trial.
    pub request: ReplayRequest,
    /// Where.
    pub path: PathBuf,
    /// Its size, bytes.
    pub bytes: u64,
    /// Whether the trial was run again for it after the sweep (it was in the journal already).
    pub rerun: bool,
}

/// The replays of a sweep: which trials, at what rate, and what has been written.
#[derive(Debug, Clone)]
pub struct SweepReplays {
    /// The trials to replay (in every grid cell).
    pub requests: Vec<ReplayRequest>,
    /// Samples per simulated second ([`super::SampleClock`]).
    pub hz: f64,
    /// The folder of each grid cell's outputs, by cell.
    pub cell_dirs: Vec<PathBuf>,
    written: Arc<Mutex<Vec<Result<WrittenReplay, String>>>>,
}

impl SweepReplays {
    /// Replays of `requests` in every cell of `cfg`'s sweep, sampled at `hz`.
    ///
    /// # Errors
    /// [`ReplayError::Spec`] for a bad `hz`, or with a sharded sweep (`cfg.shard`): a shard
    /// runs only part of the trials; replay them with `usar replay` instead.
    pub fn new(
        cfg: &SweepConfig,
        requests: Vec<ReplayRequest>,
        hz: f64,
    ) -> Result<Self, ReplayError> {
        ReplayRecorder::new(hz)?;
        if cfg.shard.is_some() && !requests.is_empty() {
            return Err(ReplayError::Spec(
                "--replay cannot be used with --shard (run `usar replay` for a trial instead)"
                    .into(),
            ));
        }
        let cell_dirs = match &cfg.grid {
            Some(g) => g.cells.iter().map(|c| cfg.out_dir.join(&c.dir)).collect(),
            None => vec![cfg.out_dir.clone()],
        };
        Ok(Self {
            requests,
            hz,
            cell_dirs,
            written: Arc::new(Mutex::new(Vec::new())),
        })
    }

    /// A per-trial observer factory that records the requested trials (and writes their
    /// pages when they end) and also makes `inner`'s observers, if any.
    pub fn observer_factory(&self, inner: Option<TrialObserverFactory>) -> TrialObserverFactory {
        let this = self.clone();
        Arc::new(move |key: &TrialKey| {
            let own = this.observer_for(key);
            let other = inner.as_ref().and_then(|f| f(key));
            match (own, other) {
                (Some(a), Some(b)) => Some(Box::new(Pair(a, b)) as Box<dyn StepObserver>),
                (a, b) => a.or(b),
            }
        })
    }

    fn observer_for(&self, key: &TrialKey) -> Option<Box<dyn StepObserver>> {
        let request = ReplayRequest {
            method: key.method.clone(),
            trial: key.trial,
        };
        if !self.requests.contains(&request) {
            return None;
        }
        let recorder = ReplayRecorder::new(self.hz).ok()?;
        let path = self.cell_dirs.get(key.cell)?.join(request.file_name());
        Some(Box::new(WriteWhenDone {
            recorder,
            cell: key.cell,
            request,
            path,
            written: Arc::clone(&self.written),
        }))
    }

    /// After the sweep: writes the replays of requested trials this run did not run (run
    /// again alone, see the module docs), skips failed ones, and returns every replay written,
    /// by cell and request order.
    ///
    /// # Errors
    /// The first replay that could not be recorded or written (during the sweep or now).
    pub fn finish(
        &self,
        cfg: &SweepConfig,
        outcome: &SweepOutcome,
    ) -> Result<Vec<WrittenReplay>, ReplayError> {
        let during: Vec<Result<WrittenReplay, String>> =
            std::mem::take(&mut *self.written.lock().unwrap_or_else(PoisonError::into_inner));
        let mut done = Vec::new();
        for w in during {
            done.push(w.map_err(ReplayError::Spec)?);
        }
        let failed = |cell: usize, r: &ReplayRequest| {
            outcome
                .failures()
                .any(|f| f.cell == cell && f.method == r.method && f.trial == r.trial)
        };
        for (cell, scenario) in cfg.cell_scenarios().into_iter().enumerate() {
            for r in &self.requests {
                let have = done.iter().any(|w| w.cell == cell && &w.request == r);
                if have || failed(cell, r) {
                    continue;
                }
                done.push(self.rerun(cfg, cell, scenario, r)?);
            }
        }
        done.sort_by_key(|w| {
            let i = self.requests.iter().position(|r| r == &w.request);
            (w.cell, i)
        });
        Ok(done)
    }

    /// Runs trial `r` of cell `cell` again, alone, and writes its replay.
    fn rerun(
        &self,
        cfg: &SweepConfig,
        cell: usize,
        scenario: &usar_sim::scenario::Scenario,
        r: &ReplayRequest,
    ) -> Result<WrittenReplay, ReplayError> {
        let model = trust_model(scenario).map_err(|e| ReplayError::Spec(format!("{e:#}")))?;
        let arg = cfg
            .methods
            .iter()
            .find(|m| {
                usar_sweep::sweep::canonical_method(m, &cfg.method_factory, &model, cfg.base_seed)
                    .is_ok_and(|c| c == r.method)
            })
            .ok_or_else(|| ReplayError::Spec(format!("no method {}", r.method)))?;
        let ctx = TrialContext::for_trial(cfg.base_seed, r.trial);
        let method = cfg
            .method_factory
            .build(arg, &model, &ctx)
            .map_err(|e| ReplayError::Spec(format!("{e:#}")))?;
        let sim = Simulation::builder(scenario)
            .method(method)
            .trial(r.trial)
            .seed(ctx.seed)
            .duration_s(cfg.duration_of(scenario))
            .build()?;
        let t = record_trial(sim, self.hz, None)?;
        let path = self.cell_dirs[cell].join(r.file_name());
        let bytes = write_replay(scenario, &t.recording, &path)?;
        Ok(WrittenReplay {
            cell,
            request: r.clone(),
            path,
            bytes,
            rerun: true,
        })
    }
}

/// Records a trial and writes its page once it has ended.
struct WriteWhenDone {
    recorder: ReplayRecorder,
    cell: usize,
    request: ReplayRequest,
    path: PathBuf,
    written: Arc<Mutex<Vec<Result<WrittenReplay, String>>>>,
}

impl StepObserver for WriteWhenDone {
    fn on_start(&mut self, sim: &Simulation) {
        self.recorder.on_start(sim);
    }

    fn on_step(&mut self, sim: &Simulation) {
        self.recorder.on_step(sim);
        if !sim.is_finished() {
            return;
        }
        let Some(rec) = self.recorder.take() else {
            return;
        };
        let result = write_replay(sim.scenario(), &rec, &self.path)
            .map(|bytes| WrittenReplay {
                cell: self.cell,
                request: self.request.clone(),
                path: self.path.clone(),
                bytes,
                rerun: false,
            })
            .map_err(|e| {
                format!(
                    "replay of {} trial {}: {e}",
                    self.request.method, self.request.trial
                )
            });
        self.written
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .push(result);
    }
}

/// Two boxed observers, called in order.
struct Pair(Box<dyn StepObserver>, Box<dyn StepObserver>);

impl StepObserver for Pair {
    fn on_start(&mut self, sim: &Simulation) {
        self.0.on_start(sim);
        self.1.on_start(sim);
    }

    fn on_step(&mut self, sim: &Simulation) {
        self.0.on_step(sim);
        self.1.on_step(sim);
    }
}

#[cfg(test)]
mod tests {
    use rne_core::grouping::{Eng, GroupingMethod};

    use super::*;
    use usar_sweep::sweep::{MethodFactory, canonical_method};

    /// ENG under the name `hp_sort`.
    struct HpSort;

    impl GroupingMethod for HpSort {
        fn name(&self) -> &str {
            "hp_sort"
        }
        fn assign(
            &self,
            request: &rne_core::grouping::GroupingRequest,
        ) -> rne_core::Result<rne_core::grouping::Assignment> {
            Eng.assign(request)
        }
    }

    /// A name as typed on the command line to its display name, through a factory that knows
    /// the built-ins and `hp_sort`.
    fn canon(m: &str) -> Option<String> {
        let factory = MethodFactory::new(|name, model, ctx| match name {
            "hp_sort" => Ok(Box::new(HpSort) as Box<dyn GroupingMethod>),
            other => MethodFactory::builtin().build(other, model, ctx),
        });
        let model = rne_core::TrustModel::with_weights(rne_core::Weights::uniform(7).ok()?);
        canonical_method(m, &factory, &model, 1).ok()
    }

    #[test]
    fn replay_lists_are_parsed_and_checked_against_the_sweep() {
        let methods = vec!["RNE".to_string(), "DIS".to_string(), "hp_sort".to_string()];
        let specs = vec!["rne:0, DIS:2".to_string(), "rne:0,hp_sort:1".to_string()];
        let got = parse_replay_list(&specs, &methods, 3, &canon).unwrap();
        let want = [("RNE", 0), ("DIS", 2), ("hp_sort", 1)].map(|(m, trial)| ReplayRequest {
            method: m.into(),
            trial,
        });
        assert_eq!(got, want);
        assert_eq!(got[1].file_name(), "replay-dis-2.html");
        assert_eq!(got[2].file_name(), "replay-hp_sort-1.html");
        let err = |s: &str| {
            parse_replay_list(&[s.to_string()], &methods, 3, &canon)
                .unwrap_err()
                .to_string()
        };
        assert!(err("rne:3").contains("trial 3 is out of range (the sweep runs trials 0 to 2)"));
        assert!(err("eng:0").contains("the sweep runs no method \"eng\""));
        assert!(err("foo:0").contains("no method"));
        // A method of the user's own is matched as its factory knows it, not re-cased.
        assert!(err("HP_SORT:0").contains("the sweep runs no method \"HP_SORT\""));
        assert!(err("rne").contains("expected METHOD:TRIAL"));
        assert!(err("rne:x").contains("is not a trial index"));
        assert!(!err("rne:-1").is_empty());
    }
}
