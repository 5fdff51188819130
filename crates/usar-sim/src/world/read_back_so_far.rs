//! [`ReadBackSoFar`]: the robots a step has read back at some point of it, for work on them
//! that may run beside Rapier's step ([`super::World::step_beside`]).
//!
//! Not in the paper. Under `sim.physics: NearBodies` a large team reads the robots far from
//! any contact back while Rapier steps the others (`step.rs`); what only reads a robot's own
//! state after the step (the mission's step costs) can run for those robots there, and for
//! the rest after the step ([`super::World::read_back_rest`]), with the same bits as one
//! pass over the team after the step.

use super::robot::RobotState;

/// Which robots a [`ReadBackSoFar`] covers.
#[derive(Debug, Clone, Copy)]
pub(super) enum Covered<'a> {
    /// Every robot.
    All,
    /// No robot.
    None,
    /// The robots `id` with `near[id] == false` (read back beside Rapier's step).
    Far(&'a [bool]),
    /// The robots `id` with `near[id] == true` (read back from their bodies after it).
    Near(&'a [bool]),
}

/// Which robots the step after the read-back part handed to its caller leaves for
/// [`super::World::read_back_rest`]: every robot (no part was handed over, [`super::World::step`]),
/// none (the whole read-back was handed over) or the robots near a contact
/// (`sim.physics: NearBodies`: the far ones were).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(super) enum Rest {
    /// Every robot (no part was handed over; also before the first step).
    #[default]
    All,
    /// No robot.
    None,
    /// The robots near a contact.
    Near,
}

impl<'a> Covered<'a> {
    /// The robots `rest` leaves, `near` the contact gate's marks of the step.
    pub(super) fn rest(rest: Rest, near: &'a [bool]) -> Self {
        match rest {
            Rest::All => Self::All,
            Rest::None => Self::None,
            Rest::Near => Self::Near(near),
        }
    }
}

/// The robots a step has read back (`covers`), with every robot's state and dose factor (by
/// id; a robot not covered may still hold the last step's), and whether work over them may
/// run on the calling rayon pool ([`super::World::per_robot_parallel`]).
#[derive(Debug, Clone, Copy)]
pub struct ReadBackSoFar<'a> {
    pub(super) robots: &'a [RobotState],
    pub(super) radiation_factors: &'a [f64],
    pub(super) covered: Covered<'a>,
    pub(super) parallel: bool,
}

impl ReadBackSoFar<'_> {
    /// Every robot's state, by id ([`super::World::robots`]); this step's for the robots
    /// [`ReadBackSoFar::covers`].
    pub fn robots(&self) -> &[RobotState] {
        self.robots
    }

    /// Every robot's dose factor, by id ([`super::World::radiation_factors`]); this step's for
    /// the robots [`ReadBackSoFar::covers`].
    pub fn radiation_factors(&self) -> &[f64] {
        self.radiation_factors
    }

    /// Whether this view hands over no robot at all (every robot was handed over earlier in
    /// the step, or none is due), so a pass over the team may be skipped.
    pub fn covers_none(&self) -> bool {
        matches!(self.covered, Covered::None)
    }

    /// The robots this view hands over, in id order, when they are the near robots of
    /// `sim.physics: NearBodies` (the rest of its step, usually a small part of the team):
    /// `None` for every other view, whose robots [`ReadBackSoFar::covers`] tells one by one.
    pub fn near_ids(&self) -> Option<impl Iterator<Item = usize> + '_> {
        match self.covered {
            Covered::Near(near) => Some(
                near.iter()
                    .enumerate()
                    .filter(|(_, n)| **n)
                    .map(|(id, _)| id),
            ),
            Covered::All | Covered::None | Covered::Far(_) => None,
        }
    }

    /// Whether robot `id` (below the team size) is one of the robots this view hands over: read
    /// back in this part of the step (before the first step, [`super::World::read_back_rest`]
    /// hands over every robot, as it stands).
    pub fn covers(&self, id: usize) -> bool {
        match self.covered {
            Covered::All => true,
            Covered::None => false,
            Covered::Far(near) => !near[id],
            Covered::Near(near) => near[id],
        }
    }

    /// Whether work over the robots may run in parallel (a large team on a pool of more than
    /// one thread), as the world's own per-robot stages do.
    pub fn parallel(&self) -> bool {
        self.parallel
    }
}
