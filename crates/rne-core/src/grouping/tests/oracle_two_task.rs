//! Test-only oracle: the two-task grouping as it was before tasks became data (easy/hard
//! written into the types), kept verbatim in logic so that the `K`-task methods can be checked
//! to give exactly its groups for `K = 2`. Do not "improve" this file: it is the reference.
//!
//! It reads a `K = 2` [`GroupingRequest`]: the easy task is the easier one
//! (`hardest_first()[1]`), the hard task `hardest_first()[0]`.

use crate::combinations::Bipartition;
use crate::grouping::{GroupingRequest, HierarchicalRne, RobotSnapshot};
use crate::needs::NeedsVector;
use crate::{Result, RneError};

const TIE_TOLERANCE: f64 = 1e-12;

fn beats(candidate: f64, best: f64) -> bool {
    candidate > best + TIE_TOLERANCE * best.abs().max(1.0)
}

/// The oracle's result: ids per task, each sorted.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct EasyHard {
    pub easy: Vec<usize>,
    pub hard: Vec<usize>,
}

impl EasyHard {
    fn new(mut easy: Vec<usize>, mut hard: Vec<usize>) -> Self {
        easy.sort_unstable();
        hard.sort_unstable();
        Self { easy, hard }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Task {
    Easy,
    Hard,
}

impl Task {
    fn other(self) -> Self {
        match self {
            Self::Easy => Self::Hard,
            Self::Hard => Self::Easy,
        }
    }
}

/// `(easy task index, hard task index)` of a two-task request.
fn tasks(req: &GroupingRequest) -> (usize, usize) {
    assert_eq!(req.tasks(), 2, "the oracle knows two tasks");
    (req.hardest_first()[1], req.hardest_first()[0])
}

/// Per kind `(easy, hard)` quota.
fn quotas(req: &GroupingRequest) -> Vec<(usize, usize)> {
    let (e, h) = tasks(req);
    req.quotas().iter().map(|q| (q[e], q[h])).collect()
}

/// `[easy, hard]` distances of a robot.
fn dist(req: &GroupingRequest, r: &RobotSnapshot) -> [f64; 2] {
    let (e, h) = tasks(req);
    [r.distance_to_goal_m[e], r.distance_to_goal_m[h]]
}

/// The old materialising ASC.
fn combinations(n: usize, m: usize) -> Vec<Vec<usize>> {
    let mut out = Vec::new();
    let mut current: Vec<usize> = (0..m).collect();
    loop {
        out.push(current.clone());
        let Some(i) = (0..m).rev().find(|&i| current[i] < n - m + i) else {
            return out;
        };
        current[i] += 1;
        for k in i + 1..m {
            current[k] = current[k - 1] + 1;
        }
    }
}

fn two_way_splits(n: usize, m: usize) -> Vec<Bipartition> {
    let symmetric = 2 * m == n && n > 0;
    combinations(n, m)
        .into_iter()
        .filter(|first| !symmetric || first.first() == Some(&0))
        .map(|first| {
            let second = (0..n).filter(|i| first.binary_search(i).is_err()).collect();
            Bipartition { first, second }
        })
        .collect()
}

/// DIS as before: nearest-first, nearer task (equal: easy) if its quota has room.
pub(crate) fn dis(req: &GroupingRequest) -> EasyHard {
    let nearer = |d: [f64; 2]| if d[1] < d[0] { Task::Hard } else { Task::Easy };
    let idx = |t: Task| t as usize;
    let mut order: Vec<_> = req.robots().iter().collect();
    order.sort_by(|a, b| {
        let (da, db) = (dist(req, a), dist(req, b));
        da[idx(nearer(da))]
            .total_cmp(&db[idx(nearer(db))])
            .then(a.id.cmp(&b.id))
    });
    let mut left: Vec<[usize; 2]> = quotas(req).iter().map(|q| [q.0, q.1]).collect();
    let (mut easy, mut hard) = (Vec::new(), Vec::new());
    for robot in order {
        let mut task = nearer(dist(req, robot));
        if left[robot.kind][idx(task)] == 0 {
            task = task.other();
        }
        left[robot.kind][idx(task)] -= 1;
        match task {
            Task::Easy => easy.push(robot.id),
            Task::Hard => hard.push(robot.id),
        }
    }
    EasyHard::new(easy, hard)
}

fn top_ranked_to_hard(
    req: &GroupingRequest,
    better_first: impl Fn(&RobotSnapshot, &RobotSnapshot) -> std::cmp::Ordering,
) -> EasyHard {
    let (mut easy, mut hard) = (Vec::new(), Vec::new());
    for (kind, quota) in quotas(req).iter().enumerate() {
        let mut members = req.members_of_kind(kind);
        members.sort_by(|a, b| better_first(a, b));
        for (rank, robot) in members.into_iter().enumerate() {
            if rank < quota.1 {
                hard.push(robot.id)
            } else {
                easy.push(robot.id)
            }
        }
    }
    EasyHard::new(easy, hard)
}

/// ENG as before.
pub(crate) fn eng(req: &GroupingRequest) -> EasyHard {
    top_ranked_to_hard(req, |a, b| b.energy_pct.total_cmp(&a.energy_pct))
}

/// HP_DIS as before.
pub(crate) fn hp_dis(req: &GroupingRequest) -> EasyHard {
    top_ranked_to_hard(req, |a, b| {
        b.hp_pct
            .total_cmp(&a.hp_pct)
            .then(dist(req, a)[1].total_cmp(&dist(req, b)[1]))
    })
}

struct Pair {
    first: Vec<usize>,
    second: Vec<usize>,
    first_task: Option<Task>,
}

fn needs_of<'a>(req: &'a GroupingRequest, ids: &[usize]) -> Vec<&'a NeedsVector> {
    ids.iter()
        .filter_map(|&id| req.robot(id))
        .map(|r| &r.needs)
        .collect()
}

