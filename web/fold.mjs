// Fold interpolation and reflection: the browser's copy of crates/core/src/interpolate.rs
// and crates/core/src/fold/reflect.rs (same rules, same floating-point order;
// tests/it/interpolate_parity.rs checks parity).
//
// A fold (f1, f2) folds the border arc walked anticlockwise from f1 to f2. Between two
// folds each endpoint moves linearly; the span (f2 − f1 mod 2π) moves straight from its
// start to its end value, never through 0 or 2π, and of the ways that do so the one with
// the least travel |d1| + |d2| wins (ties: the shortest way for f1).
//
// A fold of several arcs (an analysis step's `arcs`), or one made along a line of its own
// (`steps[k].line`), is turned over instead: every vertex inside one of its arcs turns about
// the one line by the same angle π·turn, seen from above (`turnArcs`); turn 1 is the
// reflection the analysis predicts, and vertices outside the arcs never move.

export const TAU = 2 * Math.PI;
// Rust's f64::MIN_POSITIVE (the smallest normal number).
const MIN_POSITIVE = 2.2250738585072014e-308;

/** Rust's f64::rem_euclid. */
function remEuclid(x, m) {
  const r = x % m;
  return r < 0 ? r + Math.abs(m) : r;
}

export function wrap(angle) {
  return remEuclid(angle, TAU);
}

/** x taken into (−π, π]. */
export function shortest(x) {
  const r = wrap(x);
  return r > Math.PI ? r - TAU : r;
}

/** How far each endpoint moves [d1, d2] going from fold `from` to fold `to`. */
export function displacements(from, to) {
  const spanChange = wrap(to[1] - to[0]) - wrap(from[1] - from[0]);
  const d1 = shortest(to[0] - from[0]);
  const cost = (d) => Math.abs(d) + Math.abs(d + spanChange);
  let best = d1;
  for (const d of [d1, d1 - TAU, d1 + TAU]) {
    if (cost(d) < cost(best) - 1e-12) best = d;
  }
  return [best, best + spanChange];
}

/** The fold at fraction tau ∈ [0, 1] of the way (tau 0 and 1 give the ends exactly). */
export function foldAt(from, to, tau) {
  if (tau <= 0) return [wrap(from[0]), wrap(from[1])];
  if (tau >= 1) return [wrap(to[0]), wrap(to[1])];
  const [d1, d2] = displacements(from, to);
  return [wrap(from[0] + tau * d1), wrap(from[1] + tau * d2)];
}

/** `steps` folds from `from` to `to`, both included. */
export function foldPath(from, to, steps) {
  const last = Math.max(steps - 1, 1);
  const out = [];
  for (let t = 0; t < steps; t++) {
    out.push(t === steps - 1 && t > 0 ? foldAt(from, to, 1) : foldAt(from, to, t / last));
  }
  return out;
}

/** Point at border parameter s (fractional vertex index, cyclic). */
export function pointAt(points, s) {
  const n = points.length;
  s = remEuclid(s, n);
  const k = Math.min(Math.floor(s), n - 1);
  const t = s - k;
  const a = points[k];
  const b = points[(k + 1) % n];
  return [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t];
}

/** Indices strictly inside the anticlockwise arc from f1 to f2. */
export function foldedVertices(n, fold) {
  const s1 = (wrap(fold[0]) * n) / TAU;
  const span = (wrap(fold[1] - fold[0]) * n) / TAU;
  const out = [];
  for (let v = 0; v < n; v++) {
    const offset = remEuclid(v - s1, n);
    if (offset > 1e-9 && offset < span - 1e-9) out.push(v);
  }
  return out;
}

/** Reflect p across the XY line through a and b (z kept). */
export function reflectXY(p, a, b) {
  const dx = b[0] - a[0];
  const dy = b[1] - a[1];
  const len2 = dx * dx + dy * dy;
  const norms = a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  if (len2 <= Number.EPSILON * Math.max(norms, MIN_POSITIVE)) return p.slice();
  const px = p[0] - a[0];
  const py = p[1] - a[1];
  const t = (px * dx + py * dy) / len2;
  const fx = a[0] + t * dx;
  const fy = a[1] + t * dy;
  return [2 * fx - p[0], 2 * fy - p[1], p[2]];
}

