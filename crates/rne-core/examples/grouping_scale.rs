//! Time and peak memory of grouping a 1,000-robot team (500 carriers, 333 suppliers,
//! 167 observers, 4 tasks) with each built-in method, one run each. Peak memory is the
//! process's peak resident set (`VmHWM` in `/proc/self/status`, Linux), printed before and
//! after the groupings, so the difference is what the groupings added. For an outside check:
//!
//! ```sh
//! cargo build --release -p rne-core --example grouping_scale
//! /usr/bin/time -v target/release/examples/grouping_scale   # "Maximum resident set size"
//! ```

use std::time::Instant;

use rne_core::grouping::{GroupingMethod, HierarchicalRne, METHOD_NAMES, method_from_name};
use rne_core::{TrustModel, Weights};

#[path = "../benches/support/large_team.rs"]
mod large_team;

/// The process's peak resident set size in kB (`VmHWM`), if the platform reports it.
fn peak_rss_kb() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

fn main() {
    let request = large_team::large_team([500, 333, 167], 4, 7);
    let model = TrustModel::with_weights(Weights::uniform(7).expect("weights"));
    let before = peak_rss_kb();
    println!("peak RSS before grouping: {before:?} kB");
    for name in METHOD_NAMES {
        let method: Box<dyn GroupingMethod> = method_from_name(name, &model).expect("method");
        let t = Instant::now();
        let a = method.group(&request).expect("grouping");
        let sizes: Vec<usize> = a.groups.iter().map(Vec::len).collect();
        println!(
            "{name:>6}: {:>9.3} ms, group sizes {sizes:?}",
            t.elapsed().as_secs_f64() * 1e3
        );
    }
    let out = HierarchicalRne::new(model)
        .group_detailed(&request)
        .expect("grouping");
    for b in &out.bisections {
        println!(
            "  bisection task {}: J = {:.6}, heuristic kinds {:?}",
            b.task, b.between_rne, b.heuristic_kinds
        );
    }
    let after = peak_rss_kb();
    println!("peak RSS after grouping: {after:?} kB");
}
