//! The design phase of a multiverse run (`--design N`, [`super::design`]): run the design
//! points that have no point file yet, this run's own first (its shard's: point `j` to
//! shard `j mod N`; or all), then, for a shard, the other shards' still missing (the
//! universes need the whole design): shards running side by side finish their own at about
//! the same time and then help with what is left, and a shard that starts late finds the
//! design done. Two shards that run the same point write the same bytes.

use std::path::Path;

use super::error::MultiverseError;

use super::design::{DesignPoint, design_plan, evaluate_point};
use super::plan::MultiversePlan;
use super::setup::{CheckedMultiverse, MultiverseSetup};
use usar_sweep::data::hooks::Stopped;
use usar_sweep::progress::count_bar;

/// Runs the design points not done yet into `dir` (this run's own first, then the rest,
/// each looked for again just before it runs), each written as it ends; returns how many
/// ran. Shows a bar over them when `bar` (on a terminal).
///
/// # Errors
/// An I/O error writing a point, the thread pool, or [`Stopped`] when the stop flag is set
/// (the points done are kept; a rerun continues).
pub fn run_design(
    setup: &MultiverseSetup,
    checked: &CheckedMultiverse,
    plan: &MultiversePlan,
    dir: &Path,
    bar: bool,
) -> Result<usize, MultiverseError> {
    let n = setup.design;
    let sum = plan.identity_sum();
    let sizes = (setup.free.len(), setup.targets.targets().len());
    let points = design_plan(
        n,
        checked.universes.len(),
        &setup.free,
        setup.digits,
        setup.calibration_seed,
    );
    let first = setup.shard.map_or(0, |s| s.index);
    let order = (0..n).map(|k| (k + first) % n);
    let (own, others): (Vec<usize>, Vec<usize>) = order
        .filter(|&j| DesignPoint::read(dir, j, n, &sum, sizes).is_none())
        .partition(|j| setup.shard.is_none_or(|s| j % s.count == s.index));
    let pb = count_bar(bar, (own.len() + others.len()) as u64, "design points");
    let mut ran = 0;
    for &j in own.iter().chain(&others) {
        if setup.hooks.stopped() {
            return Err(Stopped.into());
        }
        if DesignPoint::read(dir, j, n, &sum, sizes).is_some() {
            pb.inc(1);
            continue;
        }
        let (u, values) = &points[j];
        let point = evaluate_point(setup, j, &checked.universes[*u], values)?;
        if setup.hooks.stopped() {
            return Err(Stopped.into());
        }
        point.write(dir, n, &sum)?;
        ran += 1;
        pb.inc(1);
    }
    pb.finish_and_clear();
    Ok(ran)
}

/// Every point of `plan`'s design in `dir`, in design order; `Err` with the indices of the
/// points missing (or not verifying) when some are.
pub fn read_design(plan: &MultiversePlan, dir: &Path) -> Result<Vec<DesignPoint>, Vec<usize>> {
    let n = plan.identity.design;
    let sum = plan.identity_sum();
    let sizes = (plan.identity.free.len(), plan.identity.targets.len());
    let mut points = Vec::with_capacity(n);
    let mut missing = Vec::new();
    for j in 0..n {
        match DesignPoint::read(dir, j, n, &sum, sizes) {
            Some(p) => points.push(p),
            None => missing.push(j),
        }
    }
    if missing.is_empty() {
        Ok(points)
    } else {
        Err(missing)
    }
}

/// The message for a design with `missing` points (not expected after [`run_design`]: a
/// point file removed while the run went on).
pub fn missing_message(missing: &[usize], design: usize) -> String {
    let first: Vec<String> = missing.iter().take(5).map(|j| format!("d{j}")).collect();
    format!(
        "the design is not complete: {} of {design} points are missing or do not verify \
         ({}{}); run this command again",
        missing.len(),
        first.join(", "),
        if missing.len() > 5 { ", ..." } else { "" }
    )
}
