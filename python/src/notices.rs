//! The libraries' warnings as Python warnings: a process-wide `tracing` subscriber
//! ([`usar_sweep::notice`]) collects each warning the libraries emit, on whichever thread
//! (rayon workers run without the GIL), and [`flush`] gives them to Python as
//! `warnings.warn(message, usar.UsarWarning)` when a call returns to Python. Progress lines
//! (`tracing::info!`) are dropped: the package reports progress through `progress=`.

use std::ffi::CString;
use std::sync::{Mutex, PoisonError};

use pyo3::prelude::*;

use crate::errors::UsarWarning;

/// Warnings emitted and not yet given to Python, oldest first.
static PENDING: Mutex<Vec<String>> = Mutex::new(Vec::new());

/// Installs the collecting subscriber; once per process (a second call, e.g. when the
/// module is loaded again, keeps the first).
pub fn install() {
    let installed = usar_sweep::notice::install(|level, message| {
        if level <= usar_sweep::notice::Level::WARN {
            let mut pending = PENDING.lock().unwrap_or_else(PoisonError::into_inner);
            pending.push(message.to_string());
        }
    });
    // Installed already: by this module, loaded before, and the collector is the same.
    drop(installed);
}

/// Gives every pending warning to Python, oldest first, as a `usar.UsarWarning`.
///
/// # Errors
/// The exception a warning filter makes of one (`-W error`); the warnings after it are
/// dropped.
pub fn flush(py: Python<'_>) -> PyResult<()> {
    let pending = std::mem::take(&mut *PENDING.lock().unwrap_or_else(PoisonError::into_inner));
    if pending.is_empty() {
        return Ok(());
    }
    let category = py.get_type::<UsarWarning>();
    let stacklevel = user_stacklevel(py);
    for message in pending {
        let text = CString::new(message.replace('\0', " "))?;
        PyErr::warn(py, category.as_any(), &text, stacklevel)?;
    }
    Ok(())
}

/// The `stacklevel` of `warnings.warn` that names the caller's own line: 1 (the Python frame
/// that called into the native module) plus each frame of the `usar` package above it, so a
/// warning of `usar.sweep(...)` points at the line of the notebook or script that called it.
/// 1 when the frames cannot be read.
fn user_stacklevel(py: Python<'_>) -> i32 {
    let walk = || -> PyResult<i32> {
        let file: String = py.import("usar")?.getattr("__file__")?.extract()?;
        let package = std::path::Path::new(&file)
            .parent()
            .map(|p| format!("{}{}", p.to_string_lossy(), std::path::MAIN_SEPARATOR))
            .unwrap_or_default();
        let mut frame = py.import("sys")?.call_method1("_getframe", (0,))?;
        let mut level = 1;
        loop {
            let code_file: String = frame.getattr("f_code")?.getattr("co_filename")?.extract()?;
            let back = frame.getattr("f_back")?;
            if package.is_empty() || !code_file.starts_with(&package) || back.is_none() {
                return Ok(level);
            }
            frame = back;
            level += 1;
        }
    };
    walk().unwrap_or(1)
}

/// `result`, after the pending warnings are given to Python: a library call's end. An error
/// of `result` wins over one of [`flush`].
///
/// # Errors
/// `result`'s error, else [`flush`]'s.
pub fn flushed<T>(py: Python<'_>, result: PyResult<T>) -> PyResult<T> {
    let warned = flush(py);
    let value = result?;
    warned.map(|()| value)
}
