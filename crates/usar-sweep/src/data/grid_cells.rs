//! The cells of a parameter grid ([`Grid`]): each the base scenario with one value of each
//! varied field, and the name of its folder. [`crate::grid`] builds and validates them from
//! the `--vary` arguments.

use usar_sim::scenario::{Scenario, ScenarioSpec};

use crate::vary::{Override, Vary};

/// The cells of a parameter sweep.
#[derive(Debug, Clone)]
pub struct Grid {
    /// The parsed `--vary` arguments, in order.
    pub varies: Vec<Vary>,
    /// The cells, first `--vary` varying slowest.
    pub cells: Vec<GridCell>,
}

/// One cell: the base scenario with one value of each varied field.
#[derive(Debug, Clone)]
pub struct GridCell {
    /// Index in [`Grid::cells`].
    pub index: usize,
    /// The overrides that make this cell, one per `--vary`, in `--vary` order.
    pub overrides: Vec<Override>,
    /// The cell's scenario spec (what its `scenario.ron` holds).
    pub spec: ScenarioSpec,
    /// The cell's validated scenario.
    pub scenario: Scenario,
    /// Name of the cell's folder under the output folder (see [`crate::grid::names::cell_dir`]).
    pub dir: String,
}

impl GridCell {
    /// The value of each varied field as written, in `--vary` order.
    pub fn values(&self) -> Vec<String> {
        self.overrides
            .iter()
            .map(|o| o.value.text.clone())
            .collect()
    }
}

impl Grid {
    /// The varied field paths, in `--vary` order.
    pub fn fields(&self) -> Vec<String> {
        self.varies.iter().map(|v| v.path.to_string()).collect()
    }
}
