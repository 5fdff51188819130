//! The metrics of a trial, typed once: every numeric column of `trials.csv`, for any number of
//! tasks. A [`Metric`] is a [`Quantity`] (rescuees, energy cost, ...) over a [`Scope`] (one
//! task, or all of them); its column name, label and value all come from here, so claims,
//! figures and command-line options cannot name a metric that does not exist (an unknown name
//! is an error where it is parsed, [`Metric::parse`]).

use serde::Serialize;
use usar_sim::mission::{TrialResult, per};

/// Which tasks a per-task quantity covers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Scope {
    /// The task with this id (its index in the scenario's task list).
    Task(usize),
    /// All tasks together.
    Total,
}

/// What a metric measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Quantity {
    /// Rescuees delivered.
    Rescued,
    /// Energy spent by robots while in the task's group, percent points summed over robots.
    Energy,
    /// HP lost by robots while in the task's group, percent points summed over robots.
    Hp,
    /// Energy per rescuee, percent points (undefined without rescuees).
    EnergyPerRescuee,
    /// HP per rescuee, percent points (undefined without rescuees).
    HpPerRescuee,
    /// Rounds started (the last one possibly cut by the time limit); per trial, no scope.
    Rounds,
    /// Mean length of the completed rounds, seconds (undefined if none completed); per trial,
    /// no scope.
    MeanRound,
}

impl Quantity {
    /// Whether the quantity can never be negative, so that its confidence intervals stop at 0
    /// (`usar_report::stats::Summary::of_non_negative`). Every quantity
    /// measured now is a count, a cost or a length of time; a new quantity must say.
    pub fn is_non_negative(self) -> bool {
        match self {
            Quantity::Rescued
            | Quantity::Energy
            | Quantity::Hp
            | Quantity::EnergyPerRescuee
            | Quantity::HpPerRescuee
            | Quantity::Rounds
            | Quantity::MeanRound => true,
        }
    }
}

/// One metric of a trial: a quantity over a scope. The quantities measured per trial
/// ([`Quantity::Rounds`], [`Quantity::MeanRound`]) have scope [`Scope::Total`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Metric {
    /// What it measures.
    pub quantity: Quantity,
    /// Over which tasks.
    pub scope: Scope,
}

/// One value of a `trials.csv` row, serialised as the column's type (an integer count, a
/// float, or an empty cell for an undefined float).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Cell {
    /// A count.
    Count(u32),
    /// A number.
    Number(f64),
    /// A number that may be undefined (empty cell).
    Maybe(Option<f64>),
}

impl Cell {
    /// The value as a number, `None` for an undefined one.
    pub fn value(self) -> Option<f64> {
        match self {
            Cell::Count(n) => Some(f64::from(n)),
            Cell::Number(x) => Some(x),
            Cell::Maybe(x) => x,
        }
    }
}

impl Quantity {
    fn per_task(self) -> bool {
        !matches!(self, Quantity::Rounds | Quantity::MeanRound)
    }
}

impl Metric {
    /// A quantity over `scope`.
    pub const fn new(quantity: Quantity, scope: Scope) -> Self {
        Self { quantity, scope }
    }

    /// Every metric of a trial with `k` tasks, in `trials.csv` column order: rescuees (total,
    /// then per task), energy (per task, then total), HP (likewise), rounds, energy and HP per
    /// rescuee (per task, then total), mean round time.
    pub fn all(k: usize) -> Vec<Metric> {
        let tasks = || (0..k).map(Scope::Task);
        let mut out = vec![Metric::new(Quantity::Rescued, Scope::Total)];
        out.extend(tasks().map(|s| Metric::new(Quantity::Rescued, s)));
        for q in [Quantity::Energy, Quantity::Hp] {
            out.extend(tasks().map(|s| Metric::new(q, s)));
            out.push(Metric::new(q, Scope::Total));
        }
        out.push(Metric::new(Quantity::Rounds, Scope::Total));
        for q in [Quantity::EnergyPerRescuee, Quantity::HpPerRescuee] {
            out.extend(tasks().map(|s| Metric::new(q, s)));
            out.push(Metric::new(q, Scope::Total));
        }
        out.push(Metric::new(Quantity::MeanRound, Scope::Total));
        out
    }

