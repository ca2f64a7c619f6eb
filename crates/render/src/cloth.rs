//! The folded cloth seen from above, as the web app draws it: its layers, the height of
//! each border vertex, and each fold's line across the cloth it folds.
//!
//! A fold is known by the line it was made along and the arcs of the border it turned over (core's
//! [`Made`]; the last fold may still be turning, `turn` < 1, drawn from above: each point at
//! [`turn_about`]). The border itself is core's synthesised state ([`Stack`]): each vertex inside
//! an arc moves, and lies a layer above the stack it lands on, as the fold search synthesises a
//! fold ([`SynthesisParams::lift`] of the flat cloth's radius: one lift for the search and the
//! drawing). The cloth between the border's vertices is a set of layers, each a piece of the flat
//! cloth (a simple polygon) moved by the folds that turned it over:
//! - a fold cuts every layer along its line into pieces, one polygon per connected piece on
//!   each side: the line's crossings of a layer's outline, ordered along the line, pair up
//!   into the chords that lie inside it (a simple polygon is entered and left in turn), and
//!   each piece is walked along the outline, jumping along a chord at each crossing;
//! - a piece turns over with the fold when the border vertices it holds are the ones the
//!   fold moves (a concave outline may leave a piece on the fold's side that its arcs do not
//!   hold: it stays, as its vertices do), or, holding no border vertex (a piece cut out by
//!   earlier folds), when it lies on the side the moved vertices lie on;
//! - the pieces that turn over land on top, their order reversed, as a folded stack lands.
//!
//! A layer's `flips` counts how often it was turned over: odd, its underside shows. The
//! heights keep the layers apart ([`Layers::heights`]): the state's disk sees layers apart,
//! not two sheets at one height.
//!
//! ```
//! use close_core::border::Point;
//! use close_core::fold::state::Made;
//! use close_core::geometry::{Line, Point2, Vector2};
//! use close_render::cloth::layers;
//! // A square folded in half along x = 0.5: vertices 1 and 2 (x = 1) turn over.
//! let square: Vec<Point> = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
//!     .iter().map(|p| Point::new(p[0], p[1], 0.0)).collect();
//! let line = Line { point: Point2::new(0.5, 0.0), direction: Vector2::new(0.0, 1.0) };
//! let folded = layers(&square, &[Made { line, arcs: vec![[0.5, 2.5]] }], 1.0);
//! assert_eq!(folded.layers.iter().map(|l| l.flips).collect::<Vec<_>>(), [0, 1]);
//! assert!(folded.heights[1] > 0.0 && folded.heights[0] == 0.0);
//! ```

use serde::Serialize;

use close_core::analysis::Analysis;
use close_core::angle::ArcVertices;
use close_core::border::{to_xyz, Normalisation, Point};
use close_core::error::Result;
#[cfg(doc)]
use close_core::fold::params::SynthesisParams;
use close_core::fold::state::{Made, Stack};
use close_core::fold::Params;
use close_core::geometry::{Folding, Line};
use close_core::interpolate::{turn_about, Interpolation, Motion};
use close_core::plan::{Action, Case, PlanStep};

/// One fold as drawn: as made, and how far it has turned (0 not at all, 1 folded over, the
/// reflection across its line).
#[derive(Clone, Copy)]
struct Drawing<'a> {
    made: &'a Made,
    turn: f64,
}

impl Drawing<'_> {
    /// Where the fold takes `p`.
    fn moves(&self, p: &Point) -> Point {
        if self.turn >= 1.0 {
            self.made.line.reflect(p)
        } else {
            turn_about(p, &self.made.line, self.turn)
        }
    }

    /// Per vertex of a border of `n`: whether the fold moves it.
    fn moved(&self, n: usize) -> Vec<bool> {
        let mut moved = vec![false; n];
        if self.turn > 0.0 {
            for arc in &self.made.arcs {
                for v in ArcVertices::of(n, arc[0], arc[1]).vertices() {
                    moved[v] = true;
                }
            }
        }
        moved
    }
}

