//! The files `usar slurm` writes into `<out>/slurm/`: an sbatch script for a job array (one
//! task per shard of the sweep or multiverse, [`ShardedWork`]), an sbatch script for the
//! merge, and `submit.sh`, which submits both with the merge chained to the array by
//! `--dependency=afterok`.
//!
//! The scripts are plain and commented so that a user can edit them (a module to load, a
//! quality of service, another time limit). Reference: Slurm's `sbatch(1)` (job arrays,
//! `SLURM_ARRAY_TASK_ID`, `SLURM_CPUS_PER_TASK`, `--parsable`, `--dependency=afterok:<id>`).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use usar_sim::scenario::path_text;

use crate::atomic::FileError;
use crate::data::owner::RunKind;
use crate::data::owner::before_claim::{SLURM_JOB_EXT, SLURM_LOG_EXT, SLURM_LOGS, SLURM_SUBMIT};
use crate::shard::{MAX_SHARDS, SweepPlan, shell_join};
use crate::slurm::error::SlurmError;

/// What the functions of this module return.
type Result<T> = std::result::Result<T, SlurmError>;

/// What the tasks of a Slurm array run, shard by shard: a sweep ([`SweepPlan`], `usar sweep
/// ... --shard I/N`) or a multiverse (`usar_study::multiverse::MultiversePlan`, `usar multiverse
/// ... --shard I/N`); the merge job runs `usar merge OUT` for both.
pub trait ShardedWork {
    /// The `usar` subcommand each task runs: `sweep` or `multiverse`. It also names the
    /// array's script (`<subcommand>.sbatch`) and its logs.
    fn subcommand(&self) -> &'static str;
    /// The kind of run whose folder the shards and the merge write into
    /// ([`RunKind::ShardedSweep`] or [`RunKind::Multiverse`]).
    fn run_kind(&self) -> RunKind;
    /// The scenario file as named on the command line (relative to the working folder).
    fn scenario_file(&self) -> PathBuf;
    /// The options after the scenario that repeat the work (without `--shard`, `--out`,
    /// `--threads`).
    fn work_options(&self) -> Vec<String>;
    /// What the merge writes, in words, for the scripts' comments.
    fn merged_files(&self) -> &'static str;
}

impl ShardedWork for SweepPlan {
    fn subcommand(&self) -> &'static str {
        "sweep"
    }

    fn run_kind(&self) -> RunKind {
        RunKind::ShardedSweep
    }

    fn scenario_file(&self) -> PathBuf {
        self.scenario_path.clone()
    }

    fn work_options(&self) -> Vec<String> {
        self.sweep_options()
    }

    fn merged_files(&self) -> &'static str {
        "trials.csv, summary.csv, the figures and report.md"
    }
}

/// Name of the folder, under the sweep's output folder, that holds the Slurm files.
pub const SLURM_DIR: &str = crate::data::owner::before_claim::SLURM_SCRIPTS;

/// The Slurm resources of the array's tasks (and of the merge job, which takes one CPU).
/// Each value is passed to `#SBATCH` as written; `None` leaves the cluster's default.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SlurmOptions {
    /// Array tasks, one shard each, `1..=MAX_SHARDS`.
    pub shards: usize,
    /// `--partition`.
    pub partition: Option<String>,
    /// `--time`, the limit per task in one of Slurm's formats (`MM`, `MM:SS`, `HH:MM:SS`, `D-HH`,
    /// `D-HH:MM`, `D-HH:MM:SS`, `UNLIMITED`; checked by [`check_options`]).
    pub time: Option<String>,
    /// `--cpus-per-task` (>= 1): each shard runs its trials on this many threads.
    pub cpus_per_task: usize,
    /// `--mem`, memory per task: digits and an optional unit `K`/`M`/`G`/`T` (`4G`, `500M`;
    /// megabytes when none; checked by [`check_options`]).
    pub mem: Option<String>,
    /// `--account`.
    pub account: Option<String>,
}

/// Everything the scripts are made from.
#[derive(Clone, Copy)]
pub struct SlurmJob<'a> {
    /// The sweep or multiverse (scenario and options).
    pub plan: &'a dyn ShardedWork,
    /// The sweep's output folder, as the jobs should name it (absolute is safest).
    pub out_dir: &'a Path,
    /// The folder the jobs `cd` into first: where the scenario path of the plan is valid.
    pub workdir: &'a Path,
    /// The `usar` executable the jobs run.
    pub usar: &'a Path,
    /// Resources.
    pub options: &'a SlurmOptions,
}

