//! The package's exceptions, and the library's errors as them: a job's error carries the very
//! message the command line prints after `error:` ([`fitjob::chain`]), and a usage error (an
//! unknown name, a value out of its range, a bad array) is a `ValueError` as well, so
//! `except ValueError` catches what the command line would exit 2 for.

use pyo3::exceptions::{PyException, PyValueError};
use pyo3::PyErr;

pyo3::create_exception!(
    triwb,
    WorkbenchError,
    PyException,
    "A job of the workbench failed (an unreadable file, a mesh that cannot be fitted, an output \
     that could not be written); the message is the one the command line prints."
);

pyo3::create_exception!(
    triwb,
    UsageError,
    PyValueError,
    "An argument is wrong whatever the input: an unknown name, a value outside its range, an \
     array of the wrong shape, type or content (the command line exits 2 for these)."
);

/// A fit job's error as the exception the command line's exit status stands for.
pub fn job_error(e: fitjob::JobError) -> PyErr {
    let message = fitjob::chain(&e);
    if e.is_usage() {
        UsageError::new_err(message)
    } else {
        WorkbenchError::new_err(message)
    }
}

/// A usage error with `message`.
pub fn usage(message: impl Into<String>) -> PyErr {
    UsageError::new_err(message.into())
}

/// A run error with `message`.
pub fn failed(message: impl Into<String>) -> PyErr {
    WorkbenchError::new_err(message.into())
}