/// One layer of cloth: a polygon (XY) and how often it was turned over.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Layer {
    pub points: Vec<[f64; 2]>,
    pub flips: usize,
}

/// The cloth after some folds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Layers {
    /// Bottom first: each drawn over the ones before it.
    pub layers: Vec<Layer>,
    /// Each border vertex's height: its own z, each fold that turned it lifting it over
    /// what it lies on (see the module doc).
    pub heights: Vec<f64>,
    /// Each fold's line across the cloth it folded (XY): from the least to the greatest
    /// projection of that state's border on the line.
    pub lines: Vec<[[f64; 2]; 2]>,
    /// The border after the folds (each vertex moved by the folds that moved it).
    #[serde(skip)]
    pub border: Vec<Point>,
}

/// A polygon corner: where it is, and the border vertex it is (none for a cut's point).
#[derive(Debug, Clone, Copy)]
struct Corner {
    at: Point,
    vertex: Option<usize>,
}

type Piece = Vec<Corner>;

/// The cloth of `flat` (a border, anticlockwise) after `folds`, made in order, the last of
/// them turned `turn` of the way over (1: all folded).
pub fn layers(flat: &[Point], folds: &[Made], turn: f64) -> Layers {
    let n = flat.len();
    let radius = Normalisation::of(flat).map_or(1.0, |m| m.radius);
    let lift = Params::default().synthesis.lift * radius;
    let mut state = Stack::flat(flat);
    let mut stack: Vec<(Piece, usize)> =
        vec![(flat.iter().enumerate().map(|(k, &at)| Corner { at, vertex: Some(k) }).collect(), 0)];
    let mut lines = Vec::with_capacity(folds.len());
    for (k, made) in folds.iter().enumerate() {
        let fold = Drawing { made, turn: if k + 1 == folds.len() { turn } else { 1.0 } };
        let border = state.points().to_vec();
        lines.push(across(&border, &made.line));
        let moved = fold.moved(n);
        if !moved.contains(&true) {
            continue;
        }
        let side = fold_side(&border, &moved, &made.line);
        let (mut kept, mut turned) = (Vec::new(), Vec::new());
        for (piece, flips) in &stack {
            for (piece, positive) in split(piece, &made.line) {
                if turns(&piece, positive, side, &moved) {
                    let piece = piece.iter().map(|c| Corner { at: fold.moves(&c.at), ..*c });
                    turned.push((piece.collect(), flips + 1));
                } else {
                    kept.push((piece, *flips));
                }
            }
        }
        turned.reverse();
        kept.extend(turned);
        stack = kept;
        state.fold(made, lift);
        if fold.turn < 1.0 {
            // Still turning: the flap drawn where the turn has taken it so far.
            let mut drawn = state.points().to_vec();
            for v in (0..n).filter(|&v| moved[v]) {
                let at = fold.moves(&border[v]);
                drawn[v] = Point::new(at.x, at.y, drawn[v].z);
            }
            state = Stack::flat(&drawn);
        }
    }
    let layers = stack
        .into_iter()
        .map(|(piece, flips)| Layer {
            points: piece.iter().map(|c| [c.at.x, c.at.y]).collect(),
            flips,
        })
        .collect();
    let border = state.points().to_vec();
    Layers { layers, heights: border.iter().map(|p| p.z).collect(), lines, border }
}

/// `flat` with the `prior` folds made on it in order, each as an analysis step reports it
/// (its `line` by default through the first arc's start and the last arc's end on the state
/// it folds): the state they leave, and each as made.
pub fn make(flat: &[Point], prior: &[Folding]) -> Result<(Vec<Point>, Vec<Made>)> {
    let (state, lines) = close_core::interpolate::fold_in_turn(flat, prior)?;
    let n = flat.len();
    let made = prior
        .iter()
        .zip(lines)
        .map(|(fold, line)| Made::from_angles(line, &fold.arcs, n))
        .collect();
    Ok((state, made))
}

