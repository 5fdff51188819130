//! The plan of a multiverse, `multiverse.json`: what it runs ([`MultiverseIdentity`]: the
//! base scenario's hash, the axes, targets, free fields, methods, trials, seeds, budget,
//! sample and the build of `usar`) and how it was asked for (the paths as given, the working
//! folder, the output folder). A run writes it at the top of its output folder (a shard into
//! its shard folder, `shards/<I>-of-<N>/`); a run finds a plan of another identity there and
//! refuses (or with `--overwrite` starts afresh); `usar merge` rebuilds the outputs from it
//! and the universes' records, and names the commands that run missing shards.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use usar_sim::scenario::path_text;

use super::axes::Axes;
use super::error::MultiverseError;
use super::setup::{CheckedMultiverse, MultiverseSetup};
use super::universe::{Sample, Universe, factorial_size, select};
use crate::calibrate::{FreeField, Optimizer, Target};
use usar_report::claims::Claim;
use usar_sweep::atomic::write_atomic;
use usar_sweep::bounded_file::{MAX_MULTIVERSE_PLAN_BYTES, read_small};
use usar_sweep::data::owner::RunKind;
use usar_sweep::fingerprint::{fnv1a64_hex, scenario_hash};
use usar_sweep::shard::{Shard, shell_join};
use usar_sweep::slurm::ShardedWork;

/// What the functions of this module return.
type Result<T, E = MultiverseError> = std::result::Result<T, E>;

/// The plan's file name.
pub const PLAN_FILE: &str = usar_sweep::data::owner::evidence::MULTIVERSE_PLAN;

/// The plan's format (1); another format is another multiverse.
pub const PLAN_FORMAT: u32 = 1;

/// What a multiverse runs: two runs with equal identities make the same universes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MultiverseIdentity {
    /// [`PLAN_FORMAT`].
    pub format: u32,
    /// The version of `usar`.
    pub version: String,
    /// The build of `usar` (`git describe`, [`usar_report::report::software_build`]): another build
    /// may simulate differently.
    pub build: String,
    /// The base scenario's name.
    pub scenario: String,
    /// The base scenario's hash ([`usar_sweep::fingerprint::scenario_hash`]).
    pub scenario_hash: String,
    /// The axes.
    pub axes: Axes,
    /// The calibration targets.
    pub targets: Vec<Target>,
    /// The claims each universe's comparison checks, in file order (none: only
    /// admissibility). A plan written before claims files read as the paper's five
    /// (`scenarios/paper-claims.ron`), which every multiverse then checked.
    #[serde(default = "paper_claims_list")]
    pub claims: Vec<Claim>,
    /// The free fields.
    pub free: Vec<FreeField>,
    /// The methods' display names, in order.
    pub methods: Vec<String>,
    /// Comparison trials per method.
    pub trials: u32,
    /// Base seed of the comparison.
    pub seed: u64,
    /// Trial length, seconds (`None`: each universe's `mission.duration_s`).
    pub duration_s: Option<f64>,
    /// Trials per method of each calibration evaluation.
    pub calibration_trials: u32,
    /// Base seed of the calibrations.
    pub calibration_seed: u64,
    /// Most evaluations per calibration.
    pub max_evals: usize,
    /// Significant digits of the calibrated values.
    pub digits: u32,
    /// The sample of universes (`None`: the full factorial).
    pub sample: Option<Sample>,
    /// Design evaluations shared by the universes' calibrations (`--design`; 0: none, and
    /// then absent from the JSON, as in plans written before designs).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub design: usize,
    /// The calibrations' search, `cma-es` (`None`: Nelder-Mead, absent from the JSON).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub optimizer: Option<String>,
    /// The calibrations' check on unseen trials (`None`: none, absent from the JSON).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub check: Option<UnseenCheck>,
}

/// A check of each calibration's points in band on unseen trials
/// ([`MultiverseIdentity::check`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct UnseenCheck {
    /// Trials per method (>= 1).
    pub trials: u32,
    /// Their base seed.
    pub seed: u64,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

