//! The semantic label: CloSE in plain words, with no learning.
//!
//! From the corners θ_1 < … < θ_n and a fold (f1, f2): the number of corners ("circular"
//! when more than [`CIRCULAR_CORNERS`]); the corners (1-based, in border order) strictly
//! inside the folded arc; for each folded corner the share of each adjacent side that is
//! folded; and a class. A corner within half an edge of a fold point lies on the fold line:
//! it is reported as such and never counted as folded, so a fold that ends exactly on a
//! corner gets one answer, not a coin flip. A cloth with no corner (or a circular one) has
//! its folds told by their share of the border and the border points they run between
//! ("the border from 90° to 270° is folded over"), as angles 2πs/N of the border.
//!
//! The classes are those of Kamat, Borràs, Torras, "CloSE", Sec. IV (semantic labelling).
//!
//! **Numbering.** The sentence names corner k by its 1-based number in border order, as a
//! person counts ("corner 1" is the first corner, `corner_vertices[0]` of an analysis).
//! Every structured field that holds such a number has the corner's border vertex index
//! beside it (`folded_corner_vertices` beside `folded_corners`, `from_vertex` beside
//! `from_corner`, …): the 0-based index of the vertex in border order, the index into an
//! analysis's `corner_vertices` values and its `predicted_end` rows (the input's own index
//! is `border_indices[vertex]`).
//!
//! A sequence of two or more folds is also read as a whole, as a person would say it
//! ([`SequenceClass`], our extension), from where each fold's line lies across the state it
//! is made on (the folds replayed on the start border): across the line, the share of that
//! state's width on the side turned over, and how far the flap reaches. A fold is "in half"
//! when that share is within [`SEQUENCE_HALF_PERCENT`] of 50 %: a stacked napkin's third
//! fold in half turns a quarter of its start border, but half the state it is made on. Two
//! such folds are "in quarters", three "in eighths"; two sides folded in are two folds from
//! opposite sides, along nearly parallel lines, whose flaps reach alike (within
//! [`EVEN_PERCENT`] of the start's width): "in thirds" alone (the second then folds half
//! the state over the first), "both sides folded in, then folded in half" with a fold in
//! half after them, "folded in half, then both sides folded in" in the other order. Whether
//! a fold after the first is "in half" in its own label is judged the same way, and it is
//! never called askew (the start border's sides are not its state's); its corners and the
//! sides it cuts are still told on the start border. The sentences are made from the classes,
//! so the text and the structured fields cannot disagree.
//!
//! ```
//! use close_core::border::Point;
//! use close_core::geometry::{Fold, Folding};
//! use close_core::label::{label, FoldClass};
//! use std::f64::consts::PI;
//! // A square of 8 vertices with corners at 0, 2, 4, 6, folded along the diagonal 0–4.
//! let square: Vec<Point> = [[0, 0], [1, 0], [2, 0], [2, 1], [2, 2], [1, 2], [0, 2], [0, 1]]
//!     .iter()
//!     .map(|&[x, y]| Point::new(x as f64, y as f64, 0.0))
//!     .collect();
//! let l = label(&square, &[0, 2, 4, 6], &[Folding::new(Fold::new(0.0, PI))]);
//! assert_eq!(l.folds[0].class, FoldClass::DiagonallyFoldedInHalf);
//! assert_eq!(l.folds[0].folded_corners, vec![2]);
//! ```

use serde::{Deserialize, Serialize};

use crate::angle::{angle_to_param, wrap_tau, ON_LINE_EDGES};
use crate::border::Point;
use crate::fold::apply;
use crate::geometry::{Arc, Fold, Folding, Line, Vector2};

/// More corners than this and the cloth is called circular.
pub const CIRCULAR_CORNERS: usize = 20;
/// A corner closer than [`ON_LINE_EDGES`] to a fold point lies on the fold line, or closer
/// than this share of the border: a simulated cloth's fold through a corner misses it by a
/// vertex or two (1.1 of 172 on `physics__pentagon_f1_half_axis`, 1.4 of 190 on
/// `physics__trousers_f1_half_left_onto_right`), a few degrees on the fold circle.
const ON_LINE_SHARE: f64 = 0.015;
/// Percentages this close count as equal (askew otherwise; of a sequence's flaps, alike).
pub const EVEN_PERCENT: f64 = 10.0;
/// A fold whose folded share is this close to 50% is "in half".
const HALF_PERCENT: f64 = 12.0;

/// The kind of fold, as a person would say it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum FoldClass {
    FoldedInHalf,
    DiagonallyFoldedInHalf,
    OneSideFolded,
    FoldedInHalfAskew,
    OneSideAskew,
    CornerFolded,
    /// A round cloth (or one with no corner) folded by the given share.
    Folded,
}

impl FoldClass {
    pub(crate) fn phrase(self) -> &'static str {
        match self {
            FoldClass::FoldedInHalf => "folded in half",
            FoldClass::DiagonallyFoldedInHalf => "diagonally folded in half",
            FoldClass::OneSideFolded => "one side folded",
            FoldClass::FoldedInHalfAskew => "folded in half askew",
            FoldClass::OneSideAskew => "one side folded askew",
            FoldClass::CornerFolded => "corner folded",
            FoldClass::Folded => "folded",
        }
    }
}

