//! `multiverse.md`: the command, the set-up (axes with the paper's words, free fields,
//! targets, trials), the admissible share, per claim the share of admissible universes where
//! it holds (is not significant, does not hold), each target's statistic across the universes,
//! a table per axis (per alternative, the share
//! of its admissible universes where each claim holds), the figures, and every universe
//! (choices, admissible, loss, calibrated values, status and message).
//!
//! Made from the plan and the records alone, with no date or timing: the same multiverse
//! gives the same bytes on any thread count, resumed or merged from shards.

use std::fmt::Write;

use super::conclusions::conclusions;
use super::plan::MultiversePlan;
use super::record::UniverseRecord;
use super::sensitivity_md::{deciding_choices, near_admissible};
use super::spec_curve::spec_curve_file;
use super::tally::{Tally, VerdictCount, share};
use crate::calibrate::progress::loss_text;
use usar_report::claims::Claim;

/// The figure of each target's statistic per universe (`super::outputs` draws it).
pub const TARGETS_FIGURE_FILE: &str = "targets.svg";

/// `text` as a table cell: `|` escaped, line breaks as spaces.
fn cell(text: &str) -> String {
    text.replace('|', "\\|").replace(['\n', '\r'], " ")
}

/// The text of `multiverse.md` for the records (in universe order).
pub fn multiverse_md(plan: &MultiversePlan, records: &[UniverseRecord]) -> String {
    let tally = Tally::of(records, &plan.identity.axes.sizes(), &plan.identity.claims);
    let mut r = String::new();
    let _ = writeln!(r, "# Multiverse: {}\n", plan.identity.scenario);
    set_up(&mut r, plan, records.len());
    claims(&mut r, &tally, plan.sampled(), &plan.identity.claims);
    let _ = writeln!(r, "## What this run can conclude\n");
    let _ = writeln!(r, "{}", conclusions(&tally, plan));
    near_admissible(&mut r, plan, records);
    targets(&mut r, plan, records);
    by_axis(&mut r, plan, &tally);
    deciding_choices(&mut r, plan, records);
    if !plan.identity.claims.is_empty() {
        figures(&mut r, &plan.identity.claims);
    }
    universes(&mut r, plan, records);
    r
}

/// The command and the set-up.
fn set_up(r: &mut String, plan: &MultiversePlan, count: usize) {
    let id = &plan.identity;
    let _ = writeln!(r, "```sh\n{}\n```\n", plan.command(None));
    let _ = writeln!(r, "## Set-up\n");
    let drawn = match id.sample {
        Some(s) => format!("a sample drawn without replacement with seed {}", s.seed),
        None => "every one".into(),
    };
    let length = id
        .duration_s
        .map_or("each universe's mission.duration_s".into(), |d| {
            format!("{d} s")
        });
    let _ = writeln!(
        r,
        "- base scenario: `{}` (scenario hash `{}`); build `{}`\n- universes: {count} of the \
         factorial's {} ({drawn}), one alternative per axis\n- in each: the free fields are \
         calibrated to the targets ({}, at most {} evaluations of {} x {} trials, base \
         seed {}, values to {} significant digits{}{}); the universe is **admissible** when every \
         target's statistic lies in its band (loss 0){}\n- then the comparison on the calibrated \
         scenario: {} x {} trials of {length}, base seed {} (common random numbers)\n",
        plan.scenario_path,
        id.scenario_hash,
        if id.build.is_empty() {
            "unrecorded"
        } else {
            &id.build
        },
        plan.factorial(),
        if id.optimizer.is_some() {
            "CMA-ES"
        } else {
            "Nelder-Mead"
        },
        id.max_evals,
        id.methods.join(", "),
        id.calibration_trials,
        id.calibration_seed,
        id.digits,
        if id.design > 0 {
            format!(
                "; starting where an emulator fitted to {} shared design evaluations predicts \
                 the least loss",
                id.design
            )
        } else {
            String::new()
        },
        id.check.map_or(String::new(), |c| format!(
            "; a point in band is checked on {} unseen trials per method, base seed {}",
            c.trials, c.seed
        )),
        if id.check.is_some() {
            ", on the calibration's trials and on the unseen ones"
        } else {
            ""
        },
        id.methods.join(", "),
        id.trials,
        id.seed,
    );
    axes_and_targets(r, plan);
}