/// The name `--optimizer` takes for `o`, or `None` for the default (Nelder-Mead).
fn optimizer_name(o: Optimizer) -> Option<String> {
    match o {
        Optimizer::NelderMead => None,
        Optimizer::CmaEs => Some("cma-es".into()),
    }
}

/// The paper's claims, for a plan written before claims files ([`MultiverseIdentity::claims`]).
fn paper_claims_list() -> Vec<Claim> {
    usar_report::claims::paper_claims().claims().to_vec()
}

/// A multiverse's plan: its identity and how it was asked for.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MultiversePlan {
    /// What it runs.
    pub identity: MultiverseIdentity,
    /// The base scenario's path as given.
    pub scenario_path: String,
    /// The axes file's path as given.
    pub axes_path: String,
    /// The targets file's path as given.
    pub targets_path: String,
    /// The claims file's path as given (`None`: no claims).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub claims_path: Option<String>,
    /// `--near-loss`: the largest calibration loss of a near-admissible universe, whose shares
    /// `multiverse.md` gives as a sensitivity variant (`None`: none). A report option, not
    /// part of the identity.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub near_loss: Option<f64>,
    /// The output folder as given.
    pub out: PathBuf,
    /// The folder the paths are relative to (absolute), when known.
    pub working_dir: Option<PathBuf>,
}

impl MultiversePlan {
    /// The plan of `setup` (checked as `checked`) writing into `out`.
    ///
    /// # Errors
    /// The scenario cannot be serialised for its hash (not expected).
    pub fn of(setup: &MultiverseSetup, checked: &CheckedMultiverse, out: &Path) -> Result<Self> {
        Ok(Self {
            identity: MultiverseIdentity {
                format: PLAN_FORMAT,
                version: env!("CARGO_PKG_VERSION").to_string(),
                build: usar_sweep::data::software::software_build().to_owned(),
                scenario: checked.scenario.name().to_owned(),
                scenario_hash: scenario_hash(&checked.scenario).map_err(|source| {
                    MultiverseError::Serialise {
                        what: "the scenario",
                        source,
                    }
                })?,
                axes: setup.axes.clone(),
                targets: setup.targets.targets().to_vec(),
                claims: setup
                    .claims
                    .as_ref()
                    .map_or_else(Vec::new, |c| c.claims().to_vec()),
                free: setup.free.clone(),
                methods: checked.methods.clone(),
                trials: setup.comparison.trials,
                seed: setup.comparison.base_seed,
                duration_s: setup.comparison.duration_s,
                calibration_trials: setup.calibration_trials,
                calibration_seed: setup.calibration_seed,
                max_evals: setup.max_evals,
                digits: setup.digits,
                sample: setup.sample,
                design: setup.design,
                optimizer: optimizer_name(setup.optimizer),
                check: (setup.check_trials > 0).then_some(UnseenCheck {
                    trials: setup.check_trials,
                    seed: setup.check_seed(),
                }),
            },
            scenario_path: setup.origin.clone(),
            axes_path: setup.axes.origin().to_owned(),
            targets_path: setup.targets.origin().to_owned(),
            claims_path: setup.claims.as_ref().map(|c| c.origin().to_owned()),
            near_loss: setup.near_loss,
            out: out.to_path_buf(),
            working_dir: setup.working_dir.clone(),
        })
    }

    /// The identity's checksum: FNV-1a 64 of its JSON ([`fnv1a64_hex`]); records verify
    /// against it.
    pub fn identity_sum(&self) -> String {
        let json = serde_json::to_string(&self.identity).unwrap_or_default();
        fnv1a64_hex(json.as_bytes())
    }

    /// The plan's path in `dir`.
    pub fn path_in(dir: &Path) -> PathBuf {
        dir.join(PLAN_FILE)
    }

    /// Writes the plan as `dir/multiverse.json` (pretty JSON, atomically).
    ///
    /// # Errors
    /// An I/O error.
    pub fn write(&self, dir: &Path) -> Result<()> {
        let json =
            serde_json::to_string_pretty(self).map_err(|source| MultiverseError::Serialise {
                what: "the plan",
                source,
            })?;
        Ok(write_atomic(
            &Self::path_in(dir),
            format!("{json}\n").as_bytes(),
        )?)
    }