/// The share of one side (corner to next corner) that lies on the folded arc.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct SideFold {
    /// 1-based corner numbers at the side's ends.
    pub from_corner: usize,
    pub to_corner: usize,
    /// Border vertex indices (0-based) of those two corners.
    pub from_vertex: usize,
    pub to_vertex: usize,
    pub folded_percent: f64,
}

/// One folded corner and the folded share of its two sides.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct FoldedCorner {
    /// 1-based corner number.
    pub corner: usize,
    /// Its border vertex index (0-based).
    pub vertex: usize,
    pub before: SideFold,
    pub after: SideFold,
}

/// The label of one fold.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct FoldLabel {
    pub class: FoldClass,
    /// 1-based numbers of the corners strictly inside the folded arc.
    pub folded_corners: Vec<usize>,
    /// Their border vertex indices (0-based), in the same order.
    pub folded_corner_vertices: Vec<usize>,
    /// 1-based numbers of corners lying on the fold line.
    pub corners_on_fold_line: Vec<usize>,
    /// Their border vertex indices (0-based), in the same order.
    pub corner_vertices_on_fold_line: Vec<usize>,
    pub corner_sides: Vec<FoldedCorner>,
    /// Sides cut by the fold line (where the fold points lie), with their folded share.
    pub cut_sides: Vec<SideFold>,
    /// Share of the border (by vertex parameter) on the folded arc.
    pub folded_percent: f64,
    /// The folded arc's ends on the border, in degrees [0, 360): from f1 anticlockwise to f2.
    pub border_degrees: [f64; 2],
    pub text: String,
}

/// The label of a whole CloSE state.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Label {
    pub text: String,
    pub corners: usize,
    pub circular: bool,
    pub folds: Vec<FoldLabel>,
    /// The folds read as a whole, for two or more folds.
    pub sequence: Option<SequenceLabel>,
}

/// A fold of a sequence whose line leaves this close to 50 % of its state's width on the
/// side turned over is "in half" (tighter than `HALF_PERCENT`: a towel's third is no half).
pub const SEQUENCE_HALF_PERCENT: f64 = 6.0;
/// Two folds' turned sides this close to opposite (the cosine between them at most its
/// negation: 26°) are folded in from opposite sides.
const OPPOSITE_COSINE: f64 = 0.9;

/// How a sequence of folds reads as a whole.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum SequenceClass {
    /// Two folds, each in half.
    InQuarters,
    /// Three folds, each in half.
    InEighths,
    /// Two sides folded in from opposite sides, their flaps alike (the second over the first).
    InThirds,
    /// Two sides folded in, then a fold in half.
    SidesInThenHalf,
    /// A fold in half, then two sides of it folded in.
    HalfThenSidesIn,
    /// Any other sequence, told fold by fold.
    Folds,
}

/// A sequence of folds read as a whole.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct SequenceLabel {
    pub class: SequenceClass,
    /// Where each fold's line lies across the state it is made on: the share (percent) of
    /// that state's width, measured across the line, on the side turned over; `None` for a
    /// fold without a line there.
    pub across_percent: Vec<Option<f64>>,
    /// Whether each fold, in order, folded its state in half (`across_percent` within
    /// [`SEQUENCE_HALF_PERCENT`] of 50).
    pub in_half: Vec<bool>,
    pub text: String,
}

/// Where a fold's line lies across the state it is made on.
#[derive(Debug, Clone, Copy)]
struct Across {
    /// Unit normal to the line, towards the side turned over.
    towards: Vector2,
    /// How far the turned vertices reach past the line.
    flap: f64,
    /// How far the state reaches past the line on the side that stays.
    rest: f64,
    /// The start state's width along `towards`.
    start_width: f64,
}

impl Across {
    /// Of `folding`, made along `line` on `state` (start state `start`): `None` when it turns
    /// no vertex or the state has no width across the line.
    fn of(start: &[Point], state: &[Point], folding: &Folding, line: &Line) -> Option<Across> {
        let normal = Vector2::new(-line.direction.y, line.direction.x);
        let offset = |p: &Point| normal.dot(&(p.xy() - line.point));
        let turned: Vec<usize> =
            folding.arcs.iter().flat_map(|arc| arc.folded_vertices(state.len())).collect();
        let side = turned.iter().map(|&v| offset(&state[v])).sum::<f64>().signum();
        let flap = turned.iter().map(|&v| side * offset(&state[v])).fold(0.0, f64::max);
        let rest = state.iter().map(|p| -side * offset(p)).fold(0.0, f64::max);
        let (low, high) = start
            .iter()
            .map(offset)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), t| (lo.min(t), hi.max(t)));
        (flap + rest > 0.0 && high > low).then(|| Across {
            towards: side * normal,
            flap,
            rest,
            start_width: high - low,
        })
    }

    fn percent(&self) -> f64 {
        100.0 * self.flap / (self.flap + self.rest)
    }

    fn in_half(&self) -> bool {
        (self.percent() - 50.0).abs() <= SEQUENCE_HALF_PERCENT
    }
}

