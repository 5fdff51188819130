//! Hierarchical RNE trust-based grouping (Algorithm 1), generalised to any number of kinds,
//! to per-kind quotas and to `K >= 1` tasks.

use serde::{Deserialize, Serialize};

use crate::combinations::{Bipartition, split_count, two_way_splits};
use crate::error::{Result, RneError};
use crate::grouping::assignment::Assignment;
use crate::grouping::method::GroupingMethod;
use crate::grouping::outcome::HierarchicalOutcome;
use crate::grouping::request::GroupingRequest;
use crate::grouping::robot::RobotSnapshot;
use crate::grouping::score_tie::beats;
use crate::grouping::split_heuristic::heuristic_split;
use crate::grouping::split_scorer::SplitScorer;
use crate::needs::{NeedsMatrix, NeedsVector};
use crate::rne::TrustModel;

/// Default of [`HierarchicalRne::exact_split_limit`]: 200,000 splits per kind (a kind of up
/// to 20 robots is always split exactly: `C(20, 10) / 2 = 92,378`).
pub const DEFAULT_EXACT_SPLIT_LIMIT: u64 = 200_000;

/// RNE trust-based grouping, paper Algorithm 1 (with Algorithms 2-4), generalised to `K`
/// tasks by recursive bisection down the difficulty order.
///
/// **Two tasks (the paper).** Kinds are processed in index order (= the merge order; paper:
/// carrier, supplier, observer). For kind `k` with quota `(e_k, h_k)` (easy, hard):
///
/// 1. **Split** (Alg. 1 lines 3-5, Alg. 2): among all splits of the kind into subgroups of
///    sizes `e_k` and `h_k` ([`two_way_splits`], each unordered split once), take the one with
///    the largest *between-RNE* `J(A, B) = T(A||B) + T(B||A)` (group distributions, Eq. 16;
///    0 if a side is empty). Ties: first in ASC order.
/// 2. **Merge** (Alg. 1 lines 6-11): the running pair `(X1, X2)` is merged with the kind's
///    pair `(Y1, Y2)` by the pairing `(X1+Y1, X2+Y2)` or `(X1+Y2, X2+Y1)` with the larger
///    `J` between the two merged groups. Ties: the first pairing.
/// 3. **Assign** (Sec. VI.C): the merged group with the higher trust within itself, i.e. the
///    lower [`within_group_rne`](Self::within_group_rne), goes to the hard task (ties: the
///    group holding the first kind's first subgroup).
///
/// Quotas: when `e_k != h_k` the sizes say which subgroup of kind `k` is bound for which
/// task, so only pairings consistent with that are feasible, and once any such kind is
/// merged the final easy/hard choice is forced by the quotas (step 3 is skipped; reported
/// by [`Bisection::forced_by_quotas`](crate::grouping::Bisection::forced_by_quotas)). With
/// equal quotas (the paper's 3/2/1 per task) every pairing is feasible and step 3 decides.
///
/// **`K` tasks.** With the tasks `t_1, ..., t_K` from the hardest to the easiest, level `l`
/// runs steps 1-3 on the robots not yet assigned, with `t_l` as the "hard" side (quota
/// `q_k[t_l]`) and all easier tasks together as the "easy" side (quota
/// `sum_{i > l} q_k[t_i]`); the hard side's group goes to `t_l` and the next level splits the
/// easy side's group. The easiest task takes what is left. `K = 2` is the paper's algorithm
/// exactly; `K = 1` sends everyone to the one task.
///
/// **Large kinds.** Step 1 is exact (every split scored, the paper's result with its
/// tie-breaking) while the kind's split count ([`split_count`]`(n_k, e_k)`) is at most
/// [`exact_split_limit`](Self::exact_split_limit) (default [`DEFAULT_EXACT_SPLIT_LIMIT`]);
/// beyond it a heuristic finds a split of the same sizes within the same scheme: initial
/// splits from sorting the members by each needs share, improved by pairwise swaps between
/// the halves (Kernighan-Lin style) until no swap increases `J` (see
/// [`best_split_heuristic`](Self::best_split_heuristic); `docs/trust-model.md`, "Grouping at
/// scale"). Steps 2-3 are unchanged.
///
/// Cost: exact step 1 scores `split_count(n_k, e_k)` splits in `O(n_k j)` each; the heuristic
/// is about `O(n_k^2 j)`; steps 2-3 are `O(n j)` per merge and per level. Memory is `O(n j)`
/// whatever the team size: splits are enumerated lazily.
///
/// # Reference
/// `G_k = argmax_{(A,B) ∈ ASC(kind k)} J(A,B)`; `G_{1..k} = argmax_{pairings of G_{1..k-1}, G_k} J`;
/// `hard = argmin_{G ∈ G_{1..K}} mean_{r ∈ G} T(D_r || D_G)`; paper Algorithm 1 and Sec. VI.C;
/// the `K`-task recursion is ours (`docs/trust-model.md`, "K tasks").
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HierarchicalRne {
    model: TrustModel,
    #[serde(default = "default_limit")]
    exact_split_limit: u64,
}

