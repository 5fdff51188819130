//! A claim's effect in one universe: the claim's subject minus its strongest rival, signed so
//! that a positive effect is the claim's direction, with the 95 % Welch confidence interval
//! of that difference ([`usar_report::stats::welch_interval`]), and the verdict and p of
//! [`usar_report::claims::check_claim`] as the sweep reports give them.
//!
//! The strongest rival is the other method with the best mean in the claim's direction (the
//! highest for a claim that the subject is highest, the lowest for one that it is lowest;
//! the first in method order among equals), over the methods with at least one value. For a
//! "lowest" claim the difference is negated (rival minus subject), so for every claim an
//! effect above 0 means the subject beats its strongest rival, and a confidence interval
//! above 0 means it does so clearly.

use serde::{Deserialize, Serialize};

use usar_report::claims::{ClaimCheck, Direction};
use usar_report::stats::{Summary, welch_interval};
use usar_report::targets::float_text;

/// One claim's effect and verdict in one universe.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClaimEffect {
    /// The claim's id (`1`, `4a`; [`usar_report::claims::Claim::id`]).
    pub claim: String,
    /// The verdict in words ([`usar_report::claims::Verdict::words`]: `holds`, `not significant`,
    /// `does not hold`, `not tested`).
    pub verdict: String,
    /// The strongest rival (display name), `None` when no other method has a value.
    pub rival: Option<String>,
    /// Subject minus rival, signed so that > 0 is the claim's direction; units of the
    /// claim's metric (rescuees, percent points). NaN without a subject or rival value.
    #[serde(with = "float_text")]
    pub effect: f64,
    /// Lower end of the 95 % Welch confidence interval of the effect; NaN with fewer than two
    /// values on either side.
    #[serde(with = "float_text")]
    pub ci_low: f64,
    /// Upper end of that interval; NaN likewise.
    #[serde(with = "float_text")]
    pub ci_high: f64,
    /// The largest p over every rival of the claim's own test after its correction (the p
    /// the verdict is decided by, [`ClaimCheck::worst_p`]); NaN when some test is undefined.
    #[serde(with = "float_text")]
    pub p: f64,
}

/// The effect of a checked claim.
pub fn claim_effect(check: &ClaimCheck) -> ClaimEffect {
    let sign = match check.claim.direction {
        Direction::More => 1.0,
        Direction::Less => -1.0,
    };
    let rival = check
        .comparisons
        .iter()
        .filter(|c| c.other_summary.n > 0 && c.other_summary.mean.is_finite())
        .fold(None::<(&str, &Summary)>, |best, c| match best {
            Some((_, b)) if sign * c.other_summary.mean <= sign * b.mean => best,
            _ => Some((&c.other, &c.other_summary)),
        });
    let (effect, low, high) = match rival {
        Some((_, r)) if check.subject_summary.n > 0 => {
            let i = welch_interval(&check.subject_summary, r);
            if sign > 0.0 {
                (i.diff, i.low, i.high)
            } else {
                (-i.diff, -i.high, -i.low)
            }
        }
        _ => (f64::NAN, f64::NAN, f64::NAN),
    };
    // `+ 0.0` turns a negated 0 (a "lowest" claim's tie) into 0, so that files write `0`.
    ClaimEffect {
        claim: check.claim.id.to_string(),
        verdict: check.verdict.words().to_string(),
        rival: rival.map(|(name, _)| name.to_string()),
        effect: effect + 0.0,
        ci_low: low + 0.0,
        ci_high: high + 0.0,
        p: check.worst_p(),
    }
}

#[cfg(test)]
mod tests {
    use usar_sim::mission::TrialResult;

    use super::*;
    use usar_report::claims::{Claim, check_claim, paper_claims};