    /// Reads `dir/multiverse.json` (at most [`MAX_MULTIVERSE_PLAN_BYTES`] of a regular file,
    /// [`read_small`]); `None` when there is none.
    ///
    /// # Errors
    /// An unreadable file, one that is not a regular file or is longer than the limit, or one
    /// that is not a multiverse plan.
    pub fn read(dir: &Path) -> Result<Option<Self>> {
        let path = Self::path_in(dir);
        if !usar_sweep::journal::something_at(&path) {
            return Ok(None);
        }
        let bytes = read_small(&path, MAX_MULTIVERSE_PLAN_BYTES)?;
        let plan = serde_json::from_slice(&bytes).map_err(|source| MultiverseError::NotAPlan {
            path: path_text(&path),
            source,
        })?;
        Ok(Some(plan))
    }

    /// Whether the universes are a `--sample` smaller than the factorial (their shares are
    /// estimates of the factorial's, with intervals).
    pub fn sampled(&self) -> bool {
        self.identity
            .sample
            .is_some_and(|s| (s.n as u64) < self.factorial())
    }

    /// The size of the full factorial.
    pub fn factorial(&self) -> u64 {
        factorial_size(&self.identity.axes.sizes()).unwrap_or(0)
    }

    /// The universes the multiverse runs, in index order (empty if the plan's axes or sample
    /// are refused, which a written plan's never are).
    pub fn universes(&self) -> Vec<Universe> {
        select(&self.identity.axes.sizes(), self.identity.sample).unwrap_or_default()
    }

    /// The options after `SCENARIO` that repeat this multiverse (every one written out, so
    /// that the command does not depend on defaults).
    pub fn options(&self) -> Vec<String> {
        let id = &self.identity;
        let mut a = vec!["--axes".to_string(), self.axes_path.clone()];
        a.extend(["--targets".to_string(), self.targets_path.clone()]);
        for t in id.targets.iter().filter(|t| t.report_only) {
            a.extend(["--report-only".to_string(), t.name.clone()]);
        }
        if let Some(c) = &self.claims_path {
            a.extend(["--claims".to_string(), c.clone()]);
        }
        if let Some(l) = self.near_loss {
            a.extend(["--near-loss".to_string(), l.to_string()]);
        }
        for f in &id.free {
            a.extend(["--free".to_string(), f.to_string()]);
        }
        a.extend(["--methods".to_string(), id.methods.join(",").to_lowercase()]);
        a.extend(["--trials".to_string(), id.trials.to_string()]);
        a.extend(["--seed".to_string(), id.seed.to_string()]);
        if let Some(d) = id.duration_s {
            a.extend(["--duration".to_string(), d.to_string()]);
        }
        a.extend([
            "--calibration-trials".to_string(),
            id.calibration_trials.to_string(),
            "--calibration-seed".to_string(),
            id.calibration_seed.to_string(),
            "--max-evals".to_string(),
            id.max_evals.to_string(),
        ]);
        if let Some(s) = id.sample {
            a.extend([
                "--sample".to_string(),
                s.n.to_string(),
                "--sample-seed".to_string(),
                s.seed.to_string(),
            ]);
        }
        if id.design > 0 {
            a.extend(["--design".to_string(), id.design.to_string()]);
        }
        if let Some(o) = &id.optimizer {
            a.extend(["--optimizer".to_string(), o.clone()]);
        }
        if let Some(c) = id.check {
            a.extend([
                "--check-trials".to_string(),
                c.trials.to_string(),
                "--check-seed".to_string(),
                c.seed.to_string(),
            ]);
        }
        a
    }

    /// `usar multiverse SCENARIO <options> [--shard I/N] --out OUT` for a POSIX shell, with
    /// the paths as given (see [`MultiversePlan::shard_command`] for another folder).
    pub fn command(&self, shard: Option<Shard>) -> String {
        self.command_at(shard, &self.out, None)
    }

    /// The command that runs (or continues) `shard` into `out_dir` as shown in the folder
    /// `here`: when that is not [`MultiversePlan::working_dir`], the file paths and `out_dir`
    /// are made absolute so that it runs from anywhere.
    pub fn shard_command(&self, shard: Shard, out_dir: &Path, here: Option<&Path>) -> String {
        self.command_at(Some(shard), out_dir, here)
    }