fn default_limit() -> u64 {
    DEFAULT_EXACT_SPLIT_LIMIT
}

impl HierarchicalRne {
    /// A grouping method using `model` (weights, smoothing, alignment, log base), with the
    /// default exact split limit ([`DEFAULT_EXACT_SPLIT_LIMIT`]).
    pub fn new(model: TrustModel) -> Self {
        Self {
            model,
            exact_split_limit: DEFAULT_EXACT_SPLIT_LIMIT,
        }
    }

    /// The same method with another exact split limit: a kind is split exactly while its
    /// number of splits is at most `limit` (unit: splits, as counted by [`split_count`]),
    /// heuristically beyond. `0` makes every kind of two or more robots heuristic; `u64::MAX`
    /// makes every kind exact (at any cost in time, never in memory).
    pub fn with_exact_split_limit(mut self, limit: u64) -> Self {
        self.exact_split_limit = limit;
        self
    }

    /// The exact split limit in splits per kind (default [`DEFAULT_EXACT_SPLIT_LIMIT`]).
    pub fn exact_split_limit(&self) -> u64 {
        self.exact_split_limit
    }

    /// `true` if a kind of `n` robots split into `first_size` and `n - first_size` is split
    /// exactly: its [`split_count`] is at most the limit, or it has a single split.
    pub fn split_is_exact(&self, n: usize, first_size: usize) -> bool {
        let count = split_count(n, first_size);
        count <= 1 || count <= u128::from(self.exact_split_limit)
    }

    /// The trust model.
    pub fn model(&self) -> &TrustModel {
        &self.model
    }

    /// Between-RNE of two groups: the symmetric sum `J(A,B) = T(A||B) + T(B||A)` of group
    /// RNEs (Eq. 17), `>= 0`, possibly `+inf` without smoothing. Defined as 0 if either group
    /// is empty (nothing to compare). `O((|A| + |B|) j)`.
    ///
    /// # Errors
    /// As [`TrustModel::group_group`].
    pub fn between_rne(&self, a: &[&NeedsVector], b: &[&NeedsVector]) -> Result<f64> {
        if a.is_empty() || b.is_empty() {
            return Ok(0.0);
        }
        let da = self
            .model
            .group_distribution(&NeedsMatrix::from_members(a.iter().copied())?)?;
        let db = self
            .model
            .group_distribution(&NeedsMatrix::from_members(b.iter().copied())?)?;
        Ok(self.model.rne(&da, &db)? + self.model.rne(&db, &da)?)
    }

    /// Within-group RNE: the mean over members `r` of the agent-group RNE `T(D_r || D_G)`
    /// (Eq. 12) to the group `G` they belong to. Lower = the group trusts itself more. 0 for an
    /// empty group. `O(|G| j)`.
    ///
    /// # Errors
    /// As [`TrustModel::agent_group`].
    pub fn within_group_rne(&self, group: &[&NeedsVector]) -> Result<f64> {
        if group.is_empty() {
            return Ok(0.0);
        }
        let dg = self
            .model
            .group_distribution(&NeedsMatrix::from_members(group.iter().copied())?)?;
        let mut sum = 0.0;
        for member in group {
            sum += self.model.rne(&self.model.distribution(member)?, &dg)?;
        }
        Ok(sum / group.len() as f64)
    }

    /// Step 1 for one kind: the split of `members` into subgroups of sizes
    /// `(first_size, members.len() - first_size)` and its [`between_rne`](Self::between_rne):
    /// [`best_split_exact`](Self::best_split_exact) if
    /// [`split_is_exact`](Self::split_is_exact), otherwise
    /// [`best_split_heuristic`](Self::best_split_heuristic). Indices refer to `members`.
    ///
    /// # Errors
    /// As the two methods.
    pub fn best_split(
        &self,
        members: &[&NeedsVector],
        first_size: usize,
    ) -> Result<(Bipartition, f64)> {
        if self.split_is_exact(members.len(), first_size) {
            self.best_split_exact(members, first_size)
        } else {
            self.best_split_heuristic(members, first_size)
        }
    }

