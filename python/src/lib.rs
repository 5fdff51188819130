//! `usar._usar`: the native module of the Python package `usar` (PyO3). It wraps the library
//! crates (rne-core, usar-sim, usar-sweep, usar-report, usar-study) and nothing else: the
//! Python API, its docstrings and its argument checks for Python types live in `python/usar/`
//! (see docs/python.md).
//!
//! - [`scenario`]: `Scenario` (load, from_ron, set, to_ron, check);
//! - [`run`]: one trial, as `usar run --json` writes it;
//! - [`sweep`]: a sweep in memory or into a folder, as `usar sweep` runs it;
//! - [`py_method`]: a grouping method written in Python, called once per round;
//! - [`core_fns`]: RNE trust, the built-in grouping methods and a trial's seed as functions;
//! - [`episode`]: `usar.gym`'s episode trial recording its paths, and its picture from them;
//! - [`detached`]: running work with the GIL released while watching for Ctrl-C;
//! - [`read_file`]: reading a scenario file so that Ctrl-C works while it waits;
//! - [`errors`]: the exception types and the conversion of library errors;
//! - [`notices`]: the libraries' warnings as `usar.UsarWarning`s.

use pyo3::prelude::*;

pub mod check_data;
pub mod core_fns;
pub mod detached;
pub mod episode;
pub mod errors;
pub mod json_value;
pub mod methods;
pub mod notices;
pub mod pictures;
pub mod py_method;
pub mod raster;
pub mod read_file;
pub mod ron_value;
pub mod run;
pub mod scenario;
pub mod studies;
pub mod sweep;
pub mod verdicts;

/// The native module `usar._usar`.
#[pymodule]
fn _usar(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_class::<scenario::Scenario>()?;
    m.add("GroupingError", py.get_type::<errors::GroupingError>())?;
    m.add("TrialError", py.get_type::<errors::TrialError>())?;
    m.add("ScenarioWarning", py.get_type::<errors::ScenarioWarning>())?;
    m.add("UsarWarning", py.get_type::<errors::UsarWarning>())?;
    notices::install();
    // The libraries' messages name a setting by its keyword argument (`pass overwrite=True`).
    if usar_sweep::settings::set_namer(errors::keyword).is_err() {
        // Installed already, by an earlier load of this module: the same namer.
    }
    m.add_function(wrap_pyfunction!(run::run_trial, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::run_sweep, m)?)?;
    m.add_function(wrap_pyfunction!(pictures::render, m)?)?;
    m.add_function(wrap_pyfunction!(studies::run_calibration, m)?)?;
    m.add_function(wrap_pyfunction!(studies::run_multiverse_py, m)?)?;
    m.add_function(wrap_pyfunction!(pictures::replay, m)?)?;
    m.add_function(wrap_pyfunction!(raster::rasterize_svg, m)?)?;
    m.add_class::<episode::PathLog>()?;
    m.add_function(wrap_pyfunction!(episode::run_trial_logged, m)?)?;
    m.add_function(wrap_pyfunction!(episode::episode_svg, m)?)?;
    m.add_function(wrap_pyfunction!(core_fns::trust, m)?)?;
    m.add_function(wrap_pyfunction!(core_fns::builtin_group, m)?)?;
    m.add_function(wrap_pyfunction!(core_fns::trial_seed, m)?)?;
    m.add_function(wrap_pyfunction!(verdicts::claim_verdicts, m)?)?;
    m.add_function(wrap_pyfunction!(verdicts::compare_values, m)?)?;
    m.add("METHOD_NAMES", rne_core::grouping::METHOD_NAMES.to_vec())?;
    Ok(())
}
