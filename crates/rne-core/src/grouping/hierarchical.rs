//! Hierarchical RNE trust-based grouping (Algorithm 1), generalised to any number of kinds and
//! to per-kind quotas.

use serde::{Deserialize, Serialize};

use crate::combinations::{Bipartition, two_way_splits};
use crate::error::Result;
use crate::grouping::assignment::Assignment;
use crate::grouping::method::GroupingMethod;
use crate::grouping::request::{GroupingRequest, Task};
use crate::needs::{NeedsMatrix, NeedsVector};
use crate::rne::TrustModel;

/// Relative tolerance under which two scores count as tied (the earlier candidate wins).
const TIE_TOLERANCE: f64 = 1e-12;

/// `true` if `candidate` beats `best` by more than the tie tolerance.
fn beats(candidate: f64, best: f64) -> bool {
    candidate > best + TIE_TOLERANCE * best.abs().max(1.0)
}

/// The result of [`HierarchicalRne::group_detailed`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HierarchicalOutcome {
    /// The final assignment.
    pub assignment: Assignment,
    /// Symmetric RNE `T(E||H) + T(H||E)` between the final easy and hard groups.
    pub between_rne: f64,
    /// Within-group RNE (see [`HierarchicalRne::within_group_rne`]) of `[easy, hard]`.
    pub within_rne: [f64; 2],
    /// `true` if unequal quotas fixed which merged group goes hard (the trust rule was not
    /// needed); `false` if the more trusted group was chosen for the hard task.
    pub forced_by_quotas: bool,
}

/// RNE trust-based grouping, paper Algorithm 1 (with Algorithms 2-4), generalised.
///
/// Kinds are processed in index order (= the merge order; paper: carrier, supplier,
/// observer). For kind `k` with quota `(e_k, h_k)`:
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
/// by [`HierarchicalOutcome::forced_by_quotas`]). With equal quotas (the paper's 3/2/1 per
/// task) every pairing is feasible and step 3 decides.
///
/// # Reference
/// `G_k = argmax_{(A,B) ∈ ASC(kind k)} J(A,B)`; `G_{1..k} = argmax_{pairings of G_{1..k-1}, G_k} J`;
/// `hard = argmin_{G ∈ G_{1..K}} mean_{r ∈ G} T(D_r || D_G)`; paper Algorithm 1 and Sec. VI.C.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HierarchicalRne {
    model: TrustModel,
}

/// A pair of groups (robot ids) and, if fixed by unequal quotas, the task of the first.
struct Pair {
    first: Vec<usize>,
    second: Vec<usize>,
    first_task: Option<Task>,
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
    /// is empty (nothing to compare).
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
    /// empty group.
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
    /// first in ASC order on ties, and its score. Indices refer to `members`.
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
        Ok(best.unwrap_or((
            Bipartition {
                first: vec![],
                second: vec![],
            },
            0.0,
        )))
    }

    fn needs_of<'a>(request: &'a GroupingRequest, ids: &[usize]) -> Vec<&'a NeedsVector> {
        ids.iter()
            .filter_map(|&id| request.robot(id))
            .map(|r| &r.needs)
            .collect()
    }

    /// Runs steps 1-3 and returns the assignment with its diagnostics.
    ///
    /// # Errors
    /// As [`TrustModel::group_distribution`] (e.g. [`crate::RneError::LengthMismatch`] if a
    /// robot's needs vector does not match the weights).
    pub fn group_detailed(&self, request: &GroupingRequest) -> Result<HierarchicalOutcome> {
        let mut acc: Option<Pair> = None;
        for (kind, quota) in request.quotas().iter().enumerate() {
            let robots = request.members_of_kind(kind);
            if robots.is_empty() {
                continue;
            }
            let needs: Vec<_> = robots.iter().map(|r| &r.needs).collect();
            let (split, _) = self.best_split(&needs, quota.easy)?;
            let ids = |idx: &[usize]| idx.iter().map(|&i| robots[i].id).collect::<Vec<_>>();
            let pair = Pair {
                first: ids(&split.first),
                second: ids(&split.second),
                first_task: (quota.easy != quota.hard).then_some(Task::Easy),
            };
            acc = Some(match acc {
                None => pair,
                Some(x) => self.merge(request, x, pair)?,
            });
        }
        let Some(pair) = acc else {
            return Err(crate::RneError::Empty { what: "team" });
        };
        let g1 = Self::needs_of(request, &pair.first);
        let g2 = Self::needs_of(request, &pair.second);
        let within = [self.within_group_rne(&g1)?, self.within_group_rne(&g2)?];
        let between_rne = self.between_rne(&g1, &g2)?;
        let first_task = pair.first_task.unwrap_or(if beats(within[0], within[1]) {
            Task::Easy
        } else {
            Task::Hard
        });
        let (assignment, within_rne) = match first_task {
            Task::Easy => (Assignment::new(pair.first, pair.second), within),
            Task::Hard => (
                Assignment::new(pair.second, pair.first),
                [within[1], within[0]],
            ),
        };
        Ok(HierarchicalOutcome {
            assignment,
            between_rne,
            within_rne,
            forced_by_quotas: pair.first_task.is_some(),
        })
    }

    /// Step 2: merges the running pair `x` with a kind's pair `y`.
    fn merge(&self, request: &GroupingRequest, x: Pair, y: Pair) -> Result<Pair> {
        let mut best: Option<(Pair, f64)> = None;
        for flip in [false, true] {
            let (y1, y2) = if flip {
                (&y.second, &y.first)
            } else {
                (&y.first, &y.second)
            };
            let y_task = if flip {
                y.first_task.map(Task::other)
            } else {
                y.first_task
            };
            if let (Some(a), Some(b)) = (x.first_task, y_task)
                && a != b
            {
                continue; // infeasible under the quotas
            }
            let first: Vec<usize> = x.first.iter().chain(y1).copied().collect();
            let second: Vec<usize> = x.second.iter().chain(y2).copied().collect();
            let score = self.between_rne(
                &Self::needs_of(request, &first),
                &Self::needs_of(request, &second),
            )?;
            if best.as_ref().is_none_or(|(_, s)| beats(score, *s)) {
                best = Some((
                    Pair {
                        first,
                        second,
                        first_task: x.first_task.or(y_task),
                    },
                    score,
                ));
            }
        }
        // At least one pairing is always feasible: a fixed pair can be flipped to agree.
        Ok(best.map(|(p, _)| p).unwrap_or(x))
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