impl std::fmt::Debug for SlurmJob<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SlurmJob")
            .field("work", &self.plan.subcommand())
            .field("scenario", &self.plan.scenario_file())
            .field("out_dir", &self.out_dir)
            .field("workdir", &self.workdir)
            .field("usar", &self.usar)
            .field("options", &self.options)
            .finish()
    }
}

/// The paths of the written files.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SlurmFiles {
    /// `<out>/slurm/sweep.sbatch` (`multiverse.sbatch` for a multiverse): the job array.
    pub array: PathBuf,
    /// `<out>/slurm/merge.sbatch`: the merge.
    pub merge: PathBuf,
    /// `<out>/slurm/submit.sh`: submits both, chained.
    pub submit: PathBuf,
    /// `<out>/slurm/logs/`: the jobs' output files.
    pub logs: PathBuf,
}

impl SlurmFiles {
    /// The paths of a sweep's files under `out_dir/slurm/`.
    pub fn under(out_dir: &Path) -> Self {
        Self::of(out_dir, "sweep")
    }

    /// The paths under `out_dir/slurm/` of the work whose tasks run `usar <subcommand>`: the
    /// array is `<subcommand>.sbatch`.
    pub fn of(out_dir: &Path, subcommand: &str) -> Self {
        let d = out_dir.join(SLURM_DIR);
        Self {
            array: d.join(format!("{subcommand}.{SLURM_JOB_EXT}")),
            merge: d.join(format!("merge.{SLURM_JOB_EXT}")),
            submit: d.join(SLURM_SUBMIT),
            logs: d.join(SLURM_LOGS),
        }
    }
}

/// Refuses options that would make a broken script.
///
/// # Errors
/// A shard count of 0 or above [`MAX_SHARDS`], `--cpus-per-task 0`, a value that is empty
/// or holds a line break or a space (it would end the `#SBATCH` line), a `--time` in none of
/// Slurm's time formats or a `--mem` that is not a size (sbatch would refuse both, after the
/// files are written).
pub fn check_options(o: &SlurmOptions) -> Result<()> {
    if o.shards == 0 || o.shards > MAX_SHARDS {
        return Err(SlurmError::Shards { max: MAX_SHARDS });
    }
    if o.cpus_per_task == 0 {
        return Err(SlurmError::CpusPerTask);
    }
    let named = [
        ("--partition", &o.partition),
        ("--time", &o.time),
        ("--mem", &o.mem),
        ("--account", &o.account),
    ];
    for (name, v) in named {
        if let Some(v) = v
            && (v.is_empty() || v.chars().any(char::is_whitespace))
        {
            return Err(SlurmError::NotOneWord {
                option: name,
                value: v.clone(),
            });
        }
    }
    if let Some(t) = &o.time
        && !is_slurm_time(t)
    {
        return Err(SlurmError::Time { value: t.clone() });
    }
    if let Some(m) = &o.mem
        && !is_slurm_memory(m)
    {
        return Err(SlurmError::Memory { value: m.clone() });
    }
    Ok(())
}

/// Whether `t` is one of the time limits `sbatch --time` documents: `M`, `M:S`, `H:M:S`,
/// `D-H`, `D-H:M`, `D-H:M:S` (each field digits), or `UNLIMITED`/`INFINITE` (any case).
/// Reference: Slurm's `sbatch(1)`, option `--time`.
fn is_slurm_time(t: &str) -> bool {
    if t.eq_ignore_ascii_case("unlimited") || t.eq_ignore_ascii_case("infinite") {
        return true;
    }
    let digits = |f: &str| !f.is_empty() && f.bytes().all(|b| b.is_ascii_digit());
    let (days, clock) = match t.split_once('-') {
        Some((d, rest)) => (Some(d), rest),
        None => (None, t),
    };
    let fields: Vec<&str> = clock.split(':').collect();
    days.is_none_or(digits) && fields.len() <= 3 && fields.iter().all(|f| digits(f))
}

