//! `report.md`'s section on the claims of a claims file: how a verdict is reached, a table of
//! the verdicts naming the test that ran, and one subsection per claim with every rival's
//! comparison (paired and unpaired).

use std::fmt::Write as _;

use crate::analysis::CellAnalysis;
use crate::claims::{ClaimCheck, Claims, Comparison, Correction};
use crate::table::{mean_sd, num, pval};

/// The report's section on its claims (`claims`, a claims file): how a verdict is reached, a
/// table of the verdicts, and one subsection per claim ([`claim_section`]).
pub(super) fn claims(r: &mut String, a: &CellAnalysis, claims: &Claims) {
    let _ = writeln!(r, "## Claims\n");
    let _ = writeln!(
        r,
        "The claims of `{}`. Each says one method (its subject) has a better mean of a metric \
         than each of its rivals. It **holds** when the subject is better than every rival \
         (for a paired test, the mean of the paired differences points the claimed way; for an \
         unpaired one, the means do) and each pairwise one-sided test (the claim's) has p < \
         alpha, after the claim's correction over its rivals if it has one (Holm); it is **not \
         significant** when the differences point the claimed way but some p >= alpha; it \
         **does not hold** when a rival is as good or better; it is **not tested** when the \
         sweep lacks what it needs. Requiring every pairwise test to reject is an \
         intersection-union test, so a claim needs no correction for its error rate to stay \
         at alpha.\n\n\
         The paired tests (the default) compare trial k of the subject with trial k of the \
         rival: every method runs on the same draws (same trial index, same seed: common \
         random numbers), so what a trial's draw adds to both cancels in their difference. \
         Only trials both methods have a value for are paired; a paired claim with fewer than \
         2 pairs is not tested. The paired t-test is Student's t on the differences (p from \
         statrs's Student's t CDF); the Wilcoxon signed-rank test drops zero differences and \
         is exact without ties for up to 50 pairs, tie- and continuity-corrected normal \
         otherwise (Hollander & Wolfe 1999, 3.1). The unpaired tests are Welch's t-test \
         (unequal variances; the statistic and its Welch-Satterthwaite degrees of freedom are \
         computed here, the p-value from statrs's Student's t CDF) and the one-sided \
         Mann-Whitney U test (statrs `mannwhitneyu`). Every test is oriented so that a \
         positive t (a U above n²/2, a W+ above n(n+1)/4) points the claimed way; `difference` \
         is the subject's mean minus the rival's. `p(reverse)` is the p of the claim's t-test \
         (paired or Welch's) for the opposite direction.\n",
        claims.origin()
    );
    let _ = writeln!(r, "| claim | test | verdict |\n|---|---|---|");
    for c in &a.claims {
        let _ = writeln!(
            r,
            "| ({}) {} | {} | **{}** |",
            c.claim.id,
            c.claim.sentence,
            ran_words(c),
            c.verdict.words()
        );
    }
    r.push('\n');
    for c in &a.claims {
        claim_section(r, a, c);
    }
}

/// The claim's test, level and correction, with the pairs it ran over for a paired test:
/// `one-sided paired t-test over 10 pairs of trials, alpha 0.05`.
fn ran_words(c: &ClaimCheck) -> String {
    if c.claim.test.is_paired() && c.reason.is_none() {
        c.claim.test_words_naming(&c.test_run_words())
    } else {
        c.claim.test_words()
    }
}

