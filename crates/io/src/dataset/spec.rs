//! The folds of the built-in dataset, written as points along the sides of each shape.
//!
//! A fold is two endpoints, each a fraction along a side of the shape's polygon
//! ([`Outline::on_side`]), so it means the same thing whatever N is. Walking the border
//! anticlockwise from the first endpoint to the second covers the side that folds: the
//! orientation of the fold coordinates (f1, f2) in Kamat, Borràs, Torras, "CloSE: A
//! Geometric Shape-Agnostic Cloth State Representation". A name ending in `_wrap` has its
//! folded arc running through border vertex 0.
//!
//! These are nominal folds ("half", "diagonal"): the samples fold at them moved a seeded
//! random part of an edge off the vertex and half-edge grid ([`fold_off_grid`]), so that no
//! fold point sits where a search may start, and a perfect score has to be earned.
//!
//! ```
//! use close_io::dataset::shapes::{outline, Shape};
//! use close_io::dataset::spec::single_folds;
//! let napkin = outline(Shape::Napkin);
//! let diagonal = single_folds(Shape::Napkin).into_iter().find(|s| s.name == "diagonal").unwrap();
//! assert_eq!(diagonal.params(&napkin), [0.0, 38.0]);
//! ```

use super::shapes::{Outline, Shape};
use close_core::error::Result;
use close_core::rng::SplitMix64;

/// A fold endpoint: (side, fraction along it).
pub type At = (usize, f64);

/// A named fold of a flat shape.
#[derive(Debug, Clone, PartialEq)]
pub struct FoldSpec {
    pub name: &'static str,
    pub from: At,
    pub to: At,
    /// Also made as a grid mesh (rectangular shapes only).
    pub mesh: bool,
}

impl FoldSpec {
    /// The border parameters (fractional vertex indices) of the two endpoints.
    pub fn params(&self, outline: &Outline) -> [f64; 2] {
        [param(outline, self.from), param(outline, self.to)]
    }

    /// The same fold, also made as a grid mesh.
    const fn meshed(self) -> FoldSpec {
        FoldSpec { mesh: true, ..self }
    }
}

fn param(outline: &Outline, at: At) -> f64 {
    outline.on_side(at.0, at.1)
}

const fn fs(name: &'static str, from: At, to: At) -> FoldSpec {
    FoldSpec { name, from, to, mesh: false }
}

