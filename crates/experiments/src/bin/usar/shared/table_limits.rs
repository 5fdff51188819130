//! How many robots and tasks `usar check` and `usar run` list one by one: beyond these bounds
//! they print summaries whose lines stay short (`--robots` and `--tasks` list every one).

/// Teams of at most this many robots get the per-robot table (`usar check`, `usar run`) and the
/// groups' robot ids (`usar run`); larger ones a summary per kind (counts, start extent,
/// distance ranges, final levels) and group sizes, unless `--robots`.
pub const ROBOTS_TABLE_MAX: usize = 50;

/// Scenarios of at most this many tasks get a line per task and a column per task: quotas and
/// distances in `usar check`'s summary, rescuees per round in `usar run`'s rounds table; more
/// get a summary of the tasks (counts, ranges, the first and last few), unless `--tasks`.
pub const TASKS_TABLE_MAX: usize = 12;
