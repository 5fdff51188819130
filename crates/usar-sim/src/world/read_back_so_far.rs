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

    /// The robots this view hands over ([`ReadBackSoFar::covers`]), in id order: every robot,
    /// none, or those of one side of `sim.physics: NearBodies`' gate (one scan of its flags).
    pub fn covered_ids(&self) -> impl Iterator<Item = usize> + '_ {
        let n = match self.covered {
            Covered::None => 0,
            Covered::All | Covered::Far(_) | Covered::Near(_) => self.robots.len(),
        };
        (0..n).filter(move |&id| self.covers(id))
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

    /// Whether work over the robots may run in parallel, as the world's own per-robot stages
    /// do: a large team on a pool of more than one thread, when this view hands over the
    /// whole team or its far robots (`sim.physics: NearBodies`). The near robots (the rest of
    /// such a step, usually a few) and an empty view are better served by one loop over
    /// [`ReadBackSoFar::covered_ids`].
    pub fn parallel(&self) -> bool {
        self.parallel && matches!(self.covered, Covered::All | Covered::Far(_))
    }
}
