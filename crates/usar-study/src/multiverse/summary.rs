//! The terminal summary of a multiverse run: what ran, the admissible share, per claim where
//! it holds, and the files written (for a shard: what it did and the merge to run next).

use std::fmt::Write;

use super::outcome::MultiverseOutcome;
use super::tally::{Tally, share};
use usar_sweep::shard::shell_join;

/// The summary text of `o`, one item per line; `out_dir` is the output folder as given.
pub fn summary_text(o: &MultiverseOutcome, out_dir: &std::path::Path) -> String {
    let mut s = String::new();
    let plan = &o.plan;
    let total = plan.universes().len();
    let what = match o.shard {
        Some(sh) => format!("shard {sh} of multiverse {}", plan.identity.scenario),
        None => format!("multiverse {}", plan.identity.scenario),
    };
    let _ = writeln!(
        s,
        "{what}: {} of {total} universes ({} run now, {} from earlier runs) in {:.2} s",
        o.records.len(),
        o.ran,
        o.reused,
        o.wall_s
    );
    let t = Tally::of(
        &o.records,
        &plan.identity.axes.sizes(),
        &plan.identity.claims,
    );
    let _ = writeln!(
        s,
        "admissible: {}; invalid {}, failed {}",
        share(t.admissible, t.universes, plan.sampled()),
        t.invalid,
        t.failed
    );
    if o.shard.is_some() {
        let merge = shell_join(&["usar".into(), "merge".into(), out_dir.display().to_string()]);
        let _ = writeln!(s, "when every shard is done: {merge}");
        return s;
    }
    if !plan.identity.claims.is_empty() {
        let _ = writeln!(s, "\nclaims (share of the admissible universes):");
    }
    for (c, count) in plan.identity.claims.iter().zip(&t.claims) {
        let _ = writeln!(
            s,
            "  ({}) {}: holds {}, not significant {}, does not hold {}",
            c.id,
            c.sentence,
            share(count.holds, count.universes, plan.sampled()),
            share(count.not_significant, count.universes, plan.sampled()),
            share(count.does_not_hold, count.universes, plan.sampled())
        );
    }
    let _ = writeln!(s, "\nwrote:");
    for f in &o.files {
        let _ = writeln!(s, "  {}", f.display());
    }
    s
}
