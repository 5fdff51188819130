//! [`run_multiverse`]: check the setup, lock the output folder, refuse (or clear) a
//! multiverse of other parameters, write the plan, run each universe that has no record yet,
//! and write the top files.

use std::path::Path;
use std::time::Instant;

use super::design_run::{missing_message, read_design, run_design};
use super::emulator::Emulator;
use super::error::MultiverseError;
use super::folder::{clear, refuse_others};
use super::outcome::MultiverseOutcome;
use super::outputs::write_outputs;
use super::plan::MultiversePlan;
use super::progress::{Display, MultiverseProgress};
use super::record::{RecordRead, Status, UniverseRecord};
use super::setup::{CheckedMultiverse, MultiverseSetup};
use super::universe_run::{UniverseRun, universe_dir};
use usar_sweep::atomic::remove_stale_temps;
use usar_sweep::data::hooks::Stopped;
use usar_sweep::data::owner::{RunKind, claim};
use usar_sweep::lock::OutputLock;
use usar_sweep::shard::shard_dir;

/// What the functions of this module return.
type Result<T> = std::result::Result<T, MultiverseError>;

/// Runs the paper's method comparison in every universe of `setup` (or of its shard),
/// writing into `dir`: per universe its folder `universes/<id>/` (scenario, calibration,
/// comparison, record), and without a shard `multiverse.csv`, `multiverse.md` and one
/// `spec_curve_<claim>.svg` per claim at the top.
///
/// Universes run one after another, each on `setup.threads` threads. Running it again
/// continues: a universe with a record is not run again (one that failed is retried), and a
/// universe stopped half-way continues its calibration's trace and its comparison's journal.
/// The top files are made from the records alone, so they are the same bytes on any thread
/// count, resumed or not, and merged from shards (`super::merge_multiverse`). A folder
/// holding a multiverse of other parameters is refused unless `setup.overwrite`.
///
/// ```no_run
/// use std::path::Path;
/// use usar_study::calibrate::{FreeField, Targets};
/// use usar_study::multiverse::{Axes, MultiverseProgress, MultiverseSetup, run_multiverse};
///
/// let text = std::fs::read_to_string("scenarios/paper.ron")?;
/// let base = usar_sim::scenario::parse_spec(&text, "scenarios/paper.ron")?;
/// let axes = Axes::load(Path::new("my-axes.ron"))?;
/// let targets = Targets::load(Path::new("scenarios/paper-targets.ron"))?;
/// let free = vec![FreeField::parse("mission.search_time_budget_s=6..30")?];
/// let mut setup = MultiverseSetup {
///     calibration_trials: 2,
///     max_evals: 10,
///     ..MultiverseSetup::new(base, "scenarios/paper.ron", axes, targets, free)
/// };
/// setup.comparison.trials = 4;
/// let o = run_multiverse(&setup, Path::new("results/mv"), MultiverseProgress::off())?;
/// println!("{} of {} universes admissible", o.admissible(), o.records.len());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// A setup that does not fit its scenario ([`MultiverseSetup::check`]), `--overwrite` with
/// a shard, an output folder that is not a folder or belongs to another kind of run
/// ([`usar_sweep::data::owner`]), one locked by another run or holding another multiverse, or an I/O
/// error writing the plan, a universe's own files or the top files. A universe whose
/// scenario breaks a rule, whose calibration errs or whose trials fail is not an error: its
/// record says so and the others run.
pub fn run_multiverse(
    setup: &MultiverseSetup,
    dir: &Path,
    progress: MultiverseProgress,
) -> Result<MultiverseOutcome> {
    let t0 = Instant::now();
    let checked = setup.check()?;
    if setup.overwrite && setup.shard.is_some() {
        return Err(MultiverseError::OverwriteShard);
    }
    let plan = MultiversePlan::of(setup, &checked, dir)?;
    claim(dir, RunKind::Multiverse)?;
    if let Some(s) = setup.shard {
        claim(&shard_dir(dir, s), RunKind::Multiverse)?;
    }
    let _locks = lock(setup, dir)?;
    if setup.overwrite {
        clear(dir)?;
    }
    refuse_others(dir, &plan)?;
    remove_stale_temps(dir)?;
    match setup.shard {
        Some(s) => plan.write(&shard_dir(dir, s))?,
        None => plan.write(dir)?,
    }
    let emulator = match setup.design {
        0 => None,
        n => {
            run_design(setup, &checked, &plan, dir, progress.bar)?;
            let points = read_design(&plan, dir).map_err(|m| MultiverseError::Missing {
                message: missing_message(&m, n),
            })?;
            Some(Emulator::fit(
                &points,
                &setup.axes.sizes(),
                &setup.free,
                setup.targets.targets().len(),
            ))
        }
    };
    let (records, ran) = run_universes(setup, &checked, &plan, dir, progress, emulator.as_ref())?;
    let files = match setup.shard {
        Some(_) => Vec::new(),
        None => write_outputs(&plan, &records, dir)?,
    };
    Ok(MultiverseOutcome {
        reused: records.len() - ran,
        plan,
        records,
        shard: setup.shard,
        ran,
        files,
        wall_s: t0.elapsed().as_secs_f64(),
    })
}

/// The locks of a run: the whole folder's, exclusive; or for a shard, shared on the folder
/// (shards run side by side, a run of the whole folder or a merge waits) and exclusive on
/// the shard's own folder.
fn lock(setup: &MultiverseSetup, dir: &Path) -> Result<Vec<OutputLock>> {
    Ok(match setup.shard {
        None => vec![OutputLock::acquire(dir)?],
        Some(s) => vec![
            OutputLock::acquire_shared(dir)?,
            OutputLock::acquire(&shard_dir(dir, s))?,
        ],
    })
}

/// Runs the universes of the run (its shard's, or all) that have no record (or a failed
/// one); returns every record in universe order and how many ran now.
fn run_universes(
    setup: &MultiverseSetup,
    checked: &CheckedMultiverse,
    plan: &MultiversePlan,
    dir: &Path,
    progress: MultiverseProgress,
    emulator: Option<&Emulator>,
) -> Result<(Vec<UniverseRecord>, usize)> {
    let sum = plan.identity_sum();
    let run = UniverseRun {
        setup,
        plan,
        identity_sum: &sum,
        root: dir,
        emulator,
    };
    let own = checked.own(setup.shard);
    let display = Display::new(progress, own.len());
    let mut records = Vec::with_capacity(own.len());
    let mut ran = 0;
    for &j in &own {
        if setup.hooks.stopped() {
            return Err(Stopped.into());
        }
        let u = &checked.universes[j];
        let id = u.id(checked.factorial);
        match UniverseRecord::read(&universe_dir(dir, &id), &sum) {
            RecordRead::Done(r) if r.status != Status::Failed => {
                display.done(plan, &r, false);
                records.push(*r);
                continue;
            }
            RecordRead::Unusable(why) => {
                tracing::warn!("{why}; universe {id} runs again");
            }
            RecordRead::Done(_) | RecordRead::Missing => {}
        }
        display.starting(&id);
        let r = run.run(u)?;
        ran += 1;
        display.done(plan, &r, true);
        if let Some(hook) = &setup.hooks.universe_done {
            hook(&r, ran);
        }
        records.push(r);
    }
    display.finish();
    Ok((records, ran))
}
