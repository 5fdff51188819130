//! A detour's geometry: the robots it goes round ([`standing_round`]) and where it rejoins
//! the path ([`rejoin_point`]), as functions of the team as one robot sees it.
//!
//! Not in the paper (the detour rule is `docs/world-model.md`, "Detours"; path following runs
//! it, `path_following.rs`). The robots' intents and "goal reached" flags come through a
//! function, so that a detour planned ahead of the robots before it in id order
//! (`detours_ahead.rs`) sees them as it expects them to be.

use parry2d::math::Vector as Vec2;

use super::nav_state::Nav;
use super::neighbours::NeighbourIndex;
use super::path_following_params::DETOUR_REJOIN_BEYOND_M;
use super::robot::{Motion, RobotState};
use super::standing_disc::StandingDisc;
use crate::scenario::Locomotion;

/// What a detour of one robot reads of the team: every robot's navigation state and state
/// (by id), the neighbour index of their positions, whether the crowd rule holds
/// (`collision.hold_rule: Yield`: a held or blocked robot counts as standing) and the
/// largest body radius of the ground and the aerial robots (metres).
pub(super) struct Team<'a> {
    pub(super) nav: &'a [Nav],
    pub(super) robots: &'a [RobotState],
    pub(super) neighbours: &'a NeighbourIndex,
    pub(super) crowd: bool,
    pub(super) max_radius_m: [f64; 2],
}

/// Fills `out` with the keep-out discs of the robots ground robot `id`'s detour goes round,
/// in id order: the robots of its layer standing still within its sensing range (times its
/// sensing factor), or within its body radius plus theirs plus `inflation_m` (its planning
/// inflation, metres) whatever its sensing, each kept out to its body radius plus
/// `inflation_m`. A robot stands still when it has no goal it has not reached, no intended
/// motion or (under the crowd rule) was held or blocked at the last step; `seen(j)` gives
/// robot `j`'s intended velocity (m/s) and "goal reached" flag as the detour sees them.
/// Candidates come from the neighbour index; `near` is scratch.
pub(super) fn standing_round(
    team: &Team,
    id: usize,
    inflation_m: f32,
    seen: impl Fn(usize) -> (Vec2, bool),
    near: &mut Vec<usize>,
    out: &mut Vec<StandingDisc>,
) {
    let me = &team.nav[id];
    let range = me.sensing * team.robots[id].sensing_factor as f32;
    out.clear();
    // Candidates from the neighbour index (robots of this layer only) within the largest
    // reach any robot of the layer can have, in id order (the order of a scan over the team).
    let slot = usize::from(me.layer == Locomotion::Aerial);
    let reach_max = range.max(me.radius + team.max_radius_m[slot] as f32 + inflation_m);
    near.clear();
    team.neighbours
        .grid(me.layer)
        .for_each_candidate(me.pos, reach_max, |j, _| near.push(j));
    near.sort_unstable();
    for &j in near.iter() {
        let other = &team.nav[j];
        let r = &team.robots[j];
        let (intent, goal_reached) = seen(j);
        let stuck = team.crowd && (r.held || r.motion == Motion::Blocked);
        let active = r.goal.is_some() && !goal_reached;
        let still = !active || intent == Vec2::ZERO || stuck;
        // Sensed, or near enough to touch its keep-out disc: a robot with its sensing
        // cut by low HP still feels the one it is pressed against.
        let reach = range.max(me.radius + other.radius + inflation_m);
        if j != id && still && (other.pos - me.pos).length_squared() <= reach * reach {
            out.push(StandingDisc {
                center: other.pos,
                radius_m: other.radius + inflation_m,
            });
        }
    }
}

/// Where the detour of the robot of navigation state `nav` round `standing` rejoins its
/// path: the first point along the path (from the robot through its remaining waypoints) at
/// least [`DETOUR_REJOIN_BEYOND_M`] beyond the farthest rim of `standing` (path length from
/// the robot) and outside every standing disc, with the index of the first waypoint after
/// it; `None` when the path ends before such a point, or when the path from that point on
/// passes through a standing disc (a path winding back past one): the whole path is then
/// planned again.
pub(super) fn rejoin_point(nav: &Nav, standing: &[StandingDisc]) -> Option<(Vec2, usize)> {
    let (p, next) = first_point_beyond(nav, standing)?;
    let mut at = p;
    for &q in &nav.path[next..] {
        if standing.iter().any(|d| d.crosses(at, q)) {
            return None;
        }
        at = q;
    }
    Some((p, next))
}

/// The point of [`rejoin_point`] before its check of the rest of the path.
pub(super) fn first_point_beyond(nav: &Nav, standing: &[StandingDisc]) -> Option<(Vec2, usize)> {
    let beyond = standing
        .iter()
        .map(|d| (d.center - nav.pos).length() + d.radius_m)
        .fold(0.0f32, f32::max)
        + DETOUR_REJOIN_BEYOND_M;
    let clear = |p: Vec2| !standing.iter().any(|d| d.contains(p));
    let mut at = nav.pos;
    let mut walked = 0.0f32;
    // The farthest stretch walked before the point is taken: it must lie `beyond` away
    // and clear of the discs; each metre further is tried while a disc holds it.
    let mut want = beyond;
    for k in nav.following.wp..nav.path.len() {
        let next = nav.path[k];
        let leg = (next - at).length();
        while walked + leg > want {
            let p = at + (next - at) * ((want - walked) / leg);
            if clear(p) {
                // The last waypoint is the goal: a point on the last leg rejoins it.
                return Some((p, k));
            }
            want += DETOUR_REJOIN_BEYOND_M;
        }
        walked += leg;
        at = next;
    }
    None
}
