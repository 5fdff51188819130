//! The files at the top of a grid's output folder, rendered from the sweep's analysis:
//! [`csv`] (`grid.csv`), [`figures`] (one `grid_<metric>.svg` per chosen metric) and
//! [`report`] (`grid.md`).

pub mod csv;
pub mod figures;
pub mod report;