/// Each of `folds` made in turn on `start`: where its line lies across its state.
fn across_states(start: &[Point], folds: &[Folding]) -> Vec<Option<Across>> {
    let mut state = start.to_vec();
    folds
        .iter()
        .map(|folding| {
            let across =
                folding.line_on(&state).and_then(|line| Across::of(start, &state, folding, &line));
            state = apply(&state, folding);
            across
        })
        .collect()
}

/// The sequence label of two or more folds: where each lies `across` its state, and their
/// labels.
fn label_sequence(across: &[Option<Across>], labels: &[FoldLabel]) -> SequenceLabel {
    let across_percent: Vec<Option<f64>> =
        across.iter().map(|a| a.as_ref().map(Across::percent)).collect();
    let in_half: Vec<bool> =
        across.iter().map(|a| a.as_ref().is_some_and(Across::in_half)).collect();
    // A side's fold: no corner or diagonal fold.
    let of_a_side = |k: usize| {
        !matches!(labels[k].class, FoldClass::CornerFolded | FoldClass::DiagonallyFoldedInHalf)
    };
    // Folds j and k: two sides folded in from opposite sides, the first less than half its
    // state, their flaps alike (the second may fold half of what is left, as the last third
    // of a towel does).
    let ends = |j: usize, k: usize| match (across[j], across[k]) {
        (Some(a), Some(b)) => {
            a.percent() < 50.0 - SEQUENCE_HALF_PERCENT
                && of_a_side(j)
                && of_a_side(k)
                && a.towards.dot(&b.towards) <= -OPPOSITE_COSINE
                && 100.0 * (a.flap - b.flap).abs()
                    <= EVEN_PERCENT * a.start_width.max(b.start_width)
        }
        _ => false,
    };
    let class = match (labels.len(), in_half.as_slice()) {
        (2, [true, true]) => SequenceClass::InQuarters,
        (3, [true, true, true]) => SequenceClass::InEighths,
        (2, _) if ends(0, 1) => SequenceClass::InThirds,
        (3, [_, _, true]) if ends(0, 1) => SequenceClass::SidesInThenHalf,
        (3, [true, _, _]) if ends(1, 2) => SequenceClass::HalfThenSidesIn,
        _ => SequenceClass::Folds,
    };
    let text = match class {
        SequenceClass::InQuarters => {
            "Folded in quarters (in half, then in half again).".to_string()
        }
        SequenceClass::InEighths => {
            "Folded in eighths (in half, then in half again, and again).".to_string()
        }
        SequenceClass::InThirds => {
            "Folded in thirds (one side folded in, then the other side over it).".to_string()
        }
        SequenceClass::SidesInThenHalf => "Both sides folded in, then folded in half.".to_string(),
        SequenceClass::HalfThenSidesIn => "Folded in half, then both sides folded in.".to_string(),
        SequenceClass::Folds => {
            let phrases: Vec<&str> = labels.iter().map(|l| l.class.phrase()).collect();
            format!("Folded {} times: {}.", labels.len(), phrases.join(", then "))
        }
    };
    SequenceLabel { class, across_percent, in_half, text }
}

/// Length of the overlap of two cyclic intervals [a, a+la] and [b, b+lb] on a circle of length n.
fn overlap(n: f64, a: f64, la: f64, b: f64, lb: f64) -> f64 {
    [-n, 0.0, n]
        .iter()
        .map(|shift| {
            let lo = a.max(b + shift);
            let hi = (a + la).min(b + shift + lb);
            (hi - lo).max(0.0)
        })
        .sum()
}

/// Label the border `start` (its first state) with corners at `corner_vertices` (sorted)
/// and `folds`, made in turn on it. A fold of one arc is labelled by its fold (f1, f2). A
/// fold of several arcs (a multi-arc fold) is classed by the pair that spans its arcs; its
/// folded corners and share are those of its arcs, and its sentence says how many separate
/// flaps turned over. Each fold's corners and sides are told on the start border; whether a
/// later fold of a sequence is "in half", and the sequence as a whole, by where its line
/// lies across the state it is made on.
///
/// A cloth with no fold is "not folded" — unless it changed: see `Label::changed_without_fold`.
pub fn label(start: &[Point], corner_vertices: &[usize], folds: &[Folding]) -> Label {
    let n = start.len();
    let circular = corner_vertices.len() > CIRCULAR_CORNERS || corner_vertices.is_empty();
    let across = if folds.len() >= 2 { across_states(start, folds) } else { Vec::new() };
    let in_half = |k: usize| across[k].as_ref().is_some_and(Across::in_half);
    let fold_labels: Vec<FoldLabel> = folds
        .iter()
        .enumerate()
        .map(|(k, f)| {
            let made_in_half = (k > 0).then(|| in_half(k));
            match f.arcs.as_slice() {
                several @ [_, _, ..] => {
                    label_multi_arc(n, corner_vertices, f.fold, several, circular, made_in_half)
                }
                _ => label_fold(n, corner_vertices, f.fold, circular, made_in_half),
            }
        })
        .collect();
    let mut text = if corner_vertices.len() > CIRCULAR_CORNERS {
        format!("Cloth is circular ({} corners).", corner_vertices.len())
    } else if corner_vertices.is_empty() {
        "Cloth has no corners.".to_string()
    } else {
        format!("Cloth has {} corners.", corner_vertices.len())
    };
    if fold_labels.is_empty() {
        text.push_str(" It is not folded.");
    }
    let sequence = (fold_labels.len() >= 2).then(|| label_sequence(&across, &fold_labels));
    if let Some(sequence) = &sequence {
        text.push(' ');
        text.push_str(&sequence.text);
    }
    for (k, f) in fold_labels.iter().enumerate() {
        if fold_labels.len() > 1 {
            text.push_str(&format!(" Fold {}:", k + 1));
        }
        text.push(' ');
        text.push_str(&f.text);
    }
    Label { text, corners: corner_vertices.len(), circular, folds: fold_labels, sequence }
}

