//! The vocabulary of calibration targets, below everything that reads them: a target names a
//! statistic of a set of trials ([`Statistic`], over metrics named by [`MetricRef`]), the value
//! it should have and the [`Band`] it must fall in ([`Target`]); a targets file holds them
//! ([`Targets`], read through [`ron_file`]). A sweep's reports compare with them
//! (`crate::calibration`), `usar_study::calibrate` fits free fields to them and
//! `usar_study::multiverse` calibrates each universe against them.

pub mod band;
pub mod file;
pub mod float_text;
pub mod metric_ref;
pub mod ron_file;
pub mod statistic;

pub use band::Band;
pub use file::{Target, Targets, TargetsError};
pub use metric_ref::MetricRef;
pub use statistic::Statistic;