/// One state of a motion as drawn: the cloth's layers and heights, and the line of the fold
/// that moves across the state it folds (none when that fold's two points coincide).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Drawn {
    pub layers: Vec<Layer>,
    pub heights: Vec<f64>,
    pub segment: Option<[[f64; 2]; 2]>,
}

/// The states of `interpolation`, the `motion` made on `base`, as drawn: `base` is the state
/// the `prior` folds (as [`make`] made them) leave `flat` in.
pub fn motion_states(
    flat: &[Point],
    prior: &[Made],
    base: &[Point],
    motion: &Motion,
    interpolation: &Interpolation,
) -> Vec<Drawn> {
    let n = flat.len();
    (0..interpolation.borders.len())
        .map(|k| {
            let moving = match motion {
                Motion::Between { .. } => {
                    let fold = interpolation.folds[k];
                    let line = fold.line_on(base, None);
                    line.map(|line| (Made::from_angles(line, &[fold.arc()], n), 1.0))
                }
                Motion::Turn { arcs, .. } => interpolation.line.map(|line| {
                    let turn = interpolation.turns.as_ref().map_or(1.0, |t| t[k]);
                    (Made::from_angles(line, arcs, n), turn)
                }),
            };
            let turn = moving.as_ref().map_or(1.0, |m| m.1);
            let folds: Vec<Made> =
                prior.iter().cloned().chain(moving.as_ref().map(|m| m.0.clone())).collect();
            let cloth = layers(flat, &folds, turn);
            Drawn {
                segment: moving.map(|m| across(base, &m.0.line)),
                layers: cloth.layers,
                heights: cloth.heights,
            }
        })
        .collect()
}

/// One state of a plan as drawn: its border, its layers and the line of the step that led
/// to it (across the state it folds, or for an unfold the state it goes back to).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Pictured {
    pub border: Vec<[f64; 3]>,
    pub layers: Vec<Layer>,
    pub segment: Option<[[f64; 2]; 2]>,
}

/// The states a plan of `case` and `steps` goes through from the analysed state, as drawn:
/// the state now (the analysis's folds made along its lines), then one per step. An unfold
/// takes the last fold back; a fold folds the flat cloth (after the unfolds, or in place
/// of the folds now when the plan goes there directly).
pub fn plan_states(analysis: &Analysis, case: Case, steps: &[PlanStep]) -> Result<Vec<Pictured>> {
    let flat = analysis.start_border();
    let (_, mut made) = make(flat, &analysis.foldings())?;
    let n = flat.len();
    let pictured = |made: &[Made], segment: Option<&Line>| {
        let cloth = layers(flat, made, 1.0);
        Pictured {
            segment: segment.map(|line| across(&cloth.border, line)),
            border: cloth.border.iter().map(to_xyz).collect(),
            layers: cloth.layers,
        }
    };
    let mut out = vec![pictured(&made, None)];
    for step in steps {
        match step.action {
            Action::Unfold => {
                let undone = made.pop();
                out.push(pictured(&made, undone.as_ref().map(|m| &m.line)));
            }
            Action::Fold => {
                if case == Case::Direct {
                    made.clear();
                }
                // Along the line the plan made it along, on the state before it.
                let line = step.line;
                if let Some(line) = line {
                    made.push(Made::from_angles(line, &[step.fold.arc()], n));
                }
                let mut state = pictured(&made, None);
                state.segment = line.map(|line| across(flat, &line));
                out.push(state);
            }
        }
    }
    Ok(out)
}