    /// The exact step 1: every split of [`two_way_splits`] (enumerated lazily, one at a
    /// time) scored by [`between_rne`](Self::between_rne); the largest wins, the first in ASC
    /// order on ties (paper Algorithm 1 lines 3-5 with Algorithm 2). Time
    /// `O(split_count(n, first_size) n j)`, memory `O(n j)`; mind the time beyond a few
    /// hundred thousand splits.
    ///
    /// # Errors
    /// [`RneError::InvalidSubgroupSize`] if `first_size > members.len()`; as
    /// [`between_rne`](Self::between_rne).
    pub fn best_split_exact(
        &self,
        members: &[&NeedsVector],
        first_size: usize,
    ) -> Result<(Bipartition, f64)> {
        let splits = two_way_splits(members.len(), first_size)?;
        let scorer = SplitScorer::new(&self.model, members)?;
        let mut best: Option<(Bipartition, f64)> = None;
        for split in splits {
            let score = scorer.exact(&split.first, &split.second)?;
            if best.as_ref().is_none_or(|(_, s)| beats(score, *s)) {
                best = Some((split, score));
            }
        }
        // `two_way_splits` always yields at least one split.
        Ok(best.unwrap_or((Bipartition::from_sorted_first(0, vec![]), 0.0)))
    }

    /// The heuristic step 1 for kinds beyond the exact limit: a split of the same sizes with
    /// a high, locally maximal between-RNE. Initial splits sort the members by each needs
    /// share (and by their weighted total), highest `first_size` first or last; these (for
    /// kinds of more than 64 robots only the best three) are improved by swapping one member
    /// of each side while that increases `J`
    /// (candidate swaps ranked by the first-order change of `J`, each evaluated exactly from
    /// running column sums in `O(j)`; a final pass over all `first_size (n - first_size)`
    /// swaps confirms that none improves). Deterministic. Time about `O(n^2 j)`, memory
    /// `O(n j)`. The returned score is the exact [`between_rne`](Self::between_rne) of the
    /// split.
    ///
    /// # Errors
    /// [`RneError::InvalidSubgroupSize`] if `first_size > members.len()`; as
    /// [`between_rne`](Self::between_rne) for the chosen split.
    pub fn best_split_heuristic(
        &self,
        members: &[&NeedsVector],
        first_size: usize,
    ) -> Result<(Bipartition, f64)> {
        if first_size > members.len() {
            return Err(RneError::InvalidSubgroupSize {
                size: first_size,
                total: members.len(),
            });
        }
        let scorer = SplitScorer::new(&self.model, members)?;
        let split = heuristic_split(&scorer, first_size);
        let score = scorer.exact(&split.first, &split.second)?;
        Ok((split, score))
    }

    /// The needs vectors of the robots `ids` of `request`, in the order of `ids`.
    pub(crate) fn needs_of<'a>(
        request: &'a GroupingRequest,
        ids: &[usize],
    ) -> Vec<&'a NeedsVector> {
        ids.iter()
            .filter_map(|&id| request.robot(id))
            .map(|r| &r.needs)
            .collect()
    }

    /// Runs the `K`-task grouping (steps 1-3 once per bisection, hardest task first) and
    /// returns the assignment with its diagnostics.
    ///
    /// # Errors
    /// As [`TrustModel::group_distribution`] (e.g. [`crate::RneError::LengthMismatch`] if a
    /// robot's needs vector does not match the weights, [`crate::RneError::ZeroTotal`] for a
    /// subgroup whose needs are all zero).
    pub fn group_detailed(&self, request: &GroupingRequest) -> Result<HierarchicalOutcome> {
        let order = request.hardest_first();
        let mut groups = vec![Vec::new(); request.tasks()];
        let mut remaining: Vec<&RobotSnapshot> = request.robots().iter().collect();
        let mut bisections = Vec::new();
        for (level, &task) in order.iter().enumerate().take(order.len() - 1) {
            if remaining.is_empty() {
                break;
            }
            let quotas: Vec<[usize; 2]> = request
                .quotas()
                .iter()
                .map(|q| [order[level + 1..].iter().map(|&t| q[t]).sum(), q[task]])
                .collect();
            let mut cut = self.bisect(request, &remaining, &quotas, task)?;
            cut.rest.sort_unstable();
            groups[task] = cut.task;
            remaining = cut
                .rest
                .iter()
                .filter_map(|&id| request.robot(id))
                .collect();
            bisections.push(cut.bisection);
        }
        groups[order[order.len() - 1]] = remaining.iter().map(|r| r.id).collect();
        Ok(HierarchicalOutcome {
            assignment: Assignment::new(groups),
            bisections,
        })
    }
}

impl GroupingMethod for HierarchicalRne {
    fn name(&self) -> &str {
        "rne"
    }

    /// `RNE`, the paper's name (Sec. VI.C).
    fn display_name(&self) -> &str {
        "RNE"
    }

    fn assign(&self, request: &GroupingRequest) -> Result<Assignment> {
        Ok(self.group_detailed(request)?.assignment)
    }
}
