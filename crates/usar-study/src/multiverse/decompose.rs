//! Which choices decide a claim: the variance of a claim's effect over the admissible
//! universes, split by axis (and by each calibrated value), with the interaction of the two
//! axes that matter most. `multiverse.md` shows it under "Which choices decide each claim".
//!
//! For axis `i`, the share is the correlation ratio
//!
//! ```text
//! eta2_i = sum_g n_g (mean_g - mean)^2 / sum_u (y_u - mean)^2
//! ```
//!
//! over the admissible universes `u` with an effect `y_u`, grouped by the alternative `g` they
//! take of axis `i`: the first-order (main-effect) Sobol index estimated by binning, which
//! for a complete factorial is the ANOVA main-effect share. It is biased upward in a small
//! sample: with `k` alternatives seen among `n` universes its mean under no effect at all is
//! `(k - 1) / (n - 1)`, reported as the share's chance level; a share near its chance level
//! says nothing. For a calibrated (free) value the share is the squared correlation of the
//! value with the effect (a linear fit, on the log scale for a `:log` field; chance level
//! `1 / (n - 1)`). The two-way interaction of the two varying axes with the largest shares
//! is the share of their joint cells beyond the two main effects, `eta2_ij - eta2_i -
//! eta2_j`, clamped at 0 (exact for a balanced factorial, approximate for a sample).
//!
//! The total-order share of axis `i` (its main effect and every interaction it is part of) is
//! the expected variance left when every other axis is fixed, `E[Var(y | other axes)] /
//! Var(y)`, estimated as
//!
//! ```text
//! T_i = mean_h ( (L - 1) / L * sum_{u in h} (y_u - mean_h)^2 / (n_h - 1) ) / (sum_u (y_u - mean)^2 / n)
//! ```
//!
//! over the `G` groups `h` of admissible universes that agree on every axis but `i` and hold
//! at least two of them (`n_h` each, `m` in all), `L` the axis's alternatives: each group's
//! sample variance (unbiased for the `n_h` of `L` alternatives it holds), made a variance over
//! all `L` alternatives. It is the within-group form of Jansen's estimator (pairs of
//! universes that differ in that axis alone), exact (`1 - eta2` of the other axes) for a
//! complete factorial, clamped to [0, 1]; with no such group it is not estimated. Its chance
//! level, its mean under no effect, is `((L - 1) / L) / ((n - 1) / n)`. A total-order share
//! well above the first-order share says the axis acts through interactions.
//! Calibrated values have no total-order share (they are not a factorial design).
//!
//! # Reference
//! A. Saltelli et al., *Global Sensitivity Analysis: The Primer*, Wiley 2008, ch. 1 and 4
//! (first-order indices, their estimation by conditional means); M. J. W. Jansen, "Analysis
//! of variance designs for model output", Comput. Phys. Commun. 117 (1999) 35-43 (the
//! total-order index from pairs that differ in one input); K. Pearson's correlation ratio
//! (eta squared) and its bias `(k - 1) / (n - 1)` under the null (Kelley 1935).

use super::plan::MultiversePlan;
use super::record::UniverseRecord;
use usar_report::claims::Claim;

/// One input's share of a claim's effect variance.
#[derive(Debug, Clone, PartialEq)]
pub struct Share {
    /// The axis's name, or the free field's path.
    pub name: String,
    /// The share of the variance, in [0, 1].
    pub share: f64,
    /// Its mean under no effect (chance level), in [0, 1].
    pub chance: f64,
}

/// One axis's total-order share of a claim's effect variance (see the module's estimator).
#[derive(Debug, Clone, PartialEq)]
pub struct TotalShare {
    /// The share of the variance, in [0, 1].
    pub share: f64,
    /// Its mean under no effect (chance level), in [0, 1].
    pub chance: f64,
    /// The universes it is estimated from: those in a group of at least two that agree on
    /// every other axis.
    pub universes: usize,
}

