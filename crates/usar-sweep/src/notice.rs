//! Notices of the libraries as `tracing` events, and the small subscriber each front end
//! installs to show them.
//!
//! The libraries (usar-sweep, usar-report, usar-study) never write to stderr: a warning is a
//! `tracing::warn!` event (its message without a `warning: ` prefix, e.g. `report.claims:
//! ... not found`), a progress line a `tracing::info!` event (a calibration's better loss, a
//! multiverse's finished universe, a sweep's failed trial while it goes on). The program
//! decides how to show them: the `usar` binary prints each on stderr (`warning: ` before a
//! warning), the Python package turns warnings into `warnings.warn(message,
//! usar.UsarWarning)` when control returns to Python and drops progress lines. Without a
//! subscriber (another library caller) nothing is shown.
//!
//! Events fire on whichever thread does the work, rayon workers included, so a subscriber
//! must be installed process-wide ([`install`]).

use tracing::field::{Field, Visit};
use tracing::span::{Attributes, Id, Record};
use tracing::{Event, Metadata};

/// A notice's level, as [`install`]'s function gets it: `WARN` a warning, `INFO` a progress
/// line (`tracing`'s own type, re-exported for front ends that do not depend on `tracing`).
pub use tracing::Level;

/// A subscriber that hands each event's level and message to a function: warnings and
/// progress lines (levels `WARN` and `INFO`, and `ERROR`), nothing finer, no spans.
pub struct Notices<F>(pub F);

impl<F: Fn(Level, &str) + Send + Sync + 'static> tracing::Subscriber for Notices<F> {
    fn enabled(&self, metadata: &Metadata<'_>) -> bool {
        metadata.is_event() && *metadata.level() <= Level::INFO
    }

    fn max_level_hint(&self) -> Option<tracing::level_filters::LevelFilter> {
        Some(tracing::level_filters::LevelFilter::INFO)
    }

    fn new_span(&self, _: &Attributes<'_>) -> Id {
        Id::from_u64(1)
    }

    fn record(&self, _: &Id, _: &Record<'_>) {}

    fn record_follows_from(&self, _: &Id, _: &Id) {}

    fn event(&self, event: &Event<'_>) {
        let mut message = Message(String::new());
        event.record(&mut message);
        (self.0)(*event.metadata().level(), &message.0);
    }

    fn enter(&self, _: &Id) {}

    fn exit(&self, _: &Id) {}
}

/// An event's `message` field (the formatted text of `warn!("...")`), other fields ignored.
struct Message(String);

impl Visit for Message {
    fn record_str(&mut self, field: &Field, value: &str) {
        if field.name() == "message" {
            self.0 = value.to_string();
        }
    }

    fn record_debug(&mut self, field: &Field, value: &dyn std::fmt::Debug) {
        if field.name() == "message" {
            self.0 = format!("{value:?}");
        }
    }
}

/// Installs `show` as the process's subscriber: it gets every notice's level and message, on
/// the thread that emitted it (so it must not block on a lock that thread may hold). Once per
/// process, at start.
///
/// # Errors
/// A subscriber is installed already.
pub fn install(
    show: impl Fn(Level, &str) + Send + Sync + 'static,
) -> Result<(), tracing::subscriber::SetGlobalDefaultError> {
    tracing::subscriber::set_global_default(Notices(show))
}

#[cfg(test)]
mod tests {
    use std::sync::{Arc, Mutex};

    use super::*;

    #[test]
    fn warnings_and_progress_lines_reach_the_function_with_their_level() {
        let seen = Arc::new(Mutex::new(Vec::new()));
        let log = seen.clone();
        let notices = Notices(move |level: Level, m: &str| {
            log.lock().unwrap().push(format!("{level} {m}"));
        });
        tracing::subscriber::with_default(notices, || {
            tracing::warn!("report.{}: {} not found", "claims", "x.ron");
            tracing::info!("evaluation #{}", 3);
            tracing::debug!("not shown");
        });
        assert_eq!(
            *seen.lock().unwrap(),
            ["WARN report.claims: x.ron not found", "INFO evaluation #3"]
        );
    }
}