/// Prediction error (RMSE of the normalised XY border, once moved rigidly onto the observed
/// one: [`crate::metrics::aligned_rmse_xy`]) past which a step without a fold changed the
/// cloth beyond noise: the built-in samples' exact folds stay under 0.073 (the
/// web app's low-confidence limit is the same 0.1).
pub const CHANGED_RMSE: f64 = 0.1;

impl Label {
    /// Say that the steps `changed` (1-based), which found no fold, still changed the cloth
    /// beyond noise ([`CHANGED_RMSE`]): "It is not folded" would be wrong.
    pub(crate) fn changed_without_fold(&mut self, changed: &[usize]) {
        if changed.is_empty() {
            return;
        }
        let steps = if changed.len() > 1 {
            format!("steps {}", list(changed))
        } else {
            format!("step {}", changed[0])
        };
        let note = format!(" It changed, but no fold found ({steps}).");
        match self.text.strip_suffix(" It is not folded.") {
            Some(head) => self.text = format!("{head}{note}"),
            None => self.text.push_str(&note),
        }
    }
}

/// The label of `fold` on a border of `n` vertices. `made_in_half`, for a later fold of a
/// sequence, says whether it folds the state it is made on in half: that, not its share of
/// the start border, decides "in half", and no such fold is called askew.
fn label_fold(
    n: usize,
    corners: &[usize],
    fold: Fold,
    circular: bool,
    made_in_half: Option<bool>,
) -> FoldLabel {
    let nf = n as f64;
    let s1 = angle_to_param(fold.f1, n);
    let span = angle_to_param(fold.f2 - fold.f1, n);
    let folded_percent = 100.0 * span / nf;
    let near = |v: f64, s: f64| {
        let d = (v - s).rem_euclid(nf);
        d.min(nf - d) < ON_LINE_EDGES.max(ON_LINE_SHARE * nf)
    };
    let s2 = s1 + span;
    let mut folded_corners = Vec::new();
    let mut on_line = Vec::new();
    for (k, &c) in corners.iter().enumerate() {
        if near(c as f64, s1) || near(c as f64, s2) {
            on_line.push(k + 1);
        } else if fold.arc().folds_vertex(n, c, ON_LINE_EDGES) {
            folded_corners.push(k + 1);
        }
    }
    let nc = corners.len();
    let side = |k: usize| {
        // Side from corner k (0-based) to the next one.
        let (a, b) = (corners[k] as f64, corners[(k + 1) % nc] as f64);
        let len = (b - a).rem_euclid(nf);
        let len = if len == 0.0 { nf } else { len };
        SideFold {
            from_corner: k + 1,
            to_corner: (k + 1) % nc + 1,
            from_vertex: corners[k],
            to_vertex: corners[(k + 1) % nc],
            folded_percent: 100.0 * overlap(nf, a, len, s1, span) / len,
        }
    };
    // The side a fold point lies on: the last corner at or before it (wrapping).
    let side_of = |s: f64| corners.iter().rposition(|&c| c as f64 <= s).unwrap_or(nc - 1);
    let corner_sides: Vec<FoldedCorner> = if circular {
        Vec::new()
    } else {
        folded_corners
            .iter()
            .map(|&c| FoldedCorner {
                corner: c,
                vertex: corners[c - 1],
                before: side((c + nc - 2) % nc),
                after: side(c - 1),
            })
            .collect()
    };
    // A fold point on a corner runs through it and cuts no side.
    let on_corner = |s: f64| corners.iter().any(|&c| near(c as f64, s));
    let cut_sides: Vec<SideFold> = if circular {
        Vec::new()
    } else {
        [s1, s2.rem_euclid(nf)]
            .into_iter()
            .filter(|&s| !on_corner(s))
            .map(|s| side(side_of(s)))
            .collect()
    };
    let even = |a: f64, b: f64| (a - b).abs() <= EVEN_PERCENT;
    // Symmetric: the two cut sides folded alike, or, through a corner, the one cut side
    // cut in half (the axis through a corner and the middle of the opposite side). Not
    // judged for a later fold of a sequence: the start border's sides are not its state's.
    let askew = made_in_half.is_none()
        && match cut_sides.as_slice() {
            [a, b] => !even(a.folded_percent, b.folded_percent),
            [one] => !even(one.folded_percent, 50.0),
            _ => false,
        };
    let half = made_in_half.unwrap_or((folded_percent - 50.0).abs() <= HALF_PERCENT);
    let class = if circular {
        if half {
            FoldClass::FoldedInHalf
        } else {
            FoldClass::Folded
        }
    } else if on_line.len() >= 2 && half {
        FoldClass::DiagonallyFoldedInHalf
    } else {
        match folded_corners.len() {
            0 => FoldClass::OneSideFolded,
            1 => FoldClass::CornerFolded,
            _ => match (half, askew) {
                (true, false) => FoldClass::FoldedInHalf,
                (true, true) => FoldClass::FoldedInHalfAskew,
                (false, false) => FoldClass::OneSideFolded,
                (false, true) => FoldClass::OneSideAskew,
            },
        }
    };
    let border_degrees = [fold.f1, fold.f2].map(|f| wrap_tau(f).to_degrees());
    let mut text =
        fold_text(class, folded_percent, &folded_corners, &on_line, &corner_sides, &cut_sides);
    if circular {
        text.push_str(&format!(
            " The border from {:.0}° to {:.0}° is folded over.",
            border_degrees[0], border_degrees[1]
        ));
    }
    let vertices = |numbers: &[usize]| numbers.iter().map(|&c| corners[c - 1]).collect();
    FoldLabel {
        class,
        folded_corner_vertices: vertices(&folded_corners),
        folded_corners,
        corner_vertices_on_fold_line: vertices(&on_line),
        corners_on_fold_line: on_line,
        corner_sides,
        cut_sides,
        folded_percent,
        border_degrees,
        text,
    }
}

