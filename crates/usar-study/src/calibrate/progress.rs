//! What a calibration shows while it runs: a bar over the evaluations ([`usar_sweep::progress`])
//! (only drawn on a terminal, as a sweep's), a line per improvement of the best loss, and a
//! hook per new evaluation.

use std::fmt;
use std::sync::Arc;

use super::evaluate::Evaluation;
use usar_report::table::num;
use usar_sweep::progress::{ProgressBar, count_bar};

/// Called after each new evaluation is in the trace, with it and how many this run has made
/// so far (1, 2, ...). `usar calibrate`'s hidden `--stop-after N` (its tests' stand-in for a
/// kill) is built on it.
pub type EvaluationHook = Arc<dyn Fn(&Evaluation, usize) + Send + Sync>;

/// What a calibration shows while it runs. [`Progress::off`] shows nothing (for a caller
/// running many calibrations); [`Progress::terminal`] is `usar calibrate`'s.
#[derive(Clone, Default)]
pub struct Progress {
    /// A bar over the evaluations with an ETA, on stderr when it is a terminal.
    pub bar: bool,
    /// One line on stderr per evaluation that improves the best loss.
    pub improvements: bool,
    /// Called after each new evaluation.
    pub on_evaluated: Option<EvaluationHook>,
}

impl Progress {
    /// Nothing shown, no hook.
    pub fn off() -> Self {
        Self::default()
    }

    /// The bar and the improvement lines.
    pub fn terminal() -> Self {
        Self {
            bar: true,
            improvements: true,
            on_evaluated: None,
        }
    }
}

impl fmt::Debug for Progress {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Progress")
            .field("bar", &self.bar)
            .field("improvements", &self.improvements)
            .field("on_evaluated", &self.on_evaluated.is_some())
            .finish()
    }
}

/// The running display of one calibration.
pub(crate) struct Display {
    pb: ProgressBar,
    progress: Progress,
    best: f64,
    made: usize,
}

impl Display {
    /// A display for a search of at most `max_evals` evaluations, with the field names
    /// `fields` for the improvement lines.
    pub(crate) fn new(progress: &Progress, max_evals: usize) -> Self {
        let pb = count_bar(progress.bar, max_evals as u64, "evaluations");
        Self {
            pb,
            progress: progress.clone(),
            best: f64::INFINITY,
            made: 0,
        }
    }

    /// Shows evaluation `e` (`new`: run now, else taken from the trace); `fields` names the
    /// free fields.
    pub(crate) fn show(&mut self, e: &Evaluation, new: bool, fields: &[String]) {
        self.pb.inc(1);
        if e.loss < self.best || (self.best.is_infinite() && e.index == 0) {
            self.best = e.loss;
            if self.progress.improvements {
                let values: Vec<String> = fields
                    .iter()
                    .zip(&e.values)
                    .map(|(f, x)| format!("{f}={x}"))
                    .collect();
                let line = format!(
                    "evaluation #{}{}: loss {} at {}",
                    e.index,
                    if new { "" } else { " (from the trace)" },
                    loss_text(e.loss),
                    values.join(" ")
                );
                self.pb.suspend(|| tracing::info!("{line}"));
            }
        }
        self.pb
            .set_message(format!("best loss {}", loss_text(self.best)));
        if new {
            self.made += 1;
            if let Some(hook) = &self.progress.on_evaluated {
                let made = self.made;
                self.pb.suspend(|| hook(e, made));
            }
        }
    }

    /// Removes the bar.
    pub(crate) fn finish(&self) {
        self.pb.finish_and_clear();
    }
}

/// A loss as tables show it: `0`, `inf`, else 3 significant digits' worth ([`num`]).
pub fn loss_text(loss: f64) -> String {
    if loss == 0.0 {
        "0".into()
    } else if loss.is_infinite() {
        "inf".into()
    } else {
        num(loss)
    }
}
