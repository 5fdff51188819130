//! How many robots are away for rest (on their way to a rest station, at it, or on their way
//! back to their start) every 100 simulated seconds of one trial: the figures of
//! `docs/scaling.md`, "Rest stations".
//!
//! `cargo run --release -p experiments --example away_for_rest -- SCENARIO [METHOD] [DURATION_S]`
//! (defaults `rne` and the scenario's `mission.duration_s`; trial 0). Prints the counts, their
//! mean and their peak.

use anyhow::{Context, Result};
use usar_sim::mission::{Phase, Simulation};

/// Seconds between two counts.
const EVERY_S: f64 = 100.0;

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = args
        .first()
        .context("usage: away_for_rest SCENARIO [METHOD] [DURATION_S]")?;
    let scenario = usar_sim::scenario::load(path)?;
    let method = args.get(1).map_or("rne", String::as_str);
    let mut builder = Simulation::builder(&scenario).method_named(method).trial(0);
    if let Some(d) = args.get(2) {
        builder = builder.duration_s(d.parse().with_context(|| format!("DURATION_S {d:?}"))?);
    }
    let mut sim = builder.build()?;
    let (mut next_s, mut counts) = (EVERY_S, Vec::new());
    while !sim.is_finished() {
        sim.step()?;
        if sim.time_s() + 1e-9 >= next_s {
            let away = sim.robots().iter().filter(|r| {
                matches!(
                    r.phase,
                    Phase::ToRest | Phase::Recharging { .. } | Phase::RestToStart
                )
            });
            counts.push(away.count());
            next_s += EVERY_S;
        }
    }
    let mean = counts.iter().sum::<usize>() as f64 / counts.len().max(1) as f64;
    let peak = counts.iter().max().copied().unwrap_or(0);
    println!("{method}: robots away for rest every {EVERY_S} s: {counts:?}");
    println!("mean {mean:.0}, peak {peak}");
    Ok(())
}
