//! Fold points to a fraction of an edge, by analysis by synthesis on the disks.
//!
//! The cut ([`super::cut`]) says which edges were turned over, to half an edge. Where, inside
//! the crease edges, the cloth really folded, and along which line the flap was turned,
//! decides where every flap vertex lands, so we measure it the way the paper's
//! representation sees it (Kamat, Borràs, Torras, "CloSE", Sec. III: the dGLI disk of a
//! state): for a candidate fold we synthesise the end state from the START border of the
//! step (the flap turned over the line, i.e. rotated by π about it, and laid
//! [`SynthesisParams::lift`] above the highest vertex, [`super::state`]), compare its
//! probe pairs with the measured END disk ([`super::probe`]), and refine the fold
//! ([`super::refine`]). The candidate whose disk matches best wins. The end border's
//! coordinates are never read, only its disk.
//!
//! Two parametrisations: normally the line runs through the border points at s1 and s2,
//! both searched within [`SynthesisParams::reach_edges`] of the cut. When those two points
//! (nearly) coincide in the step's start frame (a second fold through two stacked layers),
//! they do not give a direction, so the line is the midpoint of the two points and a
//! searched direction. A fold of several arcs is placed by its line, the arcs following it.

use std::f64::consts::PI;

use serde::{Deserialize, Serialize};

use crate::border::{point_at, Point};
use crate::disk::Disk;
use crate::geometry::{Line, Point2, Vector2};

use super::params::SynthesisParams;
use super::probe::Probe;
use super::refine::{refine, Costs};
use super::state::{arcs_left_of, flap_axis, mean_edge, Stack};

/// A fold found by synthesis: the border parameters of its points and the line used.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Synthesis {
    /// Border parameters (fractional vertex indices) of the two fold points, in [0, N); the
    /// folded side runs anticlockwise from the first. For a fold of several arcs, the first
    /// point of the first arc and the last point of the last: the pair that spans them.
    pub s: [f64; 2],
    /// The folded arcs (border parameters, each anticlockwise from its first point), in
    /// walking order from `s[0]`: one arc, `s` itself, unless the fold line crosses the
    /// border more than twice and turns several arcs over (`synth::place`).
    pub arcs: Vec<[f64; 2]>,
    /// The direction found on the disks when the fold points coincide (a unit vector);
    /// `None` when the line runs through the two fold points.
    #[cfg_attr(feature = "schema", schemars(with = "Option<[f64; 2]>"))]
    pub direction: Option<Vector2>,
    /// Mean probe mismatch of the best candidate.
    pub mismatch: f64,
    /// Mean probe mismatch of the start state left as it was (no fold), for comparison.
    pub unfolded_mismatch: f64,
}

impl Synthesis {
    /// A fold at border parameters `s`, one arc along the line through its points, not yet
    /// measured: what `synth::place` starts from when the cut gives the points.
    pub fn guess(s: [f64; 2]) -> Synthesis {
        Synthesis {
            s,
            arcs: vec![s],
            direction: None,
            mismatch: f64::INFINITY,
            unfolded_mismatch: f64::INFINITY,
        }
    }
}

/// The line of a candidate: through the two fold points, or through their midpoint at `phi`.
pub(crate) fn line_of(before: &[Point], s: [f64; 2], phi: Option<f64>) -> Option<Line> {
    let (a, b) = (point_at(before, s[0]), point_at(before, s[1]));
    match phi {
        None => Line::through(&a, &b),
        Some(phi) => Some(Line::at_angle(Point2::new((a.x + b.x) / 2.0, (a.y + b.y) / 2.0), phi)),
    }
}

/// The line through the border point at parameter `s` of `points` at angle `phi`.
fn crossing_line(points: &[Point], s: f64, phi: f64) -> Line {
    let p = point_at(points, s);
    Line::at_angle(Point2::new(p.x, p.y), phi)
}

/// Place a candidate fold (`guess`: the cut's points, [`Synthesis::guess`], or a candidate of the
/// line search, [`super::line_search`]) on the step's start border `before` (normalised) against
/// the measured `end` disk, by the refinement ([`refine`]). A fold of one arc is placed by its two
/// points (and the direction of its line when they coincide, from the guess's direction when it has
/// one). A fold of several arcs is placed by its line (direction and offset), the arcs following
/// it. The result's `mismatch` is infinite when the guess holds several arcs and gives no line.
pub(crate) fn place(
    before: &[Point],
    start: &Disk,
    end: &Disk,
    guess: &Synthesis,
    params: &SynthesisParams,
) -> Synthesis {
    let heading = guess.direction.map(|d| d.y.atan2(d.x));
    match (guess.arcs.len(), heading) {
        (0 | 1, heading) => place_points(before, start, end, guess.s, heading, params),
        (_, Some(phi)) => {
            place_line(before, start, end, &crossing_line(before, guess.s[0], phi), params)
        }
        (_, None) => match line_of(before, guess.s, None) {
            Some(line) => place_line(before, start, end, &line, params),
            None => Synthesis { mismatch: f64::INFINITY, ..guess.clone() },
        },
    }
}