/// The axes with the paper's words and each alternative's overrides, the free fields and the
/// targets.
fn axes_and_targets(r: &mut String, plan: &MultiversePlan) {
    let id = &plan.identity;
    let _ = writeln!(r, "### Axes (`{}`)\n", plan.axes_path);
    let _ = writeln!(r, "| axis | the paper | alternatives |\n|---|---|---|");
    for a in &id.axes.axes {
        let alts: Vec<String> = a
            .alternatives
            .iter()
            .map(|alt| {
                let sets: Vec<String> = alt.set.iter().map(|s| format!("`{s}`")).collect();
                let mut sets = if sets.is_empty() {
                    "the base scenario's values".into()
                } else {
                    sets.join(", ")
                };
                let names = |n: &[String]| n.iter().map(|t| format!("{t:?}")).collect::<Vec<_>>();
                if !alt.require.is_empty() {
                    sets += &format!("; fitted: {}", names(&alt.require).join(", "));
                }
                if !alt.report_only.is_empty() {
                    sets += &format!("; report-only: {}", names(&alt.report_only).join(", "));
                }
                format!("**{}**: {sets}", alt.name)
            })
            .collect();
        let _ = writeln!(
            r,
            "| {} | {} | {} |",
            cell(&a.name),
            cell(&a.paper),
            cell(&alts.join("; "))
        );
    }
    let _ = writeln!(
        r,
        "\n### Free fields and targets (`{}`)\n",
        plan.targets_path
    );
    for f in &id.free {
        let _ = writeln!(r, "- `--free {f}`");
    }
    let _ = writeln!(
        r,
        "\n| target | statistic | value and band |\n|---|---|---|"
    );
    for t in &id.targets {
        let _ = writeln!(
            r,
            "| {} | `{}` | {} |",
            cell(&t.name),
            t.statistic,
            t.describe()
        );
    }
    if id.axes.flags_targets() {
        let _ = writeln!(
            r,
            "\nThe targets a universe fits follow its alternatives (\"fitted\" and \
             \"report-only\" in the axes above), and its admissibility with them."
        );
    }
    let _ = writeln!(r);
}

/// The admissible share and the share per claim.
fn claims(r: &mut String, t: &Tally, sampled: bool, claims_of: &[Claim]) {
    let _ = writeln!(r, "## Admissible universes\n");
    let _ = writeln!(
        r,
        "{} admissible, {} not admissible; {} invalid (their choices break a rule), {} failed \
         (run the command again to retry them).\n",
        share(t.admissible, t.universes, sampled),
        t.universes - t.admissible,
        t.invalid,
        t.failed
    );
    if claims_of.is_empty() {
        let _ = writeln!(
            r,
            "No claims were checked (`--claims FILE`, or the scenario's `report: (claims: \
             ...)`, gives them).\n"
        );
        return;
    }
    let _ = writeln!(r, "## Claims across the admissible universes\n");
    let _ = writeln!(
        r,
        "Verdicts as in the sweep's reports (each claim's test, level and correction below); \
         shares of the {} admissible universes.\n",
        t.admissible
    );
    let _ = writeln!(
        r,
        "| claim | holds | not significant | does not hold | no verdict | figure |\n|---|---|---|---|---|---|"
    );
    for (c, count) in claims_of.iter().zip(&t.claims) {
        let file = spec_curve_file(c);
        let _ = writeln!(
            r,
            "| ({}) {} ({}) | {} | {} | {} | {} | [{file}]({file}) |",
            c.id,
            c.sentence,
            c.test_words(),
            share(count.holds, count.universes, sampled),
            share(count.not_significant, count.universes, sampled),
            share(count.does_not_hold, count.universes, sampled),
            share(count.other, count.universes, sampled),
        );
    }
    let _ = writeln!(r);
}