    /// The paper's claim `i` (0-based, file order).
    fn paper(i: usize) -> &'static Claim {
        &paper_claims().claims()[i]
    }

    /// A trial of `method` with `hard` and `easy` rescuees and `energy_hard` percent points
    /// spent in the hard task (tasks `[hard, easy]`).
    fn trial(method: &str, k: u32, hard: u32, easy: u32, energy_hard: f64) -> TrialResult {
        TrialResult {
            scenario: "t".into(),
            method: method.into(),
            trial: k,
            seed: u64::from(k),
            duration_s: 600.0,
            tasks: tasks(),
            rescued: vec![hard, easy],
            energy_spent_pct: vec![energy_hard, 1.0],
            hp_lost_pct: vec![1.0, 1.0],
            rounds: Vec::new(),
            robots: Vec::new(),
        }
    }

    fn tasks() -> Vec<String> {
        vec!["hard".into(), "easy".into()]
    }

    fn methods() -> Vec<String> {
        ["RNE", "DIS", "ENG"].map(String::from).to_vec()
    }

    /// RNE rescues 13, 14, 15 in the hard task; DIS 5, 6, 7; ENG 8, 9, 10. Energy in the hard
    /// task: RNE 30 each, DIS 60, ENG 40.
    fn results() -> Vec<TrialResult> {
        let mut out = Vec::new();
        for (k, (r, d, e)) in [(13, 5, 8), (14, 6, 9), (15, 7, 10)]
            .into_iter()
            .enumerate()
        {
            let k = k as u32;
            out.push(trial("RNE", k, r, 1, 30.0));
            out.push(trial("DIS", k, d, 1, 60.0));
            out.push(trial("ENG", k, e, 1, 40.0));
        }
        out
    }

    #[test]
    fn a_highest_claim_is_measured_against_the_best_rival() {
        // Claim 2: RNE rescues the most in the hard task. Strongest rival: ENG (mean 9).
        let check = check_claim(paper(1), &results(), &methods(), &tasks());
        let e = claim_effect(&check);
        assert_eq!(e.rival.as_deref(), Some("ENG"));
        assert_eq!(e.verdict, "holds");
        assert!((e.effect - 5.0).abs() < 1e-12, "{e:?}");
        // sd 1 and 1, n 3: se = sqrt(1/3 + 1/3) = 0.816497, dof = 4, t(0.975, 4) = 2.776445:
        // 5 ± 2.266958.
        assert!((e.ci_low - (5.0 - 2.266_958)).abs() < 1e-5, "{e:?}");
        assert!((e.ci_high - (5.0 + 2.266_958)).abs() < 1e-5, "{e:?}");
        assert!((e.p - check.worst_p()).abs() < 1e-15);
    }

    #[test]
    fn a_named_rival_without_values_leaves_the_claim_untested() {
        // ENG rescues nobody in the hard task: its cost per hard rescuee has no value.
        let mut r = results();
        for t in r.iter_mut().filter(|t| t.method == "ENG") {
            t.rescued[0] = 0;
        }
        let mut claim = paper(3).clone();
        claim.rivals = usar_report::claims::Rivals::Only(vec!["eng".into()]);
        let check = check_claim(&claim, &r, &methods(), &tasks());
        assert_eq!(check.verdict, usar_report::claims::Verdict::NotTested);
        assert_eq!(
            check.reason.as_deref(),
            Some("no trial of its rival ENG has a value of energy_per_hard_rescuee_pct")
        );
        // Against every rival, ENG is left out and DIS decides.
        let check = check_claim(paper(3), &r, &methods(), &tasks());
        assert_eq!(check.comparisons.len(), 1);
        assert_eq!(check.verdict, usar_report::claims::Verdict::Holds);
    }

    #[test]
    fn a_lowest_claim_is_signed_so_that_positive_is_its_direction() {
        // Claim 4a: RNE has the lowest energy per hard rescuee. RNE 30/13, 30/14, 30/15 (2.14
        // on average); ENG 40/8, 40/9, 40/10 (4.48); DIS 60/5, 60/6, 60/7 (10.2). Rival: ENG.
        let check = check_claim(paper(3), &results(), &methods(), &tasks());
        let e = claim_effect(&check);
        assert_eq!(e.rival.as_deref(), Some("ENG"));
        let rne = (30.0 / 13.0 + 30.0 / 14.0 + 2.0) / 3.0;
        let eng = (5.0 + 40.0 / 9.0 + 4.0) / 3.0;
        assert!((e.effect - (eng - rne)).abs() < 1e-12, "{e:?}");
        assert!(e.effect > 0.0 && e.ci_low < e.effect && e.effect < e.ci_high);
        // The interval is that of rival minus subject: the mirror of subject minus rival.
        let i = welch_interval(&check.subject_summary, &check.comparisons[1].other_summary);
        assert!((e.ci_low + i.high).abs() < 1e-12 && (e.ci_high + i.low).abs() < 1e-12);
    }

    #[test]
    fn a_claim_that_fails_has_a_negative_effect_and_no_values_give_nan() {
        // Claim 3: DIS rescues the most in the easy task; every method rescues 1 there, so the
        // effect is 0 with a point interval and the claim does not hold.
        let check = check_claim(paper(2), &results(), &methods(), &tasks());
        let e = claim_effect(&check);
        assert_eq!(e.verdict, "does not hold");
        assert_eq!((e.effect, e.ci_low, e.ci_high), (0.0, 0.0, 0.0));
        // Claim 2 with DIS as the subject's only rival and RNE losing: negative.
        let mut r = results();
        r.retain(|t| t.method != "ENG");
        for t in r.iter_mut().filter(|t| t.method == "DIS") {
            t.rescued[0] += 20;
        }
        let e = claim_effect(&check_claim(paper(1), &r, &methods()[..2], &tasks()));
        assert_eq!(e.rival.as_deref(), Some("DIS"));
        assert!((e.effect + 12.0).abs() < 1e-12 && e.ci_high < 0.0, "{e:?}");
        // No rival at all.
        let only: Vec<TrialResult> = results()
            .into_iter()
            .filter(|t| t.method == "RNE")
            .collect();
        let e = claim_effect(&check_claim(paper(1), &only, &methods()[..1], &tasks()));
        assert_eq!(e.rival, None);
        assert!(e.effect.is_nan() && e.ci_low.is_nan() && e.p.is_nan());
        assert_eq!(e.verdict, "not tested");
    }
}
