// Canvas drawing shared by the Interpolate and Plan views: a viewport from border
// coordinates to pixels, cloth layers, fold lines, arrows and corner numbers.

import { TAU, applyFold, arcsVertices, foldLine, turnAbout, turnArcs } from "./fold.mjs";

/** Maps border points to a canvas, fitted to `bounds` {x0, x1, y0, y1} with `pad` pixels. */
export function viewport(canvas, bounds, pad) {
  const { width, height } = canvas;
  const b = bounds;
  const scale = Math.min((width - 2 * pad) / (b.x1 - b.x0 || 1), (height - 2 * pad) / (b.y1 - b.y0 || 1));
  const ox = (width - scale * (b.x1 - b.x0)) / 2;
  const oy = (height - scale * (b.y1 - b.y0)) / 2;
  return { X: (p) => ox + scale * (p[0] - b.x0), Y: (p) => height - (oy + scale * (p[1] - b.y0)) };
}

/**
 * A font size, in the canvas's own pixels, that shows as `css` CSS pixels at the width the
 * canvas is drawn at (a 900 px canvas on a phone is shrunk to a third); width/50 while the
 * canvas is not laid out.
 */
export function textSize(canvas, css = 13) {
  const shown = canvas.getBoundingClientRect().width;
  return Math.round(shown > 0 ? (css * canvas.width) / shown : canvas.width / 50);
}

/** XY bounds of several borders. */
export function boundsOf(borders) {
  const xs = borders.flatMap((b) => b.map((p) => p[0]));
  const ys = borders.flatMap((b) => b.map((p) => p[1]));
  return { x0: Math.min(...xs), x1: Math.max(...xs), y0: Math.min(...ys), y1: Math.max(...ys) };
}

/** Stroke (and optionally fill) the closed polygon `pts` through the viewport `v`. */
export function polygon(ctx, v, pts, { stroke, fill, width = 2, dash = [] }) {
  if (pts.length === 0) return;
  ctx.beginPath();
  pts.forEach((p, k) => (k ? ctx.lineTo(v.X(p), v.Y(p)) : ctx.moveTo(v.X(p), v.Y(p))));
  ctx.closePath();
  if (fill) {
    ctx.fillStyle = fill;
    ctx.fill("nonzero");
  }
  if (stroke) {
    ctx.setLineDash(dash);
    ctx.strokeStyle = stroke;
    ctx.lineWidth = width;
    ctx.stroke();
    ctx.setLineDash([]);
  }
}

/** Which side of the line a→b point p is on (sign of the cross product). */
const side = (a, b, p) => (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);

/** The part of polygon `pts` with side(a, b, ·)·sign ≥ 0 (Sutherland–Hodgman, one edge). */
function clip(pts, a, b, sign) {
  const out = [];
  pts.forEach((p, k) => {
    const q = pts[(k + 1) % pts.length];
    const [sp, sq] = [sign * side(a, b, p), sign * side(a, b, q)];
    if (sp >= 0) out.push(p);
    if ((sp >= 0) !== (sq >= 0)) {
      const t = sp / (sp - sq);
      out.push([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])]);
    }
  });
  return out.length >= 3 ? out : [];
}

/** Reflect p across the XY line through a and b. */
function reflect(p, a, b) {
  const [dx, dy] = [b[0] - a[0], b[1] - a[1]];
  const len2 = dx * dx + dy * dy || 1;
  const t = ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2;
  return [2 * (a[0] + t * dx) - p[0], 2 * (a[1] + t * dy) - p[1], p[2]];
}

/**
 * How a fold is made on `border`. A fold is [f1, f2], made along the line through its two
 * border points; or {fold, line, turn, arcs}, made along `line` (an analysis step's, for a
 * fold whose two points lie on top of each other or that turns several `arcs`, by default
 * [fold]) and turned the fraction `turn` of the way. Gives its angles, the arcs it turns,
 * two points a, b of its line, and where it takes a point p.
 */
export function made(border, f) {
  if (Array.isArray(f)) {
    const [a, b] = foldLine(border, f);
    return { fold: f, arcs: [f], a, b, move: (p) => reflect(p, a, b) };
  }
  // a and b span the border along the line, so they also draw it across the cloth.
  const { point, direction } = f.line;
  const along = border.map((p) => (p[0] - point[0]) * direction[0] + (p[1] - point[1]) * direction[1]);
  const at = (t) => [point[0] + t * direction[0], point[1] + t * direction[1], 0];
  const [lo, hi] = [Math.min(...along), Math.max(...along)];
  return { fold: f.fold, arcs: f.arcs ?? [f.fold], a: at(lo), b: at(hi > lo ? hi : lo + 1), move: (p) => turnAbout(p, f.line, f.turn ?? 1) };
}

