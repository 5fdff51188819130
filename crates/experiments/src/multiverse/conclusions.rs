//! What a multiverse run can and cannot conclude, written from its counts ([`Tally`]), not by
//! hand: the admissible share and, per claim, where it holds among the admissible universes,
//! each with its [`clopper_pearson`] interval when the universes are a sample of the factorial.
//! `multiverse.md` shows it under "What this run can conclude".

use std::fmt::Write;

use super::tally::{Tally, clopper_pearson, share};
use crate::claims::CLAIMS;

/// The paragraph of conclusions for `t`: `sampled` when the universes are a `--sample` of
/// the `factorial` universes (the shares are estimates, with intervals); else the shares are
/// those of the universes with a record (the factorial's own once every one has run).
pub fn conclusions(t: &Tally, sampled: bool, factorial: u64) -> String {
    let mut r = String::new();
    if t.universes == 0 {
        let _ = writeln!(r, "No universe has a record yet: nothing to conclude.");
        return r;
    }
    let _ = write!(
        r,
        "- {} of the universes are admissible",
        share(t.admissible, t.universes)
    );
    if sampled {
        let (lo, hi) = clopper_pearson(t.admissible, t.universes).unwrap_or((0.0, 1.0));
        let _ = writeln!(
            r,
            ". They are a random sample of the {factorial} universes of the factorial: the \
             admissible share of the whole factorial lies between {:.0} and {:.0} % (95 %).",
            100.0 * lo,
            100.0 * hi
        );
    } else if t.universes as u64 == factorial {
        let _ = writeln!(
            r,
            ": the whole factorial ran, so this is the share of the readings the axes write \
             under which the model reaches its targets, not an estimate."
        );
    } else {
        let _ = writeln!(
            r,
            ": only {} of the factorial's {factorial} universes have a record (the run is not \
             complete), and they are not a random sample of it: the shares below are of those.",
            t.universes
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
    for (c, count) in CLAIMS.iter().zip(&t.claims) {
        let (k, n) = (count.holds, count.universes);
        let Some((lo, hi)) = clopper_pearson(k, n) else {
            continue;
        };
        let (lo, hi) = if sampled {
            (lo, hi)
        } else {
            let p = k as f64 / n as f64;
            (p, p)
        };
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
            c.id, c.text
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
    use crate::multiverse::record::tests::record;

    #[test]
    fn a_sample_gets_intervals_and_a_whole_factorial_exact_shares() {
        let records: Vec<_> = (0..5).map(|i| record(i, &[0, 1], 0.0)).collect();
        let t = Tally::of(&records, &[2, 2]);
        let sampled = conclusions(&t, true, 64);
        assert!(
            sampled.contains(
                "5/5 (100 %, 95 % CI 48 to 100 %) of the universes are admissible. They are a \
                 random sample of the 64 universes"
            ),
            "{sampled}"
        );
        // Claim 1 holds in all five: at least 48 % is not "most".
        assert!(
            sampled.contains("(1) RNE rescues the most in total: cannot be said to hold in most"),
            "{sampled}"
        );
        let whole = conclusions(&t, false, 5);
        assert!(whole.contains("the whole factorial ran"), "{whole}");
        assert!(whole.contains("(1) RNE rescues the most in total: holds in most admissible readings (at least 100 %)"), "{whole}");
        let none = Tally::of(&[record(0, &[0, 0], 3.0)], &[2, 2]);
        assert!(conclusions(&none, true, 4).contains("No universe is admissible"));
        assert!(conclusions(&Tally::of(&[], &[2]), true, 2).contains("nothing to conclude"));
    }
}
