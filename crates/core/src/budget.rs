//! Work budgets and deadlines: what a request may cost, estimated before the work starts,
//! and a flag the work's loops check so that a job whose answer nobody waits for stops.
//!
//! The cost of an analysis is its dGLI cells: a disk of an N-vertex border has N(N−1)/2 edge
//! pairs (Kamat, Borràs, Torras, "CloSE: A Geometric Shape-Agnostic Cloth State
//! Representation", Sec. III, the dGLI disk), one disk per analysed frame, so time grows
//! with frames × N². An interpolation's answer holds vertices × steps points. A [`Budget`]
//! refuses an estimate over its limit with [`Error::OverBudget`], naming the limit, before
//! anything is computed. A [`Deadline`] is a point in time and a cancellation flag shared by
//! clones: the server cancels it when the request is dropped (time-out, closed connection)
//! and the loops return [`Error::Cancelled`] at their next check.
//!
//! ```
//! use close_core::budget::{Budget, Deadline};
//! let budget = Budget { max_cells: 1_000_000, ..Budget::default() };
//! assert!(budget.analysis(10, 300).is_ok()); // 900 000 cells
//! assert!(budget.analysis(12, 300).unwrap_err().to_string().contains("1000000"));
//!
//! let deadline = Deadline::default(); // never expires on its own
//! let job = deadline.clone();
//! assert!(job.check().is_ok());
//! deadline.cancel();
//! assert!(job.check().is_err());
//! ```

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::error::{Error, Result};

/// Largest costs a caller accepts. The default is unlimited (the library and the CLI); the
/// server sets its own ([`Budget::SERVER`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Budget {
    /// Most dGLI cells of one analysis: analysed frames × N².
    pub max_cells: u64,
    /// Most points in one interpolation: vertices × steps.
    pub max_points: u64,
}

impl Default for Budget {
    fn default() -> Self {
        Budget { max_cells: u64::MAX, max_points: u64::MAX }
    }
}

impl Budget {
    /// The web server's limits: an analysis of at most 10⁸ cells (4 frames of 5000 vertices,
    /// 100 frames of 1000) takes a few seconds on two cores; 2·10⁶ interpolated points are
    /// about 60 MB of JSON.
    pub const SERVER: Budget = Budget { max_cells: 100_000_000, max_points: 2_000_000 };

    /// Refuse an analysis of `frames` frames of `n` vertices over [`Budget::max_cells`].
    pub fn analysis(&self, frames: usize, n: usize) -> Result<()> {
        let cells = (frames as u64).saturating_mul((n as u64).saturating_mul(n as u64));
        within("analysed frames × N² (dGLI cells)", cells, self.max_cells)
    }

    /// Refuse an interpolation of `n` vertices in `steps` steps over [`Budget::max_points`].
    pub fn interpolation(&self, n: usize, steps: usize) -> Result<()> {
        within(
            "vertices × steps of the interpolation",
            (n as u64).saturating_mul(steps as u64),
            self.max_points,
        )
    }
}

fn within(what: &'static str, got: u64, limit: u64) -> Result<()> {
    if got > limit {
        return Err(Error::OverBudget { what, got, limit });
    }
    Ok(())
}

/// When a job must stop: an optional point in time and a cancellation flag shared by every
/// clone. The default never expires and is never cancelled.
#[derive(Debug, Clone, Default)]
pub struct Deadline {
    at: Option<Instant>,
    cancelled: Arc<AtomicBool>,
}

impl Deadline {
    /// A deadline `limit` from now.
    pub fn after(limit: Duration) -> Self {
        Deadline { at: Instant::now().checked_add(limit), cancelled: Arc::default() }
    }

    /// Stop every job holding a clone of this deadline at its next check.
    pub fn cancel(&self) {
        self.cancelled.store(true, Ordering::Relaxed);
    }

    /// True once cancelled or past the deadline.
    pub fn expired(&self) -> bool {
        self.cancelled.load(Ordering::Relaxed) || self.at.is_some_and(|at| Instant::now() >= at)
    }

    /// [`Error::Cancelled`] once [`Deadline::expired`]: the `?` of a loop's check.
    pub fn check(&self) -> Result<()> {
        if self.expired() {
            return Err(Error::Cancelled);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn budgets_refuse_over_the_limit_and_name_it() {
        let b = Budget { max_cells: 100, max_points: 10 };
        assert!(b.analysis(1, 10).is_ok());
        assert_eq!(
            b.analysis(2, 10),
            Err(Error::OverBudget {
                what: "analysed frames × N² (dGLI cells)",
                got: 200,
                limit: 100
            })
        );
        assert!(b.interpolation(5, 2).is_ok());
        assert!(matches!(b.interpolation(5, 3), Err(Error::OverBudget { got: 15, limit: 10, .. })));
        // Huge counts saturate instead of wrapping round to a small product.
        assert!(b.analysis(usize::MAX, usize::MAX).is_err());
        assert!(Budget::default().analysis(usize::MAX, usize::MAX).is_ok());
    }

    #[test]
    fn deadlines_expire_in_time_or_when_cancelled() {
        assert!(!Deadline::default().expired());
        assert!(Deadline::after(Duration::ZERO).expired());
        let d = Deadline::after(Duration::from_secs(3600));
        assert!(d.check().is_ok());
        let job = d.clone();
        d.cancel();
        assert_eq!(job.check(), Err(Error::Cancelled));
    }
}
