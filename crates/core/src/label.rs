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
//! ([`SequenceClass`], our extension): each fold "in half" when it turns over half the
//! border's vertices of the state it is made on (within [`SEQUENCE_HALF_PERCENT`]), "in
//! quarters" for two such folds, "in eighths" for three; "in thirds" for two sides folded in
//! alike (less than half each) at disjoint ends of the border; "both sides folded in, then
//! folded in half" for those two and a fold in half after them, "folded in half, then both
//! sides folded in" for the other order. The sentence is made from the class, so the text
//! and the structured field cannot disagree.
//!
//! ```
//! use close_core::geometry::{Fold, Folding};
//! use close_core::label::{label, FoldClass};
//! use std::f64::consts::PI;
//! // A square of 8 vertices with corners at 0, 2, 4, 6, folded along the diagonal 0–4.
//! let l = label(8, &[0, 2, 4, 6], &[Folding::new(Fold::new(0.0, PI))]);
//! assert_eq!(l.folds[0].class, FoldClass::DiagonallyFoldedInHalf);
//! assert_eq!(l.folds[0].folded_corners, vec![2]);
//! ```

use serde::{Deserialize, Serialize};

use crate::angle::{angle_to_param, wrap_tau, ON_LINE_EDGES};
use crate::geometry::{Arc, Fold, Folding};

/// More corners than this and the cloth is called circular.
pub const CIRCULAR_CORNERS: usize = 20;
/// A corner closer than [`ON_LINE_EDGES`] to a fold point lies on the fold line, or closer
/// than this share of the border: a simulated cloth's fold through a corner misses it by a
/// vertex or two (1.1 of 172 on `physics__pentagon_f1_half_axis`, 1.4 of 190 on
/// `physics__trousers_f1_half_left_onto_right`), a few degrees on the fold circle.
const ON_LINE_SHARE: f64 = 0.015;
/// Percentages this close count as equal (askew otherwise).
const EVEN_PERCENT: f64 = 10.0;
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

/// A fold of a sequence turning this close to 50% of the border's vertices is "in half"
/// (tighter than `HALF_PERCENT`: a towel's third, 40% of its border, is not a half).
pub const SEQUENCE_HALF_PERCENT: f64 = 6.0;

/// How a sequence of folds reads as a whole.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum SequenceClass {
    /// Two folds, each in half.
    InQuarters,
    /// Three folds, each in half.
    InEighths,
    /// Two sides folded in (less than half each, alike) at disjoint ends of the border.
    InThirds,
    /// Two sides folded in at disjoint ends, then a fold in half.
    SidesInThenHalf,
    /// A fold in half, then two sides of it folded in at disjoint ends.
    HalfThenSidesIn,
    /// Any other sequence, told fold by fold.
    Folds,
}

/// A sequence of folds read as a whole.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct SequenceLabel {
    pub class: SequenceClass,
    /// Whether each fold, in order, turned half the border over (within
    /// [`SEQUENCE_HALF_PERCENT`]).
    pub in_half: Vec<bool>,
    pub text: String,
}