/** Whether fold `f` has begun: a fold along a line turned by nothing leaves the cloth as it lies. */
const begun = (f) => Array.isArray(f) || (f.turn ?? 1) > 0;

/** The border after fold `f` (see `made`). */
export function folded(border, f) {
  if (Array.isArray(f)) return applyFold(border, f);
  // Only the arcs turn, as the analysis predicts (fold.mjs, checked against the server).
  return turnArcs(border, f.arcs ?? [f.fold], f.line, f.turn ?? 1);
}

/** The border after `folds` (see `made`), in order. */
export const foldAll = (border, folds) => folds.reduce(folded, border);

/**
 * The cloth's layers after `folds` (applied in order to `flat`, see `made`), bottom first:
 * each {points, flips}. A fold cuts every layer along its line; the parts on the folded side
 * turn over onto the top, their stacking order reversed, as a folded stack lands. The
 * outline of the border itself is `folded` applied in order; the layers are its fill.
 */
export function layers(flat, folds) {
  let stack = [{ points: flat, flips: 0 }];
  let border = flat;
  for (const f of folds.filter(begun)) {
    const { arcs, a, b, move } = made(border, f);
    const moved = arcsVertices(border.length, arcs);
    if (moved.length && Math.hypot(b[0] - a[0], b[1] - a[1]) > 0) {
      const centre = moved.reduce((s, v) => [s[0] + border[v][0], s[1] + border[v][1], 0], [0, 0, 0]).map((c) => c / moved.length);
      const sign = Math.sign(side(a, b, centre)) || 1;
      const keep = stack.map((l) => ({ ...l, points: clip(l.points, a, b, -sign) })).filter((l) => l.points.length);
      const flipped = stack
        .map((l) => ({ points: clip(l.points, a, b, sign).map(move), flips: l.flips + 1 }))
        .filter((l) => l.points.length)
        .reverse();
      stack = [...keep, ...flipped];
    }
    border = folded(border, f);
  }
  return { stack, border };
}

/** Layer fills: the cloth's top side blue, its underside (turned over once, thrice…) orange. */
const LAYER_FILL = ["rgba(31, 111, 235, 0.22)", "rgba(221, 107, 32, 0.42)"];

/** Draw the cloth after `folds`: each layer filled (flap over base, see-through), then the outline. */
export function drawCloth(ctx, v, flat, folds, { outline = "#1f6feb", width = 2.5 } = {}) {
  const { stack, border } = layers(flat, folds);
  for (const layer of stack) polygon(ctx, v, layer.points, { fill: LAYER_FILL[layer.flips % 2], stroke: "rgba(17, 24, 39, 0.25)", width: 1 });
  polygon(ctx, v, border, { stroke: outline, width });
  return border;
}

/** A straight line between two border points. */
export function line(ctx, v, p, q, color, width = 3) {
  ctx.beginPath();
  ctx.moveTo(v.X(p), v.Y(p));
  ctx.lineTo(v.X(q), v.Y(q));
  ctx.strokeStyle = color;
  ctx.lineWidth = width;
  ctx.stroke();
}

/**
 * A pick → place arrow from p to q (border points) bowed away from `centre` (a point of the
 * cloth), or towards it when there is no room on the canvas outside: a corner put straight back or folded straight over travels along the cloth's own
 * edge (a half fold's corner lands on the neighbouring corner), where a straight arrow would
 * hide under the outline. The bow, a quadratic curve whose middle stands a quarter of the
 * arrow's length off the chord (at least 14 px), keeps it visible. Gives its middle point
 * (canvas px).
 */