/// Whether `m` is a memory size `sbatch --mem` reads: digits, then optionally a unit `K`,
/// `M`, `G` or `T` (any case, optionally followed by `B`). Reference: Slurm's `sbatch(1)`,
/// option `--mem`.
fn is_slurm_memory(m: &str) -> bool {
    let number_end = m.bytes().take_while(u8::is_ascii_digit).count();
    let unit = m[number_end..].to_ascii_uppercase();
    number_end > 0 && ["", "K", "M", "G", "T", "KB", "MB", "GB", "TB"].contains(&unit.as_str())
}

/// Refuses paths the scripts cannot hold: a line break in any of them would end a comment or
/// an `#SBATCH` line and leave the rest of the path as a command bash runs, and a double
/// quote in the output folder would end the quoted `#SBATCH --output` value.
///
/// # Errors
/// The first such path, naming its option, in one line.
pub fn check_paths(job: &SlurmJob<'_>) -> Result<()> {
    let scenario = job.plan.scenario_file();
    let paths = [
        ("the scenario path", scenario.as_path()),
        ("--out", job.out_dir),
        ("the current folder", job.workdir),
        ("the usar executable's path", job.usar),
    ];
    for (name, path) in paths {
        let text = path.to_string_lossy();
        if text.contains(['\n', '\r']) {
            return Err(SlurmError::LineBreak {
                what: name,
                path: text.into_owned(),
            });
        }
    }
    if job.out_dir.to_string_lossy().contains('"') {
        return Err(SlurmError::OutQuote {
            path: job.out_dir.display().to_string(),
        });
    }
    Ok(())
}

/// A path as the value of an `#SBATCH` line: in double quotes when it holds a space (sbatch
/// reads quoted values there).
fn directive_value(p: &Path) -> String {
    let s = p.display().to_string();
    if s.chars().any(char::is_whitespace) {
        format!("\"{s}\"")
    } else {
        s
    }
}

fn q(p: &Path) -> String {
    shell_join(&[p.display().to_string()])
}

/// The `#SBATCH` lines for the resources shared by both scripts.
fn resource_lines(s: &mut String, o: &SlurmOptions) {
    let named = [
        ("partition", &o.partition),
        ("time", &o.time),
        ("account", &o.account),
    ];
    for (name, v) in named {
        match v {
            Some(v) => {
                let _ = writeln!(s, "#SBATCH --{name}={v}");
            }
            None => {
                let _ = writeln!(
                    s,
                    "##SBATCH --{name}=...    (the cluster's default; remove one # to set it)"
                );
            }
        }
    }
}

/// The job array's script: one task per shard, each running
/// `usar sweep SCENARIO <options> --shard $SLURM_ARRAY_TASK_ID/N --threads $SLURM_CPUS_PER_TASK`.
pub fn array_script(job: &SlurmJob<'_>) -> String {
    let o = job.options;
    let n = o.shards;
    let work = job.plan.subcommand();
    let files = SlurmFiles::of(job.out_dir, work);
    let name = job_name(job.plan);
    let mut s = String::from("#!/bin/bash\n");
    let _ = write!(
        s,
        "# The {work} of {scenario} as a Slurm job array of {n} tasks, written by `usar slurm`.\n\
         # Task I runs shard I/{n} of the {work} (a fixed, balanced share of its work) into\n\
         # {out}/shards/; when every task has succeeded, merge.sbatch (chained to this array\n\
         # by submit.sh with --dependency=afterok) writes the tables, figures and report.\n\
         # A task that failed or ran out of time: submit that task again with\n\
         #   sbatch --array=I {array}\n\
         # (it continues its journal), then the merge: sbatch {merge}\n\
         # Edit freely: the #SBATCH lines are sbatch options (man sbatch).\n",
        scenario = job.plan.scenario_file().display(),
        out = job.out_dir.display(),
        array = files.array.display(),
        merge = files.merge.display(),
    );
    let _ = writeln!(s, "#SBATCH --job-name={name}");
    let _ = writeln!(s, "#SBATCH --array=0-{}", n - 1);
    let _ = writeln!(s, "#SBATCH --ntasks=1");
    let _ = writeln!(s, "#SBATCH --cpus-per-task={}", o.cpus_per_task);
    match &o.mem {
        Some(m) => {
            let _ = writeln!(s, "#SBATCH --mem={m}");
        }
        None => {
            s.push_str("##SBATCH --mem=...    (the cluster's default; remove one # to set it)\n")
        }
    }
    resource_lines(&mut s, o);
    let log = files.logs.join(format!("{work}-%A_%a.{SLURM_LOG_EXT}"));
    let _ = writeln!(s, "#SBATCH --output={}", directive_value(&log));
    let mut words = vec![
        job.usar.display().to_string(),
        work.to_string(),
        job.plan.scenario_file().display().to_string(),
    ];
    words.extend(job.plan.work_options());
    words.extend(["--out".to_string(), job.out_dir.display().to_string()]);
    let _ = write!(
        s,
        "\nset -euo pipefail\n\
         # The scenario path is relative to the folder `usar slurm` ran in.\n\
         cd {workdir}\n\n\
         # This task's shard; its trials run on the task's CPUs.\n\
         # (--quiet: no progress bar in the log.)\n\
         {cmd} \\\n    --shard \"${{SLURM_ARRAY_TASK_ID}}/{n}\" --threads \"${{SLURM_CPUS_PER_TASK:-1}}\" --quiet\n",
        workdir = q(job.workdir),
        cmd = shell_join(&words),
    );
    s
}