/// Per axis: per alternative, the admissible universes taking it and where each claim holds.
fn by_axis(r: &mut String, plan: &MultiversePlan, t: &Tally) {
    let _ = writeln!(r, "## Where each claim holds, by alternative\n");
    let _ = writeln!(
        r,
        "Per alternative: the admissible universes that take it, and the share of them in which \
         each claim holds.\n"
    );
    let heads: Vec<String> = plan
        .identity
        .claims
        .iter()
        .map(|c| format!("({}) holds", c.id))
        .collect();
    for (a, axis) in plan.identity.axes.axes.iter().enumerate() {
        let _ = writeln!(r, "### {}\n", axis.name);
        let _ = writeln!(
            r,
            "| alternative | admissible universes | {} |\n|---|---|{}",
            heads.join(" | "),
            "---|".repeat(heads.len())
        );
        for (k, alt) in axis.alternatives.iter().enumerate() {
            let counts: &[VerdictCount] = t
                .by_alternative
                .get(a)
                .and_then(|x| x.get(k))
                .map_or(&[], |v| v.as_slice());
            let n = counts.first().map_or(0, |c| c.universes);
            let holds: Vec<String> = counts
                .iter()
                .map(|c| share(c.holds, c.universes, plan.sampled()))
                .collect();
            let _ = writeln!(r, "| {} | {n} | {} |", cell(&alt.name), holds.join(" | "));
        }
        let _ = writeln!(r);
    }
}

/// Per target, the compared universes whose statistic (over the comparison's trials) lies in
/// its band, and the figure of every universe's statistic.
fn targets(r: &mut String, plan: &MultiversePlan, records: &[UniverseRecord]) {
    let _ = writeln!(
        r,
        "## The targets across the universes
"
    );
    let _ = writeln!(
        r,
        "Each target's statistic over each compared universe's comparison trials (at its \
         calibrated values): the universes in its band. Report-only targets (as the targets \
         file marks them; an axis may fit or report them in its universes) are not part of \
         admissibility.\n"
    );
    let _ = writeln!(
        r,
        "| target | band | universes in band | lowest | highest |"
    );
    let _ = writeln!(r, "|---|---|---|---|---|");
    for (k, t) in plan.identity.targets.iter().enumerate() {
        let xs: Vec<f64> = records
            .iter()
            .filter_map(|u| u.comparison.as_ref()?.targets.get(k).copied())
            .filter(|x| x.is_finite())
            .collect();
        let inside = xs.iter().filter(|&&x| t.holds(x)).count();
        let (lo, hi) = xs
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        let (lo, hi) = if xs.is_empty() {
            (String::new(), String::new())
        } else {
            (format!("{lo:.3}"), format!("{hi:.3}"))
        };
        let name = if t.report_only {
            format!("{} (report only)", t.name)
        } else {
            t.name.clone()
        };
        let _ = writeln!(
            r,
            "| {} | {} | {} | {lo} | {hi} |",
            cell(&name),
            cell(&t.describe()),
            share(inside, xs.len(), plan.sampled())
        );
    }
    let _ = writeln!(
        r,
        "\n![Each target's statistic per universe]({TARGETS_FIGURE_FILE})\n"
    );
}

/// The specification curves.
fn figures(r: &mut String, claims: &[Claim]) {
    let _ = writeln!(r, "## Specification curves\n");
    let _ = writeln!(
        r,
        "Top: the claim's effect (its subject minus the strongest rival, > 0 in the claim's \
         direction) per admissible universe, sorted, with its 95 % Welch confidence interval, \
         coloured by verdict. Bottom: the alternatives each universe takes.\n"
    );
    for c in claims {
        let file = spec_curve_file(c);
        let _ = writeln!(r, "![Claim {}: {}]({file})\n", c.id, c.sentence);
    }
}

