//! The method-independent statistics `scenarios/paper.ron` is calibrated against, pooled over
//! every trial of a sweep (all methods together), and their targets: the authors' results sheet
//! (`RNE_experiments_for_paper.ods` of the public repository RNE-Agent-Trust-Model-SMC2021, 4
//! methods x 10 trials x 600 s, pooled the same way). See `docs/calibration.md`.
//!
//! Every statistic is a ratio of means over the pooled trials (not a mean of per-trial
//! ratios), as the targets were computed from the sheet. They compare the tasks named `easy`
//! and `hard`; for other scenarios they are undefined (NaN).

use usar_sim::mission::TrialResult;

/// One pooled statistic.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Statistic {
    /// Rounds started per trial (the last one cut by the time limit included).
    RoundsPerTrial,
    /// Mean easy-task rescuees over mean hard-task rescuees.
    EasyOverHardRescuees,
    /// Mean rescuees per trial, both tasks.
    TotalRescuees,
    /// Mean easy-task rescuees over mean rounds per trial.
    EasyRescueesPerRound,
    /// Mean hard-task rescuees over mean rounds per trial.
    HardRescueesPerRound,
    /// Mean HP lost over mean energy spent by the hard task's groups.
    HardHpOverEnergy,
    /// Mean HP lost over mean energy spent by the easy task's groups.
    EasyHpOverEnergy,
    /// Mean energy spent by the hard task's groups over that of the easy task's.
    HardOverEasyEnergy,
    /// Mean HP lost by the hard task's groups over that of the easy task's.
    HardOverEasyHp,
}

/// A calibration target: the authors' pooled value and the band ours must fall in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Target {
    /// The statistic.
    pub statistic: Statistic,
    /// Short label for tables.
    pub label: &'static str,
    /// The value in the authors' sheet.
    pub value: f64,
    /// Half-width of the accepted band: `|ours - value| <= band`.
    pub band: f64,
}

impl Target {
    /// Whether `x` lies in the band (boundaries included).
    pub fn holds(&self, x: f64) -> bool {
        (x - self.value).abs() <= self.band
    }
}

/// The nine targets of issue 8, from the authors' results sheet.
pub const TARGETS: [Target; 9] = [
    Target {
        statistic: Statistic::RoundsPerTrial,
        label: "rounds per trial",
        value: 6.2,
        band: 0.6,
    },
    Target {
        statistic: Statistic::EasyOverHardRescuees,
        label: "easy / hard rescuees",
        value: 1.36,
        band: 0.2,
    },
    Target {
        statistic: Statistic::TotalRescuees,
        label: "rescuees per trial",
        value: 152.0,
        band: 15.0,
    },
    Target {
        statistic: Statistic::EasyRescueesPerRound,
        label: "easy rescuees per round",
        value: 14.2,
        band: 2.0,
    },
    Target {
        statistic: Statistic::HardRescueesPerRound,
        label: "hard rescuees per round",
        value: 10.5,
        band: 2.0,
    },
    Target {
        statistic: Statistic::HardHpOverEnergy,
        label: "hard HP / hard energy",
        value: 0.62,
        band: 0.12,
    },
    Target {
        statistic: Statistic::EasyHpOverEnergy,
        label: "easy HP / easy energy",
        value: 0.09,
        band: 0.04,
    },
    Target {
        statistic: Statistic::HardOverEasyEnergy,
        label: "hard / easy energy",
        value: 1.18,
        band: 0.12,
    },
    Target {
        statistic: Statistic::HardOverEasyHp,
        label: "hard / easy HP",
        value: 8.4,
        band: 3.0,
    },
];

/// Means over a set of trials of the quantities the statistics are built from.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Means {
    rounds: f64,
    easy: f64,
    hard: f64,
    energy_easy: f64,
    energy_hard: f64,
    hp_easy: f64,
    hp_hard: f64,
}

impl Means {
    /// The means over `results`, or `None` unless every result has tasks named `easy` and
    /// `hard`.
    fn of(results: &[TrialResult]) -> Option<Self> {
        let ids: Vec<(usize, usize)> = results
            .iter()
            .map(|r| Some((r.task_id("easy")?, r.task_id("hard")?)))
            .collect::<Option<_>>()?;
        let n = results.len() as f64;
        let mean = |f: &dyn Fn(&TrialResult, usize, usize) -> f64| {
            results
                .iter()
                .zip(&ids)
                .map(|(r, &(e, h))| f(r, e, h))
                .sum::<f64>()
                / n
        };
        Some(Self {
            rounds: mean(&|r, _, _| r.rounds.len() as f64),
            easy: mean(&|r, e, _| f64::from(r.rescued[e])),
            hard: mean(&|r, _, h| f64::from(r.rescued[h])),
            energy_easy: mean(&|r, e, _| r.energy_spent_pct[e]),
            energy_hard: mean(&|r, _, h| r.energy_spent_pct[h]),
            hp_easy: mean(&|r, e, _| r.hp_lost_pct[e]),
            hp_hard: mean(&|r, _, h| r.hp_lost_pct[h]),
        })
    }
}