/// Fold points (border parameters) and, when searched, the line's direction.
type Points = ([f64; 2], Option<f64>);

/// The bits of fold points, to tell equal ones apart.
fn points_key(&(s, phi): &Points) -> [u64; 3] {
    [s[0].to_bits(), s[1].to_bits(), phi.map_or(u64::MAX, f64::to_bits)]
}

/// Place the fold points `s` (border parameters, the folded side anticlockwise from s[0])
/// on the step's start border `before` (normalised) against the measured `end` disk: the
/// refinement over all eight neighbours in (s1, s2), so a line sliding along both sides at
/// once is followed, within [`SynthesisParams::reach_edges`] of `s`. When the two points
/// coincide the direction is searched too: from `heading` (the direction of a line that
/// gave `s`, radians) or else the best of [`SynthesisParams::directions`] per half turn,
/// again over a half turn from the best start, then with the points.
fn place_points(
    before: &[Point],
    start: &Disk,
    end: &Disk,
    s: [f64; 2],
    heading: Option<f64>,
    params: &SynthesisParams,
) -> Synthesis {
    let n = before.len();
    let nf = n as f64;
    let flat = super::seed::is_flat(before);
    let probe = Probe::around(start, end, &[s], flat, params.scale(flat), params);
    let axis = flap_axis(before, params.lift);
    let directions = params.directions;
    let cost = |&(s, phi): &Points| {
        let s = s.map(|x| x.rem_euclid(nf));
        line_of(before, s, phi)
            .map_or(f64::INFINITY, |line| probe.cost(&Stack::new(before, axis, &[s], &line)))
    };
    let mut costs = Costs::new(cost, points_key);
    let half_turn = |costs: &mut Costs<_, _, _>, s: [f64; 2]| {
        costs
            .least((0..directions).map(|k| (s, Some(PI * k as f64 / directions as f64))).collect())
            .and_then(|((_, phi), _)| phi)
    };
    let (a, b) = (point_at(before, s[0]), point_at(before, s[1]));
    let coincide = (a.xy() - b.xy()).norm() < params.coincide_edges * mean_edge(before);
    let phi = if coincide { heading.or_else(|| half_turn(&mut costs, s)) } else { None };
    // Start from the best of the given points and their snaps to the vertices either side and
    // the nearest half edge: exact data folds through those, and its optimum is needle sharp.
    let snaps = |x: f64| [x, x.floor(), x.ceil(), (2.0 * x).round() / 2.0];
    let starts = snaps(s[0])
        .into_iter()
        .flat_map(|a| snaps(s[1]).into_iter().map(move |b| ([a, b], phi)))
        .collect();
    let start = costs.least(starts).map_or(s, |((t, _), _)| t);
    let phi = if coincide { half_turn(&mut costs, start) } else { None };
    let best = costs.least(vec![(start, phi)]).unwrap_or(((start, phi), f64::INFINITY));
    // Steps of h edges along the border and h times π / `directions` in angle.
    let angle_step = PI / directions as f64;
    let neighbours = |&(centre, centre_phi): &Points, h: f64| -> Vec<Points> {
        let turns: &[f64] = if centre_phi.is_some() { &[-1.0, 0.0, 1.0] } else { &[0.0] };
        [-1.0, 0.0, 1.0]
            .iter()
            .flat_map(|&d1| {
                [-1.0, 0.0, 1.0]
                    .iter()
                    .flat_map(move |&d2| turns.iter().map(move |&dp| (d1, d2, dp)))
            })
            .filter(|&step| step != (0.0, 0.0, 0.0))
            .map(|(d1, d2, dp)| {
                let phi = centre_phi.map(|p| p + dp * (h * angle_step));
                ([centre[0] + d1 * h, centre[1] + d2 * h], phi)
            })
            .filter(|(t, _)| {
                (t[0] - s[0]).abs() <= params.reach_edges
                    && (t[1] - s[1]).abs() <= params.reach_edges
            })
            .collect()
    };
    let ((s, phi), mismatch) = refine(&mut costs, best, (0.5, params.step_edges), neighbours);
    let s = s.map(|x| x.rem_euclid(nf));
    Synthesis {
        s,
        arcs: vec![s],
        direction: phi.map(|p| Vector2::new(p.cos(), p.sin())),
        mismatch,
        unfolded_mismatch: probe.unfolded(),
    }
}

