//! Running library work off the Python thread: the work runs on a thread of its own while the
//! calling thread waits with the GIL released (so Python grouping methods on the worker
//! threads can take it), waking every [`POLL`] to check for Ctrl-C (`PyErr_CheckSignals`)
//! and to report progress.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use pyo3::prelude::*;

/// How often the waiting thread wakes: Ctrl-C is seen within this, progress drawn as often.
pub const POLL: Duration = Duration::from_millis(25);

/// Runs `work` on a new thread and waits for it with the GIL released. Every [`POLL`] it
/// checks for signals and calls `tick` (with the GIL). On a signal's exception (Ctrl-C:
/// `KeyboardInterrupt`) it sets `stop`, waits for `work` to return (it must watch `stop`) and
/// returns that exception.
///
/// # Errors
/// The signal's exception, an error of `tick`, or a `RuntimeError` if `work` panicked.
pub fn run_detached<T: Send>(
    py: Python<'_>,
    stop: &Arc<AtomicBool>,
    work: impl FnOnce() -> T + Send,
    mut tick: impl FnMut(Python<'_>) -> PyResult<()>,
) -> PyResult<T> {
    std::thread::scope(|scope| {
        let handle = scope.spawn(work);
        let mut failure: Option<PyErr> = None;
        while !handle.is_finished() {
            py.detach(|| std::thread::sleep(POLL));
            if failure.is_some() {
                continue;
            }
            let checked = py.check_signals().and_then(|()| tick(py));
            if let Err(e) = checked {
                stop.store(true, Ordering::SeqCst);
                failure = Some(e);
            }
        }
        let joined = py.detach(|| handle.join());
        match (failure, joined) {
            (Some(e), _) => Err(e),
            (None, Ok(value)) => Ok(value),
            (None, Err(_)) => Err(pyo3::exceptions::PyRuntimeError::new_err(
                "the native worker thread panicked (a bug: please report it)",
            )),
        }
    })
}
