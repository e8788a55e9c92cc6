//! Where a call's parallel work runs. The library parallelizes inside a job (rayon: the
//! repair, the estimators, the G1 scan and the tessellation), on one pool shared by the whole
//! process. That is what one fit at a time wants; but rayon work started from two Python
//! threads queues on that one pool, so the two fits do not run side by side. A call given
//! `threads=n` runs on a pool of its own of `n` threads instead: two Python threads (or a
//! thread pool, or Dask's threaded workers) each fitting with `threads=1` run truly in
//! parallel, one core each.

use pyo3::prelude::*;

use crate::errors::{failed, usage};

/// The largest pool a call may ask for: 1024 threads. Each reserves its own stack, and no
/// machine this runs on has nearly that many cores; a typo (`threads=100000`) would otherwise
/// try to start them all.
pub const MAX_THREADS: usize = 1024;

/// Runs `work` without the GIL: on the process's shared pool when `threads` is None, else on a
/// pool of `threads` threads of its own (built for this call; a few tens of microseconds).
pub fn run<R: Send>(
    py: Python<'_>,
    threads: Option<usize>,
    work: impl FnOnce() -> R + Send,
) -> PyResult<R> {
    match threads {
        None => Ok(py.detach(work)),
        Some(0) => Err(usage(
            "threads must be at least 1 (None: the process's shared pool)",
        )),
        Some(n) if n > MAX_THREADS => Err(usage(format!(
            "threads={n}: at most {MAX_THREADS} (a pool of its own a call; None: the process's shared pool)"
        ))),
        Some(n) => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| failed(format!("no thread pool of {n} threads: {e}")))?;
            Ok(py.detach(|| pool.install(work)))
        }
    }
}
