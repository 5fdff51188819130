//! Hierarchical RNE trust-based grouping (Algorithm 1), generalised to any number of kinds,
//! to per-kind quotas and to `K >= 1` tasks.

use serde::{Deserialize, Serialize};

use crate::combinations::{Bipartition, two_way_splits};
use crate::error::Result;
use crate::grouping::assignment::Assignment;
use crate::grouping::method::GroupingMethod;
use crate::grouping::outcome::HierarchicalOutcome;
use crate::grouping::request::GroupingRequest;
use crate::grouping::robot::RobotSnapshot;
use crate::needs::{NeedsMatrix, NeedsVector};
use crate::rne::TrustModel;

/// Relative tolerance under which two scores count as tied (the earlier candidate wins).
pub(crate) const TIE_TOLERANCE: f64 = 1e-12;

/// `true` if `candidate` beats `best` by more than the tie tolerance.
pub(crate) fn beats(candidate: f64, best: f64) -> bool {
    candidate > best + TIE_TOLERANCE * best.abs().max(1.0)
}

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
/// Cost: step 1 scores every split of a kind (`C(n_k, e_k)`, halved for equal halves), each
/// in `O(n_k j)`; steps 2-3 are `O(n j)` per merge and per level.
///
/// # Reference
/// `G_k = argmax_{(A,B) ∈ ASC(kind k)} J(A,B)`; `G_{1..k} = argmax_{pairings of G_{1..k-1}, G_k} J`;
/// `hard = argmin_{G ∈ G_{1..K}} mean_{r ∈ G} T(D_r || D_G)`; paper Algorithm 1 and Sec. VI.C;
/// the `K`-task recursion is ours (`docs/trust-model.md`, "K tasks").
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HierarchicalRne {
    model: TrustModel,
}

impl HierarchicalRne {
    /// A grouping method using `model` (weights, smoothing, alignment, log base).
    pub fn new(model: TrustModel) -> Self {
        Self { model }
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
    /// `(first_size, members.len() - first_size)` with the largest [`between_rne`](Self::between_rne),
    /// first in ASC order on ties, and its score. Indices refer to `members`. The splits are
    /// enumerated lazily ([`two_way_splits`]).
    ///
    /// # Errors
    /// [`crate::RneError::InvalidSubgroupSize`] if `first_size > members.len()`; as
    /// [`between_rne`](Self::between_rne).
    pub fn best_split(
        &self,
        members: &[&NeedsVector],
        first_size: usize,
    ) -> Result<(Bipartition, f64)> {
        let mut best: Option<(Bipartition, f64)> = None;
        for split in two_way_splits(members.len(), first_size)? {
            let a: Vec<_> = split.first.iter().map(|&i| members[i]).collect();
            let b: Vec<_> = split.second.iter().map(|&i| members[i]).collect();
            let score = self.between_rne(&a, &b)?;
            if best.as_ref().is_none_or(|(_, s)| beats(score, *s)) {
                best = Some((split, score));
            }
        }
        // `two_way_splits` always yields at least one split.
        Ok(best.unwrap_or((Bipartition::from_first(0, vec![]), 0.0)))
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

    fn assign(&self, request: &GroupingRequest) -> Result<Assignment> {
        Ok(self.group_detailed(request)?.assignment)
    }
}
