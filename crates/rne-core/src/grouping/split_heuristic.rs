//! The heuristic split of a kind too large to enumerate: sorted initial splits improved by
//! pairwise swaps (Kernighan-Lin style) until no swap increases the between-RNE `J`.

use crate::combinations::Bipartition;
use crate::grouping::score_tie::beats;
use crate::grouping::split_scorer::{Scratch, SplitScorer};

/// Kinds of up to this many robots improve every initial split by swaps; larger kinds only
/// the [`REFINED_STARTS`] best (the swap passes cost about `n^2 j` each).
const REFINE_ALL_UP_TO: usize = 64;
/// How many of the best initial splits are improved by swaps in kinds of more than
/// [`REFINE_ALL_UP_TO`] robots (the best result wins).
const REFINED_STARTS: usize = 3;
/// Candidates per side in the first-order swap window (`WINDOW^2` exact evaluations).
const WINDOW: usize = 8;
/// Safety cap on accepted swaps per refinement: `MAX_SWAPS_PER_MEMBER * n`. Every accepted
/// swap raises `J` by more than the tie tolerance, so the search ends anyway; the cap only
/// bounds the time on pathological inputs (reaching it keeps the best split found).
const MAX_SWAPS_PER_MEMBER: usize = 4;
/// Splits with more than this many swap pairs `m (n - m)` skip the exhaustive pass over every
/// pair (step 2 then ends when the window holds no improving swap). The pass costs about
/// 0.3 us per pair on one core (0.02 s at this bound; 0.8 s for a kind of 5,000 split 625 /
/// 4,375, and an RNE grouping of 10,000 robots makes 63 such passes); on
/// `scenarios/swarm-10000.ron`'s team no pass found a swap its window had missed. Every split
/// of the paper's scenarios and of `swarm-1000.ron` (at most 250 x 250 = 62,500 pairs) keeps
/// the pass, and its groups are unchanged.
pub(crate) const FULL_SCAN_MAX_PAIRS: usize = 65_536;

/// `true` if `new` improves on `old`: any defined score beats an undefined one (`-inf`),
/// otherwise by more than the tie tolerance.
fn improves(new: f64, old: f64) -> bool {
    if old == f64::NEG_INFINITY {
        new > old
    } else {
        beats(new, old)
    }
}

/// A split of the scorer's `n` members with `m` in the first side, chosen heuristically:
///
/// 1. **Initial splits:** for each needs category `k`, the members sorted by their share of
///    `k` (weighted need `k` over their weighted total; ties by index), the `m` highest in the
///    first side, and the `m` lowest; the same by weighted total. That is `2 (j + 1)`
///    projections of the members' needs distributions.
/// 2. **Swaps:** all of them (kinds of up to [`REFINE_ALL_UP_TO`] robots) or the
///    [`REFINED_STARTS`] best by `J` (larger kinds) are improved by swapping one member of
///    each side while a swap increases `J`; the best result wins (ties: the earlier).
///
/// `m` must be `<= n` (the caller checks). `O(n log n j)` for the starts; per accepted swap
/// `O(n j)`; a final pass that proves no swap helps evaluates all `m (n - m)` swaps in `O(j)`
/// each, when there are at most [`FULL_SCAN_MAX_PAIRS`] (else the search ends at the first
/// window without an improving swap, and the split costs `O(n log n j)` plus `O(n j)` per
/// accepted swap).
pub(crate) fn heuristic_split(scorer: &SplitScorer<'_>, m: usize) -> Bipartition {
    heuristic_split_counted(scorer, m).0
}

/// [`heuristic_split`] and the number of swaps it scored.
fn heuristic_split_counted(scorer: &SplitScorer<'_>, m: usize) -> (Bipartition, u64) {
    let n = scorer.n();
    if m == 0 || m == n {
        return (Bipartition::from_sorted_first(n, (0..m).collect()), 0);
    }
    let mut w = scorer.scratch();
    let mut starts: Vec<(Vec<bool>, f64)> = initial_splits(scorer, m)
        .into_iter()
        .map(|s| {
            let (sa, sb) = scorer.sums_of(&s);
            let score = scorer.score(&sa, &sb, &mut w);
            (s, score)
        })
        .collect();
    // Stable: equal scores keep the order of the starts.
    starts.sort_by(|a, b| b.1.total_cmp(&a.1));
    let mut best: Option<(Vec<bool>, f64)> = None;
    let refined = if n <= REFINE_ALL_UP_TO {
        starts.len()
    } else {
        REFINED_STARTS
    };
    for (start, _) in starts.into_iter().take(refined) {
        let (split, score) = refine(scorer, start, &mut w);
        if best.as_ref().is_none_or(|(_, s)| improves(score, *s)) {
            best = Some((split, score));
        }
    }
    let in_first = best.map(|(s, _)| s).unwrap_or_default();
    let split = Bipartition::from_sorted_first(n, (0..n).filter(|&r| in_first[r]).collect());
    (split, w.swaps_scored())
}