/// The single folds of each shape.
pub fn single_folds(kind: Shape) -> Vec<FoldSpec> {
    match kind {
        // Sides: 0 bottom, 1 right, 2 top (right to left), 3 left (top to bottom).
        Shape::Napkin => vec![
            fs("half_vertical", (0, 0.5), (2, 0.5)).meshed(),
            fs("half_vertical_wrap", (2, 0.5), (0, 0.5)),
            fs("half_horizontal", (1, 0.5), (3, 0.5)),
            fs("half_horizontal_wrap", (3, 0.5), (1, 0.5)),
            fs("diagonal", (0, 0.0), (2, 0.0)).meshed(),
            fs("diagonal_wrap", (3, 0.0), (1, 0.0)),
            fs("corner", (0, 0.63), (1, 0.37)),
            fs("corner_asym_wrap", (3, 0.6), (0, 0.3)),
            fs("askew", (0, 0.28), (2, 0.36)),
            fs("strip_wrap", (2, 0.75), (0, 0.25)),
            fs("big_part", (0, 0.25), (2, 0.75)),
            fs("thirds", (0, 2.0 / 3.0), (2, 1.0 / 3.0)),
        ],
        Shape::Towel => vec![
            fs("half_short", (0, 0.5), (2, 0.5)),
            fs("half_short_wrap", (2, 0.5), (0, 0.5)),
            fs("half_long", (1, 0.5), (3, 0.5)),
            fs("half_long_wrap", (3, 0.5), (1, 0.5)),
            fs("diagonal", (0, 0.0), (2, 0.0)),
            fs("corner45", (0, 0.75), (1, 0.5)).meshed(),
            fs("askew", (0, 0.2), (2, 0.4)),
            fs("thirds", (0, 2.0 / 3.0), (2, 1.0 / 3.0)),
            fs("thirds_wrap", (2, 2.0 / 3.0), (0, 1.0 / 3.0)),
            fs("strip_long", (1, 0.7), (3, 0.3)),
            fs("big_part", (3, 0.3), (1, 0.7)),
        ],
        // One side all the way round: t is the fraction of the turn from vertex 0.
        Shape::CircularTowel => vec![
            fs("half", (0, 0.133), (0, 0.633)),
            fs("half_wrap", (0, 0.629), (0, 0.129)),
            fs("cap_small", (0, 0.05), (0, 0.23)),
            fs("cap_wrap", (0, 0.917), (0, 0.098)),
            fs("third_cap", (0, 0.156), (0, 0.49)),
            fs("big_wrap", (0, 0.49), (0, 0.155)),
            fs("askew", (0, 0.316), (0, 0.733)),
        ],
        // Sides start at: 0 hem mid, 1 hem right, 2 right armpit, 3–4 right sleeve end,
        // 5 right shoulder, 6 neck right, 7 V, 8 neck left, 9 left shoulder, 10–11 left
        // sleeve end, 12 left armpit, 13 hem left.
        Shape::TShirt => vec![
            fs("half_vertical", (7, 0.0), (0, 0.0)),
            fs("half_vertical_right", (0, 0.0), (7, 0.0)),
            fs("bottom_up_wrap", (12, 0.45 / 0.95), (1, 0.5 / 0.95)),
            fs("top_down", (1, 0.5 / 0.95), (12, 0.45 / 0.95)),
            fs("sleeve_left", (9, 0.0), (12, 0.0)),
            fs("sleeve_right", (2, 0.0), (5, 0.0)),
            fs("sleeve_right_partial", (2, 0.5), (4, 0.5)),
            fs("diagonal_wrap", (13, 0.4), (5, 0.0)),
            fs("corner_hem", (0, 0.6), (1, 0.2)),
            fs("corner_hem_left", (12, 0.8), (13, 0.4)),
            fs("askew_wrap", (13, 0.2), (1, 0.7)),
        ],
        // Corners: 0–1 hem, 2 right armpit, 3–4 right strap, 5 neck, 6–7 left strap, 8 left armpit.
        Shape::Top => vec![
            fs("half_vertical", (0, 0.5), (5, 0.0)),
            fs("half_vertical_wrap", (5, 0.0), (0, 0.5)),
            fs("bottom_up_wrap", (8, 0.4 / 0.9), (1, 0.5 / 0.9)),
            fs("top_down", (1, 0.5 / 0.9), (8, 0.4 / 0.9)),
            fs("corner_hem", (0, 0.7), (1, 0.3)),
            fs("strap", (2, 0.5), (4, 0.5)),
            fs("askew", (0, 0.1), (2, 0.2)),
            fs("hem_strip_wrap", (8, 0.7), (1, 0.3)),
        ],
        // Corners: 0 left hem outer, 1 left hem inner, 2 crotch, 3 right hem inner,
        // 4 right hem outer, 5 waist right, 6 waist left.
        Shape::Trousers => vec![
            fs("half_vertical_wrap", (5, 0.5), (2, 0.0)),
            fs("half_vertical_right", (2, 0.0), (5, 0.5)),
            fs("legs_up_wrap", (6, 0.25 / 1.1), (4, 0.85 / 1.1)),
            fs("waist_down", (4, 0.85 / 1.1), (6, 0.25 / 1.1)),
            fs("left_cuff_wrap", (6, 0.85 / 1.1), (1, 0.25 / 0.72)),
            fs("right_cuff", (2, 0.47 / 0.72), (4, 0.25 / 1.1)),
            fs("right_leg_askew", (2, 0.5), (4, 0.4)),
            fs("waist_corner", (4, 0.8), (5, 0.2)),
        ],
        // Corners: 0 hem left, 1 hem right, 2 waist right, 3 waist left.
        Shape::Skirt => vec![
            fs("half_vertical", (0, 0.5), (2, 0.5)),
            fs("half_vertical_wrap", (2, 0.5), (0, 0.5)),
            fs("hem_up_wrap", (3, 0.7), (1, 0.3)),
            fs("waist_down", (1, 0.6), (3, 0.4)),
            fs("corner", (0, 0.8), (1, 0.25)),
            fs("askew", (0, 0.3), (2, 0.3)),
            fs("diagonal", (0, 0.0), (2, 0.0)),
        ],
    }
}

/// Draws of a sample's fold endpoints tried before its last refusal is the answer.
const DRAWS: usize = 32;