/// The label of a fold that turned the `arcs` over together (a line crossing the border
/// 2k times, k ≥ 2): classed by the pair `fold` that spans them, with the corners and the
/// share of the border that lie on the arcs themselves, and a sentence naming the flaps.
fn label_multi_arc(
    n: usize,
    corners: &[usize],
    fold: Fold,
    arcs: &[Arc],
    circular: bool,
    made_in_half: Option<bool>,
) -> FoldLabel {
    let mut out = label_fold(n, corners, fold, circular, made_in_half);
    let nf = n as f64;
    let on_arcs = |v: usize| {
        arcs.iter().any(|&Arc { a, b }| {
            (v as f64 - angle_to_param(a, n)).rem_euclid(nf) < angle_to_param(b - a, n)
        })
    };
    out.folded_corners.retain(|&c| on_arcs(corners[c - 1]));
    out.folded_corner_vertices.retain(|&v| on_arcs(v));
    out.corner_sides.retain(|s| on_arcs(s.vertex));
    out.folded_percent =
        arcs.iter().map(|&Arc { a, b }| 100.0 * angle_to_param(b - a, n) / nf).sum();
    // The sentence is told again from the fields kept: the spanning fold's own would name
    // corners between the arcs, which do not turn.
    let mut text = fold_text(
        out.class,
        out.folded_percent,
        &out.folded_corners,
        &out.corners_on_fold_line,
        &out.corner_sides,
        &out.cut_sides,
    );
    if circular {
        text.push_str(&format!(
            " The border from {:.0}° to {:.0}° is folded over.",
            out.border_degrees[0], out.border_degrees[1]
        ));
    }
    let flaps = match arcs.len() {
        2 => "both".to_string(),
        k => format!("all {k}"),
    };
    out.text = format!(
        "{text} The fold line crosses the border {} times and {flaps} flaps on its folded side turn over together (a multi-arc fold).",
        2 * arcs.len(),
    );
    out
}

fn list(items: &[usize]) -> String {
    items.iter().map(|c| c.to_string()).collect::<Vec<_>>().join(", ")
}

