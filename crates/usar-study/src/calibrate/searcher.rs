//! The objective a calibration's search minimises ([`super::optimizer::Objective`]): a point
//! in normalised coordinates becomes rounded free values; values already in the search's
//! sequence give their loss again, values recorded by an earlier run (the trace) join the
//! sequence without running, and new values are evaluated, appended to the trace and shown.
//! The evaluation budget counts the sequence (reused points included, so that a resumed
//! calibration stops where an uninterrupted one does); the time budget only new runs.

use std::collections::HashMap;
use std::time::Instant;

use super::evaluate::{Evaluation, Evaluator};
use super::free::FreeField;
use super::optimizer::{Objective, Scored, StopReason};
use super::progress::Display;
use super::trace::Trace;
use super::trace_error::TraceError;

/// The key of a set of free values: their bits.
pub(crate) fn key(values: &[f64]) -> Vec<u64> {
    values.iter().map(|x| x.to_bits()).collect()
}

/// The calibration's objective.
pub(crate) struct Searcher<'a> {
    pub(crate) evaluator: &'a Evaluator<'a>,
    pub(crate) free: &'a [FreeField],
    pub(crate) digits: u32,
    /// Evaluations of an earlier run, by their values.
    pub(crate) cache: HashMap<Vec<u64>, Evaluation>,
    /// The sequence so far.
    pub(crate) sequence: Vec<Evaluation>,
    /// Position in `sequence` by values.
    pub(crate) positions: HashMap<Vec<u64>, usize>,
    pub(crate) trace: Trace,
    pub(crate) max_evals: usize,
    /// No new evaluation starts after this (the first always runs).
    pub(crate) deadline: Option<Instant>,
    /// No new evaluation starts once this is set ([`usar_sweep::data::hooks::CalibrationHooks`]).
    pub(crate) stop: Option<std::sync::Arc<std::sync::atomic::AtomicBool>>,
    pub(crate) display: Display,
    /// Evaluations run now, and taken from the trace.
    pub(crate) ran: usize,
    pub(crate) reused: usize,
    /// A trace that could not be written: the search stops and the calibration fails.
    pub(crate) error: Option<TraceError>,
}

impl Searcher<'_> {
    /// The rounded free values at normalised point `u`.
    pub(crate) fn values_at(&self, u: &[f64]) -> Vec<f64> {
        self.free
            .iter()
            .zip(u)
            .map(|(f, &x)| f.from_unit(x, self.digits))
            .collect()
    }

    fn field_names(&self) -> Vec<String> {
        self.free.iter().map(FreeField::label).collect()
    }
}

impl Objective for Searcher<'_> {
    fn loss(&mut self, u: &[f64]) -> Result<Scored, StopReason> {
        let values = self.values_at(u);
        let k = key(&values);
        if let Some(&i) = self.positions.get(&k) {
            return Ok(Scored {
                loss: self.sequence[i].search_loss(),
                fresh: false,
            });
        }
        if self.sequence.len() >= self.max_evals {
            return Err(StopReason::MaxEvals);
        }
        let index = self.sequence.len();
        let (mut e, new) = match self.cache.remove(&k) {
            Some(e) => {
                self.reused += 1;
                (e, false)
            }
            None => {
                if usar_sweep::data::hooks::is_set(self.stop.as_ref()) {
                    return Err(StopReason::Interrupted);
                }
                if index > 0 && self.deadline.is_some_and(|d| Instant::now() >= d) {
                    return Err(StopReason::MaxTime);
                }
                let mut e = self.evaluator.evaluate(&values);
                if usar_sweep::data::hooks::is_set(self.stop.as_ref()) {
                    // Stopped while it ran: some trials were skipped, so it is not kept.
                    return Err(StopReason::Interrupted);
                }
                e.index = index;
                if let Err(err) = self.trace.append(&e) {
                    // The search only knows reasons to stop; the caller sees `error` first
                    // and fails with it, whatever reason is given here.
                    self.error = Some(err);
                    return Err(StopReason::Stalled);
                }
                self.ran += 1;
                (e, true)
            }
        };
        e.index = index;
        let fields = self.field_names();
        self.display.show(&e, new, &fields);
        let loss = e.search_loss();
        self.positions.insert(k, index);
        self.sequence.push(e);
        Ok(Scored { loss, fresh: true })
    }
}