/// Make the built-in sample `name` (of an `n`-vertex border) folded at its `nominal` folds'
/// border parameters moved off the grid: each endpoint a seeded random 0.1–0.4 of an edge
/// either way, so it is neither a vertex nor a half-edge. `fold` makes the sample from the
/// drawn parameters; a draw it refuses (the arc crosses the line, the chord leaves the
/// cloth) is drawn again. The seed is the name: a sample's draw depends on nothing else.
pub fn fold_off_grid<T, const K: usize>(
    name: &str,
    n: usize,
    nominal: [[f64; 2]; K],
    mut fold: impl FnMut([[f64; 2]; K]) -> Result<T>,
) -> Result<([[f64; 2]; K], T)> {
    let mut rng = SplitMix64::from_name(name);
    let mut attempt = 0;
    loop {
        attempt += 1;
        let drawn = nominal.map(|f| f.map(|s| off_grid(s, n, &mut rng)));
        match fold(drawn) {
            Ok(sample) => return Ok((drawn, sample)),
            Err(e) if attempt >= DRAWS => return Err(e),
            Err(_) => {}
        }
    }
}

/// `s` moved 0.1–0.4 of an edge either way, to a point at least 0.1 of an edge from every
/// vertex and half-edge, in [0, n).
fn off_grid(s: f64, n: usize, rng: &mut SplitMix64) -> f64 {
    loop {
        let step = rng.range(0.1, 0.4);
        let t = (if rng.uniform() < 0.5 { s - step } else { s + step }).rem_euclid(n as f64);
        let half = t.rem_euclid(0.5);
        if half.min(0.5 - half) >= 0.1 {
            return t;
        }
    }
}

/// A fold of the folded cloth: `first` flat, then `second` on the folded border (its
/// endpoints are points of the original sides, wherever the first fold moved them).
#[derive(Debug, Clone, PartialEq)]
pub struct SecondFoldSpec {
    pub shape: Shape,
    pub name: &'static str,
    pub first: FoldSpec,
    pub second: FoldSpec,
}

impl SecondFoldSpec {
    /// The border parameters of the first and the second fold.
    pub fn params(&self, outline: &Outline) -> [[f64; 2]; 2] {
        [self.first.params(outline), self.second.params(outline)]
    }
}

