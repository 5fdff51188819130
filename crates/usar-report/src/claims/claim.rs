//! One claim of a claims file: "`subject` has a higher (or lower) mean of `metric` than each of
//! its `rivals`", with the test, the level and the correction it is judged by.
//!
//! ```ron
//! (
//!     id: "2",
//!     sentence: "RNE rescues more in the hard task than every baseline",
//!     subject: "RNE",
//!     rivals: Every,               // or Only(["DIS", "HP_DIS"])
//!     metric: "rescued_hard",      // any trials.csv column: per task, total, per rescuee
//!     direction: More,             // or Less
//!     test: PairedT,               // or Wilcoxon, Welch, MannWhitney; default PairedT
//!     alpha: 0.05,                 // default 0.05
//!     correction: None,            // or Holm; default None
//! )
//! ```

use serde::{Deserialize, Serialize};

use crate::targets::metric_ref::MetricRef;

/// The significance level of a claim that does not give one (one-sided): 0.05.
pub const DEFAULT_ALPHA: f64 = 0.05;

/// Which way a claim says its metric goes for its subject.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Direction {
    /// The subject's mean is higher than each rival's (rescuees).
    More,
    /// The subject's mean is lower than each rival's (a cost).
    Less,
}

impl Direction {
    /// `higher` or `lower`, for sentences.
    pub fn words(self) -> &'static str {
        match self {
            Direction::More => "higher",
            Direction::Less => "lower",
        }
    }
}

/// The methods a claim's subject is compared with.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Rivals {
    /// Every other method of the sweep (the default).
    #[default]
    Every,
    /// These methods, by name (case and `-`/`_` ignored, [`method_key`]); each must be in the
    /// sweep for the claim to be tested.
    Only(Vec<String>),
}

/// The one-sided test of "the subject is better than a rival".
///
/// The paired tests ([`Test::PairedT`], the default, and [`Test::Wilcoxon`]) compare trial k
/// of the subject with trial k of the rival: a sweep runs every method on the same draws
/// (same trial index, same seed: common random numbers), so what a trial's draw adds to both
/// cancels. Only trials both methods have a value for are paired. The unpaired tests
/// ([`Test::Welch`], [`Test::MannWhitney`]) compare the two samples as independent ones.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Test {
    /// Student's paired t-test on the per-trial differences (`crate::paired::paired_t_greater`),
    /// the default: the paired member of the t family of [`Test::Welch`].
    #[default]
    PairedT,
    /// The Wilcoxon signed-rank test on the per-trial differences, zero differences dropped
    /// (`crate::paired::wilcoxon_greater`), which does not assume normality.
    Wilcoxon,
    /// Welch's t-test (unequal variances; `crate::stats::welch_greater`), unpaired.
    Welch,
    /// The Mann-Whitney U test (statrs `mannwhitneyu`, normal approximation with continuity
    /// correction; `crate::stats::mann_whitney_greater`), unpaired, which does not assume
    /// normality.
    MannWhitney,
}

impl Test {
    /// `paired t-test`, `Wilcoxon signed-rank test`, `Welch` or `Mann-Whitney U`, for reports.
    pub fn words(self) -> &'static str {
        match self {
            Test::PairedT => "paired t-test",
            Test::Wilcoxon => "Wilcoxon signed-rank test",
            Test::Welch => "Welch",
            Test::MannWhitney => "Mann-Whitney U",
        }
    }

    /// Whether the test pairs trial k of the subject with trial k of the rival.
    pub fn is_paired(self) -> bool {
        matches!(self, Test::PairedT | Test::Wilcoxon)
    }
}

/// How a claim's p-values over its rivals are corrected for their number.
///
/// A claim holds only when every rival's test rejects, an intersection-union test (Berger
/// 1982): at level alpha without any correction, so [`Correction::None`] is the default and
/// keeps the claim's error rate at alpha. [`Correction::Holm`] (Holm 1979) also controls the
/// family-wise error of the pairwise statements read one by one ("RNE beats DIS", "RNE beats
/// ENG"), at the cost of power.
///
/// # Reference
/// R. L. Berger, "Multiparameter hypothesis testing and acceptance sampling", Technometrics
/// 24(4), 1982. S. Holm, "A simple sequentially rejective multiple test procedure", Scand. J.
/// Statist. 6(2), 1979.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Correction {
    /// Each rival's p compared with alpha as it is (the default).
    #[default]
    None,
    /// Holm's step-down adjustment over the rivals compared ([`super::holm_adjusted`]).
    Holm,
}

