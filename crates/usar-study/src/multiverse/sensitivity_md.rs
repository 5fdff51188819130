//! The two sections of `multiverse.md` that test how far its verdicts lean on its choices:
//! the shares among the near-admissible universes (`--near-loss`), and which axes and
//! calibrated values decide each claim ([`super::decompose`]).

use std::fmt::Write;

use super::decompose::{Decomposition, Scope, Share, decompose_over, decompose_within};
use super::plan::MultiversePlan;
use super::record::UniverseRecord;
use super::sensitivity_figure::sensitivity_file;
use super::tally::{Tally, share};

/// "Sensitivity: near-admissible universes": with `--near-loss`, the admissible share and
/// each claim's shares again with every universe whose loss is at most the given one counted
/// as admissible. Nothing without `--near-loss`.
pub fn near_admissible(r: &mut String, plan: &MultiversePlan, records: &[UniverseRecord]) {
    let Some(max_loss) = plan.near_loss else {
        return;
    };
    let id = &plan.identity;
    let t = Tally::within(records, &id.axes.sizes(), &id.claims, max_loss);
    let sampled = plan.sampled();
    let _ = writeln!(
        r,
        "## Sensitivity: near-admissible universes (loss <= {max_loss})\n"
    );
    let _ = writeln!(
        r,
        "The shares again with every universe whose calibration came within a loss of \
         {max_loss} of the bands counted as admissible (`--near-loss {max_loss}`): {} of the \
         universes.\n",
        share(t.admissible, t.universes, sampled)
    );
    if id.claims.is_empty() {
        return;
    }
    let _ = writeln!(
        r,
        "| claim | holds | not significant | does not hold | no verdict |\n|---|---|---|---|---|"
    );
    for (c, count) in id.claims.iter().zip(&t.claims) {
        let _ = writeln!(
            r,
            "| ({}) {} | {} | {} | {} | {} |",
            c.id,
            c.sentence,
            share(count.holds, count.universes, sampled),
            share(count.not_significant, count.universes, sampled),
            share(count.does_not_hold, count.universes, sampled),
            share(count.other, count.universes, sampled),
        );
    }
    let _ = writeln!(
        r,
        "\nPer claim, the two axes that explain the most of its effect's variance among these \
         universes (first-order share, chance level in brackets; as in \"Which choices decide \
         each claim\"):\n"
    );
    for c in &id.claims {
        let strongest = match decompose_within(plan, records, c, max_loss) {
            Some(d) => d
                .strongest()
                .iter()
                .take(2)
                .map(|&a| format!("{} ({})", d.axes[a].name, pct(&d.axes[a])))
                .collect::<Vec<_>>()
                .join(" and "),
            None => "fewer than 3 universes with an effect, or an effect that does not vary".into(),
        };
        let _ = writeln!(r, "- ({}): {strongest}", c.id);
    }
    let _ = writeln!(r);
}

/// "Which choices decide each claim": per claim, the share of its effect's variance over the
/// admissible universes that each axis and each calibrated value explains (with its chance
/// level), and the interaction of the two strongest axes ([`super::decompose`], its
/// estimator); then the same over every compared universe, admissible or not.
pub fn deciding_choices(r: &mut String, plan: &MultiversePlan, records: &[UniverseRecord]) {
    let id = &plan.identity;
    if id.claims.is_empty() {
        return;
    }
    let _ = writeln!(r, "## Which choices decide each claim\n");
    let _ = writeln!(
        r,
        "Per claim, the share of the variance of its effect over the admissible universes that \
         each axis explains (the correlation ratio: the first-order Sobol index estimated from \
         the means per alternative; the ANOVA main-effect share for a whole factorial), each \
         calibrated value explains (its squared correlation with the effect), and the \
         interaction of the two strongest axes adds; and each axis's total-order share (its \
         main effect and every interaction it is part of: the variance left when every other \
         axis is fixed, from the admissible universes that differ in that axis alone, counted \
         in the column). In brackets, the share's chance level, its mean were the input to \
         have no effect at all: a share near it says nothing. Then the same over every \
         compared universe, admissible or not: what moves the claim across the readings, \
         whether or not they fit the authors' statistics. Estimators and references: \
         `usar_study::multiverse::decompose`.\n"
    );
    for c in &id.claims {
        let _ = writeln!(r, "### ({}) {}\n", c.id, c.sentence);
        for scope in [Scope::Admissible, Scope::Compared] {
            if scope == Scope::Compared {
                let _ = writeln!(
                    r,
                    "Over every compared universe, admissible or not (how the readings move \
                     the effect, whether the bands hold or not):\n"
                );
            }
            match decompose_over(plan, records, c, scope) {
                Some(d) => claim_table(r, &d, scope),
                None => {
                    let _ = writeln!(
                        r,
                        "Fewer than 3 {} with an effect, or an effect that does not vary: \
                         nothing to split.\n",
                        scope.noun()
                    );
                }
            }
        }
        let file = sensitivity_file(c);
        let _ = writeln!(r, "![Claim {}: what decides it]({file})\n", c.id);
    }
}

