//! Colour maps for disk values: a robust scale, a sigmoid squash, and two ramps.
//!
//! A disk is mostly near zero with a few large cells (corners, the fold line), so a linear
//! map would show only those. Values are squashed as t = tanh(v / s), with s a robust scale:
//! the 95th percentile of |v| (or max |v| when that percentile is zero, e.g. a diff disk that
//! is zero almost everywhere). Then t ∈ [−1, 1] picks a colour:
//! - diverging: blue (t = −1) – white (t = 0) – orange (t = +1), for signed values;
//! - sequential: white (t = 0) → dark blue (t = 1), for non-negative values.
//!
//! ```
//! use close_render::colour::{Scale, Ramp};
//! let scale = Scale::of(&[0.0, 1.0, -2.0, 0.5]);
//! assert_eq!(Ramp::Diverging.colour(scale.squash(0.0)), [255, 255, 255]);
//! ```

use std::cmp::Ordering;

/// Fraction of |v| below the robust scale.
pub const SCALE_PERCENTILE: f64 = 0.95;

/// The robust scale s of a set of values (never zero, never NaN).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Scale {
    /// s in t = tanh(v / s).
    pub s: f64,
    /// Largest finite |v|.
    pub max: f64,
}

impl Scale {
    /// Scale of `values`, ignoring non-finite ones.
    pub fn of(values: &[f64]) -> Scale {
        Scale::of_all(&[values])
    }

    /// One scale for several sets of values (panels that must share their colours).
    pub fn of_all(sets: &[&[f64]]) -> Scale {
        let mut abs: Vec<f64> =
            sets.iter().flat_map(|v| v.iter()).filter(|v| v.is_finite()).map(|v| v.abs()).collect();
        if abs.is_empty() {
            return Scale { s: 1.0, max: 0.0 };
        }
        let k = ((abs.len() - 1) as f64 * SCALE_PERCENTILE).round() as usize;
        let (_, &mut p, _) =
            abs.select_nth_unstable_by(k, |a, b| a.partial_cmp(b).unwrap_or(Ordering::Equal));
        let max = abs.iter().copied().fold(0.0, f64::max);
        // A flat disk has nothing to show: any positive scale leaves it white.
        let s = if p > 0.0 {
            p
        } else if max > 0.0 {
            max
        } else {
            1.0
        };
        Scale { s, max }
    }

    /// A scale given by a caller (e.g. fixed through an animation), if it is usable:
    /// s positive and finite, max finite and not negative.
    pub fn fixed(s: f64, max: f64) -> Option<Scale> {
        (s.is_finite() && s > 0.0 && max.is_finite() && max >= 0.0).then_some(Scale { s, max })
    }

    /// t = tanh(v / s) ∈ [−1, 1]; a non-finite value counts as 0.
    pub fn squash(&self, v: f64) -> f64 {
        if v.is_finite() {
            (v / self.s).tanh()
        } else {
            0.0
        }
    }

    /// The value whose squash is `t` (for colour-bar labels), t ∈ (−1, 1).
    pub fn unsquash(&self, t: f64) -> f64 {
        self.s * t.atanh()
    }
}

/// A colour ramp over t.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ramp {
    /// Blue – white – orange, t ∈ [−1, 1].
    Diverging,
    /// White → dark blue, t ∈ [0, 1] (negative t is clamped to 0).
    Sequential,
}

/// ColorBrewer RdBu blues, from white outwards.
const BLUES: [[u8; 3]; 6] = [
    [255, 255, 255],
    [209, 229, 240],
    [146, 197, 222],
    [67, 147, 195],
    [33, 102, 172],
    [5, 48, 97],
];
/// ColorBrewer PuOr oranges, from white outwards.
const ORANGES: [[u8; 3]; 6] =
    [[255, 255, 255], [254, 224, 182], [253, 184, 99], [224, 130, 20], [179, 88, 6], [127, 59, 8]];
/// ColorBrewer YlGnBu, white to dark.
const SEQUENTIAL: [[u8; 3]; 6] =
    [[255, 255, 255], [237, 248, 177], [127, 205, 187], [44, 127, 184], [37, 52, 148], [8, 29, 88]];