/// Whether a scenario with these task names has the statistics: tasks named `easy` and
/// `hard` (without them every statistic is NaN and the reports say so in one sentence).
pub fn applies_to(tasks: &[String]) -> bool {
    ["easy", "hard"]
        .iter()
        .all(|name| tasks.iter().any(|t| t == name))
}

/// `statistic` pooled over `results` (every trial weighs the same, whatever its method). NaN
/// for no results or results without tasks named `easy` and `hard`; a ratio with a zero
/// denominator is infinite or NaN, as IEEE division gives.
pub fn pooled(statistic: Statistic, results: &[TrialResult]) -> f64 {
    let Some(m) = Means::of(results).filter(|_| !results.is_empty()) else {
        return f64::NAN;
    };
    match statistic {
        Statistic::RoundsPerTrial => m.rounds,
        Statistic::EasyOverHardRescuees => m.easy / m.hard,
        Statistic::TotalRescuees => m.easy + m.hard,
        Statistic::EasyRescueesPerRound => m.easy / m.rounds,
        Statistic::HardRescueesPerRound => m.hard / m.rounds,
        Statistic::HardHpOverEnergy => m.hp_hard / m.energy_hard,
        Statistic::EasyHpOverEnergy => m.hp_easy / m.energy_easy,
        Statistic::HardOverEasyEnergy => m.energy_hard / m.energy_easy,
        Statistic::HardOverEasyHp => m.hp_hard / m.hp_easy,
    }
}

/// Every target with our pooled value, in [`TARGETS`] order.
pub fn check(results: &[TrialResult]) -> Vec<(Target, f64)> {
    TARGETS
        .iter()
        .map(|t| (*t, pooled(t.statistic, results)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trial(rounds: usize, easy: u32, hard: u32, e: (f64, f64), hp: (f64, f64)) -> TrialResult {
        // Tasks listed hard first, as in paper.ron.
        TrialResult {
            scenario: "t".into(),
            method: "M".into(),
            trial: 0,
            seed: 0,
            duration_s: 600.0,
            tasks: vec!["hard".into(), "easy".into()],
            rescued: vec![hard, easy],
            energy_spent_pct: vec![e.1, e.0],
            hp_lost_pct: vec![hp.1, hp.0],
            rounds: vec![
                usar_sim::mission::RoundRecord {
                    start_s: 0.0,
                    end_s: 1.0,
                    completed: true,
                    groups: vec![vec![], vec![]],
                    rescued: vec![0, 0],
                };
                rounds
            ],
            robots: vec![],
        }
    }

    #[test]
    fn statistics_are_ratios_of_pooled_means() {
        let r = [
            trial(6, 90, 60, (400.0, 500.0), (40.0, 300.0)),
            trial(4, 70, 40, (300.0, 400.0), (20.0, 200.0)),
        ];
        let close = |s, x: f64| (pooled(s, &r) - x).abs() < 1e-12;
        assert!(close(Statistic::RoundsPerTrial, 5.0));
        assert!(close(Statistic::EasyOverHardRescuees, 80.0 / 50.0));
        assert!(close(Statistic::TotalRescuees, 130.0));
        assert!(close(Statistic::EasyRescueesPerRound, 16.0));
        assert!(close(Statistic::HardRescueesPerRound, 10.0));
        assert!(close(Statistic::HardHpOverEnergy, 250.0 / 450.0));
        assert!(close(Statistic::EasyHpOverEnergy, 30.0 / 350.0));
        assert!(close(Statistic::HardOverEasyEnergy, 450.0 / 350.0));
        assert!(close(Statistic::HardOverEasyHp, 250.0 / 30.0));
        assert!(pooled(Statistic::TotalRescuees, &[]).is_nan());
        let mut other = r[0].clone();
        other.tasks = vec!["a".into(), "b".into()];
        assert!(pooled(Statistic::TotalRescuees, &[other]).is_nan());
        assert!(TARGETS[0].holds(6.8) && !TARGETS[0].holds(6.81));
    }
}