/// How a claim's effect varies over a set of universes (the admissible ones, [`Scope`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Decomposition {
    /// Universes of the set with a finite effect.
    pub n: usize,
    /// Per axis, in axis order.
    pub axes: Vec<Share>,
    /// Per axis, in axis order, its total-order share (`None`: no two universes differ in
    /// that axis alone).
    pub total: Vec<Option<TotalShare>>,
    /// Per free field, in `--free` order.
    pub free: Vec<Share>,
    /// The two axes with the largest shares (their indices) and their interaction, when at
    /// least two axes vary.
    pub interaction: Option<(usize, usize, Share)>,
}

impl Decomposition {
    /// The indices of the axes by share, largest first (ties by axis order).
    pub fn strongest(&self) -> Vec<usize> {
        let mut order: Vec<usize> = (0..self.axes.len()).collect();
        order.sort_by(|&a, &b| self.axes[b].share.total_cmp(&self.axes[a].share));
        order
    }
}

/// The universes a decomposition is over.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scope {
    /// The admissible universes (calibration loss 0): the verdict's own set.
    Admissible,
    /// Every universe whose comparison ran, admissible or not: how the rules move the claim
    /// across the whole space of readings, whether the bands hold or not.
    Compared,
}

impl Scope {
    /// The largest calibration loss a universe of the scope may have: 0, or unbounded.
    pub fn max_loss(self) -> f64 {
        match self {
            Scope::Admissible => 0.0,
            Scope::Compared => f64::INFINITY,
        }
    }

    /// The scope's universes in a sentence: `admissible universes`, `compared universes`.
    pub fn noun(self) -> &'static str {
        match self {
            Scope::Admissible => "admissible universes",
            Scope::Compared => "compared universes",
        }
    }
}

/// The decomposition of `claim`'s effect over the universes of `scope` among `records` of
/// `plan`; `None` with fewer than 3 of them with a finite effect, or when the effect does not
/// vary.
pub fn decompose_over(
    plan: &MultiversePlan,
    records: &[UniverseRecord],
    claim: &Claim,
    scope: Scope,
) -> Option<Decomposition> {
    decompose_within(plan, records, claim, scope.max_loss())
}

/// The decomposition of `claim`'s effect over `records` of `plan`; `None` with fewer than 3
/// admissible universes with a finite effect, or when the effect does not vary.
pub fn decompose(
    plan: &MultiversePlan,
    records: &[UniverseRecord],
    claim: &Claim,
) -> Option<Decomposition> {
    decompose_within(plan, records, claim, 0.0)
}

/// [`decompose`] over the universes whose calibration loss is at most `max_loss` (0: the
/// admissible ones; larger: the near-admissible ones of `--near-loss`; infinite: every
/// universe whose calibration ran).
pub fn decompose_within(
    plan: &MultiversePlan,
    records: &[UniverseRecord],
    claim: &Claim,
    max_loss: f64,
) -> Option<Decomposition> {
    let rows: Vec<(&UniverseRecord, f64)> = records
        .iter()
        .filter(|r| r.within_loss(max_loss))
        .filter_map(|r| Some((r, r.claim(&claim.id)?.effect)))
        .filter(|(_, y)| y.is_finite())
        .collect();
    let n = rows.len();
    let y: Vec<f64> = rows.iter().map(|(_, y)| *y).collect();
    let mean = y.iter().sum::<f64>() / n.max(1) as f64;
    let total: f64 = y.iter().map(|v| (v - mean).powi(2)).sum();
    if n < 3 || total <= 0.0 {
        return None;
    }
    let id = &plan.identity;
    let key = |axes: &[usize], r: &UniverseRecord| -> Vec<usize> {
        axes.iter()
            .map(|&a| r.choices.get(a).copied().unwrap_or(0))
            .collect()
    };
    let eta2 = |axes: &[usize]| -> (f64, usize) {
        let keys: Vec<Vec<usize>> = rows.iter().map(|(r, _)| key(axes, r)).collect();
        between(&keys, &y, mean, total)
    };
    let chance = |groups: usize| (groups.saturating_sub(1)) as f64 / (n - 1) as f64;
    let axes: Vec<Share> = id
        .axes
        .axes
        .iter()
        .enumerate()
        .map(|(a, axis)| {
            let (share, groups) = eta2(&[a]);
            Share {
                name: axis.name.clone(),
                share,
                chance: chance(groups),
            }
        })
        .collect();
    let free = id
        .free
        .iter()
        .enumerate()
        .map(|(f, field)| {
            let x: Vec<f64> = rows
                .iter()
                .map(|(r, _)| {
                    let x = r
                        .calibration
                        .as_ref()
                        .and_then(|c| c.values.get(f).copied())
                        .unwrap_or(f64::NAN);
                    // A field searched on a log scale is correlated on that scale.
                    if field.log { x.ln() } else { x }
                })
                .collect();
            Share {
                name: field.label(),
                share: r_squared(&x, &y),
                chance: 1.0 / (n - 1) as f64,
            }
        })
        .collect();
    let count = id.axes.axes.len();
    let others = |a: usize| -> Vec<usize> { (0..count).filter(|&b| b != a).collect() };
    let total = (0..count)
        .map(|a| {
            let keys: Vec<Vec<usize>> = rows.iter().map(|(r, _)| key(&others(a), r)).collect();
            let alternatives = id.axes.axes[a].alternatives.len();
            within(&keys, &y, total / n as f64, alternatives)
        })
        .collect();
    let mut d = Decomposition {
        n,
        axes,
        total,
        free,
        interaction: None,
    };
    d.interaction = interaction(&d, &eta2, &chance);
    Some(d)
}