/// The sequence label of `folds` (two or more) and their labels.
fn label_sequence(n: usize, folds: &[Folding], labels: &[FoldLabel]) -> SequenceLabel {
    let in_half: Vec<bool> =
        labels.iter().map(|l| (l.folded_percent - 50.0).abs() <= SEQUENCE_HALF_PERCENT).collect();
    // A side folded in: less than half, and no corner or diagonal fold (a third of a
    // towel, 40 % of its border, is "folded in half" alone by the wider HALF_PERCENT).
    let side_in = |k: usize| {
        labels[k].folded_percent < 50.0 - SEQUENCE_HALF_PERCENT
            && !matches!(
                labels[k].class,
                FoldClass::CornerFolded | FoldClass::DiagonallyFoldedInHalf
            )
    };
    // Folds turning disjoint ends of the start border (no vertex on both).
    let disjoint = |a: &Folding, b: &Folding| {
        !a.arcs.iter().any(|x| {
            b.arcs.iter().any(|y| {
                (0..n).any(|v| {
                    x.folds_vertex(n, v, ON_LINE_EDGES) && y.folds_vertex(n, v, ON_LINE_EDGES)
                })
            })
        })
    };
    // Folds j and k: two sides folded in alike at disjoint ends.
    let ends = |j: usize, k: usize| {
        side_in(j)
            && side_in(k)
            && (labels[j].folded_percent - labels[k].folded_percent).abs() <= EVEN_PERCENT
            && disjoint(&folds[j], &folds[k])
    };
    let class = match (folds.len(), in_half.as_slice()) {
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
    SequenceLabel { class, in_half, text }
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

/// Label a border of `n` vertices with corners at `corner_vertices` (sorted) and `folds`,
/// in order. A fold of one arc is labelled by its fold (f1, f2). A fold of several arcs (a
/// multi-arc fold) is classed by the pair that spans its arcs; its folded corners and share
/// are those of its arcs, and its sentence says how many separate flaps turned over. Lines
/// play no part.
///
/// A cloth with no fold is "not folded" — unless it changed: see `Label::changed_without_fold`.
pub fn label(n: usize, corner_vertices: &[usize], folds: &[Folding]) -> Label {
    let circular = corner_vertices.len() > CIRCULAR_CORNERS || corner_vertices.is_empty();
    let fold_labels: Vec<FoldLabel> = folds
        .iter()
        .map(|f| match f.arcs.as_slice() {
            several @ [_, _, ..] => label_multi_arc(n, corner_vertices, f.fold, several, circular),
            _ => label_fold(n, corner_vertices, f.fold, circular),
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
    let sequence = (fold_labels.len() >= 2).then(|| label_sequence(n, folds, &fold_labels));
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

fn label_fold(n: usize, corners: &[usize], fold: Fold, circular: bool) -> FoldLabel {
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
    // cut in half (the axis through a corner and the middle of the opposite side).
    let askew = match cut_sides.as_slice() {
        [a, b] => !even(a.folded_percent, b.folded_percent),
        [one] => !even(one.folded_percent, 50.0),
        _ => false,
    };
    let half = (folded_percent - 50.0).abs() <= HALF_PERCENT;
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
) -> FoldLabel {
    let mut out = label_fold(n, corners, fold, circular);
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

    /// Ordinary folds, one arc each.
    fn folds(pairs: &[[f64; 2]]) -> Vec<Folding> {
        pairs.iter().map(|&f| Folding::new(Fold::from(f))).collect()
    }
    fn angle(s: f64) -> f64 {
        param_to_angle(s, 76)
    }

    #[test]
    fn classes_of_the_napkin_folds() {
        let class =
            |a: f64, b: f64| label(76, &SQUARE, &folds(&[[angle(a), angle(b)]])).folds[0].class;
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
        let l = label(76, &SQUARE, &folds(&[[angle(12.0), angle(26.0)]]));
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
        let l = label(76, &SQUARE, &[folding]);
        assert_eq!(l.folds[0].folded_corners, vec![2]);
        assert_eq!(l.folds[0].folded_corner_vertices, vec![19]);
    }

    #[test]
    fn fold_on_a_corner_is_not_a_coin_flip() {
        // A hair either side of the corner gives the same answer.
        for eps in [-1e-9, 0.0, 1e-9] {
            let l = label(76, &SQUARE, &folds(&[[angle(eps), angle(38.0 - eps)]]));
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
            172,
            &pentagon,
            &folds(&[[param_to_angle(100.1, 172), param_to_angle(14.0, 172)]]),
        );
        let fold = &l.folds[0];
        assert_eq!(fold.class, FoldClass::FoldedInHalf, "{}", l.text);
        assert_eq!(fold.corners_on_fold_line, vec![4]);
        assert!(l.text.contains("through corner 4") && !l.text.contains("side 4–5"), "{}", l.text);
        // Off the middle of the opposite side, it is askew.
        let off = label(
            172,
            &pentagon,
            &folds(&[[param_to_angle(100.1, 172), param_to_angle(22.0, 172)]]),
        );
        assert_eq!(off.folds[0].class, FoldClass::FoldedInHalfAskew, "{}", off.text);
    }

    #[test]
    fn a_change_without_a_fold_is_said() {
        let mut l = label(76, &SQUARE, &[]);
        l.changed_without_fold(&[1]);
        assert_eq!(l.text, "Cloth has 4 corners. It changed, but no fold found (step 1).");
        let mut folded = label(76, &SQUARE, &folds(&[[angle(9.5), angle(47.5)]]));
        let before = folded.text.clone();
        folded.changed_without_fold(&[2, 3]);
        assert_eq!(folded.text, format!("{before} It changed, but no fold found (steps 2, 3)."));
        let mut still = label(76, &SQUARE, &[]);
        still.changed_without_fold(&[]);
        assert!(still.text.ends_with("It is not folded."));
    }

    #[test]
    fn round_cloth() {
        let corners: Vec<usize> = (0..64).collect();
        let l = label(64, &corners, &folds(&[[0.0, PI]]));
        assert!(l.circular);
        assert_eq!(l.folds[0].class, FoldClass::FoldedInHalf);
        assert!(l.text.starts_with("Cloth is circular"));
        let unfolded = label(64, &corners, &[]);
        assert!(unfolded.text.contains("not folded"));
    }

    #[test]
    fn a_cloth_without_corners_is_told_by_its_border() {
        let l = label(160, &[], &folds(&[[PI / 2.0, 3.0 * PI / 2.0]]));
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

    #[test]
    fn sequences_read_as_a_whole_and_the_text_says_the_class() {
        // The square of 76 vertices: in half (left onto right), then its two top quarters
        // (one of each layer) down.
        let quarters = [turning(&[[47.5, 9.5]]), turning(&[[28.5, 47.5], [47.5, 66.5]])];
        // Opposite ends in (a third of the width each), then in half across.
        let third = |a: f64, b: f64| turning(&[[a, b]]);
        let sides = [third(50.7, 6.3), third(12.7, 44.3)];
        let sides_in_then_half = [sides[0].clone(), sides[1].clone(), turning(&[[9.5, 47.5]])];
        let half_then_sides_in = [turning(&[[9.5, 47.5]]), sides[0].clone(), sides[1].clone()];
        // One side folded, then a corner: no name for the whole.
        let other = [third(55.0, 2.0), turning(&[[12.0, 26.0]])];
        let cases: [(&[Folding], SequenceClass, &str); 5] = [
            (
                &quarters,
                SequenceClass::InQuarters,
                "Folded in quarters (in half, then in half again).",
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
            let l = label(76, &SQUARE, folds);
            let sequence = l.sequence.as_ref().expect("two folds or more");
            assert_eq!(sequence.class, class, "{}", l.text);
            assert!(sequence.text.starts_with(says), "{}", sequence.text);
            assert!(l.text.contains(&sequence.text), "{}", l.text);
            assert_eq!(sequence.in_half.len(), folds.len());
        }
        assert!(label(76, &SQUARE, &quarters[..1]).sequence.is_none());
    }

    #[test]
    fn a_multi_arc_fold_names_only_the_corners_its_arcs_turn() {
        // Two flaps, around corners 2 and 4; corner 3 lies between them and stays.
        let l = label(76, &SQUARE, &[turning(&[[12.0, 26.0], [50.0, 64.0]])]);
        let fold = &l.folds[0];
        assert_eq!(fold.folded_corners, vec![2, 4]);
        assert!(fold.text.contains("Corners 2, 4 are folded"), "{}", fold.text);
        assert!(!fold.text.contains("2, 3"), "{}", fold.text);
    }
}