/// The line at angle `phi` to the x axis whose signed distance from the origin (along its
/// left normal) is `rho`.
pub(crate) fn line_at(phi: f64, rho: f64) -> Line {
    Line {
        point: Point2::new(-rho * phi.sin(), rho * phi.cos()),
        direction: Vector2::new(phi.cos(), phi.sin()),
    }
}

/// Place a fold that turns every arc of the border left of `line` over it: a line that
/// crosses a stacked border 2k times (k ≥ 2) folds k arcs at once (the stacked legs of
/// trousers folded in half; a shirt's hem with a sleeve lying across it). The fold points
/// no longer give the line, so the line itself is refined ([`refine`]), over its direction
/// and offset from `line`, and the arcs follow it. The result spans the arcs: `s` runs from
/// the first point of the first arc to the last point of the last.
fn place_line(
    before: &[Point],
    start: &Disk,
    end: &Disk,
    line: &Line,
    params: &SynthesisParams,
) -> Synthesis {
    let phi0 = line.angle();
    let rho0 = line.direction.x * line.point.y - line.direction.y * line.point.x;
    let flat = super::seed::is_flat(before);
    let arcs = arcs_left_of(before, line);
    let probe = Probe::around(start, end, &arcs, flat, params.scale(flat), params);
    let axis = flap_axis(before, params.lift);
    let folded = |phi: f64, rho: f64| {
        let line = line_at(phi, rho);
        let arcs = arcs_left_of(before, &line);
        (line, arcs)
    };
    let cost = |&[phi, rho]: &[f64; 2]| {
        let (line, arcs) = folded(phi, rho);
        if arcs.is_empty() {
            f64::INFINITY
        } else {
            probe.cost(&Stack::new(before, axis, &arcs, &line))
        }
    };
    let mut costs = Costs::new(cost, |&[phi, rho]: &[f64; 2]| [phi.to_bits(), rho.to_bits()]);
    let best = costs.least(vec![[phi0, rho0]]).unwrap_or(([phi0, rho0], f64::INFINITY));
    // Steps of h mean edges in offset and h times π / `directions` in angle.
    let (edge, angle_step) = (mean_edge(before), PI / params.directions as f64);
    let neighbours = |&[phi, rho]: &[f64; 2], h: f64| -> Vec<[f64; 2]> {
        [-1.0, 0.0, 1.0]
            .iter()
            .flat_map(|&dp| [-1.0, 0.0, 1.0].iter().map(move |&dr| (dp, dr)))
            .filter(|&step| step != (0.0, 0.0))
            .map(|(dp, dr)| [phi + dp * (h * angle_step), rho + dr * (h * edge)])
            .collect()
    };
    let ([phi, rho], mismatch) = refine(&mut costs, best, (1.0, params.step_edges), neighbours);
    let (line, arcs) = folded(phi, rho);
    let s = match (arcs.first(), arcs.last()) {
        (Some(first), Some(last)) => [first[0], last[1]],
        _ => [0.0; 2],
    };
    Synthesis {
        s,
        arcs,
        direction: Some(line.direction),
        mismatch,
        unfolded_mismatch: probe.unfolded(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fold::fixtures::{fold_by_hand, square};
    use crate::rng::SplitMix64;

    #[test]
    fn an_off_grid_fold_is_placed_within_a_tenth_of_an_edge() {
        // Folds through seeded random points along two edges, not at vertices or half edges;
        // refine starts from the nearest half edges, as the cut gives them.
        let before = square(10, 0.7, |_| 0.0);
        let start = Disk::of_border(&before);
        let mut rng = SplitMix64::new(16);
        for _ in 0..4 {
            let truth = [
                rng.below(6) as f64 + 2.0 + rng.range(0.1, 0.9),
                rng.below(6) as f64 + 21.0 + rng.range(0.1, 0.9),
            ];
            // Laid at a height of its own, not the synthesis's lift.
            let end = Disk::of_border(&fold_by_hand(&before, truth, 0.006));
            let guess = truth.map(|s| (2.0 * s).round() / 2.0);
            let params = SynthesisParams::default();
            let found = place(&before, &start, &end, &Synthesis::guess(guess), &params);
            let error = [0, 1].map(|k| (found.s[k] - truth[k]).abs());
            assert!(
                error.iter().all(|&e| e <= 0.1),
                "truth {truth:?}, found {:?}: {error:?} edges off",
                found.s
            );
            assert!(found.mismatch < 0.2 * found.unfolded_mismatch, "{found:?}");
        }
    }
}