/// One claim's table over the universes of `scope`, strongest axis first, and the sentence
/// naming the two strongest.
fn claim_table(r: &mut String, d: &Decomposition, scope: Scope) {
    let order = d.strongest();
    let _ = writeln!(
        r,
        "{} {} with an effect. The two axes that matter most: {}.\n",
        d.n,
        scope.noun(),
        order
            .iter()
            .take(2)
            .map(|&a| format!("{} ({})", d.axes[a].name, pct(&d.axes[a])))
            .collect::<Vec<_>>()
            .join(" and ")
    );
    let _ = writeln!(
        r,
        "| input | share of the variance (chance) | total-order share (chance; universes) \
         |\n|---|---|---|"
    );
    for &a in &order {
        let total = match &d.total[a] {
            Some(t) => format!(
                "{:.0} % (chance {:.0} %; {})",
                100.0 * t.share,
                100.0 * t.chance,
                t.universes
            ),
            None => "no two differ in it alone".into(),
        };
        let _ = writeln!(
            r,
            "| axis: {} | {} | {total} |",
            d.axes[a].name,
            pct(&d.axes[a])
        );
    }
    if let Some((_, _, i)) = &d.interaction {
        let _ = writeln!(r, "| interaction: {} | {} | |", i.name, pct(i));
    }
    for f in &d.free {
        let _ = writeln!(r, "| calibrated: {} | {} | |", f.name, pct(f));
    }
    let _ = writeln!(r);
}

/// `37 % (chance 12 %)`.
fn pct(s: &Share) -> String {
    format!(
        "{:.0} % (chance {:.0} %)",
        100.0 * s.share,
        100.0 * s.chance
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multiverse::plan::tests::plan;
    use crate::multiverse::record::tests::record;

    #[test]
    fn near_admissible_universes_are_counted_up_to_the_loss_given() {
        let records = [
            record(0, &[0, 0], 0.0),
            record(1, &[1, 1], 0.5),
            record(2, &[0, 2], 3.0),
        ];
        let mut r = String::new();
        near_admissible(&mut r, &plan(), &records);
        assert!(r.is_empty(), "nothing without --near-loss");
        let mut p = plan();
        p.near_loss = Some(1.0);
        near_admissible(&mut r, &p, &records);
        assert!(
            r.contains("## Sensitivity: near-admissible universes (loss <= 1)"),
            "{r}"
        );
        assert!(
            r.contains("counted as admissible (`--near-loss 1`): 2/3 (67 %)"),
            "{r}"
        );
        assert!(
            r.contains("| (1) RNE rescues the most in total | 2/2 (100 %) |"),
            "{r}"
        );
        assert!(
            r.contains(
                "- (1): fewer than 3 universes with an effect, or an effect that does not vary"
            ),
            "{r}"
        );
        let options = p.options();
        assert!(
            options.windows(2).any(|w| w == ["--near-loss", "1"]),
            "{options:?}"
        );
    }

    #[test]
    fn each_claim_names_the_axes_that_decide_it() {
        let mut records = Vec::new();
        for (i, (a, b)) in [(0, 0), (0, 1), (1, 0), (1, 1), (0, 2), (1, 2)]
            .into_iter()
            .enumerate()
        {
            let mut r = record(i as u64, &[a, b], 0.0);
            if let Some(c) = r.comparison.as_mut() {
                c.claims[0].effect = 10.0 * b as f64;
            }
            records.push(r);
        }
        let mut r = String::new();
        deciding_choices(&mut r, &plan(), &records);
        assert!(r.contains("### (1) RNE rescues the most in total"), "{r}");
        assert!(
            r.contains(
                "6 admissible universes with an effect. The two axes that matter most: b \
                        (100 % (chance 40 %)) and a (0 % (chance 20 %))."
            ),
            "{r}"
        );
        assert!(r.contains("| calibrated: mission.energy_pct_per_m | 0 % (chance 20 %) |"));
        assert!(
            r.contains(
                "Over every compared universe, admissible or not (how the readings move the \
                 effect, whether the bands hold or not):\n\n6 compared universes with an effect. \
                 The two axes that matter most: b (100 % (chance 40 %))"
            ),
            "{r}"
        );
        // Four of them out of the bands: two admissible are too few, the six compared are not.
        for rec in &mut records[2..] {
            if let Some(c) = rec.calibration.as_mut() {
                c.loss = 0.5;
            }
        }
        let mut loose = String::new();
        deciding_choices(&mut loose, &plan(), &records);
        assert!(
            loose.contains(
                "Fewer than 3 admissible universes with an effect, or an effect that does not \
                 vary: nothing to split."
            ),
            "{loose}"
        );
        assert!(
            loose.contains("6 compared universes with an effect"),
            "{loose}"
        );
        // The paper's other claims have no effect in these records.
        assert!(r.contains(
            "### (2) RNE rescues more in the hard task than every baseline\n\n\
                            Fewer than 3"
        ));
    }
}
