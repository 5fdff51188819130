//! The integration tests of `experiments`, one test binary (each file a module: linking the
//! workspace and Rapier once, not once per file): the `usar` command line run as a process
//! (`env!("CARGO_BIN_EXE_usar")`) and the sweeps it is built on, with the helpers they share
//! in `common`. (The studies' libraries are tested in `usar-study`.) The long checks are
//! `#[ignore]`d with their reason (`cargo test --release -p experiments --test integration --
//! --ignored`; CI runs them in release).

mod calibrate_cli;
mod check_cli;
mod check_many_tasks;
mod claims_files;
mod common;
mod hostile_folders;
mod json_schema;
mod long_names;
mod multiverse_cli;
mod output_owners;
mod output_paths;
mod render_cli;
mod replay_browser;
mod replay_cli;
mod report_sections;
mod run_cli;
mod shard_commands;
mod shard_merge;
mod shard_mixing;
mod slurm_cli;
mod study_inputs;
mod sweep_custom;
mod sweep_failure;
mod sweep_grid;
mod sweep_grid_resume;
mod sweep_journal_checks;
mod sweep_limits;
mod sweep_lock;
mod sweep_resume;
mod sweep_threads;
mod tasks_cli;
mod trust_cli;
mod usage_errors;