    /// Column name in `trials.csv` (and `metric` value of `summary.csv` and `grid.csv`) for a
    /// trial with tasks `tasks`, e.g. `rescued_hard`, `energy_total_pct`,
    /// `hp_per_easy_rescuee_pct`, `hp_per_rescuee_pct`, `rounds`.
    ///
    /// # Panics
    /// If the scope names a task id not in `tasks` (a programming error).
    pub fn name(&self, tasks: &[String]) -> String {
        let task = |t: usize| tasks[t].as_str();
        match (self.quantity, self.scope) {
            (Quantity::Rescued, Scope::Total) => "rescued_total".into(),
            (Quantity::Rescued, Scope::Task(t)) => format!("rescued_{}", task(t)),
            (Quantity::Energy, Scope::Total) => "energy_total_pct".into(),
            (Quantity::Energy, Scope::Task(t)) => format!("energy_{}_pct", task(t)),
            (Quantity::Hp, Scope::Total) => "hp_total_pct".into(),
            (Quantity::Hp, Scope::Task(t)) => format!("hp_{}_pct", task(t)),
            (Quantity::EnergyPerRescuee, Scope::Total) => "energy_per_rescuee_pct".into(),
            (Quantity::EnergyPerRescuee, Scope::Task(t)) => {
                format!("energy_per_{}_rescuee_pct", task(t))
            }
            (Quantity::HpPerRescuee, Scope::Total) => "hp_per_rescuee_pct".into(),
            (Quantity::HpPerRescuee, Scope::Task(t)) => format!("hp_per_{}_rescuee_pct", task(t)),
            (Quantity::Rounds, _) => "rounds".into(),
            (Quantity::MeanRound, _) => "mean_round_s".into(),
        }
    }

    /// The quantity's name without the task, for long-form tables (`trials_long.csv`):
    /// `rescued`, `energy_pct`, `hp_pct`, `energy_per_rescuee_pct`, `hp_per_rescuee_pct`,
    /// `rounds`, `mean_round_s`.
    pub fn quantity_name(&self) -> &'static str {
        match self.quantity {
            Quantity::Rescued => "rescued",
            Quantity::Energy => "energy_pct",
            Quantity::Hp => "hp_pct",
            Quantity::EnergyPerRescuee => "energy_per_rescuee_pct",
            Quantity::HpPerRescuee => "hp_per_rescuee_pct",
            Quantity::Rounds => "rounds",
            Quantity::MeanRound => "mean_round_s",
        }
    }

    /// The task column of long-form tables: the task's name, `total`, or empty for the
    /// per-trial quantities.
    ///
    /// # Panics
    /// As [`Metric::name`].
    pub fn task_name<'a>(&self, tasks: &'a [String]) -> &'a str {
        match self.scope {
            _ if !self.quantity.per_task() => "",
            Scope::Total => "total",
            Scope::Task(t) => &tasks[t],
        }
    }

    /// Label for tables and figures, e.g. `rescuees, hard`, `energy / rescuee (%)`.
    ///
    /// # Panics
    /// As [`Metric::name`].
    pub fn label(&self, tasks: &[String]) -> String {
        let scope = match self.scope {
            Scope::Total => "total",
            Scope::Task(t) => &tasks[t],
        };
        match (self.quantity, self.scope) {
            (Quantity::Rescued, _) => format!("rescuees, {scope}"),
            (Quantity::Energy, _) => format!("energy cost {scope} (%)"),
            (Quantity::Hp, _) => format!("HP cost {scope} (%)"),
            (Quantity::EnergyPerRescuee, Scope::Total) => "energy / rescuee (%)".into(),
            (Quantity::EnergyPerRescuee, _) => format!("energy / {scope} rescuee (%)"),
            (Quantity::HpPerRescuee, Scope::Total) => "HP / rescuee (%)".into(),
            (Quantity::HpPerRescuee, _) => format!("HP / {scope} rescuee (%)"),
            (Quantity::Rounds, _) => "rounds".into(),
            (Quantity::MeanRound, _) => "mean round time (s)".into(),
        }
    }

    /// The metric of `r` as a typed CSV cell.
    ///
    /// # Panics
    /// If the scope names a task id `r` does not have (a programming error).
    pub fn cell(&self, r: &TrialResult) -> Cell {
        let task_or_total = |per_task: &dyn Fn(usize) -> f64, total: f64| match self.scope {
            Scope::Task(t) => per_task(t),
            Scope::Total => total,
        };
        match self.quantity {
            Quantity::Rescued => Cell::Count(match self.scope {
                Scope::Task(t) => r.rescued[t],
                Scope::Total => r.rescued_total(),
            }),
            Quantity::Energy => Cell::Number(task_or_total(
                &|t| r.energy_spent_pct[t],
                r.energy_total_pct(),
            )),
            Quantity::Hp => Cell::Number(task_or_total(&|t| r.hp_lost_pct[t], r.hp_total_pct())),
            Quantity::EnergyPerRescuee => Cell::Maybe(match self.scope {
                Scope::Task(t) => r.energy_per_rescuee(t),
                Scope::Total => per(r.energy_total_pct(), r.rescued_total()),
            }),
            Quantity::HpPerRescuee => Cell::Maybe(match self.scope {
                Scope::Task(t) => r.hp_per_rescuee(t),
                Scope::Total => per(r.hp_total_pct(), r.rescued_total()),
            }),
            Quantity::Rounds => Cell::Count(r.rounds.len() as u32),
            Quantity::MeanRound => Cell::Maybe(r.mean_round_s()),
        }
    }

    /// The metric's value for `r`; `None` when undefined (a cost per rescuee without rescuees,
    /// a mean round time without a completed round).
    ///
    /// # Panics
    /// As [`Metric::cell`].
    pub fn value(&self, r: &TrialResult) -> Option<f64> {
        self.cell(r).value()
    }

    /// The metric called `name` for tasks `tasks` (see [`Metric::name`]).
    pub fn parse(name: &str, tasks: &[String]) -> Option<Metric> {
        Metric::all(tasks.len())
            .into_iter()
            .find(|m| m.name(tasks) == name)
    }
}