/// The segment of `line` across the closed border `points`: from its first to its last
/// crossing of the border, the stretch of the line the cloth lies on (a line near a corner
/// of a garment crosses it there, not the whole garment's width); for a line that does not
/// cross it twice, from the least to the greatest projection of a point on the line.
pub fn across(points: &[Point], line: &Line) -> [[f64; 2]; 2] {
    let (px, py) = (line.point.x, line.point.y);
    let length = line.direction.x.hypot(line.direction.y);
    let (dx, dy) = (line.direction.x / length, line.direction.y / length);
    let along = |x: f64, y: f64| (x - px) * dx + (y - py) * dy;
    let extent = |t: &[f64]| {
        t.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)))
    };
    let crossings: Vec<f64> = (0..points.len())
        .filter_map(|k| {
            let (a, b) = (&points[k], &points[(k + 1) % points.len()]);
            let (oa, ob) = (offset(a, line), offset(b, line));
            // Where the edge meets the line (at its first end when it lies along the line).
            let s = if oa == ob { 0.0 } else { oa / (oa - ob) };
            (oa * ob <= 0.0).then(|| along(a.x + s * (b.x - a.x), a.y + s * (b.y - a.y)))
        })
        .collect();
    let (lo, hi) = match extent(&crossings) {
        (lo, hi) if lo < hi => (lo, hi),
        _ => extent(&points.iter().map(|p| along(p.x, p.y)).collect::<Vec<_>>()),
    };
    let (lo, hi) = if lo <= hi { (lo, hi) } else { (0.0, 0.0) };
    [[px + lo * dx, py + lo * dy], [px + hi * dx, py + hi * dy]]
}

/// Signed distance of `p` from `line`, positive on its left.
fn offset(p: &Point, line: &Line) -> f64 {
    let (ux, uy) = (line.direction.x, line.direction.y);
    (p.y - line.point.y) * ux - (p.x - line.point.x) * uy
}

/// Whether the vertices the fold moves lie mostly on the line's left.
fn fold_side(border: &[Point], moved: &[bool], line: &Line) -> bool {
    let sum: f64 = border.iter().zip(moved).filter(|(_, &m)| m).map(|(p, _)| offset(p, line)).sum();
    sum >= 0.0
}

/// Whether a piece on the `positive` side turns over with a fold that moves the `moved`
/// vertices and lies on the `side` side (see the module doc).
fn turns(piece: &[Corner], positive: bool, side: bool, moved: &[bool]) -> bool {
    let (mut turning, mut staying) = (0, 0);
    for v in piece.iter().filter_map(|c| c.vertex) {
        if moved.get(v).copied().unwrap_or(false) {
            turning += 1;
        } else {
            staying += 1;
        }
    }
    match turning.cmp(&staying) {
        std::cmp::Ordering::Greater => true,
        std::cmp::Ordering::Less => false,
        std::cmp::Ordering::Equal => positive == side,
    }
}

/// The pieces of the simple polygon `piece` on either side of `line`, each with whether it
/// lies on the left. A point on the line counts as left, so every crossing lies strictly
/// inside an edge. A polygon that is not simple (its crossings do not pair up as a simple
/// polygon's do) is cut into two half-planes instead.
fn split(piece: &[Corner], line: &Line) -> Vec<(Piece, bool)> {
    let left: Vec<bool> = piece.iter().map(|c| offset(&c.at, line) >= 0.0).collect();
    if left.iter().all(|&l| l) || left.iter().all(|&l| !l) {
        return vec![(piece.to_vec(), left.first().copied().unwrap_or(true))];
    }
    // The outline with a node at each crossing: (corner, side; None at a crossing).
    let n = piece.len();
    let mut nodes: Vec<(Corner, Option<bool>)> = Vec::with_capacity(n + 8);
    for k in 0..n {
        let (a, b) = (piece[k], piece[(k + 1) % n]);
        nodes.push((a, Some(left[k])));
        if left[k] != left[(k + 1) % n] {
            let (sa, sb) = (offset(&a.at, line), offset(&b.at, line));
            let t = sa / (sa - sb);
            let at = a.at + (b.at - a.at) * t;
            nodes.push((Corner { at, vertex: None }, None));
        }
    }
    // Crossings in order along the line; consecutive ones bound a chord inside.
    let along = |p: &Point| {
        (p.x - line.point.x) * line.direction.x + (p.y - line.point.y) * line.direction.y
    };
    let mut crossings: Vec<usize> = (0..nodes.len()).filter(|&k| nodes[k].1.is_none()).collect();
    crossings.sort_by(|&a, &b| along(&nodes[a].0.at).total_cmp(&along(&nodes[b].0.at)));
    let mut partner = vec![usize::MAX; nodes.len()];
    for pair in crossings.chunks(2) {
        if let [a, b] = *pair {
            partner[a] = b;
            partner[b] = a;
        }
    }
    walk(&nodes, &partner).unwrap_or_else(|| halves(piece, line))
}