/// The merge job's script: `usar merge <out>` on one CPU.
pub fn merge_script(job: &SlurmJob<'_>) -> String {
    let work = job.plan.subcommand();
    let files = SlurmFiles::of(job.out_dir, work);
    let mut s = String::from("#!/bin/bash\n");
    let _ = write!(
        s,
        "# Merges the {n} shards of the {work} of {scenario} into {out}:\n\
         # {merged}, the same as the {work} on one machine.\n\
         # submit.sh submits it with --dependency=afterok:<array job id>, so it starts once\n\
         # every task of the array has succeeded. By hand: sbatch {merge}\n",
        n = job.options.shards,
        merged = job.plan.merged_files(),
        scenario = job.plan.scenario_file().display(),
        out = job.out_dir.display(),
        merge = files.merge.display(),
    );
    let _ = writeln!(s, "#SBATCH --job-name={}-merge", job_name(job.plan));
    s.push_str("#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n");
    resource_lines(&mut s, job.options);
    let log = files.logs.join(format!("merge-%j.{SLURM_LOG_EXT}"));
    let _ = writeln!(s, "#SBATCH --output={}", directive_value(&log));
    let _ = write!(
        s,
        "\nset -euo pipefail\ncd {workdir}\n{usar} merge {out}\n",
        workdir = q(job.workdir),
        usar = q(job.usar),
        out = q(job.out_dir),
    );
    s
}

/// `submit.sh`: submits the array, then the merge chained to it with
/// `--dependency=afterok:<array job id>`, and prints both job ids.
pub fn submit_script(job: &SlurmJob<'_>) -> String {
    let files = SlurmFiles::of(job.out_dir, job.plan.subcommand());
    format!(
        "#!/bin/sh\n\
         # Submits the job array of the shards, then the merge, which waits until every\n\
         # task of the array has succeeded (afterok). Written by `usar slurm`.\n\
         set -eu\n\
         array=$(sbatch --parsable {array})\n\
         array=${{array%%;*}}    # --parsable prints <id> or <id>;<cluster>\n\
         merge=$(sbatch --parsable --dependency=afterok:\"$array\" {merge})\n\
         echo \"submitted the array as job $array and the merge as job ${{merge%%;*}}\"\n",
        array = q(&files.array),
        merge = q(&files.merge),
    )
}

/// `usar-<scenario name>`, with characters other than ASCII letters, digits, `-`, `_` and `.`
/// replaced by `_`.
fn job_name(plan: &dyn ShardedWork) -> String {
    let stem = plan
        .scenario_file()
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "sweep".into());
    let clean: String = stem
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "-_.".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect();
    format!("usar-{clean}")
}

/// Writes the three files and creates the logs folder under `job.out_dir/slurm/`; the scripts
/// are made executable.
///
/// # Errors
/// Bad options ([`check_options`]), paths a script cannot hold ([`check_paths`]), or an I/O
/// error.
pub fn write_scripts(job: &SlurmJob<'_>) -> Result<SlurmFiles> {
    check_options(job.options)?;
    check_paths(job)?;
    let files = SlurmFiles::of(job.out_dir, job.plan.subcommand());
    std::fs::create_dir_all(&files.logs).map_err(FileError::io(format!(
        "creating folder {}",
        path_text(&files.logs)
    )))?;
    let scripts = [
        (&files.array, array_script(job)),
        (&files.merge, merge_script(job)),
        (&files.submit, submit_script(job)),
    ];
    for (path, text) in scripts {
        crate::atomic::write_atomic(path, text.as_bytes())?;
        make_executable(path)?;
    }
    Ok(files)
}

