//! The plan of a sharded sweep: what `usar sweep` was asked to run (the scenario file's text
//! and the sweep options), kept as `plan.json` in every shard's folder so that `usar merge`
//! can rebuild the sweep's configuration, and so that messages can give the exact command
//! that runs a shard again.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use usar_sim::scenario::path_text;

use crate::atomic::{FileError, write_atomic};
use crate::bounded_file::{MAX_SHARD_PLAN_BYTES, read_small};
use crate::data::shard_split::Shard;

/// Why a plan could not be written or read.
#[derive(Debug, thiserror::Error)]
pub enum PlanError {
    /// An I/O error, naming the path.
    #[error(transparent)]
    File(#[from] FileError),
    /// The file is not the JSON of a plan.
    #[error("{path}: not a sweep plan")]
    NotAPlan {
        /// The file's path, as shown.
        path: String,
        /// serde_json's error.
        #[source]
        source: serde_json::Error,
    },
    /// The plan could not be written as JSON (not expected).
    #[error("serialising the sweep plan")]
    Serialise(#[source] serde_json::Error),
}

/// File name of the plan in a shard's folder.
pub const PLAN_FILE: &str = "plan.json";

/// The options of `usar sweep` that decide what a sweep runs (not how: threads, resume and
/// progress are left out), with the scenario file's text.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepPlan {
    /// The scenario file as it was named on the command line (relative to the folder the
    /// command ran in); used in reports and in the commands messages suggest.
    pub scenario_path: PathBuf,
    /// The scenario file's text when the shard ran (what `usar merge` loads, so that a later
    /// edit of the file cannot change a merge; the journal's scenario hashes guard the rest).
    pub scenario_text: String,
    /// The `--vary` arguments, in order (empty: no grid).
    pub vary: Vec<String>,
    /// The `--methods` names, in order, as given.
    pub methods: Vec<String>,
    /// `--trials` (>= 1).
    pub trials: u32,
    /// `--seed`; `None`: the scenario's `sim.seed`.
    pub seed: Option<u64>,
    /// `--duration`, seconds; `None`: each cell's `mission.duration_s`.
    pub duration_s: Option<f64>,
    /// `--grid-metrics` (empty: the default metrics).
    pub grid_metrics: Vec<String>,
    /// The folder the shard's command ran in, absolute: [`SweepPlan::shard_command`] run from
    /// another folder makes the scenario path absolute against it. `None` when unknown (a
    /// plan written before this field existed, or no current folder).
    #[serde(default)]
    pub working_dir: Option<PathBuf>,
    /// `--targets`: the targets file the reports compare with, as given (relative to
    /// `working_dir`); `None`: none. A report option: `usar merge` renders with it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub targets: Option<PathBuf>,
    /// `--claims`: the claims file the reports check, as given (relative to `working_dir`);
    /// `None`: none. A report option: `usar merge` renders with it. (A plan of an older
    /// `usar` with `"claims": true` reads as none: `usar merge --claims FILE` gives them.)
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "de_claims"
    )]
    pub claims: Option<PathBuf>,
}

/// A claims path, or the former boolean, read as none either way (the file it meant is not
/// known; `usar merge --claims scenarios/paper-claims.ron` checks the paper's).
fn de_claims<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<PathBuf>, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum PathOrBool {
        // The former flag; its value no longer says which claims.
        Bool(#[allow(dead_code)] bool),
        Path(Option<PathBuf>),
    }
    match PathOrBool::deserialize(d)? {
        PathOrBool::Bool(_) => Ok(None),
        PathOrBool::Path(p) => Ok(p),
    }
}

impl SweepPlan {
    /// Path of the plan in the folder `dir`.
    pub fn path_in(dir: &Path) -> PathBuf {
        dir.join(PLAN_FILE)
    }

    /// Writes the plan as `dir/plan.json` (pretty JSON, atomically).
    ///
    /// # Errors
    /// An I/O error.
    pub fn write(&self, dir: &Path) -> Result<(), PlanError> {
        let json = serde_json::to_string_pretty(self).map_err(PlanError::Serialise)?;
        Ok(write_atomic(
            &Self::path_in(dir),
            format!("{json}\n").as_bytes(),
        )?)
    }