    /// The command that runs `shard` (or, for `None`, every universe) into `out_dir`, shown
    /// in the folder `here` (see [`MultiversePlan::shard_command`]).
    pub fn command_at(&self, shard: Option<Shard>, out_dir: &Path, here: Option<&Path>) -> String {
        let moved = match (&self.working_dir, here) {
            (Some(wd), Some(here)) if wd != here => Some((wd, here)),
            _ => None,
        };
        let file = |p: &str| match moved {
            Some((wd, _)) => wd.join(p).display().to_string(),
            None => p.to_string(),
        };
        let mut plan = self.clone();
        plan.axes_path = file(&self.axes_path);
        plan.targets_path = file(&self.targets_path);
        plan.claims_path = self.claims_path.as_deref().map(file);
        let mut words = vec![
            "usar".to_string(),
            "multiverse".to_string(),
            file(&self.scenario_path),
        ];
        words.extend(plan.options());
        if let Some(s) = shard {
            words.extend(["--shard".to_string(), s.to_string()]);
        }
        let out = match moved {
            Some((_, here)) => here.join(out_dir),
            None => out_dir.to_path_buf(),
        };
        words.extend(["--out".to_string(), out.display().to_string()]);
        shell_join(&words)
    }
}

impl ShardedWork for MultiversePlan {
    fn subcommand(&self) -> &'static str {
        "multiverse"
    }

    fn run_kind(&self) -> RunKind {
        RunKind::Multiverse
    }

    fn scenario_file(&self) -> PathBuf {
        PathBuf::from(&self.scenario_path)
    }

    fn work_options(&self) -> Vec<String> {
        self.options()
    }

    fn merged_files(&self) -> &'static str {
        "multiverse.csv, multiverse.md and the specification curves"
    }
}