/// The second-fold samples. A fold of a stack needs the two layers' free edges apart where
/// the line crosses them (exact halves put them on top of each other and the fold points
/// would coincide), so "half" first folds here leave a margin.
pub fn second_folds() -> Vec<SecondFoldSpec> {
    let sf = |shape, name, first: (At, At), second: (At, At)| SecondFoldSpec {
        shape,
        name,
        first: fs("first", first.0, first.1),
        second: fs("second", second.0, second.1),
    };
    vec![
        // Right 45 % over, then the whole stack folded top down / bottom up.
        sf(Shape::Napkin, "half_then_half", ((0, 0.55), (2, 0.45)), ((1, 0.5), (3, 0.5))),
        sf(Shape::Napkin, "half_then_half_wrap", ((0, 0.55), (2, 0.45)), ((3, 0.5), (1, 0.5))),
        // Exact half, then the top layer's corner (right side's top end, now on the left).
        sf(Shape::Napkin, "half_then_corner", ((0, 0.5), (2, 0.5)), ((1, 0.75), (2, 0.25))),
        // Letter fold: right third over, then left third over it.
        sf(
            Shape::Napkin,
            "thirds_then_thirds",
            ((0, 2.0 / 3.0), (2, 1.0 / 3.0)),
            ((2, 2.0 / 3.0), (0, 1.0 / 3.0)),
        ),
        // Diagonal, then the top layer's corner (corner 1, now on corner 3).
        sf(Shape::Napkin, "diagonal_then_corner", ((0, 0.0), (2, 0.0)), ((0, 0.7), (1, 0.3))),
        // Short-axis near-half, then the stack along the long axis.
        sf(Shape::Towel, "half_then_half", ((0, 0.55), (2, 0.45)), ((1, 0.5), (3, 0.5))),
        // Long-axis near-half (top down), then the stack's right half over.
        sf(Shape::Towel, "half_long_then_half", ((1, 0.55), (3, 0.45)), ((0, 0.5), (2, 0.5))),
        // Diagonal, then a second fold across the crease taking its far end.
        sf(Shape::Towel, "diagonal_then_diagonal", ((0, 0.0), (2, 0.0)), ((0, 0.75), (2, 0.5))),
        // Half, then the top layer's sleeve.
        sf(Shape::TShirt, "half_then_sleeve", ((7, 0.0), (0, 0.0)), ((9, 0.0), (12, 0.0))),
        // Legs up over the waist part, then the stack's left half over (waist middle to crotch).
        sf(
            Shape::Trousers,
            "legs_up_then_half",
            ((6, 0.25 / 1.1), (4, 0.85 / 1.1)),
            ((5, 0.5), (2, 0.0)),
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dataset::exact_fold::fold_border;
    use crate::dataset::shapes::outline;
    use std::collections::HashSet;

    /// Every endpoint is a fraction of a side that exists.
    fn on_a_side(kind: Shape, at: At) -> bool {
        at.0 < outline(kind).side_starts.len() && (0.0..=1.0).contains(&at.1)
    }

    #[test]
    fn every_single_fold_folds_its_flat_shape() {
        for kind in Shape::ALL {
            let o = outline(kind);
            let specs = single_folds(kind);
            let names: HashSet<&str> = specs.iter().map(|s| s.name).collect();
            assert_eq!(names.len(), specs.len(), "{kind:?}: repeated fold names");
            for s in &specs {
                assert!(on_a_side(kind, s.from) && on_a_side(kind, s.to), "{kind:?} {}", s.name);
                let [f1, f2] = s.params(&o);
                let folded = fold_border(&o.points, f1, f2, 0.01)
                    .unwrap_or_else(|e| panic!("{kind:?} {}: {e}", s.name));
                assert!(
                    !s.mesh || crate::dataset::grid::grid_mesh(kind).is_some(),
                    "{kind:?} {}: no grid to fold",
                    s.name
                );
                // A "_wrap" fold moves vertex 0; every fold leaves part of the cloth.
                assert!(
                    !s.name.ends_with("_wrap") || folded[0] != o.points[0],
                    "{kind:?} {}",
                    s.name
                );
                assert!(folded.iter().zip(&o.points).any(|(a, b)| a == b), "{kind:?} {}", s.name);
            }
        }
    }

    #[test]
    fn every_second_fold_folds_the_folded_shape() {
        for s in second_folds() {
            let o = outline(s.shape);
            let [f, g] = s.params(&o);
            let once = fold_border(&o.points, f[0], f[1], 0.01).unwrap();
            let twice =
                fold_border(&once, g[0], g[1], 0.01).unwrap_or_else(|e| panic!("{}: {e}", s.name));
            // The second fold moves vertices the first left, or turns folded ones back.
            assert!(twice.iter().zip(&once).any(|(a, b)| a != b), "{}", s.name);
        }
    }

    #[test]
    fn drawn_folds_are_off_the_grid_near_the_nominal_and_seeded_by_name() {
        let nominal = [[9.5, 47.5], [0.0, 38.0]];
        let draw = |name: &str| fold_off_grid(name, 76, nominal, Ok).unwrap().0;
        let drawn = draw("napkin__x");
        assert_eq!(drawn, draw("napkin__x"));
        assert_ne!(drawn, draw("napkin__y"));
        for (d, f) in drawn.iter().flatten().zip(nominal.iter().flatten()) {
            let moved = close_core::angle::wrap_pi((d - f) / 76.0 * std::f64::consts::TAU) * 76.0
                / std::f64::consts::TAU;
            assert!((0.1..=0.4).contains(&moved.abs()), "{f} → {d}");
            let half = d.rem_euclid(0.5);
            assert!(half.min(0.5 - half) >= 0.1 - 1e-12 && (0.0..76.0).contains(d), "{d}");
        }
        // A refused draw is drawn again; one refused every time is the error.
        let mut calls = 0;
        let (_, second) = fold_off_grid("napkin__x", 76, nominal, |_| {
            calls += 1;
            if calls < 3 {
                Err(close_core::error::Error::Cancelled)
            } else {
                Ok(calls)
            }
        })
        .unwrap();
        assert_eq!(second, 3);
        assert!(fold_off_grid("napkin__x", 76, nominal, |_| Err::<(), _>(
            close_core::error::Error::Cancelled
        ))
        .is_err());
    }

    #[test]
    fn params_are_the_polygon_points() {
        let napkin = outline(Shape::Napkin);
        assert_eq!(fs("x", (0, 0.5), (2, 0.5)).params(&napkin), [9.5, 47.5]);
        assert_eq!(fs("x", (3, 1.0), (1, 0.0)).params(&napkin), [0.0, 19.0]);
    }
}