    /// Reads `dir/plan.json` ([`read_small`]: at most [`MAX_SHARD_PLAN_BYTES`] of a regular
    /// file).
    ///
    /// # Errors
    /// A missing or unreadable file, one that is not a regular file or is longer than the
    /// limit, or one that is not a plan.
    pub fn read(dir: &Path) -> Result<Self, PlanError> {
        let path = Self::path_in(dir);
        let bytes = read_small(&path, MAX_SHARD_PLAN_BYTES)?;
        serde_json::from_slice(&bytes).map_err(|source| PlanError::NotAPlan {
            path: path_text(&path),
            source,
        })
    }

    /// The options after `SCENARIO` that repeat this sweep: `--methods`, `--trials`, then
    /// `--seed`, `--duration`, each `--vary`, `--grid-metrics`, `--targets` and `--claims`
    /// when given. Numbers are written so that they parse back to the same value.
    pub fn sweep_options(&self) -> Vec<String> {
        self.options_with_files(self.targets.as_deref(), self.claims.as_deref())
    }

    /// The targets file of `--targets` as a path from `here` (the current folder): as given
    /// when `here` is [`SweepPlan::working_dir`] (or either is unknown), else joined to the
    /// folder the shard ran in.
    pub fn targets_path(&self, here: Option<&Path>) -> Option<PathBuf> {
        self.seen_from(self.targets.as_ref()?, here)
    }

    /// The claims file of `--claims` as a path from `here`, as [`SweepPlan::targets_path`].
    pub fn claims_path(&self, here: Option<&Path>) -> Option<PathBuf> {
        self.seen_from(self.claims.as_ref()?, here)
    }

    /// `t` (relative to [`SweepPlan::working_dir`]) as a path from `here`.
    fn seen_from(&self, t: &Path, here: Option<&Path>) -> Option<PathBuf> {
        Some(match (&self.working_dir, here) {
            (Some(wd), Some(here)) if wd != here => wd.join(t),
            _ => t.to_path_buf(),
        })
    }

    /// [`SweepPlan::sweep_options`] with `targets` and `claims` for the report files.
    fn options_with_files(&self, targets: Option<&Path>, claims: Option<&Path>) -> Vec<String> {
        let mut a = vec![
            "--methods".to_string(),
            self.methods.join(","),
            "--trials".to_string(),
            self.trials.to_string(),
        ];
        if let Some(seed) = self.seed {
            a.extend(["--seed".to_string(), seed.to_string()]);
        }
        if let Some(d) = self.duration_s {
            a.extend(["--duration".to_string(), d.to_string()]);
        }
        for v in &self.vary {
            a.extend(["--vary".to_string(), v.clone()]);
        }
        if !self.grid_metrics.is_empty() {
            a.extend(["--grid-metrics".to_string(), self.grid_metrics.join(",")]);
        }
        if let Some(t) = targets {
            a.extend(["--targets".to_string(), t.display().to_string()]);
        }
        if let Some(c) = claims {
            a.extend(["--claims".to_string(), c.display().to_string()]);
        }
        a
    }

    /// The shell command that runs (or continues) `shard` of this sweep into `out_dir`:
    /// `usar sweep SCENARIO <options> --shard I/N --out DIR`, every word quoted for a POSIX
    /// shell where it needs it.
    ///
    /// `out_dir` is relative to `here`, the folder the command is shown in, and so is the
    /// command when `here` is [`SweepPlan::working_dir`] (or that is unknown); otherwise the
    /// scenario path and `out_dir` are made absolute, so that the command runs from any
    /// folder.
    pub fn shard_command(&self, shard: Shard, out_dir: &Path, here: Option<&Path>) -> String {
        let (scenario, out) = match (&self.working_dir, here) {
            (Some(wd), Some(here)) if wd != here => {
                (wd.join(&self.scenario_path), here.join(out_dir))
            }
            _ => (self.scenario_path.clone(), out_dir.to_path_buf()),
        };
        let targets = self.targets_path(here);
        let claims = self.claims_path(here);
        let mut words = vec![
            "usar".to_string(),
            "sweep".to_string(),
            scenario.display().to_string(),
        ];
        words.extend(self.options_with_files(targets.as_deref(), claims.as_deref()));
        words.extend([
            "--shard".to_string(),
            shard.to_string(),
            "--out".to_string(),
            out.display().to_string(),
        ]);
        shell_join(&words)
    }
}

