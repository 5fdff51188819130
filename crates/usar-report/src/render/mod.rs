//! Top-down SVG picture of a scenario, optionally with the paths robots took (`usar render`).
//!
//! [`picture`] assembles the whole picture (and the bare map the replay draws over) from its
//! parts: the [`layout`] of the field, the [`map`] of what does not move, the [`robots`] and
//! their paths, the [`legend`], the robots' [`paths`] sampled during a trial, drawn on the [`canvas`] with the shapes of [`shapes`] in the
//! colours of [`palette`].

pub mod canvas;
pub mod layout;
pub mod legend;
pub mod map;
pub mod palette;
pub mod paths;
pub mod picture;
pub mod robots;
pub mod shapes;

pub use palette::{RESCUEE_COLOR, kind_color, role_color, task_color, task_strong_color};
pub use paths::{PathRecorder, TRACE_SAMPLE_S};
pub use picture::{MapFrame, render_map_svg, render_svg, render_svg_string};
pub use robots::{MAX_LABELLED_ROBOTS, Trace};