/// The `2 (j + 1)` initial splits of step 1 as membership flags.
fn initial_splits(scorer: &SplitScorer<'_>, m: usize) -> Vec<Vec<bool>> {
    let (n, j) = (scorer.n(), scorer.j());
    let totals: Vec<f64> = (0..n).map(|r| scorer.row(r).iter().sum()).collect();
    let mut out = Vec::with_capacity(2 * (j + 1));
    for key in 0..=j {
        let value = |r: usize| match key {
            k if k < j && totals[r] > 0.0 => scorer.row(r)[k] / totals[r],
            k if k < j => 0.0,
            _ => totals[r],
        };
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| value(b).total_cmp(&value(a)).then(a.cmp(&b)));
        for first in [&order[..m], &order[n - m..]] {
            let mut flags = vec![false; n];
            first.iter().for_each(|&r| flags[r] = true);
            out.push(flags);
        }
    }
    out
}

/// Step 2 from `in_first`: repeatedly apply the best swap found, first among the
/// [`WINDOW`] x [`WINDOW`] pairs with the largest first-order gains, otherwise among all
/// pairs (when there are at most [`FULL_SCAN_MAX_PAIRS`]); stop when no swap improves `J` (or
/// at the swap cap). Returns the split and its `J`.
fn refine(scorer: &SplitScorer<'_>, mut in_first: Vec<bool>, w: &mut Scratch) -> (Vec<bool>, f64) {
    let n = scorer.n();
    let mut gains = vec![0.0; n];
    let (mut sa, mut sb) = scorer.sums_of(&in_first);
    let mut current = scorer.score(&sa, &sb, w);
    for _ in 0..MAX_SWAPS_PER_MEMBER * n {
        if current == f64::INFINITY {
            break; // nothing beats an infinite J
        }
        scorer.move_gains(&sa, &sb, w, &mut gains);
        let (first, second): (Vec<usize>, Vec<usize>) = (0..n).partition(|&r| in_first[r]);
        // The WINDOW first members in the order (gain, index): selected, then sorted (the
        // same list a sort of the whole side gives, since the order is total).
        let window = |mut side: Vec<usize>, descending: bool| {
            let key = |r: &usize| if descending { -gains[*r] } else { gains[*r] };
            let order = |a: &usize, b: &usize| key(a).total_cmp(&key(b)).then(a.cmp(b));
            if side.len() > WINDOW {
                side.select_nth_unstable_by(WINDOW - 1, order);
                side.truncate(WINDOW);
            }
            side.sort_by(order);
            side
        };
        let candidates = best_swap(
            scorer,
            &sa,
            &sb,
            &window(first.clone(), true),
            &window(second.clone(), false),
            w,
        )
        .filter(|&(_, _, s)| improves(s, current))
        .or_else(|| {
            (first.len() * second.len() <= FULL_SCAN_MAX_PAIRS)
                .then(|| best_swap(scorer, &sa, &sb, &first, &second, w))
                .flatten()
        })
        .filter(|&(_, _, s)| improves(s, current));
        let Some((a, b, _)) = candidates else {
            break;
        };
        in_first[a] = false;
        in_first[b] = true;
        // Fresh sums after every swap: no drift from repeated subtraction.
        (sa, sb) = scorer.sums_of(&in_first);
        current = scorer.score(&sa, &sb, w);
    }
    (in_first, current)
}

/// The swap `(a, b, J after)` with the largest exact `J` over `a` in `first`, `b` in `second`
/// (ties: the first in that order), or `None` if either list is empty. `O(|first| |second| j)`.
fn best_swap(
    scorer: &SplitScorer<'_>,
    sa: &[f64],
    sb: &[f64],
    first: &[usize],
    second: &[usize],
    w: &mut Scratch,
) -> Option<(usize, usize, f64)> {
    let mut best: Option<(usize, usize, f64)> = None;
    for &a in first {
        for &b in second {
            let s = scorer.swap_score(sa, sb, a, b, w);
            if best.is_none_or(|(_, _, t)| improves(s, t)) {
                best = Some((a, b, s));
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::NeedsVector;
    use crate::grouping::tests::common::{Gauss, paper_needs, uniform_model};

    /// `n` carriers with the paper's needs ratios and random levels.
    fn carriers(n: usize, seed: u64) -> Vec<NeedsVector> {
        let mut g = Gauss(seed);
        (0..n)
            .map(|_| paper_needs(0, g.sample(90.0, 10.0), g.sample(80.0, 20.0)))
            .collect()
    }

    #[test]
    fn the_exhaustive_pass_runs_only_up_to_the_pair_bound() {
        let model = uniform_model();
        // 100 x 100 = 10,000 pairs: every refinement ends with a pass over all of them.
        // 300 x 300 = 90,000 > FULL_SCAN_MAX_PAIRS: the windows alone (at most 64 swaps each).
        for (n, m, exhaustive) in [(200, 100, true), (600, 300, false)] {
            let needs = carriers(n, 7);
            let members: Vec<&NeedsVector> = needs.iter().collect();
            let scorer = SplitScorer::new(&model, &members).unwrap();
            let (split, scored) = heuristic_split_counted(&scorer, m);
            assert_eq!(split.first.len(), m);
            let pairs = (m * (n - m)) as u64;
            assert_eq!(pairs <= FULL_SCAN_MAX_PAIRS as u64, exhaustive);
            if exhaustive {
                assert!(
                    scored >= REFINED_STARTS as u64 * pairs,
                    "{n}: {scored} scored"
                );
            } else {
                assert!(scored < pairs, "{n}: {scored} swaps scored, {pairs} pairs");
            }
        }
    }
}
