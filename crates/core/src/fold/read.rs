//! One step read by one search: the fold its disks point to (the seed, [`super::seed`]),
//! and when that fold leaves the end disk unexplained, the fold sequences that explain it
//! better ([`super::sequence`]), every candidate a sequence of folds made on the step's
//! start state and judged alike; a single fold is a sequence of one.
//!
//! The method sets how the seed is found and judged: [`FoldMethod::Cut`] seeds with the cut
//! (or on a stacked start the line search), placed by synthesis, and judges it against
//! sequences; [`FoldMethod::Paper`] seeds with the paper's curves and takes that fold as it
//! is, as the paper reads a step (no synthesis to judge it by: its share explained is
//! `None`).
//!
//! The end border's coordinates are never read: only its disk.

use crate::border::Point;
use crate::budget::Deadline;
use crate::disk::Disk;
use crate::error::Result;
use crate::geometry::Folding;

use super::params::Params;
use super::seed::{seed, Evidence, FoldMethod};
use super::sequence::{explain, ExplainedFold, StepFolds};

/// One step as the search sees it: its start border (normalised as the disks were), its
/// start disk and the measured end disk.
#[derive(Clone, Copy)]
pub(crate) struct Seen<'a> {
    pub(crate) before: &'a [Point],
    pub(crate) start: &'a Disk,
    pub(crate) end: &'a Disk,
}

/// What one step's disks were read as.
#[derive(Debug, Clone, PartialEq)]
pub struct Reading {
    /// How the seed was found.
    pub evidence: Evidence,
    /// The step's folds, other sequences that explain it about as well, and how much.
    pub folds: StepFolds,
}

/// Read the step from the state `before` (its border normalised as the disks were; `start`
/// its disk) to the state whose disk is `end`: at most `max_folds` folds, found by `method`
/// with the knobs `params`. An error names a knob the search cannot run with;
/// [`Cancelled`](crate::error::Error::Cancelled) once `deadline` expires.
///
/// ```
/// use close_core::border::Point;
/// use close_core::budget::Deadline;
/// use close_core::disk::Disk;
/// use close_core::fold::{read, FoldMethod, Params};
/// // A square of 32 vertices; its left half (vertices 9…23) turned over the line x = 0.
/// let square: Vec<Point> = (0..32)
///     .map(|k| {
///         let t = (k % 8) as f64 / 8.0;
///         let (x, y) = [(t, 0.0), (1.0, t), (1.0 - t, 1.0), (0.0, 1.0 - t)][k / 8];
///         Point::new(x - 0.5, y - 0.5, 0.0)
///     })
///     .collect();
/// let end: Vec<Point> =
///     square.iter().map(|p| if p.x < -1e-9 { Point::new(-p.x, p.y, 0.02) } else { *p }).collect();
/// let (start, end) = (Disk::of_border(&square), Disk::of_border(&end));
/// let reading =
///     read(&square, &start, &end, FoldMethod::Cut, 3, &Params::default(), &Deadline::default())?;
/// let close_core::geometry::Fold { f1, f2 } = reading.folds.folds[0].folding.fold;
/// // Vertex 4 (the middle of the bottom side) sits at angle 2π·4/32 and vertex 20 at 2π·20/32.
/// let edge = close_core::angle::edge(32);
/// assert!((f1 - 20.0 * edge).abs() < 0.3 * edge && (f2 - 4.0 * edge).abs() < 0.3 * edge);
/// assert_eq!(reading.folds.folds.len(), 1);
/// # Ok::<(), close_core::Error>(())
/// ```
pub fn read(
    before: &[Point],
    start: &Disk,
    end: &Disk,
    method: FoldMethod,
    max_folds: usize,
    params: &Params,
    deadline: &Deadline,
) -> Result<Reading> {
    params.check()?;
    let (evidence, seeded) = seed(before, start, end, method, params);
    let folds = match seeded {
        None => StepFolds::default(),
        Some(seeded) if method == FoldMethod::Paper => StepFolds {
            folds: vec![ExplainedFold {
                folding: Folding { fold: seeded.fold, arcs: seeded.arcs, line: None },
                explained: None,
            }],
            ..StepFolds::default()
        },
        Some(seeded) => {
            let seen = Seen { before, start, end };
            let placed = evidence.synthesis.as_ref();
            explain(&seen, &seeded, placed, max_folds, params, deadline)?
        }
    };
    Ok(Reading { evidence, folds })
}
