//! The extension points of a sweep ([`SweepHooks`]): a step observer per trial and a call per
//! journaled record, and the key of the trial they are called for.

use std::fmt;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use usar_sim::mission::StepObserver;

use crate::journal::TrialRecord;

/// Which trial of a sweep a hook is called for.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TrialKey {
    /// Grid cell index (0 without a grid).
    pub cell: usize,
    /// The method's display name, e.g. `RNE` or `hp_sort`.
    pub method: String,
    /// Trial index, `0..trials`.
    pub trial: u32,
    /// The trial's seed.
    pub seed: u64,
}

/// Makes a [`StepObserver`] for a trial about to run, or `None` to leave it unobserved.
pub type TrialObserverFactory =
    Arc<dyn Fn(&TrialKey) -> Option<Box<dyn StepObserver>> + Send + Sync>;

/// Called after a trial's record is in the journal, with the record and how many records this
/// run has journaled so far (1, 2, ...).
pub type JournaledHook = Arc<dyn Fn(&TrialRecord, usize) + Send + Sync>;

/// Extension points of a sweep; none by default.
///
/// Both are called on the worker thread of the trial. A panic inside `trial_observer` or the
/// observer it makes fails that trial only (its record says "panicked: ..."), as a panicking
/// grouping method does. `on_journaled` is called with the journal locked, so its calls come
/// in journal order and never overlap.
///
/// Uses: record the robot paths of chosen trials during a sweep (`trial_observer`), report
/// progress to a scheduler or stop a process at a checkpoint (`on_journaled`). The `usar`
/// binary's hidden `--fail-trial` and `--stop-after` options, which its tests use to make a
/// trial fail and to simulate a killed sweep, are built on them.
#[derive(Clone, Default)]
pub struct SweepHooks {
    /// Makes each trial's step observer.
    pub trial_observer: Option<TrialObserverFactory>,
    /// Sees each journaled record.
    pub on_journaled: Option<JournaledHook>,
    /// Set to `true` to stop the sweep (e.g. on Ctrl-C in the Python package): trials not
    /// started yet are skipped, running ones end as usual and are journaled; the sweep then
    /// returns with the skipped trials missing (a resume runs them). Default `None`.
    pub stop: Option<Arc<AtomicBool>>,
}

impl fmt::Debug for SweepHooks {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("SweepHooks")
            .field("trial_observer", &self.trial_observer.is_some())
            .field("on_journaled", &self.on_journaled.is_some())
            .field("stop", &self.stop)
            .finish()
    }
}

/// Extension points of a calibration (`usar_study::calibrate::CalibrationSetup::hooks`); none by
/// default.
#[derive(Clone, Default)]
pub struct CalibrationHooks {
    /// Makes a step observer for each trial of each evaluation (and of the check on unseen
    /// trials), as [`SweepHooks::trial_observer`] does for a sweep's. The Python package uses
    /// it to show a Python grouping method the robots' positions.
    pub trial_observer: Option<TrialObserverFactory>,
    /// Set to `true` to stop (e.g. on Ctrl-C in the Python package): the trials not started
    /// are skipped, the evaluation running is not kept (the trace holds only whole ones), no
    /// new one starts, and the calibration returns [`Stopped`] without writing its outputs
    /// (running it again continues). Default `None`.
    pub stop: Option<Arc<AtomicBool>>,
}

impl CalibrationHooks {
    /// Whether [`CalibrationHooks::stop`] is set.
    pub fn stopped(&self) -> bool {
        is_set(self.stop.as_ref())
    }
}

impl fmt::Debug for CalibrationHooks {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("CalibrationHooks")
            .field("trial_observer", &self.trial_observer.is_some())
            .field("stop", &self.stop)
            .finish()
    }
}

/// Whether a stop flag is given and set.
pub fn is_set(stop: Option<&Arc<AtomicBool>>) -> bool {
    stop.is_some_and(|s| s.load(std::sync::atomic::Ordering::SeqCst))
}

/// A calibration or multiverse stopped by its stop flag before its end. Its finished work is
/// kept (the calibration's trace, the universes' records and journals): running it again
/// with the same parameters continues.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("stopped before the end; its finished work is kept: run it again to continue")]
pub struct Stopped;
