//! `usar render`: a top-down SVG picture of a scenario, optionally with the paths the robots
//! took in one mission trial.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;
use usar_sim::mission::Simulation;
use usar_sim::scenario::{self, Scenario, path_text};

use usar_report::render::{PathRecorder, Trace, render_svg_string};
use usar_sweep::atomic::write_atomic;

const EXAMPLES: &str = "\
Examples:
  # The paper's arena: walls, debris, radiation, tasks, rest station, robots at their starts
  usar render scenarios/paper.ron --out arena.svg

  # Add the paths of trial 0 with RNE grouping over the first 200 s
  usar render scenarios/paper.ron --out trace.svg --trace --duration 200

  # Another grouping method and trial, the whole mission
  usar render scenarios/paper.ron --out trace-dis-3.svg --trace --method dis --trial 3

Methods: rne, dis, eng, hp_dis. Paths are sampled every 0.5 s of simulated time. The picture
is written atomically (a temporary file renamed over --out); parent folders are created. A
symlink given as --out is followed and stays a symlink (its target gets the picture); a FIFO or
character device (/dev/stdout) is written directly; a folder, block device or socket is
refused.";

/// Arguments of `usar render`.
#[derive(Debug, Clone, Args)]
#[command(after_help = EXAMPLES)]
pub struct RenderArgs {
    /// The scenario file (RON), e.g. scenarios/paper.ron.
    #[arg(value_name = "SCENARIO")]
    pub scenario: PathBuf,

    /// Where to write the SVG picture (a symlink is followed, a FIFO or character device is
    /// written directly; see below).
    #[arg(long, value_name = "FILE.svg")]
    pub out: PathBuf,

    /// Run one mission trial and draw the path every robot took.
    #[arg(long)]
    pub trace: bool,

    /// Grouping method of the traced trial: rne, dis, eng or hp_dis.
    #[arg(long, value_name = "NAME", default_value = "rne", requires = "trace")]
    pub method: String,

    /// Index of the traced trial (0-based; selects the starting team's energy and HP).
    #[arg(long, value_name = "N", default_value_t = 0, requires = "trace")]
    pub trial: u32,

    /// Length of the traced trial, seconds (> 0); default the scenario's mission.duration_s.
    #[arg(long, value_name = "SECONDS", requires = "trace")]
    pub duration: Option<f64>,

    #[arg(long, value_name = "N", requires = "trace", help = crate::shared::trial_build::TRIAL_THREADS_HELP)]
    pub threads: Option<usize>,
}

/// Runs one trial of `scenario` in `pool` and returns every robot's path, as
/// [`PathRecorder`] samples it.
///
/// # Errors
/// An unknown method name, bad needs weights, a non-positive duration, or a failing trial.
pub fn trace_trial(
    scenario: &Scenario,
    method: &str,
    trial: u32,
    duration_s: Option<f64>,
    pool: &rayon::ThreadPool,
) -> Result<Vec<Trace>> {
    let mut builder = Simulation::builder(scenario)
        .method_named(method)
        .trial(trial);
    if let Some(d) = duration_s {
        builder = builder.duration_s(d);
    }
    let mut sim = crate::shared::trial_build::build_trial(builder)?;
    crate::shared::trial_build::warn_if_rounded(duration_s, &sim);
    let mut recorder = PathRecorder::new();
    pool.install(|| sim.run_observed(&mut recorder))
        .with_context(|| format!("trial {trial}"))?;
    let traces = recorder.into_traces();
    Ok(traces)
}

/// Runs `usar render`, writing a one-line summary to `out`.
///
/// # Errors
/// The scenario's loader message (file:line:col, field, rule) for a bad scenario, a bad
/// option, a failing trial, or an error writing the picture.
pub fn run(args: &RenderArgs, out: &mut dyn Write) -> Result<()> {
    let pool = crate::shared::trial_build::trial_pool(args.threads)?;
    let path = &args.scenario;
    // The loader's message is complete (file:line:col, field, rule, or the I/O error), as
    // every other command prints it.
    let scenario = scenario::load(path)?;
    let traces = if args.trace {
        Some(
            trace_trial(&scenario, &args.method, args.trial, args.duration, &pool)
                .with_context(|| format!("tracing a trial of {}", path_text(path)))?,
        )
    } else {
        None
    };
    let svg = render_svg_string(&scenario, traces.as_deref())?;
    write_atomic(&args.out, svg.as_bytes()).context("--out")?;
    match &traces {
        Some(t) => writeln!(
            out,
            "wrote {} ({}: {} robots, paths of trial {} with {} over {:.1} s, {} samples each)",
            args.out.display(),
            scenario.name(),
            scenario.robots().len(),
            args.trial,
            args.method,
            args.duration.unwrap_or(scenario.mission().duration_s.get()),
            t.first().map_or(0, Vec::len)
        )?,
        None => writeln!(
            out,
            "wrote {} ({}: {} robots at their starts)",
            args.out.display(),
            scenario.name(),
            scenario.robots().len()
        )?,
    }
    Ok(())
}
