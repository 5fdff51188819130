//! The progress bars `usar` draws on stderr (indicatif), in one style, for the runs of the
//! library ([`usar_sweep::progress`]): a sweep's over the simulated time of all its jobs,
//! with the simulation rate and an ETA, and a study's over a count (a calibration's
//! evaluations, a multiverse's design points and universes). Drawn only when stderr is a
//! terminal.

use std::sync::Arc;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressState, ProgressStyle};
use usar_sweep::progress::{Bar, BarUnit, ProgressSink};

/// The sink `usar` installs at start.
pub struct TerminalBars;

impl ProgressSink for TerminalBars {
    fn bar(&self, len: u64, unit: BarUnit, message: &str) -> Option<Arc<dyn Bar>> {
        if !std::io::IsTerminal::is_terminal(&std::io::stderr()) {
            return None;
        }
        let pb = match unit {
            BarUnit::SimMicros => styled_bar(len, "{msg}, {simrate}, ETA {eta}", |s| {
                s.with_key(
                    "simrate",
                    |s: &ProgressState, w: &mut dyn std::fmt::Write| {
                        let _ = write!(w, "{:.0} sim-s/s", s.per_sec() / 1e6);
                    },
                )
            }),
            BarUnit::Count(unit) => styled_bar(
                len,
                &format!("{{pos}}/{{len}} {unit}, {{msg}}, ETA {{eta}}"),
                |s| s,
            ),
        };
        pb.set_message(message.to_string());
        Some(Arc::new(Drawn(pb)))
    }
}

/// A bar of `len` steps in the common style, `what` after the elapsed time and the bar (an
/// indicatif template), ticking every 250 ms.
fn styled_bar(
    len: u64,
    what: &str,
    style: impl FnOnce(ProgressStyle) -> ProgressStyle,
) -> ProgressBar {
    let pb = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
    let template = format!("{{elapsed_precise}} [{{bar:32.cyan/blue}}] {what}");
    let base =
        ProgressStyle::with_template(&template).unwrap_or_else(|_| ProgressStyle::default_bar());
    pb.set_style(style(base).progress_chars("=> "));
    pb.enable_steady_tick(std::time::Duration::from_millis(250));
    pb
}

/// An indicatif bar on stderr.
struct Drawn(ProgressBar);

impl Bar for Drawn {
    fn inc(&self, delta: u64) {
        self.0.inc(delta);
    }

    fn set_message(&self, message: String) {
        self.0.set_message(message);
    }

    fn suspend(&self, f: &mut dyn FnMut()) {
        self.0.suspend(f);
    }

    fn finish(&self) {
        self.0.finish_and_clear();
    }
}