fn best_split(m: &HierarchicalRne, members: &[&NeedsVector], first: usize) -> Result<Bipartition> {
    let mut best: Option<(Bipartition, f64)> = None;
    for split in two_way_splits(members.len(), first) {
        let a: Vec<_> = split.first.iter().map(|&i| members[i]).collect();
        let b: Vec<_> = split.second.iter().map(|&i| members[i]).collect();
        let score = between(m, &a, &b)?;
        if best.as_ref().is_none_or(|(_, s)| beats(score, *s)) {
            best = Some((split, score));
        }
    }
    Ok(best.expect("at least one split").0)
}

/// The old between-RNE, through `TrustModel::group_group` on needs matrices.
fn between(m: &HierarchicalRne, a: &[&NeedsVector], b: &[&NeedsVector]) -> Result<f64> {
    if a.is_empty() || b.is_empty() {
        return Ok(0.0);
    }
    let ma = crate::NeedsMatrix::from_members(a.iter().copied())?;
    let mb = crate::NeedsMatrix::from_members(b.iter().copied())?;
    Ok(m.model().group_group(&ma, &mb)? + m.model().group_group(&mb, &ma)?)
}

fn merge(m: &HierarchicalRne, req: &GroupingRequest, x: Pair, y: Pair) -> Result<Pair> {
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
            continue;
        }
        let first: Vec<usize> = x.first.iter().chain(y1).copied().collect();
        let second: Vec<usize> = x.second.iter().chain(y2).copied().collect();
        let score = between(m, &needs_of(req, &first), &needs_of(req, &second))?;
        if best.as_ref().is_none_or(|(_, s)| beats(score, *s)) {
            let first_task = x.first_task.or(y_task);
            best = Some((
                Pair {
                    first,
                    second,
                    first_task,
                },
                score,
            ));
        }
    }
    Ok(best.map(|(p, _)| p).unwrap_or(x))
}

/// The old within-group RNE: mean member-to-group RNE.
fn within(m: &HierarchicalRne, group: &[&NeedsVector]) -> Result<f64> {
    if group.is_empty() {
        return Ok(0.0);
    }
    let model = m.model();
    let dg = model.group_distribution(&crate::NeedsMatrix::from_members(group.iter().copied())?)?;
    let mut sum = 0.0;
    for member in group {
        sum += model.rne(&model.distribution(member)?, &dg)?;
    }
    Ok(sum / group.len() as f64)
}

/// Hierarchical RNE (Algorithm 1) as before, with `method`'s trust model.
pub(crate) fn rne(method: &HierarchicalRne, req: &GroupingRequest) -> Result<EasyHard> {
    let mut acc: Option<Pair> = None;
    for (kind, quota) in quotas(req).into_iter().enumerate() {
        let robots = req.members_of_kind(kind);
        if robots.is_empty() {
            continue;
        }
        let needs: Vec<_> = robots.iter().map(|r| &r.needs).collect();
        let split = best_split(method, &needs, quota.0)?;
        let ids = |idx: &[usize]| idx.iter().map(|&i| robots[i].id).collect::<Vec<_>>();
        let pair = Pair {
            first: ids(&split.first),
            second: ids(&split.second),
            first_task: (quota.0 != quota.1).then_some(Task::Easy),
        };
        acc = Some(match acc {
            None => pair,
            Some(x) => merge(method, req, x, pair)?,
        });
    }
    let pair = acc.ok_or(RneError::Empty { what: "team" })?;
    let g1 = needs_of(req, &pair.first);
    let g2 = needs_of(req, &pair.second);
    let within = [within(method, &g1)?, within(method, &g2)?];
    let first_task = pair.first_task.unwrap_or(if beats(within[0], within[1]) {
        Task::Easy
    } else {
        Task::Hard
    });
    Ok(match first_task {
        Task::Easy => EasyHard::new(pair.first, pair.second),
        Task::Hard => EasyHard::new(pair.second, pair.first),
    })
}
