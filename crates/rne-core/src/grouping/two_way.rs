//! One bisection of the hierarchical RNE grouping: Algorithm 1 (split every kind, merge the
//! kinds, assign) on a (sub)team with two sides, the hardest remaining task and the rest.

use crate::error::{Result, RneError};
use crate::grouping::hierarchical::HierarchicalRne;
use crate::grouping::outcome::Bisection;
use crate::grouping::request::GroupingRequest;
use crate::grouping::robot::RobotSnapshot;
use crate::grouping::score_tie::beats;

/// The side of a bisection a subgroup is bound for. With two tasks, `Rest` is the paper's
/// easy task and `Task` its hard task.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Side {
    Rest,
    Task,
}

impl Side {
    fn other(self) -> Self {
        match self {
            Self::Rest => Self::Task,
            Self::Task => Self::Rest,
        }
    }
}

/// A pair of groups (robot ids) and, if fixed by unequal quotas, the side of the first.
struct Pair {
    first: Vec<usize>,
    second: Vec<usize>,
    first_side: Option<Side>,
}

/// The result of [`HierarchicalRne::bisect`]: ids bound for the rest and for the task (each
/// in merge order: kind by kind, ascending ids within a kind), and the diagnostics.
pub(crate) struct Cut {
    pub rest: Vec<usize>,
    pub task: Vec<usize>,
    pub bisection: Bisection,
}

impl HierarchicalRne {
    /// Algorithm 1 on `robots` (sorted by id, at least one) with per-kind side quotas
    /// `quotas[k] = [rest, task]`:
    ///
    /// 1. split each non-empty kind with [`best_split`](Self::best_split) into a
    ///    `rest`-sized first and a `task`-sized second subgroup;
    /// 2. merge the kinds in index order, each time keeping the feasible pairing with the
    ///    larger between-RNE (ties: the first pairing);
    /// 3. if any kind had unequal side quotas the sizes fix which merged group goes to the
    ///    task; otherwise the group with the lower within-group RNE goes to the task (ties:
    ///    the group holding the first kind's first subgroup).
    ///
    /// With two tasks this is exactly the paper's Algorithm 1 with Sec. VI.C's hard-task rule.
    pub(crate) fn bisect(
        &self,
        request: &GroupingRequest,
        robots: &[&RobotSnapshot],
        quotas: &[[usize; 2]],
        task: usize,
    ) -> Result<Cut> {
        let mut acc: Option<Pair> = None;
        let mut heuristic_kinds = Vec::new();
        for (kind, &[rest, to_task]) in quotas.iter().enumerate() {
            let members: Vec<_> = robots.iter().filter(|r| r.kind == kind).collect();
            if members.is_empty() {
                continue;
            }
            let needs: Vec<_> = members.iter().map(|r| &r.needs).collect();
            if !self.split_is_exact(needs.len(), rest) {
                heuristic_kinds.push(kind);
            }
            let (split, _) = self.best_split(&needs, rest)?;
            let ids = |idx: &[usize]| idx.iter().map(|&i| members[i].id).collect::<Vec<_>>();
            let pair = Pair {
                first: ids(&split.first),
                second: ids(&split.second),
                first_side: (rest != to_task).then_some(Side::Rest),
            };
            acc = Some(match acc {
                None => pair,
                Some(x) => self.merge(request, x, pair)?,
            });
        }
        let pair = acc.ok_or(RneError::Empty { what: "team" })?;
        let g1 = Self::needs_of(request, &pair.first);
        let g2 = Self::needs_of(request, &pair.second);
        let within = [self.within_group_rne(&g1)?, self.within_group_rne(&g2)?];
        let between_rne = self.between_rne(&g1, &g2)?;
        let first_side = pair.first_side.unwrap_or(if beats(within[0], within[1]) {
            Side::Rest
        } else {
            Side::Task
        });
        let (rest, to_task, within_rne) = match first_side {
            Side::Rest => (pair.first, pair.second, within),
            Side::Task => (pair.second, pair.first, [within[1], within[0]]),
        };
        Ok(Cut {
            rest,
            task: to_task,
            bisection: Bisection {
                task,
                between_rne,
                within_rne,
                forced_by_quotas: pair.first_side.is_some(),
                heuristic_kinds,
            },
        })
    }

    /// Step 2: merges the running pair `x` with a kind's pair `y` by the feasible pairing
    /// `(X1+Y1, X2+Y2)` or `(X1+Y2, X2+Y1)` with the larger between-RNE (ties: the first).
    /// `O((|x| + |y|) j)`.
    fn merge(&self, request: &GroupingRequest, x: Pair, y: Pair) -> Result<Pair> {
        let mut best: Option<(Pair, f64)> = None;
        for flip in [false, true] {
            let (y1, y2) = if flip {
                (&y.second, &y.first)
            } else {
                (&y.first, &y.second)
            };
            let y_side = if flip {
                y.first_side.map(Side::other)
            } else {
                y.first_side
            };
            if let (Some(a), Some(b)) = (x.first_side, y_side)
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
                        first_side: x.first_side.or(y_side),
                    },
                    score,
                ));
            }
        }
        // At least one pairing is always feasible: a fixed pair can be flipped to agree.
        Ok(best.map(|(p, _)| p).unwrap_or(x))
    }
}
