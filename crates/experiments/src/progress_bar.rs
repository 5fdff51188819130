//! The progress bars, in one style: the sweep's over the simulated time of all its jobs, with
//! the simulation rate and an ETA, and a study's over a count (a calibration's evaluations, a
//! multiverse's universes), drawn on stderr (feature `outputs`, which brings indicatif);
//! without the feature, a sweep bar that is never drawn, so the sweep library needs no
//! indicatif.

#[cfg(feature = "outputs")]
pub(crate) use indicatif::ProgressBar;

/// A bar of `len` steps in the common style, `what` after the elapsed time and the bar
/// (an indicatif template), ticking every 250 ms; hidden unless `show` and stderr is a
/// terminal.
#[cfg(feature = "outputs")]
fn styled_bar(
    show: bool,
    len: u64,
    what: &str,
    style: impl FnOnce(indicatif::ProgressStyle) -> indicatif::ProgressStyle,
) -> ProgressBar {
    use indicatif::{ProgressDrawTarget, ProgressStyle};
    if !(show && std::io::IsTerminal::is_terminal(&std::io::stderr())) {
        return ProgressBar::hidden();
    }
    let pb = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
    let template = format!("{{elapsed_precise}} [{{bar:32.cyan/blue}}] {what}");
    let base =
        ProgressStyle::with_template(&template).unwrap_or_else(|_| ProgressStyle::default_bar());
    pb.set_style(style(base).progress_chars("=> "));
    pb.enable_steady_tick(std::time::Duration::from_millis(250));
    pb
}

/// A bar over the simulated time of all jobs (`total_us` microseconds), with the simulation
/// rate and an ETA; hidden unless `show` and stderr is a terminal.
#[cfg(feature = "outputs")]
pub(crate) fn progress_bar(show: bool, message: &str, total_us: u64) -> ProgressBar {
    use indicatif::ProgressState;
    let pb = styled_bar(show, total_us, "{msg}, {simrate}, ETA {eta}", |s| {
        s.with_key(
            "simrate",
            |s: &ProgressState, w: &mut dyn std::fmt::Write| {
                let _ = write!(w, "{:.0} sim-s/s", s.per_sec() / 1e6);
            },
        )
    });
    pb.set_message(message.to_string());
    pb
}

/// A bar over `count` `unit` (`evaluations`, `universes`) with a message and an ETA; hidden
/// unless `show` and stderr is a terminal.
#[cfg(feature = "outputs")]
pub(crate) fn count_bar(show: bool, count: u64, unit: &str) -> ProgressBar {
    styled_bar(
        show,
        count,
        &format!("{{pos}}/{{len}} {unit}, {{msg}}, ETA {{eta}}"),
        |s| s,
    )
}

/// A progress bar that is never drawn (the library without feature `outputs`): the methods
/// the executor calls on indicatif's bar, doing nothing.
#[cfg(not(feature = "outputs"))]
pub(crate) struct ProgressBar;

#[cfg(not(feature = "outputs"))]
impl ProgressBar {
    /// Advances the bar by `delta` (nothing to draw).
    pub(crate) fn inc(&self, _delta: u64) {}

    /// Runs `f` (with a drawn bar, `f` would run with the bar hidden).
    pub(crate) fn suspend<R>(&self, f: impl FnOnce() -> R) -> R {
        f()
    }

    /// Sets the bar's message (nothing to draw).
    pub(crate) fn set_message(&self, _message: String) {}

    /// Clears the bar (nothing to clear).
    pub(crate) fn finish_and_clear(&self) {}
}

/// Without feature `outputs` no bar is drawn, whatever `show` says.
#[cfg(not(feature = "outputs"))]
pub(crate) fn progress_bar(_show: bool, _message: &str, _total_us: u64) -> ProgressBar {
    ProgressBar
}