/// The defined values of `metric` over the trials of `method` among `results`, in their order.
pub fn values_of(results: &[TrialResult], method: &str, metric: Metric) -> Vec<f64> {
    results
        .iter()
        .filter(|r| r.method == method)
        .filter_map(|r| metric.value(r))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tasks() -> Vec<String> {
        vec!["hard".into(), "easy".into()]
    }

    #[test]
    fn two_tasks_give_the_paper_sheet_columns() {
        let names: Vec<String> = Metric::all(2).iter().map(|m| m.name(&tasks())).collect();
        assert_eq!(
            names,
            [
                "rescued_total",
                "rescued_hard",
                "rescued_easy",
                "energy_hard_pct",
                "energy_easy_pct",
                "energy_total_pct",
                "hp_hard_pct",
                "hp_easy_pct",
                "hp_total_pct",
                "rounds",
                "energy_per_hard_rescuee_pct",
                "energy_per_easy_rescuee_pct",
                "energy_per_rescuee_pct",
                "hp_per_hard_rescuee_pct",
                "hp_per_easy_rescuee_pct",
                "hp_per_rescuee_pct",
                "mean_round_s",
            ]
        );
    }

    #[test]
    fn names_parse_back_and_unknown_ones_do_not() {
        let t = tasks();
        for m in Metric::all(2) {
            assert_eq!(Metric::parse(&m.name(&t), &t), Some(m));
        }
        assert_eq!(Metric::parse("rescued_medium", &t), None);
        assert_eq!(Metric::all(3).len(), 1 + 3 + 2 * 4 + 1 + 2 * 4 + 1);
        let three: Vec<String> = vec!["a".into(), "b".into(), "c".into()];
        assert_eq!(
            Metric::parse("hp_per_c_rescuee_pct", &three),
            Some(Metric::new(Quantity::HpPerRescuee, Scope::Task(2)))
        );
    }
}
