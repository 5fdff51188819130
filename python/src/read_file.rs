//! Reading a scenario file so that Ctrl-C works while the read waits (a slow or hung network
//! file system): the read runs on a thread of its own. A FIFO, which would wait for a writer,
//! is refused before it is opened (`usar_sim::scenario::read_bounded`).

use std::path::Path;
use std::sync::mpsc::{self, TryRecvError};

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use usar_sim::scenario as sc;

use crate::detached::POLL;
use crate::errors::value_error;

/// [`sc::read_source`] of `path` (the CLI's size bound and checks) on a thread of its own,
/// while the calling thread waits with the GIL released and checks for signals every
/// [`POLL`]. On Ctrl-C it returns `KeyboardInterrupt` at once (the reading thread ends when
/// its read does).
///
/// # Errors
/// `ValueError` for a file that cannot be read (the path named), the signal's exception, or
/// `RuntimeError` if the reading thread panicked.
pub fn read_source_interruptibly(py: Python<'_>, path: &Path) -> PyResult<String> {
    let (tx, rx) = mpsc::channel();
    let p = path.to_path_buf();
    std::thread::spawn(move || {
        let _ = tx.send(sc::read_source(&p));
    });
    loop {
        py.detach(|| std::thread::sleep(POLL));
        match rx.try_recv() {
            Ok(read) => return read.map_err(value_error),
            Err(TryRecvError::Empty) => {}
            Err(TryRecvError::Disconnected) => {
                return Err(PyRuntimeError::new_err(
                    "the thread reading the scenario panicked (a bug: please report it)",
                ));
            }
        }
        py.check_signals()?;
    }
}