/// `words` joined by spaces, each quoted for a POSIX shell where it needs it
/// (`shlex::try_quote`; a word with a NUL byte, which no shell can pass, is written as is).
pub fn shell_join(words: &[String]) -> String {
    words
        .iter()
        .map(|w| shlex::try_quote(w).map_or_else(|_| w.clone(), |q| q.into_owned()))
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan(working_dir: Option<&str>) -> SweepPlan {
        SweepPlan {
            scenario_path: "scenarios/my paper.ron".into(),
            scenario_text: String::new(),
            vary: Vec::new(),
            methods: vec!["rne".into(), "dis".into()],
            trials: 2,
            seed: None,
            duration_s: None,
            grid_metrics: Vec::new(),
            working_dir: working_dir.map(PathBuf::from),
            targets: None,
            claims: None,
        }
    }

    #[test]
    fn a_command_shown_in_another_folder_than_the_shards_has_absolute_paths() {
        let shard = Shard::new(1, 2).unwrap();
        let relative = "usar sweep 'scenarios/my paper.ron' --methods 'rne,dis' --trials 2 \
                        --shard 1/2 --out 'out dir'";
        let out = Path::new("out dir");
        // Shown where the shard ran, or with either folder unknown: as the shard was run.
        let here = Some(Path::new("/home/me"));
        assert_eq!(
            plan(Some("/home/me")).shard_command(shard, out, here),
            relative
        );
        assert_eq!(plan(None).shard_command(shard, out, here), relative);
        assert_eq!(
            plan(Some("/home/me")).shard_command(shard, out, None),
            relative
        );
        assert_eq!(
            plan(Some("/home/me")).shard_command(shard, out, Some(Path::new("/tmp"))),
            "usar sweep '/home/me/scenarios/my paper.ron' --methods 'rne,dis' --trials 2 \
             --shard 1/2 --out '/tmp/out dir'"
        );
    }

    #[test]
    fn report_options_are_repeated_and_made_absolute_with_the_scenario() {
        let shard = Shard::new(0, 2).unwrap();
        let mut p = plan(Some("/home/me"));
        p.targets = Some("t.ron".into());
        p.claims = Some("c.ron".into());
        let out = Path::new("o");
        assert!(
            p.shard_command(shard, out, Some(Path::new("/home/me")))
                .ends_with("--trials 2 --targets t.ron --claims c.ron --shard 0/2 --out o")
        );
        assert!(
            p.shard_command(shard, out, Some(Path::new("/tmp")))
                .contains("--targets /home/me/t.ron --claims /home/me/c.ron")
        );
        let targets = |here: &str| p.targets_path(Some(Path::new(here)));
        assert_eq!(targets("/tmp"), Some(PathBuf::from("/home/me/t.ron")));
        assert_eq!(targets("/home/me"), Some(PathBuf::from("t.ron")));
        // A plan without report options has no such fields (plan.json as before).
        let json = serde_json::to_value(plan(None)).unwrap();
        assert!(json.get("targets").is_none() && json.get("claims").is_none());
    }

    #[test]
    fn a_plan_without_a_working_dir_still_reads() {
        let mut json = serde_json::to_value(plan(Some("/x"))).unwrap();
        json.as_object_mut().unwrap().remove("working_dir");
        let read: SweepPlan = serde_json::from_value(json).unwrap();
        assert_eq!(read, plan(None));
    }

    #[test]
    fn an_older_plans_claims_flag_reads_as_none() {
        // Shards of an older usar still merge (`usar merge --claims FILE` adds the claims).
        let mut json = serde_json::to_value(plan(None)).unwrap();
        for old in [false, true] {
            json["claims"] = old.into();
            let read: SweepPlan = serde_json::from_value(json.clone()).unwrap();
            assert_eq!(read.claims, None);
        }
        json["claims"] = "c.ron".into();
        let read: SweepPlan = serde_json::from_value(json).unwrap();
        assert_eq!(read.claims, Some(PathBuf::from("c.ron")));
    }
}