/// The interaction of the two strongest axes of `d` that vary among its universes (an axis
/// seen with one alternative has no share and no interaction), from `eta2` of a set of axes
/// (share, groups seen) and the `chance` level of a number of groups.
fn interaction(
    d: &Decomposition,
    eta2: &dyn Fn(&[usize]) -> (f64, usize),
    chance: &dyn Fn(usize) -> f64,
) -> Option<(usize, usize, Share)> {
    let varying: Vec<usize> = d
        .strongest()
        .into_iter()
        .filter(|&a| eta2(&[a]).1 >= 2)
        .collect();
    let [a, b, ..] = varying[..] else {
        return None;
    };
    let (joint, cells) = eta2(&[a, b]);
    let (ga, gb) = (eta2(&[a]).1, eta2(&[b]).1);
    let share = (joint - d.axes[a].share - d.axes[b].share).max(0.0);
    let expected = chance(cells) - chance(ga) - chance(gb);
    Some((
        a,
        b,
        Share {
            name: format!("{} x {}", d.axes[a].name, d.axes[b].name),
            share,
            chance: expected.max(0.0),
        },
    ))
}

/// The between-group share of `y` grouped by `keys` (and the number of groups seen).
fn between(keys: &[Vec<usize>], y: &[f64], mean: f64, total: f64) -> (f64, usize) {
    let mut groups: Vec<(&Vec<usize>, f64, usize)> = Vec::new();
    for (k, v) in keys.iter().zip(y) {
        match groups.iter_mut().find(|(g, _, _)| *g == k) {
            Some((_, sum, count)) => {
                *sum += v;
                *count += 1;
            }
            None => groups.push((k, *v, 1)),
        }
    }
    let ss: f64 = groups
        .iter()
        .map(|(_, sum, count)| {
            let m = sum / *count as f64;
            *count as f64 * (m - mean).powi(2)
        })
        .sum();
    ((ss / total).clamp(0.0, 1.0), groups.len())
}

/// The total-order share from the groups of `keys` with at least two members, for an axis of
/// `alternatives` (`L`): the mean over them of `(L - 1) / L` times their sample variance, over
/// `variance` (the population variance of every `y`).
fn within(
    keys: &[Vec<usize>],
    y: &[f64],
    variance: f64,
    alternatives: usize,
) -> Option<TotalShare> {
    let mut groups: Vec<(&Vec<usize>, Vec<f64>)> = Vec::new();
    for (k, v) in keys.iter().zip(y) {
        match groups.iter_mut().find(|(g, _)| *g == k) {
            Some((_, values)) => values.push(*v),
            None => groups.push((k, vec![*v])),
        }
    }
    let informative: Vec<&Vec<f64>> = groups
        .iter()
        .map(|(_, v)| v)
        .filter(|v| v.len() >= 2)
        .collect();
    let m: usize = informative.iter().map(|v| v.len()).sum();
    if m == 0 || variance <= 0.0 {
        return None;
    }
    let l = alternatives.max(2) as f64;
    let mean_variance = informative
        .iter()
        .map(|v| {
            let mean = v.iter().sum::<f64>() / v.len() as f64;
            let ss = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>();
            (l - 1.0) / l * ss / (v.len() - 1) as f64
        })
        .sum::<f64>()
        / informative.len() as f64;
    let n = y.len() as f64;
    Some(TotalShare {
        share: (mean_variance / variance).clamp(0.0, 1.0),
        chance: (((l - 1.0) / l) / ((n - 1.0) / n)).clamp(0.0, 1.0),
        universes: m,
    })
}