/// One claim: `subject` has a higher ([`Direction::More`]) or lower mean of `metric` than
/// each of `rivals`, each pairwise one-sided `test` rejecting at `alpha` after `correction`.
/// Read from a claims file and checked there ([`super::Claims`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Claim {
    /// Short id, unique in its file, also ignoring case: letters, digits, `_`, `-` and `.`, at
    /// most 32 characters (`1`, `4a`); it names the claim's files (`spec_curve_<id>.svg`).
    pub id: String,
    /// The claim in words, one line of at most
    /// [`MAX_NAME_CHARS`](crate::targets::ron_file::MAX_NAME_CHARS) characters (the paper's
    /// sentence, for the paper's claims).
    pub sentence: String,
    /// The method the claim is about, by name (`RNE`; case and `-`/`_` ignored).
    pub subject: String,
    /// The methods it is compared with; default [`Rivals::Every`].
    #[serde(default)]
    pub rivals: Rivals,
    /// The metric compared: a `trials.csv` column name (`rescued_hard`, `rescued_total`,
    /// `hp_per_hard_rescuee_pct`, `rounds`).
    pub metric: MetricRef,
    /// Higher or lower is better for the subject.
    pub direction: Direction,
    /// The pairwise test; default [`Test::PairedT`].
    #[serde(default)]
    pub test: Test,
    /// The one-sided significance level, in (0, 0.5]; default [`DEFAULT_ALPHA`].
    #[serde(default = "default_alpha")]
    pub alpha: f64,
    /// The correction over rivals; default [`Correction::None`].
    #[serde(default)]
    pub correction: Correction,
}

fn default_alpha() -> f64 {
    DEFAULT_ALPHA
}

impl Claim {
    /// Whether `method` (a sweep's method name, such as `HP_DIS`) is this claim's subject.
    pub fn is_subject(&self, method: &str) -> bool {
        method_key(&self.subject) == method_key(method)
    }

    /// The rivals among `methods` (a sweep's, in its order) and the rivals named by
    /// [`Rivals::Only`] that are not among them.
    pub fn rivals_in<'a>(&self, methods: &'a [String]) -> (Vec<&'a String>, Vec<String>) {
        match &self.rivals {
            Rivals::Every => (
                methods.iter().filter(|m| !self.is_subject(m)).collect(),
                Vec::new(),
            ),
            Rivals::Only(names) => {
                let keys: Vec<String> = names.iter().map(|n| method_key(n)).collect();
                let found = methods
                    .iter()
                    .filter(|m| keys.contains(&method_key(m)))
                    .collect();
                let missing = names
                    .iter()
                    .filter(|n| !methods.iter().any(|m| method_key(m) == method_key(n)))
                    .cloned()
                    .collect();
                (found, missing)
            }
        }
    }

    /// How the claim is judged, in words: `one-sided paired t-test, alpha 0.05` (with
    /// `, Holm-corrected` when corrected).
    pub fn test_words(&self) -> String {
        self.test_words_naming(self.test.words())
    }

    /// [`Claim::test_words`] with `test` in place of the test's name: `one-sided {test},
    /// alpha 0.05` (with `, Holm-corrected` when corrected), for a name that says more
    /// (`paired t-test over 10 pairs of trials`).
    pub fn test_words_naming(&self, test: &str) -> String {
        let holm = match self.correction {
            Correction::None => "",
            Correction::Holm => ", Holm-corrected",
        };
        format!("one-sided {test}, alpha {}{holm}", self.alpha)
    }
}

/// The key a method name is compared by in a claims file, as messages show it: `rne_core`'s
/// [`method_key`](rne_core::grouping::method_key) (the one normalisation of method names) in
/// upper case, the paper's spelling (`hp-dis`, `HP_DIS` and ` hp_dis ` are one method,
/// `HP_DIS`).
pub fn method_key(name: &str) -> String {
    rne_core::grouping::method_key(name).to_ascii_uppercase()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn claim(rivals: Rivals) -> Claim {
        Claim {
            id: "1".into(),
            sentence: "s".into(),
            subject: "rne".into(),
            rivals,
            metric: MetricRef("rescued_total".into()),
            direction: Direction::More,
            test: Test::Welch,
            alpha: 0.05,
            correction: Correction::None,
        }
    }

    #[test]
    fn rivals_are_found_by_key_and_missing_ones_named() {
        let methods: Vec<String> = ["RNE", "DIS", "HP_DIS"].map(String::from).to_vec();
        let (found, missing) = claim(Rivals::Every).rivals_in(&methods);
        assert_eq!(found, [&methods[1], &methods[2]]);
        assert!(missing.is_empty());
        let only = Rivals::Only(vec!["hp-dis".into(), "ENG".into()]);
        let (found, missing) = claim(only).rivals_in(&methods);
        assert_eq!(found, [&methods[2]]);
        assert_eq!(missing, ["ENG"]);
    }
}