fn fold_text(
    class: FoldClass,
    percent: f64,
    folded: &[usize],
    on_line: &[usize],
    corner_sides: &[FoldedCorner],
    cut_sides: &[SideFold],
) -> String {
    let mut out = format!(
        "{}{} ({percent:.0}% of the border folded over).",
        &class.phrase()[..1].to_uppercase(),
        &class.phrase()[1..]
    );
    match folded.len() {
        0 => {}
        1 => out.push_str(&format!(" Corner {} is folded", folded[0])),
        _ => out.push_str(&format!(" Corners {} are folded", list(folded))),
    }
    if let [only] = corner_sides {
        out.push_str(&format!(
            " ({:.0}% of side {}–{} and {:.0}% of side {}–{})",
            only.before.folded_percent,
            only.before.from_corner,
            only.before.to_corner,
            only.after.folded_percent,
            only.after.from_corner,
            only.after.to_corner
        ));
    }
    if !folded.is_empty() {
        out.push('.');
    }
    if !on_line.is_empty() {
        out.push_str(&format!(
            " The fold line runs through corner{} {}.",
            if on_line.len() > 1 { "s" } else { "" },
            list(on_line)
        ));
    }
    if corner_sides.len() != 1 && !cut_sides.is_empty() && on_line.len() < 2 {
        let sides: Vec<String> = cut_sides
            .iter()
            .map(|s| {
                format!("side {}–{} is {:.0}% folded", s.from_corner, s.to_corner, s.folded_percent)
            })
            .collect();
        out.push_str(&format!(
            " The fold line cuts {}; {}.",
            if cut_sides.len() > 1 { "two sides" } else { "one side" },
            sides.join(", ")
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::angle::param_to_angle;
    use std::f64::consts::PI;

    const SQUARE: [usize; 4] = [0, 19, 38, 57];

    /// The unit square's border: 76 vertices, 19 a side, anticlockwise from (0, 0); the
    /// corners at `SQUARE`.
    fn square() -> Vec<Point> {
        (0..76)
            .map(|k| {
                let t = (k % 19) as f64 / 19.0;
                let [x, y] = [[t, 0.0], [1.0, t], [1.0 - t, 1.0], [0.0, 1.0 - t]][k / 19];
                Point::new(x, y, 0.0)
            })
            .collect()
    }
    /// A border of `n` vertices on the unit circle.
    fn ring(n: usize) -> Vec<Point> {
        (0..n)
            .map(|k| {
                let t = std::f64::consts::TAU * k as f64 / n as f64;
                Point::new(t.cos(), t.sin(), 0.0)
            })
            .collect()
    }

    /// Ordinary folds, one arc each.
    fn folds(pairs: &[[f64; 2]]) -> Vec<Folding> {
        pairs.iter().map(|&f| Folding::new(Fold::from(f))).collect()
    }
    fn angle(s: f64) -> f64 {
        param_to_angle(s, 76)
    }

    #[test]
    fn classes_of_the_napkin_folds() {
        let class = |a: f64, b: f64| {
            label(&square(), &SQUARE, &folds(&[[angle(a), angle(b)]])).folds[0].class
        };
        assert_eq!(class(9.5, 47.5), FoldClass::FoldedInHalf);
        assert_eq!(class(0.0, 38.0), FoldClass::DiagonallyFoldedInHalf);
        assert_eq!(class(57.0, 19.0), FoldClass::DiagonallyFoldedInHalf);
        assert_eq!(class(12.0, 26.0), FoldClass::CornerFolded);
        assert_eq!(class(5.32, 44.84), FoldClass::FoldedInHalfAskew);
        assert_eq!(class(52.25, 4.75), FoldClass::OneSideFolded);
        assert_eq!(class(55.0, 7.0), FoldClass::OneSideAskew);
    }

    #[test]
    fn corner_fold_reports_its_sides() {
        let l = label(&square(), &SQUARE, &folds(&[[angle(12.0), angle(26.0)]]));
        let c = &l.folds[0].corner_sides[0];
        assert_eq!((c.corner, c.vertex), (2, 19));
        // Each 1-based corner number has its border vertex beside it.
        assert_eq!((c.before.from_corner, c.before.from_vertex), (1, 0));
        assert_eq!((c.before.to_corner, c.before.to_vertex), (2, 19));
        assert_eq!((c.after.from_corner, c.after.from_vertex), (2, 19));
        assert_eq!((c.after.to_corner, c.after.to_vertex), (3, 38));
        assert_eq!(l.folds[0].folded_corner_vertices, vec![19]);
        assert!((c.before.folded_percent - 100.0 * 7.0 / 19.0).abs() < 1e-9);
        assert!((c.after.folded_percent - 100.0 * 7.0 / 19.0).abs() < 1e-9);
        assert!(l.text.contains("Corner 2 is folded"), "{}", l.text);
    }

    #[test]
    fn a_multi_arc_fold_keeps_each_corner_number_beside_its_vertex() {
        // The pair spans corners 2 and 3, its arcs hold corner 2 alone.
        let arcs = [[angle(12.0), angle(26.0)], [angle(40.0), angle(45.0)]];
        let folding = Folding {
            fold: Fold::new(angle(12.0), angle(45.0)),
            arcs: arcs.iter().map(|&a| a.into()).collect(),
            line: None,
        };
        let l = label(&square(), &SQUARE, &[folding]);
        assert_eq!(l.folds[0].folded_corners, vec![2]);
        assert_eq!(l.folds[0].folded_corner_vertices, vec![19]);
    }

    #[test]
    fn fold_on_a_corner_is_not_a_coin_flip() {
        // A hair either side of the corner gives the same answer.
        for eps in [-1e-9, 0.0, 1e-9] {
            let l = label(&square(), &SQUARE, &folds(&[[angle(eps), angle(38.0 - eps)]]));
            assert_eq!(l.folds[0].folded_corners, vec![2]);
            assert_eq!(l.folds[0].corners_on_fold_line, vec![1, 3]);
            assert_eq!(l.folds[0].folded_corner_vertices, vec![19]);
            assert_eq!(l.folds[0].corner_vertices_on_fold_line, vec![0, 38]);
        }
    }

    #[test]
    fn a_fold_through_a_corner_and_the_opposite_side_is_symmetric() {
        // A pentagon of 172 vertices (corners as `physics__pentagon_f1_half_axis` finds
        // them) folded along its axis: a vertex past corner 4 to the middle of side 1–2.
        let pentagon = [0, 28, 60, 99, 140];
        let l = label(
            &ring(172),
            &pentagon,
            &folds(&[[param_to_angle(100.1, 172), param_to_angle(14.0, 172)]]),
        );
        let fold = &l.folds[0];
        assert_eq!(fold.class, FoldClass::FoldedInHalf, "{}", l.text);
        assert_eq!(fold.corners_on_fold_line, vec![4]);
        assert!(l.text.contains("through corner 4") && !l.text.contains("side 4–5"), "{}", l.text);
        // Off the middle of the opposite side, it is askew.
        let off = label(
            &ring(172),
            &pentagon,
            &folds(&[[param_to_angle(100.1, 172), param_to_angle(22.0, 172)]]),
        );
        assert_eq!(off.folds[0].class, FoldClass::FoldedInHalfAskew, "{}", off.text);
    }

    #[test]
    fn a_change_without_a_fold_is_said() {
        let mut l = label(&square(), &SQUARE, &[]);
        l.changed_without_fold(&[1]);
        assert_eq!(l.text, "Cloth has 4 corners. It changed, but no fold found (step 1).");
        let mut folded = label(&square(), &SQUARE, &folds(&[[angle(9.5), angle(47.5)]]));
        let before = folded.text.clone();
        folded.changed_without_fold(&[2, 3]);
        assert_eq!(folded.text, format!("{before} It changed, but no fold found (steps 2, 3)."));
        let mut still = label(&square(), &SQUARE, &[]);
        still.changed_without_fold(&[]);
        assert!(still.text.ends_with("It is not folded."));
    }

    #[test]
    fn round_cloth() {
        let corners: Vec<usize> = (0..64).collect();
        let l = label(&ring(64), &corners, &folds(&[[0.0, PI]]));
        assert!(l.circular);
        assert_eq!(l.folds[0].class, FoldClass::FoldedInHalf);
        assert!(l.text.starts_with("Cloth is circular"));
        let unfolded = label(&ring(64), &corners, &[]);
        assert!(unfolded.text.contains("not folded"));
    }

    #[test]
    fn a_cloth_without_corners_is_told_by_its_border() {
        let l = label(&ring(160), &[], &folds(&[[PI / 2.0, 3.0 * PI / 2.0]]));
        assert_eq!(l.corners, 0);
        assert!(l.text.starts_with("Cloth has no corners."), "{}", l.text);
        let fold = &l.folds[0];
        assert_eq!(fold.class, FoldClass::FoldedInHalf);
        assert!(
            fold.folded_corners.is_empty()
                && fold.corner_sides.is_empty()
                && fold.cut_sides.is_empty()
        );
        assert!(
            (fold.border_degrees[0] - 90.0).abs() < 1e-9
                && (fold.border_degrees[1] - 270.0).abs() < 1e-9
        );
        assert!(fold.text.contains("The border from 90° to 270° is folded over."), "{}", fold.text);
    }

    /// A fold turning `arcs` (border parameters of 76 vertices) over together.
    fn turning(arcs: &[[f64; 2]]) -> Folding {
        let arcs: Vec<Arc> = arcs.iter().map(|&[a, b]| Arc::new(angle(a), angle(b))).collect();
        Folding { fold: Fold::span(&arcs).unwrap(), arcs, line: None }
    }

    /// `folding` made along the line through `point` in `direction` (where its two points
    /// coincide on a stacked state).
    fn along(folding: Folding, point: [f64; 2], direction: [f64; 2]) -> Folding {
        let line = Line { point: point.into(), direction: direction.into() };
        Folding { line: Some(line), ..folding }
    }

    #[test]
    fn sequences_read_as_a_whole_and_the_text_says_the_class() {
        // The unit square: in half (left onto right, x = 0.5), then its top half down across
        // both layers (y = 0.5), then what is right of x = 0.75 (of both, 4 layers) over.
        let quarters = [
            turning(&[[47.5, 9.5]]),
            along(turning(&[[28.5, 47.5], [47.5, 66.5]]), [0.0, 0.5], [1.0, 0.0]),
        ];
        let mut eighths = quarters.to_vec();
        eighths.push(along(turning(&[[14.25, 42.75], [52.25, 4.75]]), [0.75, 0.0], [0.0, 1.0]));
        // In thirds: the left third in (x = 1/3), then the right one over it (x = 2/3).
        let third = |a: f64, b: f64| turning(&[[a, b]]);
        let sides = [third(50.7, 6.3), third(12.7, 44.3)];
        // Then in half across (y = 0.5).
        let sides_in_then_half = [sides[0].clone(), sides[1].clone(), turning(&[[28.5, 66.5]])];
        // In half (x = 0.5, right onto left), then a quarter of what is left in from each
        // side, each through both layers (x = 0.125, x = 0.375).
        let half_then_sides_in = [
            turning(&[[9.5, 47.5]]),
            along(turning(&[[16.625, 40.375], [54.625, 2.375]]), [0.125, 0.0], [0.0, 1.0]),
            turning(&[[7.125, 11.875], [45.125, 49.875]]),
        ];
        // One side folded, then a corner: no name for the whole.
        let other = [third(55.0, 2.0), turning(&[[12.0, 26.0]])];
        let cases: [(&[Folding], SequenceClass, &str); 6] = [
            (
                &quarters,
                SequenceClass::InQuarters,
                "Folded in quarters (in half, then in half again).",
            ),
            (
                &eighths,
                SequenceClass::InEighths,
                "Folded in eighths (in half, then in half again, and again).",
            ),
            (&sides, SequenceClass::InThirds, "Folded in thirds"),
            (
                &sides_in_then_half,
                SequenceClass::SidesInThenHalf,
                "Both sides folded in, then folded in half.",
            ),
            (
                &half_then_sides_in,
                SequenceClass::HalfThenSidesIn,
                "Folded in half, then both sides folded in.",
            ),
            (&other, SequenceClass::Folds, "Folded 2 times: one side folded, then corner folded."),
        ];
        for (folds, class, says) in cases {
            let l = label(&square(), &SQUARE, folds);
            let sequence = l.sequence.as_ref().expect("two folds or more");
            assert_eq!(sequence.class, class, "{} {:?}", l.text, sequence.across_percent);
            assert!(sequence.text.starts_with(says), "{}", sequence.text);
            assert!(l.text.contains(&sequence.text), "{}", l.text);
            assert_eq!(sequence.in_half.len(), folds.len());
        }
        assert!(label(&square(), &SQUARE, &quarters[..1]).sequence.is_none());
    }

    #[test]
    fn a_later_fold_is_told_by_where_it_lies_across_its_state() {
        let across = |folds: &[Folding]| {
            let l = label(&square(), &SQUARE, folds);
            let sequence = l.sequence.expect("two folds or more");
            let percent: Vec<f64> =
                sequence.across_percent.iter().map(|p| p.expect("a line")).collect();
            (l.folds, percent, sequence.text)
        };
        // The eighths' third fold turns 75 % of the start border over, and half its state.
        let eighths = [
            turning(&[[47.5, 9.5]]),
            along(turning(&[[28.5, 66.5]]), [0.0, 0.5], [1.0, 0.0]),
            along(turning(&[[14.25, 42.75], [52.25, 4.75]]), [0.75, 0.0], [0.0, 1.0]),
        ];
        let (folds, percent, _) = across(&eighths);
        assert!((folds[2].folded_percent - 75.0).abs() < 1.0, "{}", folds[2].folded_percent);
        assert_eq!(folds[2].class, FoldClass::FoldedInHalf, "{}", folds[2].text);
        // Within a vertex: the square's vertices are 1/19 apart.
        for p in percent {
            assert!((p - 50.0).abs() < 3.0, "{p}");
        }
        // A towel's left quarter in (x = 1/4), then what is left folded in half the same way
        // (x = 5/8): 25 % and 50 % across, though the second turns 37.5 % of the border.
        let side_then_half = [turning(&[[52.25, 4.75]]), turning(&[[11.875, 45.125]])];
        let (folds, percent, text) = across(&side_then_half);
        assert!((folds[1].folded_percent - 43.75).abs() < 1e-9, "{}", folds[1].folded_percent);
        assert!((percent[0] - 25.0).abs() < 3.0 && (percent[1] - 50.0).abs() < 3.0, "{percent:?}");
        assert_eq!(folds[1].class, FoldClass::FoldedInHalf);
        assert_eq!(text, "Folded 2 times: one side folded, then folded in half.");
        // Nor is a later fold askew: the start border's sides are not its state's.
        let askew = Fold::new(angle(5.32), angle(44.84));
        assert_eq!(label_fold(76, &SQUARE, askew, false, None).class, FoldClass::FoldedInHalfAskew);
        assert_eq!(
            label_fold(76, &SQUARE, askew, false, Some(true)).class,
            FoldClass::FoldedInHalf
        );
        // Stacked layers whose two points coincide, without a line: nowhere across.
        let unseen = [turning(&[[47.5, 9.5]]), turning(&[[28.5, 66.5]])];
        let l = label(&square(), &SQUARE, &unseen);
        let sequence = l.sequence.expect("two folds");
        assert_eq!(sequence.across_percent[1], None);
        assert_eq!(sequence.in_half, vec![true, false]);
    }

    #[test]
    fn a_multi_arc_fold_names_only_the_corners_its_arcs_turn() {
        // Two flaps, around corners 2 and 4; corner 3 lies between them and stays.
        let l = label(&square(), &SQUARE, &[turning(&[[12.0, 26.0], [50.0, 64.0]])]);
        let fold = &l.folds[0];
        assert_eq!(fold.folded_corners, vec![2, 4]);
        assert!(fold.text.contains("Corners 2, 4 are folded"), "{}", fold.text);
        assert!(!fold.text.contains("2, 3"), "{}", fold.text);
    }
}
