//! `usar replay`: record one trial while it runs and write a self-contained HTML page that
//! plays it in a browser (docs/replay.md).

use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, Result};
use clap::Args;
use usar_sim::mission::{Simulation, trial_seed};
use usar_sim::scenario;

use usar_report::replay::{record_trial, replay_html};
use usar_sweep::atomic::write_atomic;

const EXAMPLES: &str = "\
Examples:
  # Trial 0 of the paper's mission with RNE grouping, the whole 600 s
  usar replay scenarios/paper.ron --method rne --trial 0 --out replay.html

  # Trial 3 with DIS, the first 200 s, sampled at 20 Hz
  usar replay scenarios/paper.ron --method dis --trial 3 --duration 200 --hz 20 --out dis-3.html

  # 1,000 robots: keep it short (the page holds every robot at every sample)
  usar replay scenarios/swarm-1000.ron --duration 30 --out swarm.html

Open the page in a browser (no server needed): a time slider, play/pause, 1x to 64x, the
current round and each group's rescued count, marks for rounds, deadlocks, leaves to recharge
and deliveries; click a robot for its state, energy, HP and needs vector. The URL's
#t=SECONDS&robot=ID opens a given moment. --trial K uses seed trial_seed(sim.seed, K), as
trial K of `usar sweep` (with --base-seed B: of `usar sweep --seed B`); --seed S uses S itself.
The page is written atomically (a temporary file renamed over --out).";

/// A team of more robot-samples than this gets a warning: the page decodes every robot at
/// every sample into memory (60 bytes each).
const LARGE_ROBOT_SAMPLES: usize = 2_000_000;

/// Arguments of `usar replay`.
#[derive(Debug, Clone, Args)]
#[command(after_help = EXAMPLES)]
pub struct ReplayArgs {
    /// The scenario file (RON), e.g. scenarios/paper.ron.
    #[arg(value_name = "SCENARIO")]
    pub scenario: PathBuf,

    /// Grouping method: rne, dis, eng or hp_dis.
    #[arg(long, value_name = "NAME", default_value = "rne")]
    pub method: String,

    /// Index of the trial (0-based; selects the starting team's energy and HP); default 0.
    #[arg(long, value_name = "N", conflicts_with = "seed")]
    pub trial: Option<u32>,

    /// Seed of the starting team, used as is (a sweep's trials.csv `seed` column).
    #[arg(long, value_name = "SEED", conflicts_with = "base_seed")]
    pub seed: Option<u64>,

    /// Base seed of the trials (`usar sweep --seed`): trial K starts from trial_seed(BASE, K);
    /// default the scenario's sim.seed.
    #[arg(long, value_name = "BASE")]
    pub base_seed: Option<u64>,

    /// Length of the trial, seconds (> 0); default the scenario's mission.duration_s.
    #[arg(long, value_name = "SECONDS", allow_hyphen_values = true)]
    pub duration: Option<f64>,

    /// Samples per simulated second (> 0; rounded to a whole number of steps per sample);
    /// default 10, lowered so that robots times samples stay within 6,100,000 (about 1 Hz for
    /// 10,000 robots over 600 s).
    #[arg(long, value_name = "HZ", allow_hyphen_values = true)]
    pub hz: Option<f64>,

    /// Where to write the page (HTML).
    #[arg(long, value_name = "FILE.html")]
    pub out: PathBuf,

    #[arg(long, value_name = "N", help = crate::shared::trial_build::TRIAL_THREADS_HELP)]
    pub threads: Option<usize>,
}

/// Runs `usar replay`, writing a one-line summary to `out`.
///
/// # Errors
/// A bad scenario or option, a failing trial, or an error writing the page.
pub fn run(args: &ReplayArgs, out: &mut dyn Write) -> Result<()> {
    let pool = crate::shared::trial_build::trial_pool(args.threads)?;
    let path = &args.scenario;
    let scenario = scenario::load(path)?;
    let mut builder = Simulation::builder(&scenario)
        .method_named(&args.method)
        .trial(args.trial.unwrap_or(0));
    if let Some(base) = args.base_seed {
        builder = builder.seed(trial_seed(base, args.trial.unwrap_or(0)));
    }
    if let Some(seed) = args.seed {
        builder = builder.seed(seed);
    }
    if let Some(d) = args.duration {
        builder = builder.duration_s(d);
    }
    let sim = crate::shared::trial_build::build_trial(builder)?;
    crate::shared::trial_build::warn_if_rounded(args.duration, &sim);
    let dt_s = scenario.sim().dt_s.get();
    let hz = args.hz.unwrap_or_else(|| {
        usar_report::replay::default_hz(scenario.robots().len(), sim.progress().1, dt_s)
    });
    let clock =
        usar_report::replay::SampleClock::new(hz, dt_s, sim.progress().1).context("--hz")?;
    let robot_samples = clock.samples().saturating_mul(scenario.robots().len());
    if robot_samples > LARGE_ROBOT_SAMPLES {
        crate::shared::stderr_lines::warn(format!(
            "warning: {} robots x {} samples: the page will need about {} MB of memory in the \
             browser; a shorter --duration or a lower --hz keeps it light",
            scenario.robots().len(),
            clock.samples(),
            robot_samples * 60 / 1_000_000
        ));
    }
    let t0 = Instant::now();
    let t = pool
        .install(|| record_trial(sim, hz, None))
        .context("recording the trial")?;
    let html = replay_html(&scenario, &t.recording)?;
    write_atomic(&args.out, html.as_bytes()).context("--out")?;
    let bytes = html.len() as u64;
    let rec = &t.recording;
    writeln!(
        out,
        "wrote {} ({:.2} MB): {} {} trial {} (seed {}), {:.1} s at {} samples/s, {} samples x {} \
         robots, {} marks, {} rescued; {:.1} s wall-clock",
        args.out.display(),
        bytes as f64 / 1e6,
        scenario.name(),
        rec.method,
        rec.trial,
        rec.seed,
        rec.duration_s(),
        usar_report::table::sig3(rec.clock.actual_hz(rec.dt_s)),
        rec.samples,
        rec.robots,
        rec.marks.len(),
        t.result.rescued.iter().sum::<u32>(),
        t0.elapsed().as_secs_f64()
    )?;
    Ok(())
}
