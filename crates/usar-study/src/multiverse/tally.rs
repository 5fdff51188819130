//! Counts over the universes' records: how many are admissible, and how often each claim
//! holds (is not significant, does not hold) among the admissible universes, in all and per
//! alternative of each axis. `multiverse.md` and the terminal summary show them.

use super::record::{Status, UniverseRecord};
use usar_report::claims::{Claim, Verdict};

/// The verdicts a claim got in some universes.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct VerdictCount {
    /// Universes counted (each has one verdict, or none when its comparison did not run).
    pub universes: usize,
    /// Where the claim holds.
    pub holds: usize,
    /// Where it is not significant.
    pub not_significant: usize,
    /// Where it does not hold.
    pub does_not_hold: usize,
    /// Where it was not tested, does not apply, or no comparison ran.
    pub other: usize,
}

impl VerdictCount {
    /// Counts the verdict of claim `claim` in `record`.
    pub fn add(&mut self, record: &UniverseRecord, claim: &str) {
        self.universes += 1;
        let words = record.claim(claim).map(|c| c.verdict.as_str());
        match words {
            Some(w) if w == Verdict::Holds.words() => self.holds += 1,
            Some(w) if w == Verdict::NotSignificant.words() => self.not_significant += 1,
            Some(w) if w == Verdict::DoesNotHold.words() => self.does_not_hold += 1,
            _ => self.other += 1,
        }
    }
}

/// Confidence level of every share's interval ([`clopper_pearson`]): 0.95.
pub const SHARE_CONFIDENCE: f64 = 0.95;

/// The two-sided Clopper-Pearson interval of a share seen as `k` of `n` (`k <= n`, `n >= 1`)
/// at [`SHARE_CONFIDENCE`], as fractions in `[0, 1]`; `None` for `n = 0` (or `k > n`).
///
/// With `a = 1 - SHARE_CONFIDENCE`: the lower end is the `a / 2` quantile of Beta(k, n - k + 1)
/// (0 when `k = 0`), the upper end the `1 - a / 2` quantile of Beta(k + 1, n - k) (1 when
/// `k = n`). Exact in that it covers the true share at least 95 % of the time for a random
/// sample (a `--sample` of the factorial, or the admissible universes within it); conservative.
/// Seen 0 of 5: 0 to 52 %.
///
/// # Reference
/// C. J. Clopper and E. S. Pearson, "The use of confidence or fiducial limits illustrated in
/// the case of the binomial", Biometrika 26 (1934) 404-413.
pub fn clopper_pearson(k: usize, n: usize) -> Option<(f64, f64)> {
    use statrs::distribution::{Beta, ContinuousCDF};
    if n == 0 || k > n {
        return None;
    }
    let a = 1.0 - SHARE_CONFIDENCE;
    let (kf, nf) = (k as f64, n as f64);
    let lower = if k == 0 {
        0.0
    } else {
        Beta::new(kf, nf - kf + 1.0).ok()?.inverse_cdf(a / 2.0)
    };
    let upper = if k == n {
        1.0
    } else {
        Beta::new(kf + 1.0, nf - kf)
            .ok()?
            .inverse_cdf(1.0 - a / 2.0)
    };
    Some((lower, upper))
}

/// A share as the report writes it: `k/n (p %)`, with `with_interval` `k/n (p %, 95 % CI lo to
/// hi %)` (the [`clopper_pearson`] interval; for the shares of a `--sample` of the
/// factorial), or `0/0` for none.
pub fn share(k: usize, n: usize, with_interval: bool) -> String {
    match clopper_pearson(k, n) {
        None => "0/0".into(),
        Some((lo, hi)) if with_interval => format!(
            "{k}/{n} ({:.0} %, 95 % CI {:.0} to {:.0} %)",
            100.0 * k as f64 / n as f64,
            100.0 * lo,
            100.0 * hi
        ),
        Some(_) => format!("{k}/{n} ({:.0} %)", 100.0 * k as f64 / n as f64),
    }
}

/// The counts of a multiverse.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Tally {
    /// Universes with a record.
    pub universes: usize,
    /// Admissible universes.
    pub admissible: usize,
    /// Universes whose choices break a rule.
    pub invalid: usize,
    /// Universes that failed (calibration error or failed trials).
    pub failed: usize,
    /// Per claim (of the plan's, in order), the verdicts among the admissible universes.
    pub claims: Vec<VerdictCount>,
    /// Per axis, per alternative, per claim: the verdicts among the admissible universes
    /// that take the alternative (`by_alternative[axis][alt][claim]`).
    pub by_alternative: Vec<Vec<Vec<VerdictCount>>>,
}