/// The pieces of an outline with its crossings (`nodes`) and their chords (`partner`): from
/// each corner not yet taken, along the outline, across a chord at each crossing, back to
/// where it began. `None` when the walk does not close as a simple polygon's does.
fn walk(nodes: &[(Corner, Option<bool>)], partner: &[usize]) -> Option<Vec<(Piece, bool)>> {
    let len = nodes.len();
    let mut taken = vec![false; len];
    let mut pieces = Vec::new();
    for start in 0..len {
        let Some(side) = nodes[start].1 else { continue };
        if taken[start] {
            continue;
        }
        let mut piece = Vec::new();
        let mut at = start;
        for _ in 0..=len {
            piece.push(nodes[at].0);
            taken[at] = true;
            let mut next = (at + 1) % len;
            if nodes[next].1.is_none() {
                let other = *partner.get(next)?;
                if other >= len {
                    return None;
                }
                piece.push(nodes[next].0);
                piece.push(nodes[other].0);
                next = (other + 1) % len;
            }
            if next == start {
                break;
            }
            if nodes[next].1 != Some(side) || taken[next] {
                return None;
            }
            at = next;
        }
        if piece.len() > len + len / 2 + 2 {
            return None;
        }
        if piece.len() >= 3 {
            pieces.push((piece, side));
        }
    }
    Some(pieces)
}

