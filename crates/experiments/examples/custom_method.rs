//! Adding a grouping method of your own to a sweep, without touching the library.
//!
//! The paper's Algorithm 4 (NDC) sorts a needs distribution before comparing it, while
//! Definitions 1-3 compare category by category (rne-core's default). This example sweeps the
//! built-in RNE grouping against a variant, `rne_sorted`, that uses the sorted distributions,
//! plus ENG, over a few trials of `scenarios/paper.ron`, and prints the summary table. The
//! output folder holds the same files as `usar sweep` (trials.csv, summary.csv, report.md,
//! figures, journal.jsonl).
//!
//! ```sh
//! cargo run --release -p experiments --example custom_method -- [TRIALS] [OUT_DIR]
//! ```

use std::path::PathBuf;

use anyhow::{Context, Result};
use rne_core::grouping::{GroupingMethod, HierarchicalRne};
use rne_core::{Alignment, RneOptions, TrustModel};
use usar_report::analysis::Analysis;
use usar_report::output::write_outputs;
use usar_sim::mission::TrialResult;
use usar_sim::scenario;
use usar_sweep::sweep::{MethodFactory, SweepConfig, run_sweep};

fn main() -> Result<()> {
    let mut args = std::env::args().skip(1);
    let trials: u32 = args.next().map_or(Ok(3), |a| a.parse()).context("TRIALS")?;
    let out_dir = args
        .next()
        .map_or_else(|| PathBuf::from("results/custom_method"), PathBuf::from);
    let path = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenarios/paper.ron"
    ));
    let scenario = scenario::load(&path)?;

    // The new method: hierarchical RNE grouping (Algorithm 1) on sorted needs distributions
    // (Algorithm 4). Every other name falls back to the built-ins.
    let factory = MethodFactory::new(|name, model: &TrustModel, ctx| match name {
        "rne_sorted" => {
            let options = RneOptions {
                alignment: Alignment::Sorted,
                ..*model.options()
            };
            let sorted = TrustModel::new(model.weights().clone(), options)?;
            Ok(Box::new(Named("rne_sorted", HierarchicalRne::new(sorted)))
                as Box<dyn GroupingMethod>)
        }
        other => MethodFactory::builtin().build(other, model, ctx),
    });

    let cfg = SweepConfig {
        methods: ["rne", "rne_sorted", "eng"].map(String::from).to_vec(),
        method_factory: factory,
        trials,
        out_dir,
        overwrite: true,
        ..SweepConfig::new(scenario, path)
    };
    // A sweep runs (into its journal), the analysis judges, the outputs are written from it.
    let outcome = run_sweep(&cfg)?;
    let analysis = Analysis::of(&outcome);
    write_outputs(&cfg, &outcome, &analysis, &[])?;
    let results = &outcome.cells[0].results;
    println!(
        "{} trials in {:.2} s; files in {}",
        results.len(),
        outcome.wall_s,
        cfg.out_dir.display()
    );
    // Mean rescuees per task (in the scenario's task order) and in total, over trials.
    let tasks = cfg.scenario.task_names();
    let header: Vec<String> = tasks.iter().map(|t| format!("{t:>8}")).collect();
    println!(
        "method       {} {:>8}  (mean rescuees over trials)",
        header.join(" "),
        "total"
    );
    for method in &outcome.header.methods {
        let runs: Vec<&TrialResult> = results.iter().filter(|r| &r.method == method).collect();
        let mean = |f: &dyn Fn(&TrialResult) -> u32| {
            runs.iter().map(|r| f64::from(f(r))).sum::<f64>() / runs.len().max(1) as f64
        };
        let per_task: Vec<String> = (0..tasks.len())
            .map(|t| format!("{:>8.1}", mean(&|r| r.rescued[t])))
            .collect();
        println!(
            "{method:<12} {} {:>8.1}",
            per_task.join(" "),
            mean(&TrialResult::rescued_total)
        );
    }
    Ok(())
}

/// A method under another name (the name is what tables and the journal show).
struct Named<M>(&'static str, M);

impl<M: GroupingMethod> GroupingMethod for Named<M> {
    fn name(&self) -> &str {
        self.0
    }
    fn assign(
        &self,
        request: &rne_core::grouping::GroupingRequest,
    ) -> rne_core::Result<rne_core::grouping::Assignment> {
        self.1.assign(request)
    }
}
