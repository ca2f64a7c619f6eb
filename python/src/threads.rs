//! Native work with the GIL released: the calling thread waits, running Python's signal
//! handlers (Ctrl-C) and the progress callback, and a batch runs on a pool of its own.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{mpsc, Mutex};
use std::time::Duration;

use close_core::budget::Deadline;
use pyo3::prelude::*;
use rayon::prelude::*;

use crate::errors::invalid;

/// How often a thread waiting for native work wakes to run Python's signal handlers (so
/// that Ctrl-C stops the work within a fraction of a second) and the progress callback.
const POLL: Duration = Duration::from_millis(50);

/// Run `job` on `pool` (rayon's global pool when None) while this thread waits with the GIL
/// released, waking every [`POLL`] and when the job ends to run Python's signal handlers
/// and report `progress` (the `done` counter, of `total`, to a callable `(done, total)`).
/// A signal handler that raises (Ctrl-C: `KeyboardInterrupt`), or a callback that does,
/// cancels `deadline`, which the job checks between items; this returns that exception once
/// the job has stopped, so no work of this call is left running.
pub(crate) fn wait_for<R: Send>(
    py: Python<'_>,
    pool: Option<&rayon::ThreadPool>,
    deadline: &Deadline,
    progress: Option<(&AtomicUsize, usize, Py<PyAny>)>,
    job: impl FnOnce() -> R + Send,
) -> PyResult<R> {
    py.detach(|| {
        let (ended, end) = mpsc::channel::<()>();
        let result = Mutex::new(None);
        let result_slot = &result;
        let task = move || {
            let r = job();
            *result_slot.lock().unwrap_or_else(|e| e.into_inner()) = Some(r);
            drop(ended);
        };
        let watched = match pool {
            Some(pool) => pool.in_place_scope(|scope| {
                scope.spawn(|_| task());
                supervise(&end, deadline, progress.as_ref())
            }),
            None => rayon::in_place_scope(|scope| {
                scope.spawn(|_| task());
                supervise(&end, deadline, progress.as_ref())
            }),
        };
        watched?;
        result
            .into_inner()
            .unwrap_or_else(|e| e.into_inner())
            .ok_or_else(|| invalid("the work ended without an answer".into()))
    })
}

/// The waiting of [`wait_for`]: until `end` says the job ended, every [`POLL`] run the
/// signal handlers and report progress, with the GIL held only for that.
pub(crate) fn supervise(
    end: &mpsc::Receiver<()>,
    deadline: &Deadline,
    progress: Option<&(&AtomicUsize, usize, Py<PyAny>)>,
) -> PyResult<()> {
    let mut reported = None;
    loop {
        // Disconnected: the job ended (or panicked: the scope passes the panic on).
        let finished = !matches!(end.recv_timeout(POLL), Err(mpsc::RecvTimeoutError::Timeout));
        let checked = Python::attach(|py| -> PyResult<()> {
            py.check_signals()?;
            if let Some((done, total, callback)) = progress {
                let now = done.load(Ordering::Relaxed);
                if reported != Some(now) {
                    callback.call1(py, (now, *total))?;
                    reported = Some(now);
                }
            }
            Ok(())
        });
        if let Err(e) = checked {
            deadline.cancel();
            return Err(e);
        }
        if finished {
            return Ok(());
        }
    }
}

/// `work(k, deadline)` for every k < `total` on `threads` native threads (None: one per
/// core) in a pool of this call's own, whose threads have exited when it returns, under
/// [`wait_for`]: Ctrl-C stops the batch between items (and inside an analysis, at its
/// deadline checks) with `KeyboardInterrupt`; `progress` is called with (items done, total).
pub(crate) fn run_batch<T: Send>(
    py: Python<'_>,
    threads: Option<usize>,
    total: usize,
    progress: Option<&Bound<'_, PyAny>>,
    work: impl Fn(usize, &Deadline) -> T + Sync,
) -> PyResult<Vec<T>> {
    let deadline = Deadline::default();
    let done = AtomicUsize::new(0);
    let progress = progress.map(|p| (&done, total, p.clone().unbind()));
    let batch = || -> Vec<Option<T>> {
        (0..total)
            .into_par_iter()
            .map(|k| {
                if deadline.expired() {
                    return None;
                }
                let out = work(k, &deadline);
                done.fetch_add(1, Ordering::Relaxed);
                Some(out)
            })
            .collect()
    };
    // The pool's threads, joined (not only told to stop) before this returns.
    let handles = Mutex::new(Vec::new());
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .spawn_handler(|thread| {
            let handle = std::thread::Builder::new()
                .name(format!("close-{}", thread.index()))
                .spawn(move || thread.run())?;
            handles.lock().unwrap_or_else(|e| e.into_inner()).push(handle);
            Ok(())
        })
        .build()
        .map_err(|e| invalid(format!("could not start threads: {e}")))?;
    let results = wait_for(py, Some(&pool), &deadline, progress, batch);
    drop(pool);
    let handles = handles.into_inner().unwrap_or_else(|e| e.into_inner());
    py.detach(|| handles.into_iter().for_each(|h| drop(h.join())));
    results?
        .into_iter()
        .collect::<Option<Vec<T>>>()
        .ok_or_else(|| invalid("the batch was cancelled".into()))
}

/// The number of threads asked for: None (one per core) or at least 1.
pub(crate) fn thread_count(threads: Option<i64>) -> PyResult<Option<usize>> {
    match threads {
        None => Ok(None),
        Some(t) if t >= 1 => Ok(Some(usize::try_from(t).unwrap_or(usize::MAX))),
        Some(t) => {
            Err(invalid(format!("threads must be at least 1 (or None: one per core), not {t}")))
        }
    }
}