/// What differs between two identities, for a refusal: `trials 2 vs 10, axes differ`
/// (values of up to 40 characters are shown, longer ones only named).
pub fn identity_diff(old: &MultiverseIdentity, new: &MultiverseIdentity) -> String {
    let (a, b) = (
        serde_json::to_value(old).unwrap_or_default(),
        serde_json::to_value(new).unwrap_or_default(),
    );
    let (Some(a), Some(b)) = (a.as_object(), b.as_object()) else {
        return "another multiverse".into();
    };
    // Both plans' keys: a field at its default is left out of the JSON (a design, a check).
    let keys = a.keys().chain(b.keys().filter(|k| !a.contains_key(*k)));
    let diffs: Vec<String> = keys
        .filter(|k| a.get(*k) != b.get(*k))
        .map(|k| {
            let text = |m: &serde_json::Map<String, serde_json::Value>| {
                m.get(k).map_or("none".into(), |w| w.to_string())
            };
            let (x, y) = (text(a), text(b));
            if x.len() <= 40 && y.len() <= 40 {
                format!("{k} {x} vs {y}")
            } else {
                format!("{k} differ")
            }
        })
        .collect();
    if diffs.is_empty() {
        "the same multiverse".into()
    } else {
        diffs.join(", ")
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::calibrate::{Band, Statistic, Target};

    /// A plan over two axes (2 and 3 alternatives) with two free fields.
    pub(crate) fn plan() -> MultiversePlan {
        let src = "Axes(axes: [\n  (name: \"a\", paper: \"\\\"x\\\" (I)\", alternatives: [(name: \"a0\"), \
                   (name: \"a1\", set: [\"mission.pickup_s=2\"])]),\n  (name: \"b\", \
                   alternatives: [(name: \"b0\"), (name: \"b1\", set: [\"mission.recharge_s=3\"]), \
                   (name: \"b2\", set: [\"mission.recharge_s=4\"])]),\n])";
        let axes = Axes::parse(src, "axes.ron").unwrap();
        MultiversePlan {
            identity: MultiverseIdentity {
                format: PLAN_FORMAT,
                version: "0.1.0".into(),
                build: "abc".into(),
                scenario: "paper".into(),
                scenario_hash: "0123456789abcdef".into(),
                axes,
                targets: vec![Target {
                    name: "rounds".into(),
                    statistic: Statistic::Mean(usar_report::targets::MetricRef("rounds".into())),
                    value: 6.0,
                    band: Band::PlusMinus(1.0),
                    report_only: false,
                }],
                claims: usar_report::claims::paper_claims().claims().to_vec(),
                free: vec![
                    FreeField::parse("mission.energy_pct_per_m=0.05..0.2").unwrap(),
                    FreeField::parse("mission.hp_pct_per_step_in_radiation=0.001..0.02:log")
                        .unwrap(),
                ],
                methods: vec!["RNE".into(), "DIS".into()],
                trials: 2,
                seed: 2021,
                duration_s: Some(30.0),
                calibration_trials: 1,
                calibration_seed: 2021,
                max_evals: 3,
                digits: 4,
                sample: None,
                design: 0,
                optimizer: None,
                check: None,
            },
            scenario_path: "scenarios/paper.ron".into(),
            axes_path: "my axes.ron".into(),
            targets_path: "t.ron".into(),
            claims_path: None,
            near_loss: None,
            out: "out".into(),
            working_dir: Some("/home/me".into()),
        }
    }

    #[test]
    fn the_command_repeats_the_multiverse() {
        let p = plan();
        assert_eq!(
            p.command(None),
            "usar multiverse scenarios/paper.ron --axes 'my axes.ron' --targets t.ron --free \
             'mission.energy_pct_per_m=0.05..0.2' --free \
             'mission.hp_pct_per_step_in_radiation=0.001..0.02:log' --methods 'rne,dis' \
             --trials 2 --seed 2021 --duration 30 --calibration-trials 1 --calibration-seed \
             2021 --max-evals 3 --out out"
        );
        let s = Shard::new(1, 2).unwrap();
        let elsewhere = p.shard_command(s, Path::new("out"), Some(Path::new("/tmp")));
        assert!(
            elsewhere.starts_with("usar multiverse /home/me/scenarios/paper.ron --axes '/home/me/my axes.ron' --targets /home/me/t.ron"),
            "{elsewhere}"
        );
        assert!(
            elsewhere.ends_with("--shard 1/2 --out /tmp/out"),
            "{elsewhere}"
        );
        assert!(
            p.shard_command(s, Path::new("out"), Some(Path::new("/home/me")))
                .ends_with("--shard 1/2 --out out")
        );
    }

    #[test]
    fn a_plan_reads_back_and_diffs_name_what_changed() {
        let dir = tempfile::tempdir().unwrap();
        assert!(MultiversePlan::read(dir.path()).unwrap().is_none());
        let p = plan();
        p.write(dir.path()).unwrap();
        let back = MultiversePlan::read(dir.path()).unwrap().unwrap();
        assert_eq!(back, p);
        assert_eq!(back.identity_sum(), p.identity_sum());
        assert_eq!(p.universes().len(), 6);
        assert_eq!(p.factorial(), 6);
        let mut q = p.identity.clone();
        q.trials = 10;
        q.axes.axes[0].paper = "y".repeat(50);
        assert_eq!(
            identity_diff(&p.identity, &q),
            "axes differ, trials 2 vs 10"
        );
        // A field left out of one plan's JSON at its default is named too, either way.
        let mut d = p.identity.clone();
        d.design = 12;
        d.check = Some(UnseenCheck { trials: 1, seed: 7 });
        assert_eq!(
            identity_diff(&p.identity, &d),
            "design none vs 12, check none vs {\"trials\":1,\"seed\":7}"
        );
        assert_eq!(
            identity_diff(&d, &p.identity),
            "design 12 vs none, check {\"trials\":1,\"seed\":7} vs none"
        );
        assert_ne!(
            MultiversePlan {
                identity: q,
                ..p.clone()
            }
            .identity_sum(),
            p.identity_sum()
        );
        std::fs::write(MultiversePlan::path_in(dir.path()), "{").unwrap();
        let e = format!("{:#}", MultiversePlan::read(dir.path()).unwrap_err());
        assert!(e.contains("not a multiverse plan"), "{e}");
    }
}
