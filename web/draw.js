// Canvas drawing shared by the Interpolate and Plan views: a viewport from border
// coordinates to pixels, the cloth's layers and outline, fold lines, arrows and corner
// numbers. Every shape drawn is one the server computed (its layers, borders and lines).

const TAU = 2 * Math.PI;

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

/** XY bounds of several borders (lists of [x, y, …] points). */
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

/** Layer fills: the cloth's top side blue, its underside (turned over once, thrice…) orange. */
const LAYER_FILL = ["rgba(31, 111, 235, 0.22)", "rgba(221, 107, 32, 0.42)"];

/**
 * Draw a cloth state the server computed: each of its `layers` ({points, flips}, bottom
 * first) filled (flap over base, see-through), then its `border`'s outline.
 */
export function drawCloth(ctx, v, layers, border, { outline = "#1f6feb", width = 2.5 } = {}) {
  for (const layer of layers) polygon(ctx, v, layer.points, { fill: LAYER_FILL[layer.flips % 2], stroke: "rgba(17, 24, 39, 0.25)", width: 1 });
  polygon(ctx, v, border, { stroke: outline, width });
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
  // A white halo keeps the arrow apart from the outline and the fills it crosses.
  for (const [stroke, width] of [["#fff", 7], [color, 3]]) {
    ctx.beginPath();
    ctx.moveTo(x1, y1);
    ctx.quadraticCurveTo(cx, cy, x2, y2);
    ctx.strokeStyle = stroke;
    ctx.lineWidth = width;
    ctx.stroke();
  }
  // The head along the curve's end tangent (from the control point to q).
  const ang = Math.atan2(y2 - cy, x2 - cx);
  ctx.beginPath();
  ctx.moveTo(x2, y2);
  ctx.lineTo(x2 - 18 * Math.cos(ang - 0.4), y2 - 18 * Math.sin(ang - 0.4));
  ctx.lineTo(x2 - 18 * Math.cos(ang + 0.4), y2 - 18 * Math.sin(ang + 0.4));
  ctx.closePath();
  ctx.strokeStyle = "#fff";
  ctx.lineWidth = 3;
  ctx.stroke();
  ctx.fillStyle = color;
  ctx.fill();
  ctx.beginPath();
  ctx.arc(x1, y1, 5, 0, TAU);
  ctx.fill();
  return [mx + bow * nx, my + bow * ny];
}

/**
 * Dot and number the corners (their border vertices, `corners`) on `points`; corners that a fold
 * stacked on one another share one label ("1·4") instead of overprinting. A label goes above
 * right of its dot, or at the first other corner of it that is on the canvas and clear of
 * every dot and of the labels placed before it. Gives the labels' boxes (canvas px).
 */
export function labelCorners(ctx, v, points, corners, size) {
  const spots = new Map();
  corners.forEach((vertex, k) => {
    const p = points[vertex];
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