/** The border folded along `fold`, and the two points of the fold line. */
export function applyFold(points, fold) {
  const n = points.length;
  const toParam = (f) => (wrap(f) * n) / TAU;
  const a = pointAt(points, toParam(fold[0]));
  const b = pointAt(points, toParam(fold[1]));
  const out = points.map((p) => p.slice());
  for (const v of foldedVertices(n, fold)) out[v] = reflectXY(points[v], a, b);
  return out;
}

/** The fold line's end points on the flat border. */
export function foldLine(points, fold) {
  const n = points.length;
  return [pointAt(points, (wrap(fold[0]) * n) / TAU), pointAt(points, (wrap(fold[1]) * n) / TAU)];
}

/**
 * p turned about the XY line `line` ({point, direction}: the analysis's `steps[k].line`) by
 * the fraction `turn` of a half turn, seen from above (z kept): 1 is the reflection across
 * it, as the analysis folds a step whose two fold points lie on top of each other.
 */
export function turnAbout(p, line, turn = 1) {
  const [ux, uy] = line.direction;
  const t = (p[0] - line.point[0]) * ux + (p[1] - line.point[1]) * uy;
  const [fx, fy] = [line.point[0] + t * ux, line.point[1] + t * uy];
  const c = Math.cos(Math.PI * turn);
  return [fx + c * (p[0] - fx), fy + c * (p[1] - fy), p[2]];
}

/**
 * The XY line through a and b as {point, direction} (unit), as close_core's `Line::through`;
 * null when they coincide.
 */
export function lineThrough(a, b) {
  const dx = b[0] - a[0];
  const dy = b[1] - a[1];
  const len = Math.hypot(dx, dy);
  const scale = 1 + Math.hypot(a[0], a[1], a[2]) + Math.hypot(b[0], b[1], b[2]);
  return len > 1e-12 * scale ? { point: [a[0], a[1]], direction: [dx / len, dy / len] } : null;
}

/** p reflected across `line` ({point, direction}, unit) in XY, z kept: `Line::reflect`. */
export function reflectLine(p, line) {
  const [ux, uy] = line.direction;
  const px = p[0] - line.point[0];
  const py = p[1] - line.point[1];
  const t = px * ux + py * uy;
  return [line.point[0] + 2 * t * ux - px, line.point[1] + 2 * t * uy - py, p[2]];
}

/** Vertices strictly inside any of `arcs` (each [a, b], anticlockwise), increasing, each once. */
export function arcsVertices(n, arcs) {
  const inside = new Set(arcs.flatMap((arc) => foldedVertices(n, arc)));
  return [...inside].sort((a, b) => a - b);
}

/**
 * The line a turned fold uses: `line` made unit, or the line through the border points at
 * the first arc's start and the last arc's end (null when those coincide).
 */
export function arcsLine(points, arcs, line = null) {
  if (line) {
    const len = Math.hypot(line.direction[0], line.direction[1]);
    return { point: line.point.slice(), direction: [line.direction[0] / len, line.direction[1] / len] };
  }
  const [a, b] = foldLine(points, [arcs[0][0], arcs[arcs.length - 1][1]]);
  return lineThrough(a, b);
}

/**
 * `points` with `arcs` turned the fraction `turn` of a half turn about `line` (see
 * `arcsLine`): 0 leaves them as given, 1 reflects them (the analysis's prediction).
 */
export function turnArcs(points, arcs, line = null, turn = 1) {
  const out = points.map((p) => p.slice());
  const about = arcsLine(points, arcs, line);
  if (!about || turn <= 0) return out;
  for (const v of arcsVertices(points.length, arcs)) out[v] = turn >= 1 ? reflectLine(points[v], about) : turnAbout(points[v], about, turn);
  return out;
}

/** `steps` states of `turnArcs`, turns t/(steps−1) (both ends included): {turns, borders}. */
export function turnPath(points, arcs, line, steps) {
  const turns = Array.from({ length: steps }, (_, t) => t / (steps - 1));
  return { turns, borders: turns.map((turn) => turnArcs(points, arcs, line, turn)) };
}
