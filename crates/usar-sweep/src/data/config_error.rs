//! [`ConfigError`]: why a sweep's plan ([`SweepConfig`](crate::data::config::SweepConfig)) is
//! refused before it runs, in the library's terms: each error names the field of the plan it
//! is about, and a front end names that field in its own words (`usar` a flag, the Python
//! package a keyword argument).

/// A field of a sweep's plan that a [`ConfigError`] is about, named as the field of
/// [`SweepConfig`](crate::data::config::SweepConfig) it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ConfigField {
    /// `trials`: trials per method and cell.
    Trials,
    /// `methods`: the grouping methods.
    Methods,
    /// `threads`: worker threads.
    Threads,
    /// `duration_s`: the trial length, seconds.
    DurationS,
    /// `grid`: the cells of the varied fields.
    Grid,
    /// `shard`: the part of the sweep this run is.
    Shard,
}

impl ConfigField {
    /// The field's name in [`SweepConfig`](crate::data::config::SweepConfig) (and the Python
    /// package's keyword argument): `trials`, `methods`, `threads`, `duration_s`, `vary` (the
    /// grid is given as `vary` values) or `shard`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Trials => "trials",
            Self::Methods => "methods",
            Self::Threads => "threads",
            Self::DurationS => "duration_s",
            Self::Grid => "vary",
            Self::Shard => "shard",
        }
    }
}

/// Why a sweep's plan is refused before any trial runs
/// ([`check_config`](crate::sweep::check_config),
/// [`check_trial_count`](crate::sweep::check_trial_count),
/// [`check_sweep_size`](crate::sweep::check_sweep_size)).
///
/// Its `Display` is one line that starts with the field's name ([`ConfigField::name`]), then
/// [`ConfigError::problem`]: `trials must be at least 1`. A front end that names fields
/// otherwise writes its own name, then the problem (`usar`: `--trials must be at least 1`).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ConfigError {
    /// No trial per method and cell (`trials == 0`).
    #[error("trials{}", self.problem())]
    NoTrials,
    /// No worker thread (`threads == 0`).
    #[error("threads{}", self.problem())]
    NoThreads,
    /// No grouping method.
    #[error("methods{}", self.problem())]
    NoMethods,
    /// A grouping method listed twice (the same after normalising its name); `methods` is the
    /// whole list as given.
    #[error("methods{}", self.problem())]
    MethodTwice {
        /// Every method of the plan, in order.
        methods: Vec<String>,
    },
    /// A grid cell whose tasks are not the scenario's.
    #[error("vary{}", self.problem())]
    CellTasks {
        /// The scenario's task names.
        scenario: Vec<String>,
        /// The cell's task names.
        cell: Vec<String>,
    },
    /// A trial length that is not a positive number of seconds of at most
    /// [`MAX_TRIAL_STEPS`](usar_sim::scenario::MAX_TRIAL_STEPS) steps; `reason` is
    /// [`trial_steps`](usar_sim::scenario::trial_steps)' message.
    #[error("duration_s{}", self.problem())]
    TrialLength {
        /// Why the length is refused.
        reason: String,
    },
    /// More trials than a sweep may hold
    /// ([`MAX_SWEEP_TRIALS`](crate::data::limits::MAX_SWEEP_TRIALS)): cells x methods x
    /// trials (saturating).
    #[error("{}", self.problem())]
    TooManyTrials {
        /// Grid cells (1 without a grid).
        cells: usize,
        /// Grouping methods.
        methods: usize,
        /// Trials per method and cell.
        trials: u32,
        /// Their product, saturating.
        total: usize,
        /// The most trials a sweep may hold.
        limit: usize,
    },
    /// This run is shard `index` of a split into more shards than the sweep has trials (a
    /// shard would have no work).
    #[error("shard{}", self.problem())]
    TooManyShards {
        /// The shard's index, from 0.
        index: usize,
        /// Shards in the split.
        shards: usize,
        /// Trials of the whole sweep.
        total: usize,
    },
}

impl ConfigError {
    /// The field the error is about; `None` for [`ConfigError::TooManyTrials`], which is about
    /// the product of several.
    pub fn field(&self) -> Option<ConfigField> {
        Some(match self {
            Self::NoTrials => ConfigField::Trials,
            Self::NoThreads => ConfigField::Threads,
            Self::NoMethods | Self::MethodTwice { .. } => ConfigField::Methods,
            Self::CellTasks { .. } => ConfigField::Grid,
            Self::TrialLength { .. } => ConfigField::DurationS,
            Self::TooManyShards { .. } => ConfigField::Shard,
            Self::TooManyTrials { .. } => return None,
        })
    }

    /// What is wrong, as the rest of the line after the field's name: it starts with a space
    /// or a colon (`" must be at least 1"`, `": the sweep has 4 trial(s), ..."`), or, without
    /// a field, is the whole line.
    pub fn problem(&self) -> String {
        match self {
            Self::NoTrials | Self::NoThreads => " must be at least 1".into(),
            Self::NoMethods => " needs at least one method".into(),
            Self::MethodTwice { methods } => {
                format!(" lists a method twice: {}", methods.join(","))
            }
            Self::CellTasks { scenario, cell } => format!(
                ": every cell must have the scenario's tasks ({}); a cell has {}",
                scenario.join(", "),
                cell.join(", ")
            ),
            Self::TrialLength { reason } => format!(": {reason}"),
            Self::TooManyTrials {
                cells,
                methods,
                trials,
                total,
                limit,
            } => format!(
                "the sweep's {cells} cell(s) x {methods} method(s) x {trials} trials make \
                 {total} trials, more than the limit of {limit} per sweep"
            ),
            Self::TooManyShards {
                index,
                shards,
                total,
            } => format!(
                " {index}/{shards}: the sweep has {total} trial(s), so at most {total} shards \
                 have work; split it into at most {total}"
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_line_is_the_field_name_then_the_problem() {
        let cases = [
            (ConfigError::NoTrials, "trials must be at least 1"),
            (ConfigError::NoThreads, "threads must be at least 1"),
            (
                ConfigError::MethodTwice {
                    methods: vec!["rne".into(), "rne".into()],
                },
                "methods lists a method twice: rne,rne",
            ),
            (
                ConfigError::TrialLength {
                    reason: "too long".into(),
                },
                "duration_s: too long",
            ),
            (
                ConfigError::TooManyShards {
                    index: 0,
                    shards: 5,
                    total: 4,
                },
                "shard 0/5: the sweep has 4 trial(s), so at most 4 shards have work; split it \
                 into at most 4",
            ),
        ];
        for (e, line) in cases {
            assert_eq!(e.to_string(), line);
            let name = e.field().map_or("", ConfigField::name);
            assert_eq!(format!("{name}{}", e.problem()), line);
        }
        let big = ConfigError::TooManyTrials {
            cells: 2,
            methods: 4,
            trials: 200_000,
            total: 1_600_000,
            limit: 1_000_000,
        };
        assert_eq!(big.field(), None);
        assert!(
            big.to_string().starts_with("the sweep's 2 cell(s)"),
            "{big}"
        );
    }
}