/// Viridis, dark purple to yellow: every colour differs from the paper, and its lightness
/// grows steadily, so heights read in order in grey too.
const HEIGHT: [[u8; 3]; 6] =
    [[68, 1, 84], [65, 68, 135], [42, 120, 142], [34, 168, 132], [122, 209, 81], [253, 231, 37]];

/// The colour of height t ∈ [0, 1] (low to high) in the mesh picture.
pub fn height_colour(t: f64) -> [u8; 3] {
    interpolate(&HEIGHT, t)
}

impl Ramp {
    /// The colour at t.
    pub fn colour(self, t: f64) -> [u8; 3] {
        match self {
            Ramp::Diverging if t < 0.0 => interpolate(&BLUES, -t),
            Ramp::Diverging => interpolate(&ORANGES, t),
            Ramp::Sequential => interpolate(&SEQUENTIAL, t.max(0.0)),
        }
    }

    /// The t range a colour bar of this ramp spans.
    pub fn t_range(self) -> (f64, f64) {
        match self {
            Ramp::Diverging => (-1.0, 1.0),
            Ramp::Sequential => (0.0, 1.0),
        }
    }
}

/// Piecewise-linear interpolation through equally spaced `stops` at t ∈ [0, 1].
fn interpolate(stops: &[[u8; 3]], t: f64) -> [u8; 3] {
    let x = t.clamp(0.0, 1.0) * (stops.len() - 1) as f64;
    let k = (x.floor() as usize).min(stops.len() - 2);
    let f = x - k as f64;
    let (a, b) = (stops[k], stops[k + 1]);
    std::array::from_fn(|c| (a[c] as f64 + f * (b[c] as f64 - a[c] as f64)).round() as u8)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_is_robust_and_never_zero() {
        let mut values = vec![0.1; 99];
        values.push(100.0);
        let scale = Scale::of(&values);
        assert_eq!(scale.s, 0.1);
        assert_eq!(scale.max, 100.0);
        assert_eq!(Scale::of(&[0.0; 10]).s, 1.0);
        assert_eq!(Scale::of(&[f64::NAN, 0.0]).s, 1.0);
        // Mostly zero with one cell: the scale falls back to max |v|.
        let mut sparse = vec![0.0; 50];
        sparse[3] = -4.0;
        assert_eq!(Scale::of(&sparse).s, 4.0);
    }

    #[test]
    fn a_shared_scale_covers_every_panel() {
        let (small, large) = ([0.5, -1.0, 0.2], [8.0, -32.0, 4.0]);
        let shared = Scale::of_all(&[&small, &large]);
        assert_eq!(shared.max, 32.0);
        assert!(shared.s >= Scale::of(&small).s);
        assert_eq!(Scale::fixed(0.0, 1.0), None);
        assert_eq!(Scale::fixed(f64::NAN, 1.0), None);
        assert_eq!(Scale::fixed(2.0, 3.0), Some(Scale { s: 2.0, max: 3.0 }));
    }

    #[test]
    fn squash_round_trips() {
        let scale = Scale::of(&[1.0, 2.0, 3.0]);
        for v in [-2.0, 0.0, 0.7, 5.0] {
            assert!((scale.unsquash(scale.squash(v)) - v).abs() < 1e-9);
        }
    }

    #[test]
    fn ramps_are_white_at_zero_and_dark_at_the_ends() {
        assert_eq!(Ramp::Diverging.colour(0.0), [255, 255, 255]);
        assert_eq!(Ramp::Sequential.colour(0.0), [255, 255, 255]);
        assert_eq!(Ramp::Diverging.colour(-1.0), BLUES[5]);
        assert_eq!(Ramp::Diverging.colour(1.0), ORANGES[5]);
        assert_eq!(Ramp::Sequential.colour(1.0), SEQUENTIAL[5]);
        // Blue side is blue, orange side is orange.
        let [r, _, b] = Ramp::Diverging.colour(-0.6);
        assert!(b > r);
        let [r, _, b] = Ramp::Diverging.colour(0.6);
        assert!(r > b);
    }
}
