//! What the `usar` commands share, so that no command imports another: the arguments of a
//! sweep and of a multiverse, building a trial, the error line, where a scenario sets a field,
//! the scenario warnings, the short summary of a scenario of many tasks and how `usar check`
//! writes numbers, a targets or claims file checked against the scenario's tasks, the
//! per-round yields' file, the table limits of `check` and `run`, the progress bars and the
//! hidden test hooks.

pub mod check_many_tasks;
pub mod check_numbers;
pub mod error_text;
pub mod flag_tasks;
pub mod multiverse_spec;
pub mod optimizer_arg;
pub mod out_flag;
pub mod progress;
pub mod rounds_csv;
pub mod scenario_field;
pub mod scenario_warnings;
pub mod stderr_lines;
pub mod sweep_spec;
pub mod table_limits;
pub mod test_hooks;
pub mod trial_build;
