//! The experiments' data, at the bottom: the sweep's plan and outcome types, its limits and
//! its output names, in one place that imports nothing above it.
//!
//! A sweep's plan is a [`config::SweepConfig`] (with its grid's cells, [`grid_cells`], its
//! extension points, [`hooks`], and its shard, [`shard_split`], [`shard_folders`] and
//! [`sweep_plan`]), refused before it runs with a [`config_error::ConfigError`] (a study's settings with a
//! [`setting_error::SettingError`]); its jobs are [`jobs`]; what it produced is an [`outcome::SweepOutcome`].
//! A merge of shards is refused with a [`merge_error::MergeError`]. [`limits`] bounds a sweep; [`owner`] says which kind of run an output folder belongs to;
//! [`out_dir`], [`figure_list`], [`trial_length`] and [`software`] name and describe what it
//! writes. The modules above (design, run) and the `experiments` crate (analyse, write) build,
//! run, judge and write this data.

pub mod config;
pub mod config_error;
pub mod figure_list;
pub mod grid_cells;
pub mod hooks;
pub mod jobs;
pub mod limits;
pub mod merge_error;
pub mod out_dir;
pub mod outcome;
pub mod owner;
pub mod setting_error;
pub mod shard_folders;
pub mod shard_split;
pub mod software;
pub mod sweep_plan;
pub mod trial_length;