/// One claim's subsection: its verdict and, when it was tested, the subject's mean and one
/// row per rival: for an unpaired claim the difference, Welch's t-test, the Mann-Whitney U
/// test and the reverse direction's p; for a paired one ([`paired_rows`]) the pairs and both
/// paired tests beside Welch's p; with a correction, the claim's test's corrected p.
fn claim_section(r: &mut String, a: &CellAnalysis, c: &ClaimCheck) {
    let _ = writeln!(
        r,
        "### ({}) {}: **{}**\n",
        c.claim.id,
        c.claim.sentence,
        c.verdict.words()
    );
    if let Some(why) = &c.reason {
        let _ = writeln!(r, "Not tested: {why}.\n");
        return;
    }
    let label = c.metric.map_or_else(String::new, |m| m.label(&a.tasks));
    let _ = writeln!(
        r,
        "{} {}: {} (n = {}).\n",
        c.subject,
        label,
        mean_sd(&c.subject_summary),
        c.subject_summary.n
    );
    if c.claim.test.is_paired() {
        paired_rows(r, c);
        return;
    }
    let columns = [
        "difference",
        "Welch t (dof)",
        "p",
        "Mann-Whitney U",
        "p",
        "p(reverse)",
    ];
    comparison_table(r, c, &columns, |cmp| {
        format!(
            "{} | {} ({}) | {} | {} | {} | {}",
            num(c.subject_summary.mean - cmp.other_summary.mean),
            num(cmp.welch.statistic),
            num(cmp.welch.dof),
            pval(cmp.welch.p),
            num(cmp.mann_whitney.statistic),
            pval(cmp.mann_whitney.p),
            pval(cmp.welch_reverse.p),
        )
    });
}

/// A paired claim's rows: a sentence on the pairing (and the trials left unpaired), then per
/// rival its mean, the pairs, the mean paired difference, the paired t-test, the Wilcoxon
/// signed-rank test, the reverse p and the unpaired Welch p for comparison.
fn paired_rows(r: &mut String, c: &ClaimCheck) {
    let _ = writeln!(
        r,
        "Paired ({}): trial k of {} against trial k of each rival, on the same draws.",
        c.test_run_words(),
        c.subject
    );
    for cmp in c.comparisons.iter().filter(|cmp| cmp.unpaired > 0) {
        let _ = writeln!(
            r,
            "{} trial(s) of {} or {} have no partner and are left out of the pairs.",
            cmp.unpaired, c.subject, cmp.other
        );
    }
    r.push('\n');
    let columns = [
        "pairs",
        "mean paired difference",
        "paired t (dof)",
        "p",
        "Wilcoxon W+",
        "p",
        "p(reverse)",
        "Welch p (unpaired)",
    ];
    comparison_table(r, c, &columns, |cmp| {
        format!(
            "{} | {} | {} ({}) | {} | {} | {} | {} | {}",
            cmp.pairs,
            num(cmp.paired_diff),
            num(cmp.paired_t.statistic),
            num(cmp.paired_t.dof),
            pval(cmp.paired_t.p),
            num(cmp.wilcoxon.statistic),
            pval(cmp.wilcoxon.p),
            pval(cmp.reverse.p),
            pval(cmp.welch.p),
        )
    });
}

/// A claim's comparison table: the header `vs | other's mean ± sd (n)`, `columns` and, when
/// the claim is corrected, `p (Holm)`; then one row per rival: its name and mean ± sd (n),
/// `cells(rival)` (the cells of `columns`, ` | `-separated) and the corrected p.
fn comparison_table(
    r: &mut String,
    c: &ClaimCheck,
    columns: &[&str],
    cells: impl Fn(&Comparison) -> String,
) {
    let corrected = c.claim.correction != Correction::None;
    let mut names = vec!["vs", "other's mean ± sd (n)"];
    names.extend_from_slice(columns);
    if corrected {
        names.push("p (Holm)");
    }
    let _ = writeln!(r, "| {} |", names.join(" | "));
    let _ = writeln!(r, "|{}", "---|".repeat(names.len()));
    for cmp in &c.comparisons {
        let _ = write!(
            r,
            "| {} | {} ({}) | {} |",
            cmp.other,
            mean_sd(&cmp.other_summary),
            cmp.other_summary.n,
            cells(cmp)
        );
        if corrected {
            let _ = write!(r, " {} |", pval(cmp.p_adjusted));
        }
        r.push('\n');
    }
    r.push('\n');
}