/// The squared Pearson correlation of `x` and `y` (0 when either does not vary or `x` has a
/// NaN).
fn r_squared(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    if x.iter().any(|v| !v.is_finite()) || n < 2.0 {
        return 0.0;
    }
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in x.iter().zip(y) {
        sxy += (a - mx) * (b - my);
        sxx += (a - mx).powi(2);
        syy += (b - my).powi(2);
    }
    if sxx <= 0.0 || syy <= 0.0 {
        return 0.0;
    }
    (sxy * sxy / (sxx * syy)).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multiverse::plan::tests::plan;
    use crate::multiverse::record::tests::record;

    /// The test plan's axes: `a` (2 alternatives) and `b` (3); universes of every pair with
    /// claim 1's effect `f(a, b)`, all admissible.
    fn records(f: impl Fn(usize, usize) -> f64) -> Vec<UniverseRecord> {
        let mut out = Vec::new();
        let mut i = 0;
        for a in 0..2 {
            for b in 0..3 {
                let mut r = record(i, &[a, b], 0.0);
                if let Some(c) = r.comparison.as_mut() {
                    c.claims[0].effect = f(a, b);
                }
                out.push(r);
                i += 1;
            }
        }
        out
    }

    fn claim1() -> Claim {
        usar_report::claims::paper_claims().claims()[0].clone()
    }

    #[test]
    fn near_admissible_universes_join_the_decomposition_up_to_their_loss() {
        let mut rs = records(|a, b| (3 * a + b) as f64);
        for r in rs.iter_mut().filter(|r| r.choices[0] == 1) {
            r.calibration.as_mut().unwrap().loss = 2.0;
        }
        // Admissible: a = 0 only, so a explains nothing; within loss 2, a explains most.
        let only = decompose(&plan(), &rs, &claim1()).unwrap();
        assert_eq!((only.n, only.axes[0].share), (3, 0.0));
        assert_eq!(
            decompose_within(&plan(), &rs, &claim1(), 1.9).unwrap(),
            only
        );
        let near = decompose_within(&plan(), &rs, &claim1(), 2.0).unwrap();
        assert_eq!(near.n, 6);
        assert_eq!(near.strongest()[0], 0);
        assert_eq!(
            near,
            decompose(&plan(), &records(|a, b| (3 * a + b) as f64), &claim1()).unwrap()
        );
    }

    #[test]
    fn an_effect_of_one_axis_is_all_its_share() {
        let d = decompose(&plan(), &records(|a, _| a as f64 * 3.0), &claim1()).unwrap();
        assert_eq!(d.n, 6);
        assert!((d.axes[0].share - 1.0).abs() < 1e-12, "{d:?}");
        assert!(d.axes[1].share.abs() < 1e-12);
        // Chance levels: (2 - 1) / 5 and (3 - 1) / 5.
        assert!((d.axes[0].chance - 0.2).abs() < 1e-12);
        assert!((d.axes[1].chance - 0.4).abs() < 1e-12);
        assert_eq!(d.strongest(), [0, 1]);
        let (a, b, i) = d.interaction.clone().unwrap();
        assert_eq!((a, b), (0, 1));
        assert!(i.share.abs() < 1e-12);
    }

    #[test]
    fn additive_effects_split_and_an_interaction_is_what_they_leave() {
        // y = a + b: balanced, so the shares are the ANOVA's: SS_a = 6 * 0.25 = 1.5,
        // SS_b = 2 * (1 + 0 + 1) = 4, total 5.5.
        let d = decompose(&plan(), &records(|a, b| (a + b) as f64), &claim1()).unwrap();
        assert!((d.axes[0].share - 1.5 / 5.5).abs() < 1e-12, "{d:?}");
        assert!((d.axes[1].share - 4.0 / 5.5).abs() < 1e-12);
        assert!(d.interaction.unwrap().2.share < 1e-12);
        // y = a * b (b in 0..3): an interaction beyond the main effects.
        let d = decompose(&plan(), &records(|a, b| (a * b) as f64), &claim1()).unwrap();
        let (_, _, i) = d.interaction.unwrap();
        let sum = d.axes[0].share + d.axes[1].share + i.share;
        assert!(i.share > 0.05 && (sum - 1.0).abs() < 1e-12, "{i:?} {sum}");
        // The total-order shares hold the interaction: each axis's main effect plus it.
        for a in 0..2 {
            let t = d.total[a].as_ref().unwrap();
            assert!(
                (t.share - (d.axes[a].share + i.share)).abs() < 1e-12,
                "{t:?}"
            );
            assert_eq!(t.universes, 6);
        }
    }

    #[test]
    fn total_order_shares_use_universes_that_differ_in_one_axis_only() {
        // Additive: the total-order share is the main effect's.
        let d = decompose(&plan(), &records(|a, b| (a + b) as f64), &claim1()).unwrap();
        assert!((d.total[0].as_ref().unwrap().share - 1.5 / 5.5).abs() < 1e-12);
        assert!((d.total[1].as_ref().unwrap().share - 4.0 / 5.5).abs() < 1e-12);
        // Chance for axis a (2 alternatives) among 6: (1 / 2) / (5 / 6) = 0.6.
        assert!((d.total[0].as_ref().unwrap().chance - 0.6).abs() < 1e-12);
        // Keep (0,0), (1,0), (0,1), (0,2): only b = 0 pairs the a's; a = 0 groups the b's.
        let kept: Vec<_> = records(|a, b| (a + 2 * b) as f64)
            .into_iter()
            .filter(|r| r.choices[0] == 0 || r.choices[1] == 0)
            .collect();
        let d = decompose(&plan(), &kept, &claim1()).unwrap();
        let (ta, tb) = (d.total[0].clone().unwrap(), d.total[1].clone().unwrap());
        assert_eq!((ta.universes, tb.universes), (2, 3));
        // y: 0, 1, 2, 4 (mean 1.75, variance 2.1875); a's pair 0, 1: 0.25 / 2.1875.
        assert!((ta.share - 0.25 / 2.1875).abs() < 1e-12, "{ta:?}");
        // y = 3a + b without (0, 1): the group a = 0 holds 2 of b's 3 alternatives (0 and 2:
        // sample variance 2, times 2 / 3), a = 1 all three (3, 4, 5: 1, times 2 / 3); their
        // mean 1 over the variance of 0, 2, 3, 4, 5 (2.96).
        let part: Vec<_> = records(|a, b| (3 * a + b) as f64)
            .into_iter()
            .filter(|r| r.choices != [0, 1])
            .collect();
        let d = decompose(&plan(), &part, &claim1()).unwrap();
        let tb = d.total[1].clone().unwrap();
        assert!((tb.share - 1.0 / 2.96).abs() < 1e-12, "{tb:?}");
        assert_eq!(tb.universes, 5);
        // No pair differs in one axis alone: not estimated.
        let lone: Vec<_> = records(|a, b| (a + b) as f64)
            .into_iter()
            .filter(|r| r.choices == [0, 0] || r.choices == [1, 1] || r.choices == [0, 2])
            .collect();
        let d = decompose(&plan(), &lone, &claim1()).unwrap();
        assert!(d.total[0].is_none(), "{:?}", d.total);
    }

    #[test]
    fn too_few_or_constant_effects_give_nothing() {
        assert!(decompose(&plan(), &records(|_, _| 2.0), &claim1()).is_none());
        let few: Vec<_> = records(|a, _| a as f64).into_iter().take(2).collect();
        assert!(decompose(&plan(), &few, &claim1()).is_none());
    }
}
