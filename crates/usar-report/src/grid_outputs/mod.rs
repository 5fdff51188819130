//! The files at the top of a grid's output folder, rendered from the sweep's analysis:
//! [`grid_csv`] (`grid.csv`), [`grid_figures`] (one `grid_<metric>.svg` per chosen metric) and
//! [`grid_md`] (`grid.md`).

pub mod grid_csv;
pub mod grid_figures;
pub mod grid_md;
