//! What a multiverse shows while it runs: a bar over its universes ([`usar_sweep::progress`])
//! (drawn only on a terminal), and one line on stderr per universe it finishes.

use super::plan::MultiversePlan;
use super::record::{Status, UniverseRecord};
use crate::calibrate::progress::loss_text;
use usar_report::claims::Verdict;
use usar_sweep::progress::{ProgressBar, count_bar};

/// What a multiverse shows while it runs. [`MultiverseProgress::off`] shows nothing;
/// [`MultiverseProgress::terminal`] is `usar multiverse`'s (without `--quiet`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct MultiverseProgress {
    /// A bar over the universes with an ETA, on stderr when it is a terminal.
    pub bar: bool,
    /// One line on stderr per universe finished by this run.
    pub lines: bool,
}

impl MultiverseProgress {
    /// Nothing shown.
    pub fn off() -> Self {
        Self::default()
    }

    /// The bar and the lines.
    pub fn terminal() -> Self {
        Self {
            bar: true,
            lines: true,
        }
    }
}

/// The running display of one multiverse.
pub(crate) struct Display {
    pb: ProgressBar,
    lines: bool,
}

impl Display {
    /// A display over `count` universes.
    pub(crate) fn new(progress: MultiverseProgress, count: usize) -> Self {
        let pb = count_bar(progress.bar, count as u64, "universes");
        Self {
            pb,
            lines: progress.lines,
        }
    }

    /// Says that universe `id` starts.
    pub(crate) fn starting(&self, id: &str) {
        self.pb.set_message(format!("running {id}"));
    }

    /// Shows a finished universe (`new`: run now, else its record was there).
    pub(crate) fn done(&self, plan: &MultiversePlan, r: &UniverseRecord, new: bool) {
        self.pb.inc(1);
        if self.lines && new {
            let line = universe_line(plan, r);
            self.pb.suspend(|| tracing::info!("{line}"));
        }
    }

    /// Removes the bar.
    pub(crate) fn finish(&self) {
        self.pb.finish_and_clear();
    }
}

/// One line about a finished universe: its choices and what it gave.
pub fn universe_line(plan: &MultiversePlan, r: &UniverseRecord) -> String {
    let choices: Vec<String> = plan
        .identity
        .axes
        .axes
        .iter()
        .zip(&r.choices)
        .map(|(a, &k)| {
            let alt = a.alternatives.get(k).map_or("?", |x| x.name.as_str());
            format!("{}: {alt}", a.name)
        })
        .collect();
    let loss = r.calibration.as_ref().map_or("no calibration".into(), |c| {
        format!("loss {}", loss_text(c.loss))
    });
    let what = match (r.status, r.admissible()) {
        (Status::Invalid, _) => format!("invalid: {}", r.message.as_deref().unwrap_or("")),
        (Status::Failed, _) => format!("failed ({loss}): {}", r.message.as_deref().unwrap_or("")),
        (Status::Ok, false) => format!("not admissible ({loss})"),
        (Status::Ok, true) if plan.identity.claims.is_empty() => "admissible".to_string(),
        (Status::Ok, true) => {
            let holding: Vec<&str> = plan
                .identity
                .claims
                .iter()
                .filter(|c| {
                    r.claim(&c.id)
                        .is_some_and(|e| e.verdict == Verdict::Holds.words())
                })
                .map(|c| c.id.as_str())
                .collect();
            let holds = if holding.is_empty() {
                "none".into()
            } else {
                holding.join(", ")
            };
            format!("admissible; claims that hold: {holds}")
        }
    };
    format!("{} [{}]: {what}", r.id, choices.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multiverse::plan::tests::plan;
    use crate::multiverse::record::tests::record;

    #[test]
    fn a_line_names_the_choices_and_the_outcome() {
        let p = plan();
        assert_eq!(
            universe_line(&p, &record(1, &[0, 1], 0.0)),
            "u001 [a: a0, b: b1]: admissible; claims that hold: 1"
        );
        assert_eq!(
            universe_line(&p, &record(2, &[0, 2], 1.5)),
            "u002 [a: a0, b: b2]: not admissible (loss 1.50)"
        );
        let mut r = record(3, &[1, 0], 0.0);
        r.status = Status::Invalid;
        r.calibration = None;
        r.message = Some("set x=1: rule".into());
        assert_eq!(
            universe_line(&p, &r),
            "u003 [a: a1, b: b0]: invalid: set x=1: rule"
        );
    }
}
