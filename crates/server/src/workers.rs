//! A lane of CPU workers: a permit per worker, and each worker's own rayon pool.
//!
//! A job runs on the pool of the worker it got, so its parallel loops (dGLI rows, the fold
//! loss's rings) stay on that pool's threads: a light job on a one-thread pool never wakes
//! or waits for other threads, and a heavy job's loops never queue a light job's behind
//! theirs. The job is a rayon task, answered through a channel; a panic in it is caught and
//! becomes a 500, never an abort. Its permit and pool are given back when it ends.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};

use rayon::{ThreadPool, ThreadPoolBuilder};
use tokio::sync::Semaphore;

use crate::error::ApiError;
use close_core::budget::Deadline;

/// A poisoned lock only means a worker panicked mid-insert; the map itself is still valid.
pub(crate) fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// A pool that could not be built (no thread could be spawned) is `None`: its jobs run on
/// tokio's blocking threads and rayon's global pool instead.
type Pools = Arc<Mutex<Vec<Option<Arc<ThreadPool>>>>>;

pub struct Workers {
    permits: Arc<Semaphore>,
    /// The pools of the workers not busy now.
    idle_pools: Pools,
    count: usize,
    /// Jobs that stopped at a cancelled or expired deadline: what shows, without timing
    /// anything, that a dropped request's work really stopped.
    cancelled: Arc<AtomicUsize>,
    /// Jobs given to a worker so far: what shows which work runs off the async threads.
    started: AtomicUsize,
}

/// A worker's pool, given back to the idle ones when dropped.
struct Lease {
    pool: Option<Arc<ThreadPool>>,
    home: Pools,
}

impl Drop for Lease {
    fn drop(&mut self) {
        lock(&self.home).push(self.pool.take());
    }
}

impl Workers {
    /// `count` workers (at least one), each with a pool of `threads` threads.
    pub fn new(name: &'static str, count: usize, threads: usize) -> Workers {
        let count = count.max(1);
        let pools = (0..count)
            .map(|w| {
                let pool = ThreadPoolBuilder::new()
                    .num_threads(threads.max(1))
                    .thread_name(move |t| format!("close-{name}-{w}.{t}"))
                    .build();
                pool.ok().map(Arc::new)
            })
            .collect();
        Workers {
            permits: Arc::new(Semaphore::new(count)),
            idle_pools: Arc::new(Mutex::new(pools)),
            count,
            cancelled: Arc::default(),
            started: AtomicUsize::new(0),
        }
    }

    /// Workers not busy now.
    pub fn idle(&self) -> usize {
        self.permits.available_permits()
    }

    pub fn count(&self) -> usize {
        self.count
    }

    /// Jobs stopped by their deadline so far.
    pub fn cancelled(&self) -> usize {
        self.cancelled.load(Ordering::Relaxed)
    }

    /// Jobs given to a worker so far.
    pub fn started(&self) -> usize {
        self.started.load(Ordering::Relaxed)
    }

    /// Run `work` on a free worker (waiting for one), with `deadline`.
    pub async fn run<T: Send + 'static>(
        &self,
        deadline: Deadline,
        work: impl FnOnce(&Deadline) -> Result<T, ApiError> + Send + 'static,
    ) -> Result<T, ApiError> {
        let permit = self
            .permits
            .clone()
            .acquire_owned()
            .await
            .map_err(|_| ApiError::Internal("the worker pool is closed".into()))?;
        self.started.fetch_add(1, Ordering::Relaxed);
        // As many pools as permits: one is idle whenever a permit is free.
        let lease =
            Lease { pool: lock(&self.idle_pools).pop().flatten(), home: self.idle_pools.clone() };
        let pool = lease.pool.clone();
        let (answer, answered) = tokio::sync::oneshot::channel();
        let cancelled = self.cancelled.clone();
        let job = move || {
            let result = catch_unwind(AssertUnwindSafe(|| {
                // Waiting for the worker may have used up the time.
                deadline.check()?;
                work(&deadline)
            }))
            .unwrap_or_else(|_| Err(ApiError::Internal("the job failed unexpectedly".into())));
            if matches!(result, Err(ApiError::Input(close_core::error::Error::Cancelled))) {
                cancelled.fetch_add(1, Ordering::Relaxed);
            }
            // The worker is free before its answer is sent (the pool back before the
            // permit), so whoever reads the answer finds the worker idle.
            drop(lease);
            drop(permit);
            // The request may be gone: nobody to answer then.
            let _ = answer.send(result);
        };
        match pool {
            Some(pool) => pool.spawn(job),
            None => drop(tokio::task::spawn_blocking(job)),
        }
        answered
            .await
            .map_err(|_| ApiError::Internal("the job stopped without an answer".into()))?
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[tokio::test]
    async fn jobs_run_on_their_workers_pool_and_give_it_back() {
        let workers = Workers::new("test", 2, 1);
        let name = workers
            .run(Deadline::default(), |_| Ok(std::thread::current().name().map(str::to_string)))
            .await
            .unwrap();
        assert!(name.is_some_and(|n| n.starts_with("close-test-")));
        assert_eq!(workers.idle(), 2);
        assert_eq!(lock(&workers.idle_pools).len(), 2);
    }

    #[tokio::test]
    async fn a_panic_is_an_error_and_an_expired_deadline_stops_before_starting() {
        let workers = Workers::new("test", 1, 1);
        let panicked =
            workers.run(Deadline::default(), |_| -> Result<(), ApiError> { panic!("a bug") }).await;
        assert!(matches!(panicked, Err(ApiError::Internal(_))));
        let expired = Deadline::default();
        expired.cancel();
        let stopped = workers
            .run(expired, |_| -> Result<(), ApiError> { unreachable!("never started") })
            .await;
        assert!(matches!(stopped, Err(ApiError::Input(close_core::error::Error::Cancelled))));
        assert_eq!(workers.idle(), 1, "the worker is free again");
        assert_eq!(workers.cancelled(), 1);
    }
}
