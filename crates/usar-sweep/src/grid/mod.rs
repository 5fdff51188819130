//! A parameter grid: `usar sweep --vary FIELD=V1,V2,... [--vary ...]` runs the sweep once per
//! cell of the Cartesian product of the value lists (the first `--vary` varying slowest).
//!
//! [`build_grid`] makes and validates every cell before anything runs: each cell is the base
//! scenario spec with the cell's values set ([`crate::vary`]), validated exactly as a scenario
//! file is; [`names`] makes the cell folders' names. The grid's own files are written by
//! `usar_report::grid_outputs`.

pub mod build;
pub mod error;
pub mod names;

pub use crate::data::grid_cells::{Grid, GridCell};
pub use build::{build_grid, cell_count};
pub use error::GridError;