/// Every universe.
fn universes(r: &mut String, plan: &MultiversePlan, records: &[UniverseRecord]) {
    let id = &plan.identity;
    let _ = writeln!(r, "## Universes\n");
    let axes: Vec<String> = id.axes.axes.iter().map(|a| cell(&a.name)).collect();
    let free: Vec<String> = id.free.iter().map(|f| format!("`{}`", f.field)).collect();
    let _ = writeln!(
        r,
        "| universe | {} | admissible | loss | {} | bands missed | status | message |\n|---|{}---|---|{}---|---|---|",
        axes.join(" | "),
        free.join(" | "),
        "---|".repeat(axes.len()),
        "---|".repeat(free.len()),
    );
    for rec in records {
        let choices: Vec<String> = id
            .axes
            .axes
            .iter()
            .zip(&rec.choices)
            .map(|(a, &k)| {
                a.alternatives
                    .get(k)
                    .map_or(String::new(), |x| cell(&x.name))
            })
            .collect();
        let cal = rec.calibration.as_ref();
        let values: Vec<String> = (0..id.free.len())
            .map(|i| {
                cal.and_then(|c| c.values.get(i))
                    .map_or(String::new(), |&x| x.to_string())
            })
            .collect();
        let _ = writeln!(
            r,
            "| [{id}](universes/{id}/) | {} | {} | {} | {} | {} | {} | {} |",
            choices.join(" | "),
            if rec.admissible() { "yes" } else { "no" },
            cal.map_or(String::new(), |c| loss_text(c.loss)),
            values.join(" | "),
            cell(&missed(plan, rec)),
            rec.status.word(),
            cell(rec.message.as_deref().unwrap_or("")),
            id = rec.id,
        );
    }
}

/// The targets whose statistic at the universe's calibrated values lies outside its band
/// (every target, fitted or reported only: a universe's axes may flag them differently), by
/// name; empty without a calibration.
fn missed(plan: &MultiversePlan, rec: &UniverseRecord) -> String {
    let Some(cal) = &rec.calibration else {
        return String::new();
    };
    plan.identity
        .targets
        .iter()
        .zip(&cal.statistics)
        .filter(|(t, x)| !t.holds(**x))
        .map(|(t, _)| t.name.clone())
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multiverse::plan::tests::plan;
    use crate::multiverse::record::Status;
    use crate::multiverse::record::tests::record;

    #[test]
    fn the_report_has_every_section_and_universe() {
        let mut failed = record(5, &[1, 2], 0.4);
        failed.status = Status::Failed;
        failed.message = Some("comparison: 1 of 4 trials failed | x".into());
        if let Some(c) = failed.calibration.as_mut() {
            c.statistics[0] = 9.0;
        }
        let md = multiverse_md(&plan(), &[record(0, &[0, 0], 0.0), failed]);
        for part in [
            "# Multiverse: paper",
            "usar multiverse scenarios/paper.ron --axes 'my axes.ron'",
            "- universes: 2 of the factorial's 6 (every one)",
            "| a | \"x\" (I) | **a0**: the base scenario's values; **a1**: `mission.pickup_s=2` |",
            "- `--free mission.hp_pct_per_step_in_radiation=0.001..0.02:log`",
            "| rounds | `Mean(rounds)` | 6 ± 1 |",
            "1/2 (50 %) admissible, 1 not admissible; 0 invalid (their choices break a rule), 1 failed",
            "| (1) RNE rescues the most in total (one-sided paired t-test, alpha 0.05) | 1/1 (100 %) | 0/1 (0 %) | 0/1 (0 %) | 0/1 (0 %) | [spec_curve_1.svg](spec_curve_1.svg) |",
            "## What this run can conclude\n\n- 1/2 (50 %) of the universes are admissible: only 2 of the 6 universes this run makes have a record",
            "### b\n\n| alternative | admissible universes | (1) holds |",
            "| b0 | 1 | 1/1 (100 %) | 0/1 (0 %) |",
            "| b2 | 0 | 0/0 |",
            "![Claim 4b: RNE has the lowest HP cost per rescuee in the hard task](spec_curve_4b.svg)",
            "| [u000](universes/u000/) | a0 | b0 | yes | 0 | 1.25 | 0.003 |  | ok |  |",
            "| [u005](universes/u005/) | a1 | b2 | no | 0.400 | 1.25 | 0.003 | rounds | failed | comparison: 1 of 4 trials failed \\| x |",
        ] {
            assert!(md.contains(part), "missing {part:?} in\n{md}");
        }
    }
}
