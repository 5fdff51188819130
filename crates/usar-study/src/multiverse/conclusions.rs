//! What a multiverse run can and cannot conclude, written from its counts ([`Tally`]), not by
//! hand: the admissible share and, per claim, where it holds among the admissible universes,
//! each with its [`clopper_pearson`] interval when the universes are a sample of the factorial.
//! `multiverse.md` shows it under "What this run can conclude".

use std::fmt::Write;

use super::plan::MultiversePlan;
use super::tally::{Tally, clopper_pearson, share};

/// The paragraph of conclusions for the counts `t` of `plan`'s universes. Shares are
/// estimates with intervals only when the run is complete and its universes are a `--sample`
/// smaller than the factorial ([`MultiversePlan::sampled`]); a complete run of the whole
/// factorial gives the factorial's own shares; an incomplete run (universes without a record,
/// or failed) gives the shares of what it has, and says so.
pub fn conclusions(t: &Tally, plan: &MultiversePlan) -> String {
    let mut r = String::new();
    if t.universes == 0 {
        let _ = writeln!(r, "No universe has a record yet: nothing to conclude.");
        return r;
    }
    let planned = plan.universes().len();
    let complete = t.universes >= planned && t.failed == 0;
    let sampled = complete && plan.sampled();
    let _ = write!(
        r,
        "- {} of the universes are admissible",
        share(t.admissible, t.universes, sampled)
    );
    if !complete {
        let _ = writeln!(
            r,
            ": only {} of the {planned} universes this run makes have a record, {} of them \
             failed (run the command again to retry them); the shares below are of those \
             records, not of the run.",
            t.universes, t.failed
        );
    } else if sampled {
        let (lo, hi) = clopper_pearson(t.admissible, t.universes).unwrap_or((0.0, 1.0));
        let _ = writeln!(
            r,
            ". They are a random sample of the {} universes of the factorial: the admissible \
             share of the whole factorial lies between {:.0} and {:.0} % (95 %).",
            plan.factorial(),
            100.0 * lo,
            100.0 * hi
        );
    } else {
        let _ = writeln!(
            r,
            ": the whole factorial ran, so this is the share of the readings the axes write \
             under which the model reaches its targets, not an estimate."
        );
    }
    if t.admissible == 0 {
        let _ = writeln!(
            r,
            "- No universe is admissible, so the run cannot say how any claim fares under \
             readings that reach the targets: it needs other free fields, wider ranges or \
             fewer targets."
        );
        return r;
    }
    for (c, count) in plan.identity.claims.iter().zip(&t.claims) {
        let (k, n) = (count.holds, count.universes);
        let Some(interval) = clopper_pearson(k, n) else {
            continue;
        };
        let p = k as f64 / n as f64;
        let (lo, hi) = if sampled { interval } else { (p, p) };
        let verdict = if hi < 0.5 {
            format!(
                "holds in fewer than half of the admissible readings (at most {:.0} %)",
                100.0 * hi
            )
        } else if lo > 0.5 {
            format!(
                "holds in most admissible readings (at least {:.0} %)",
                100.0 * lo
            )
        } else if !sampled {
            "holds in exactly half of the admissible readings".to_string()
        } else {
            format!(
                "cannot be said to hold in most admissible readings or in fewer than half \
                 ({:.0} to {:.0} %)",
                100.0 * lo,
                100.0 * hi
            )
        };
        let _ = writeln!(
            r,
            "- ({}) {}: {verdict}; it holds in {k} of {n}.",
            c.id, c.sentence
        );
    }
    if sampled {
        let _ = writeln!(
            r,
            "- The intervals say how far a share could move in another sample of the same \
             factorial; universes share choices, so they say nothing of readings the axes do \
             not write."
        );
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multiverse::plan::tests::plan;
    use crate::multiverse::record::tests::record;
    use crate::multiverse::universe::Sample;

    fn tally(n: u64, admissible: bool) -> Tally {
        let loss = if admissible { 0.0 } else { 3.0 };
        let records: Vec<_> = (0..n).map(|i| record(i, &[0, 1], loss)).collect();
        Tally::of(&records, &[2, 3], &plan().identity.claims)
    }

    /// The test plan's factorial has 6 universes.
    #[test]
    fn a_sample_gets_intervals_a_whole_factorial_exact_shares_and_a_partial_run_says_so() {
        let whole = conclusions(&tally(6, true), &plan());
        assert!(
            whole.contains("6/6 (100 %) of the universes are admissible: the whole factorial ran"),
            "{whole}"
        );
        assert!(
            whole.contains(
                "(1) RNE rescues the most in total: holds in most admissible readings (at least \
                 100 %)"
            ),
            "{whole}"
        );
        let mut sampled = plan();
        sampled.identity.sample = Some(Sample { n: 5, seed: 1 });
        let text = conclusions(&tally(5, true), &sampled);
        assert!(
            text.contains(
                "5/5 (100 %, 95 % CI 48 to 100 %) of the universes are admissible. They are a \
                 random sample of the 6 universes"
            ),
            "{text}"
        );
        // Claim 1 holds in all five: at least 48 % is not "most".
        assert!(
            text.contains("(1) RNE rescues the most in total: cannot be said to hold in most"),
            "{text}"
        );
        let partial = conclusions(&tally(2, true), &plan());
        assert!(
            partial.contains(
                "only 2 of the 6 universes this run makes have a record, 0 of them failed"
            ),
            "{partial}"
        );
        assert!(!partial.contains("CI"), "{partial}");
        assert!(conclusions(&tally(6, false), &plan()).contains("No universe is admissible"));
        assert!(
            conclusions(&Tally::of(&[], &[2, 3], &[]), &plan()).contains("nothing to conclude")
        );
    }
}