/// The parts of `piece` in each half-plane of `line` (Sutherland–Hodgman, one edge each):
/// one polygon per side, joined along the line where the piece has several there.
fn halves(piece: &[Corner], line: &Line) -> Vec<(Piece, bool)> {
    let n = piece.len();
    [true, false]
        .into_iter()
        .filter_map(|side| {
            let inside = |c: &Corner| (offset(&c.at, line) >= 0.0) == side;
            let mut out = Vec::new();
            for k in 0..n {
                let (a, b) = (piece[k], piece[(k + 1) % n]);
                if inside(&a) {
                    out.push(a);
                }
                if inside(&a) != inside(&b) {
                    let (sa, sb) = (offset(&a.at, line), offset(&b.at, line));
                    out.push(Corner { at: a.at + (b.at - a.at) * (sa / (sa - sb)), vertex: None });
                }
            }
            (out.len() >= 3).then_some((out, side))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use close_core::fold::apply;

    #[test]
    fn a_line_is_drawn_across_the_cloth_it_crosses_not_the_whole_cloth() {
        use close_core::geometry::{Point2, Vector2};
        // An L: a line through its short arm crosses the border at y = 0 and y = 1, while the
        // L spans y = 0 … 3 along it.
        let l: Vec<Point> =
            [[0.0, 0.0], [3.0, 0.0], [3.0, 1.0], [1.0, 1.0], [1.0, 3.0], [0.0, 3.0]]
                .iter()
                .map(|&[x, y]| Point::new(x, y, 0.0))
                .collect();
        let up = Vector2::new(0.0, 1.0);
        let arm = Line { point: Point2::new(2.0, 0.5), direction: up };
        let [a, b] = across(&l, &arm);
        assert!((a[0] - 2.0).abs() < 1e-12 && a[1].abs() < 1e-12, "{a:?}");
        assert!((b[0] - 2.0).abs() < 1e-12 && (b[1] - 1.0).abs() < 1e-12, "{b:?}");
        // A line that misses the cloth: its shadow on the line.
        let off = Line { point: Point2::new(5.0, 0.0), direction: up };
        let [a, b] = across(&l, &off);
        assert!(a[1].abs() < 1e-12 && (b[1] - 3.0).abs() < 1e-12, "{a:?} {b:?}");
    }
    use close_core::geometry::{Point2, Vector2};

    /// The line through `point` along `direction`.
    fn line_at(point: [f64; 2], direction: [f64; 2]) -> Line {
        Line {
            point: Point2::new(point[0], point[1]),
            direction: Vector2::new(direction[0], direction[1]),
        }
    }

    /// A polygon through `corners` with `per` vertices a side, anticlockwise.
    fn outline(corners: &[[f64; 2]], per: usize) -> Vec<Point> {
        let m = corners.len();
        (0..m * per)
            .map(|k| {
                let (a, b) = (corners[k / per], corners[(k / per + 1) % m]);
                let t = (k % per) as f64 / per as f64;
                Point::new(a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), 0.0)
            })
            .collect()
    }

    /// Twice the signed area of a polygon.
    fn area(points: &[[f64; 2]]) -> f64 {
        let n = points.len();
        (0..n)
            .map(|k| {
                let (a, b) = (points[k], points[(k + 1) % n]);
                a[0] * b[1] - b[0] * a[1]
            })
            .sum::<f64>()
            / 2.0
    }

    /// Whether XY point `p` lies inside `polygon` (even–odd).
    fn inside(p: [f64; 2], polygon: &[[f64; 2]]) -> bool {
        let n = polygon.len();
        (0..n)
            .filter(|&k| {
                let (a, b) = (polygon[k], polygon[(k + 1) % n]);
                (a[1] > p[1]) != (b[1] > p[1])
                    && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
            })
            .count()
            % 2
            == 1
    }

    #[test]
    fn a_half_fold_gives_a_base_and_a_flap_of_half_the_area() {
        let square = outline(&[[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]], 4);
        // Vertical line x = 1: the right side (parameters 2 → 10) turns over.
        let line = line_at([1.0, 0.0], [0.0, 1.0]);
        let made = Made { line, arcs: vec![[2.0, 10.0]] };
        let out = layers(&square, std::slice::from_ref(&made), 1.0);
        assert_eq!(out.layers.len(), 2);
        assert_eq!((out.layers[0].flips, out.layers[1].flips), (0, 1));
        for layer in &out.layers {
            assert!((area(&layer.points).abs() - 2.0).abs() < 1e-12);
            // Both lie on the left half.
            assert!(layer.points.iter().all(|p| p[0] <= 1.0 + 1e-12), "{:?}", layer.points);
        }
        // The heights: the flap the fold search's lift up (a share of the radius, √2 here).
        let lift = Params::default().synthesis.lift * 2f64.sqrt();
        for (v, h) in out.heights.iter().enumerate() {
            let want = if (3..=9).contains(&v) { lift } else { 0.0 };
            assert!((h - want).abs() < 1e-12, "vertex {v}: {h}");
        }
        assert_eq!(out.lines, vec![[[1.0, 0.0], [1.0, 2.0]]]);
        // Half turned: the flap drawn from above, squeezed onto the line's side it comes from.
        let half = layers(&square, &[made], 0.5);
        assert!(area(&half.layers[1].points).abs() < 1e-9, "seen edge-on, the flap has no area");
    }

    #[test]
    fn a_line_leaving_a_concave_outline_turns_only_the_piece_its_arcs_hold() {
        // A U: two legs joined at the bottom; the line y = 1.5 crosses both legs. Only the
        // right leg's top (its arc) turns over: the left leg's top stays where it is.
        let u = outline(
            &[
                [0.0, 0.0],
                [3.0, 0.0],
                [3.0, 3.0],
                [2.0, 3.0],
                [2.0, 1.0],
                [1.0, 1.0],
                [1.0, 3.0],
                [0.0, 3.0],
            ],
            4,
        );
        let n = u.len();
        let line = line_at([0.0, 1.5], [1.0, 0.0]);
        // The right leg's outline above the line: parameters 6, at (3, 1.5), to 15, at (2, 1.5).
        let arcs = vec![[6.0, 15.0]];
        let made = Made { line, arcs: arcs.clone() };
        let out = layers(&u, std::slice::from_ref(&made), 1.0);
        let flipped: Vec<&Layer> = out.layers.iter().filter(|l| l.flips == 1).collect();
        let kept: Vec<&Layer> = out.layers.iter().filter(|l| l.flips == 0).collect();
        assert_eq!((kept.len(), flipped.len()), (2, 1), "{:?}", out.layers);
        // The kept pieces: the U's bottom and the left leg's top; the right leg's top folded
        // down over the bottom, inside x ∈ [2, 3], y ∈ [0, 1.5].
        let total: f64 = out.layers.iter().map(|l| area(&l.points).abs()).sum();
        assert!((total - 7.0).abs() < 1e-9, "the layers keep the cloth's area: {total}");
        assert!(flipped[0]
            .points
            .iter()
            .all(|p| (2.0 - 1e-9..=3.0 + 1e-9).contains(&p[0]) && p[1] <= 1.5 + 1e-9));
        assert!(kept.iter().any(|l| inside([0.5, 2.5], &l.points)), "the left leg's top stays");
        // The outline agrees: the analysis's own border after the fold has the left leg's
        // top corner (0, 3) where it was, and the right leg's (3, 3) at (3, 0).
        let border = apply(&u, &made.folding(n));
        assert!(border.iter().any(|p| (p.x, p.y) == (0.0, 3.0)));
        assert!(border.iter().any(|p| (p.x - 3.0).abs() < 1e-12 && p.y.abs() < 1e-12));
        // Every piece lies inside the drawing's bounds: nothing spills off.
        for layer in &out.layers {
            assert!(layer
                .points
                .iter()
                .all(|p| (-1e-9..=3.0 + 1e-9).contains(&p[0])
                    && (-1e-9..=3.0 + 1e-9).contains(&p[1])));
        }
    }

    #[test]
    fn a_second_fold_cuts_every_layer_and_lands_on_top() {
        let square = outline(&[[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]], 4);
        let first = Made { line: line_at([1.0, 0.0], [0.0, 1.0]), arcs: vec![[2.0, 10.0]] };
        // Then the left half (now two layers) folded along y = 1, the top onto the bottom.
        // On the folded border, the upper half is parameters 6 → 14 (the two top sides).
        let second = Made { line: line_at([0.0, 1.0], [1.0, 0.0]), arcs: vec![[6.0, 14.0]] };
        let out = layers(&square, &[first, second], 1.0);
        let flips: Vec<usize> = out.layers.iter().map(|l| l.flips).collect();
        // Bottom half of each layer kept (base, flap), the top halves turned over, the flap's
        // first: [base, flap, flap's top (2 flips), base's top (1 flip)].
        assert_eq!(flips, [0, 1, 2, 1], "{:?}", out.layers);
        for layer in &out.layers {
            assert!((area(&layer.points).abs() - 1.0).abs() < 1e-9);
            assert!(layer.points.iter().all(|p| p[0] <= 1.0 + 1e-9 && p[1] <= 1.0 + 1e-9));
        }
        assert_eq!(out.lines.len(), 2);
    }

    #[test]
    fn a_fold_that_moves_nothing_leaves_the_cloth_and_a_crossed_outline_still_draws() {
        let square = outline(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], 2);
        let line = line_at([0.5, 0.0], [0.0, 1.0]);
        let still = layers(&square, &[Made { line, arcs: vec![[1.0, 5.0]] }], 0.0);
        assert_eq!(still.layers.len(), 1);
        assert!(still.heights.iter().all(|&h| h == 0.0));
        // A bow tie (not simple): cut into its two half-planes, never a panic or a hang.
        let tie: Vec<Point> = [[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]]
            .iter()
            .map(|p| Point::new(p[0], p[1], 0.0))
            .collect();
        let out = layers(&tie, &[Made { line, arcs: vec![[0.5, 2.5]] }], 1.0);
        assert!(!out.layers.is_empty());
    }
}