#[cfg(unix)]
fn make_executable(path: &Path) -> Result<()> {
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o755)).map_err(
        FileError::io(format!("making {} executable", path_text(path))),
    )?;
    Ok(())
}

#[cfg(not(unix))]
fn make_executable(_path: &Path) -> Result<()> {
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn options() -> SlurmOptions {
        SlurmOptions {
            shards: 4,
            partition: None,
            time: Some("10".into()),
            cpus_per_task: 2,
            mem: None,
            account: None,
        }
    }

    fn plan() -> SweepPlan {
        SweepPlan {
            scenario_path: "scenarios/my paper.ron".into(),
            scenario_text: String::new(),
            vary: vec!["kinds[0].count=2,3".into()],
            methods: vec!["rne".into()],
            trials: 2,
            seed: None,
            duration_s: Some(60.0),
            grid_metrics: Vec::new(),
            working_dir: None,
            targets: None,
            claims: None,
        }
    }

    #[test]
    fn the_array_script_quotes_what_the_shell_would_split() {
        let (plan, options) = (plan(), options());
        let job = SlurmJob {
            plan: &plan,
            out_dir: Path::new("/data/out dir"),
            workdir: Path::new("/home/me/rne"),
            usar: Path::new("/home/me/rne/target/release/usar"),
            options: &options,
        };
        let s = array_script(&job);
        assert!(s.contains("#SBATCH --job-name=usar-my_paper\n"), "{s}");
        assert!(s.contains("#SBATCH --time=10\n"));
        assert!(s.contains("'scenarios/my paper.ron'"), "{s}");
        assert!(s.contains("'kinds[0].count=2,3'"), "{s}");
        assert!(s.contains("--out '/data/out dir'"), "{s}");
        assert!(s.contains("#SBATCH --output=\"/data/out dir/slurm/logs/sweep-%A_%a.out\"\n"));
        assert!(merge_script(&job).contains("merge '/data/out dir'\n"));
    }

    #[test]
    fn options_that_would_break_a_line_are_refused() {
        assert!(check_options(&options()).is_ok());
        let bad = [
            SlurmOptions {
                shards: 0,
                ..options()
            },
            SlurmOptions {
                cpus_per_task: 0,
                ..options()
            },
            SlurmOptions {
                mem: Some("4 G".into()),
                ..options()
            },
            SlurmOptions {
                account: Some("a\nb".into()),
                ..options()
            },
            SlurmOptions {
                partition: Some(String::new()),
                ..options()
            },
        ];
        for o in bad {
            assert!(check_options(&o).is_err(), "{o:?}");
        }
    }

    /// The accepted and refused values were checked against `sbatch --test-only` of Slurm
    /// 22.05.8 (Debian's slurm-wlm): it says "Invalid --time specification" or "Invalid --mem
    /// specification" for each refused one and nothing for the accepted ones.
    #[test]
    fn time_and_memory_follow_slurms_formats() {
        let with = |time: &str, mem: &str| SlurmOptions {
            time: Some(time.into()),
            mem: Some(mem.into()),
            ..options()
        };
        let good_times = [
            "10",
            "10:30",
            "1:00:00",
            "2-3",
            "2-3:04",
            "2-3:04:05",
            "UNLIMITED",
        ];
        for t in good_times {
            assert!(check_options(&with(t, "4G")).is_ok(), "{t}");
        }
        for t in ["abc", "1:2:3:4", "1.5", "10m", "1h", ":", "2-3:4:5:6"] {
            let e = check_options(&with(t, "4G")).unwrap_err().to_string();
            assert!(e.starts_with(&format!("--time {t:?}: expected")), "{e}");
            assert!(!e.contains('\n'), "{e}");
        }
        for m in ["4G", "4g", "500M", "500", "0", "4GB", "1T", "1024K", "4MB"] {
            assert!(check_options(&with("10", m)).is_ok(), "{m}");
        }
        for m in ["1.5G", "abc", "-5", "4G;x", "4X", "4GiB", "G"] {
            let e = check_options(&with("10", m)).unwrap_err().to_string();
            assert!(e.starts_with(&format!("--mem {m:?}: expected")), "{e}");
        }
    }
}
