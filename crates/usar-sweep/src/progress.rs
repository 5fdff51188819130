//! Progress of a long run (a sweep's trials, a calibration's evaluations, a multiverse's
//! design points and universes), reported to a [`ProgressSink`] the program installs once
//! ([`set_sink`]); the library draws nothing itself.
//!
//! The `usar` binary installs a sink that draws indicatif bars on stderr when it is a
//! terminal. Without a sink (a library caller, the Python package) nothing is shown, whatever
//! a run's `progress` flag says; the flag only lets a run ask for no bar when a sink is there.
//! In the manner of `tracing`: libraries report, the program decides how to show it.

use std::sync::{Arc, OnceLock};

/// What a bar counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BarUnit {
    /// Simulated time, microseconds: a sweep's trials (the sink may show a simulation rate).
    SimMicros,
    /// Whole things, named in the plural (`"evaluations"`, `"universes"`, `"design points"`).
    Count(&'static str),
}

/// A bar a [`ProgressSink`] made for one run: advanced, labelled and removed by the run.
pub trait Bar: Send + Sync {
    /// Advances the bar by `delta` units.
    fn inc(&self, delta: u64);
    /// Replaces the bar's message.
    fn set_message(&self, message: String);
    /// Runs `f` with the bar out of the way (a line written to stderr by `f` is not drawn
    /// over).
    fn suspend(&self, f: &mut dyn FnMut());
    /// Removes the bar.
    fn finish(&self);
}

/// Where runs report their progress: makes one [`Bar`] per run. Installed once per process
/// with [`set_sink`].
pub trait ProgressSink: Send + Sync {
    /// A bar over `len` units of `unit`, with the first message `message`; `None` to show
    /// nothing for this run (e.g. when stderr is not a terminal).
    fn bar(&self, len: u64, unit: BarUnit, message: &str) -> Option<Arc<dyn Bar>>;
}

static SINK: OnceLock<Box<dyn ProgressSink>> = OnceLock::new();

/// Installs the process's progress sink. Once per process: a program calls it at start.
///
/// # Errors
/// A sink is installed already (the new one is handed back, unused).
pub fn set_sink(sink: Box<dyn ProgressSink>) -> Result<(), Box<dyn ProgressSink>> {
    SINK.set(sink)
}

/// A run's bar: the installed sink's, or nothing when there is no sink or the run asked for
/// none.
pub struct ProgressBar(Option<Arc<dyn Bar>>);

impl ProgressBar {
    /// Advances the bar by `delta` units.
    pub fn inc(&self, delta: u64) {
        if let Some(b) = &self.0 {
            b.inc(delta);
        }
    }

    /// Runs `f` with the bar out of the way, and returns what it returns.
    pub fn suspend<R>(&self, f: impl FnOnce() -> R) -> R {
        let Some(b) = &self.0 else {
            return f();
        };
        let (mut f, mut out) = (Some(f), None);
        b.suspend(&mut || out = f.take().map(|f| f()));
        out.unwrap_or_else(|| unreachable!("a sink's suspend runs its function once"))
    }

    /// Replaces the bar's message.
    pub fn set_message(&self, message: String) {
        if let Some(b) = &self.0 {
            b.set_message(message);
        }
    }

    /// Removes the bar.
    pub fn finish_and_clear(&self) {
        if let Some(b) = &self.0 {
            b.finish();
        }
    }
}

/// The bar of a run that shows one when `show`: over `len` units of `unit`, first labelled
/// `message`.
fn bar(show: bool, len: u64, unit: BarUnit, message: &str) -> ProgressBar {
    ProgressBar(
        SINK.get()
            .filter(|_| show)
            .and_then(|s| s.bar(len, unit, message)),
    )
}

/// A sweep's bar over the simulated time of all its jobs (`total_us` microseconds).
pub fn progress_bar(show: bool, message: &str, total_us: u64) -> ProgressBar {
    bar(show, total_us, BarUnit::SimMicros, message)
}

/// A study's bar over `count` `unit` (`evaluations`, `universes`).
pub fn count_bar(show: bool, count: u64, unit: &'static str) -> ProgressBar {
    bar(show, count, BarUnit::Count(unit), "")
}

#[cfg(test)]
mod tests {
    use std::sync::Mutex;

    use super::*;

    #[derive(Default)]
    struct Log(Mutex<Vec<String>>);

    impl Bar for Log {
        fn inc(&self, delta: u64) {
            self.0.lock().unwrap().push(format!("inc {delta}"));
        }
        fn set_message(&self, message: String) {
            self.0.lock().unwrap().push(format!("message {message}"));
        }
        fn suspend(&self, f: &mut dyn FnMut()) {
            self.0.lock().unwrap().push("suspend".into());
            f();
        }
        fn finish(&self) {
            self.0.lock().unwrap().push("finish".into());
        }
    }

    #[test]
    fn a_bar_passes_every_call_to_the_sinks_bar_and_none_runs_the_same() {
        let log = Arc::new(Log::default());
        let shown = ProgressBar(Some(log.clone()));
        shown.inc(3);
        assert_eq!(shown.suspend(|| 7), 7);
        shown.set_message("2/4 trials".into());
        shown.finish_and_clear();
        assert_eq!(
            *log.0.lock().unwrap(),
            ["inc 3", "suspend", "message 2/4 trials", "finish"]
        );
        let hidden = ProgressBar(None);
        hidden.inc(1);
        assert_eq!(hidden.suspend(|| "ran"), "ran");
        hidden.finish_and_clear();
    }

    /// No sink is installed in the library's tests: a run asking for a bar gets none.
    #[test]
    fn without_a_sink_no_bar_is_made() {
        assert!(progress_bar(true, "0/1 trials", 10).0.is_none());
    }
}