export function bowedArrow(ctx, v, p, q, centre, color) {
  const [x1, y1, x2, y2] = [v.X(p), v.Y(p), v.X(q), v.Y(q)];
  const len = Math.hypot(x2 - x1, y2 - y1) || 1;
  const [mx, my] = [(x1 + x2) / 2, (y1 + y2) / 2];
  // The chord's normal on the side away from the cloth's centre, unless the bow would leave
  // the canvas there: then over the cloth, where it is drawn on top.
  let [nx, ny] = [-(y2 - y1) / len, (x2 - x1) / len];
  if (nx * (mx - v.X(centre)) + ny * (my - v.Y(centre)) < 0) [nx, ny] = [-nx, -ny];
  const bow = Math.max(14, 0.25 * len);
  const inside = (x, y) => x > 8 && y > 8 && x < ctx.canvas.width - 8 && y < ctx.canvas.height - 8;
  if (!inside(mx + bow * nx, my + bow * ny)) [nx, ny] = [-nx, -ny];
  // The control point stands twice the bow off: a quadratic's middle is halfway to it.
  const [cx, cy] = [mx + 2 * bow * nx, my + 2 * bow * ny];
  ctx.beginPath();
  ctx.moveTo(x1, y1);
  ctx.quadraticCurveTo(cx, cy, x2, y2);
  ctx.strokeStyle = color;
  ctx.lineWidth = 2.5;
  ctx.stroke();
  // The head along the curve's end tangent (from the control point to q).
  const ang = Math.atan2(y2 - cy, x2 - cx);
  ctx.beginPath();
  ctx.moveTo(x2, y2);
  ctx.lineTo(x2 - 14 * Math.cos(ang - 0.4), y2 - 14 * Math.sin(ang - 0.4));
  ctx.lineTo(x2 - 14 * Math.cos(ang + 0.4), y2 - 14 * Math.sin(ang + 0.4));
  ctx.closePath();
  ctx.fillStyle = color;
  ctx.fill();
  ctx.beginPath();
  ctx.arc(x1, y1, 5, 0, TAU);
  ctx.fill();
  return [mx + bow * nx, my + bow * ny];
}

/** Vertex of a corner angle on a border of n vertices. */
export const cornerVertex = (c, n) => Math.round((c * n) / TAU) % n;

/**
 * Dot and number the corners (angles) at their vertices of `points`; corners that a fold
 * stacked on one another share one label ("1·4") instead of overprinting. A label goes above
 * right of its dot, or at the first other corner of it that is on the canvas and clear of
 * every dot and of the labels placed before it. Gives the labels' boxes (canvas px).
 */
export function labelCorners(ctx, v, points, corners, size) {
  const spots = new Map();
  corners.forEach((c, k) => {
    const p = points[cornerVertex(c, points.length)];
    const key = `${Math.round(v.X(p) / 4)},${Math.round(v.Y(p) / 4)}`;
    if (!spots.has(key)) spots.set(key, { x: v.X(p), y: v.Y(p), labels: [] });
    spots.get(key).labels.push(k + 1);
  });
  const dot = size / 3;
  const taken = [...spots.values()].map(({ x, y }) => ({ x: x - dot, y: y - dot, w: 2 * dot, h: 2 * dot }));
  const clear = (b) => b.x >= 0 && b.y >= 0 && b.x + b.w <= ctx.canvas.width && b.y + b.h <= ctx.canvas.height
    && !taken.some((o) => b.x < o.x + o.w && o.x < b.x + b.w && b.y < o.y + o.h && o.y < b.y + b.h);
  ctx.font = `${size}px system-ui, sans-serif`;
  ctx.textBaseline = "top";
  const boxes = [];
  for (const { x, y, labels } of spots.values()) {
    const text = labels.join("·");
    const [w, h] = [ctx.measureText(text).width, size];
    const gap = size / 2;
    const tries = [[x + gap, y - gap - h], [x - gap - w, y - gap - h], [x + gap, y + gap], [x - gap - w, y + gap]].map(([bx, by]) => ({ x: bx, y: by, w, h }));
    const box = tries.find(clear) || tries[0];
    taken.push(box);
    boxes.push(box);
    ctx.fillStyle = "#111827";
    ctx.beginPath();
    ctx.arc(x, y, dot, 0, TAU);
    ctx.fill();
    // A white halo keeps the number readable over the fills.
    ctx.lineWidth = 3;
    ctx.strokeStyle = "#fff";
    ctx.strokeText(text, box.x, box.y);
    ctx.fillText(text, box.x, box.y);
  }
  ctx.textBaseline = "alphabetic";
  return boxes;
}

/**
 * The folded border with every layer a fold turned over lifted a cloth's thickness (1% of
 * the cloth's radius) above what it lies on, as the built-in dataset folds: two layers at
 * the same height would give the disk near-singular values where they touch.
 */
export function stacked(flat, folds) {
  const n = flat.length;
  const centre = [0, 1].map((c) => flat.reduce((sum, p) => sum + p[c], 0) / n);
  const radius = Math.max(...flat.map((p) => Math.hypot(p[0] - centre[0], p[1] - centre[1])));
  let border = flat.map((p) => p.slice());
  for (const f of folds.filter(begun)) {
    const top = Math.max(...border.map((p) => p[2]));
    const after = folded(border, f);
    for (const v of arcsVertices(n, made(border, f).arcs)) after[v][2] = 2 * top + 0.01 * radius - border[v][2];
    border = after;
  }
  return border;
}