impl Tally {
    /// Counts `records` of a multiverse whose axes have `sizes` alternatives and whose
    /// universes check `claims`.
    pub fn of(records: &[UniverseRecord], sizes: &[usize], claims: &[Claim]) -> Self {
        Self::within(records, sizes, claims, 0.0)
    }

    /// [`Tally::of`] with "admissible" read as a loss of at most `max_loss` (the
    /// near-admissible universes of `--near-loss`: [`UniverseRecord::within_loss`]).
    pub fn within(
        records: &[UniverseRecord],
        sizes: &[usize],
        claims: &[Claim],
        max_loss: f64,
    ) -> Self {
        let blank = vec![VerdictCount::default(); claims.len()];
        let mut t = Self {
            universes: records.len(),
            admissible: 0,
            invalid: 0,
            failed: 0,
            claims: blank.clone(),
            by_alternative: sizes.iter().map(|&k| vec![blank.clone(); k]).collect(),
        };
        for r in records {
            match r.status {
                Status::Invalid => t.invalid += 1,
                Status::Failed => t.failed += 1,
                Status::Ok => {}
            }
            if !r.within_loss(max_loss) {
                continue;
            }
            t.admissible += 1;
            for (c, claim) in claims.iter().enumerate() {
                t.claims[c].add(r, &claim.id);
                for (axis, &alt) in r.choices.iter().enumerate() {
                    if let Some(count) = t.by_alternative.get_mut(axis).and_then(|a| a.get_mut(alt))
                    {
                        count[c].add(r, &claim.id);
                    }
                }
            }
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multiverse::record::tests::record;

    #[test]
    fn only_admissible_universes_count_for_the_claims() {
        let mut a = record(0, &[0, 1], 0.0);
        let b = record(1, &[1, 1], 0.0);
        let c = record(2, &[1, 0], 2.0);
        if let Some(cmp) = a.comparison.as_mut() {
            cmp.claims[0].verdict = "does not hold".into();
        }
        let mut d = record(3, &[0, 0], 0.0);
        d.status = Status::Invalid;
        d.calibration = None;
        d.comparison = None;
        let t = Tally::of(
            &[a, b, c, d],
            &[2, 2],
            usar_report::claims::paper_claims().claims(),
        );
        assert_eq!(
            (t.universes, t.admissible, t.invalid, t.failed),
            (4, 2, 1, 0)
        );
        let one = t.claims[0];
        assert_eq!((one.universes, one.holds, one.does_not_hold), (2, 1, 1));
        // Claim 2 has no effect in these records: counted as other.
        assert_eq!(t.claims[1].other, 2);
        // Axis 0: alternative 0 is taken by a (does not hold), 1 by b (holds).
        assert_eq!(t.by_alternative[0][0][0].does_not_hold, 1);
        assert_eq!(t.by_alternative[0][1][0].holds, 1);
        assert_eq!(t.by_alternative[1][0][0].universes, 0);
        assert_eq!(t.by_alternative[1][1][0].universes, 2);
        assert_eq!(share(1, 3, true), "1/3 (33 %, 95 % CI 1 to 91 %)");
        assert_eq!(share(1, 3, false), "1/3 (33 %)");
        assert_eq!(share(0, 0, true), "0/0");
    }

    /// Against the closed forms of the end cases and R's `binom.test` (its Clopper-Pearson
    /// interval): 0 of 5 is 0 to 1 - 0.025^(1/5); 5 of 5 is 0.025^(1/5) to 1; 3 of 10 is
    /// 0.06673951 to 0.65245285.
    #[test]
    fn clopper_pearson_matches_the_closed_forms_and_r() {
        let tol = 1e-6;
        let (lo, hi) = clopper_pearson(0, 5).unwrap();
        assert_eq!(lo, 0.0);
        assert!((hi - (1.0 - 0.025f64.powf(0.2))).abs() < tol, "{hi}");
        let (lo, hi) = clopper_pearson(5, 5).unwrap();
        assert!((lo - 0.025f64.powf(0.2)).abs() < tol, "{lo}");
        assert_eq!(hi, 1.0);
        let (lo, hi) = clopper_pearson(3, 10).unwrap();
        assert!((lo - 0.066_739_51).abs() < tol, "{lo}");
        assert!((hi - 0.652_452_85).abs() < tol, "{hi}");
        assert_eq!(clopper_pearson(0, 0), None);
        assert_eq!(clopper_pearson(3, 2), None);
    }
}
