// Reading values off a disk picture: hover, tap or the arrow keys pick a cell, which is
// outlined on the disk and named under it (edges i and j, their pair distance d, the value;
// for a diff also the start and end values), and the two edges are marked on a border
// drawing (the border plot's picture, or the cloth Interpolate draws).
//
// The pictures are the server's PNGs. The server says where the disk lies on them (centre
// and rim radius in the picture's pixels) and sends the disks' values (GET /api/readout,
// POST /api/disk/cells); the cell under a point follows from its polar coordinates as the
// server paints it (crates/render/src/render/sector_map.rs `sector_at`): with L = ⌊N/2⌋,
// ring d = L + 1 − ⌈r·L⌉ (1 at the rim), and the sector of the pair (a, a + d) is centred at
// θ = π(2a + d + 1)/N, one edge (2π/N) wide; angle 0 points right, angles grow anticlockwise.

import { el } from "./format.js";

/** The cell {i, j, d} under picture pixel (x, y) of a disk of `n` edges at `disk` {cx, cy, radius}; null off the disk. */
export function cellAt(disk, n, x, y) {
  const [dx, dy] = [x - disk.cx, disk.cy - y];
  const r = Math.hypot(dx, dy) / disk.radius;
  if (r > 1 || n < 2) return null;
  const l = Math.floor(n / 2);
  const d = Math.min(l, Math.max(1, l + 1 - Math.ceil(r * l)));
  const theta = (Math.atan2(dy, dx) + 2 * Math.PI) % (2 * Math.PI);
  const a = Math.round(((theta * n) / Math.PI - d - 1) / 2);
  return cell(n, a, d);
}

/** The cell of ring `d` starting at edge `a` (any integer: taken mod n). */
function cell(n, a, d) {
  const i = ((a % n) + n) % n;
  return { i, j: (i + d) % n, d };
}

/** Index of pair (i, j), i ≠ j, in a condensed pair vector of `n` edges (pairs i < j, row-major). */
export function condensedIndex(n, i, j) {
  const [a, b] = i < j ? [i, j] : [j, i];
  return a * n - (a * (a + 1)) / 2 + b - a - 1;
}

/** A value with about three significant digits, as the colour bars print them. */
export function fmtValue(v) {
  const a = Math.abs(v);
  if (a === 0) return "0";
  if (a < 1e-3 || a >= 1000) return v.toExponential(1);
  return v.toFixed(a >= 100 ? 0 : a >= 10 ? 1 : a >= 1 ? 2 : 3);
}

/**
 * What each disk picture shows of a pair's start and end values, and how to say it.
 * `values(c)` gives the numbers of a cell {start, end} (or {value} for a single disk).
 */
const SHOWN = {
  disk_start: (v) => ({ value: v.start, text: `value ${fmtValue(v.start)}` }),
  disk_end: (v) => ({ value: v.end, text: `value ${fmtValue(v.end)}` }),
  diff: (v) => {
    const value = Math.abs(Math.abs(v.end) - Math.abs(v.start));
    return { value, text: `| |end| − |start| | ${fmtValue(value)} (start ${fmtValue(v.start)}, end ${fmtValue(v.end)})` };
  },
  signed_diff: (v) => {
    const value = v.end - v.start;
    return { value, text: `Δ ${fmtValue(value)} (start ${fmtValue(v.start)}, end ${fmtValue(v.end)})` };
  },
  state: (v) => ({ value: v.value, text: `value ${fmtValue(v.value)}` }),
};

/**
 * Make the picture `img` inside the focusable `button` readable: `kind` is a key of SHOWN;
 * `load()` resolves to {n, disk, size, values(i, j)} (called once, on first use; may be
 * called again after `reset`); `onCell(cell, loaded)` hears of the cell picked (null: none).
 * Gives {reset(), pick(cell)}: forget the loaded values (the picture changed), pick a cell.
 */
export function readable(button, img, kind, load, onCell = () => {}) {
  const out = el("output", { className: "cell-readout mono small" });
  out.setAttribute("aria-live", "polite");
  const wrap = el("span", { className: "picture-stack" });
  img.replaceWith(wrap);
  const mark = el("canvas", { className: "cell-mark" });
  mark.setAttribute("aria-hidden", "true");
  wrap.append(img, mark);
  button.after(out);
  const hint = el("span", { className: "visually-hidden", textContent: "Arrow keys read the disk's cells." });
  hint.id = `hint-${Math.random().toString(36).slice(2)}`;
  out.after(hint);
  button.setAttribute("aria-describedby", hint.id);
  let data = null;
  let pending = null;
  let current = null;
  const ready = () => {
    if (data) return Promise.resolve(data);
    if (!pending) pending = load().then((d) => (data = d)).finally(() => (pending = null));
    return pending;
  };
  const show = (c) => {
    current = c;
    button.dataset.cell = c ? `${c.i},${c.j}` : "";
    if (!c || !data) {
      out.textContent = "";
      mark.getContext("2d").clearRect(0, 0, mark.width, mark.height);
      onCell(null, data);
      return;
    }
    const shown = SHOWN[kind](data.values(c.i, c.j));
    out.textContent = `edges i = ${c.i}, j = ${c.j} · d = ${c.d} · ${shown.text}`;
    out.dataset.value = String(shown.value);
    outline(mark, data, c);
    onCell(c, data);
  };
  /** The cell under a pointer event, in picture pixels. */
  const under = async (e) => {
    const d = await ready();
    const r = img.getBoundingClientRect();
    const [x, y] = [((e.clientX - r.left) * d.size) / r.width, ((e.clientY - r.top) * d.size) / r.height];
    return cellAt(d.disk, d.n, x, y);
  };
  const fail = (e) => {
    if (e.name !== "AbortError") out.textContent = `(no readout: ${e.message})`;
  };
  button.addEventListener("pointermove", (e) => {
    if (e.pointerType === "mouse") under(e).then(show, fail);
  });
  button.addEventListener("pointerleave", (e) => {
    if (e.pointerType === "mouse" && document.activeElement !== button) show(null);
  });
  // A tap on the disk reads it, and the click that follows does not enlarge; off the disk it
  // enlarges. The cell is known once the values are: `tap` says how far a touch has got
  // ("pending" → "cell" or "off"; "clicked" when the click came first).
  let tap = null;
  button.addEventListener("pointerdown", (e) => {
    if (e.pointerType === "mouse") return (tap = null);
    tap = "pending";
    under(e).then((c) => {
      const clicked = tap === "clicked";
      tap = clicked ? null : c ? "cell" : "off";
      if (c) show(c);
      else if (clicked) button.click();
    }, (e) => {
      tap = null;
      fail(e);
    });
  });
  button.addEventListener(
    "click",
    (e) => {
      if (tap === null || tap === "off") return void (tap = null);
      tap = tap === "pending" ? "clicked" : null;
      e.stopImmediatePropagation();
      e.preventDefault();
    },
    { capture: true },
  );
  button.addEventListener("focus", () => ready().then(() => show(current || cell(data.n, 0, 1)), fail));
  button.addEventListener("blur", () => show(null));
  button.addEventListener("keydown", (e) => {
    const step = { ArrowLeft: [1, 0], ArrowRight: [-1, 0], ArrowUp: [0, -1], ArrowDown: [0, 1] }[e.key];
    if (!step || !data) return;
    e.preventDefault();
    const c = current || cell(data.n, 0, 1);
    const l = Math.floor(data.n / 2);
    // Left turns anticlockwise (as angles grow); up goes towards the rim (d = 1).
    show(cell(data.n, c.i + step[0], Math.min(l, Math.max(1, c.d + step[1]))));
  });
  return {
    reset() {
      data = null;
      if (current) ready().then(() => show(current), fail);
    },
    pick: (c) => ready().then(() => show(c)),
  };
}

/** Outline cell `c` on the canvas over the picture: its annular sector, in picture pixels. */
function outline(canvas, { n, disk, size }, c) {
  canvas.width = canvas.height = size;
  const ctx = canvas.getContext("2d");
  const l = Math.floor(n / 2);
  const [inner, outer] = [((l - c.d) / l) * disk.radius, ((l - c.d + 1) / l) * disk.radius];
  // The sector of pair (a, a + d) with a = i: centred at π(2i + d + 1)/N; canvas angles turn clockwise.
  const theta = (Math.PI * (2 * c.i + c.d + 1)) / n;
  const [from, to] = [-(theta + Math.PI / n), -(theta - Math.PI / n)];
  ctx.beginPath();
  ctx.arc(disk.cx, disk.cy, outer, from, to);
  ctx.arc(disk.cx, disk.cy, inner, to, from, true);
  ctx.closePath();
  ctx.lineJoin = "round";
  for (const [colour, width] of [["#fff", (4 * size) / 480], ["#111", (2 * size) / 480]]) {
    ctx.strokeStyle = colour;
    ctx.lineWidth = width;
    ctx.stroke();
  }
}

/** The colours edge i and edge j are marked in. */
export const EDGE_COLOURS = ["#d81b60", "#1e88e5"];

/**
 * Mark edges i and j of each border of `borders` ([[x, y, z], …]) on `ctx`, through `at(p)`
 * → [px, py]: a thick line with a white halo, and its name at its middle; `scale` sizes
 * lines and text (1 for a 480 px picture).
 */
export function markEdges(ctx, borders, at, c, scale = 1) {
  if (!c) return;
  ctx.save();
  ctx.lineCap = "round";
  ctx.font = `bold ${Math.round(15 * scale)}px system-ui, sans-serif`;
  ctx.textAlign = "center";
  ctx.textBaseline = "middle";
  for (const border of borders) {
    const n = border.length;
    [c.i, c.j].forEach((e, k) => {
      const [a, b] = [at(border[e]), at(border[(e + 1) % n])];
      for (const [colour, width] of [["#fff", 9 * scale], [EDGE_COLOURS[k], 5 * scale]]) {
        ctx.strokeStyle = colour;
        ctx.lineWidth = width;
        ctx.beginPath();
        ctx.moveTo(...a);
        ctx.lineTo(...b);
        ctx.stroke();
      }
    });
  }
  // Names once, by the first border's edges, offset off the line.
  const first = borders[0];
  if (first) {
    [c.i, c.j].forEach((e, k) => {
      const [a, b] = [at(first[e]), at(first[(e + 1) % first.length])];
      const [mx, my] = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
      const len = Math.hypot(b[0] - a[0], b[1] - a[1]) || 1;
      const off = 14 * scale;
      const [tx, ty] = [mx - ((b[1] - a[1]) / len) * off, my + ((b[0] - a[0]) / len) * off];
      ctx.lineWidth = 4 * scale;
      ctx.strokeStyle = "#fff";
      ctx.strokeText(k ? "j" : "i", tx, ty);
      ctx.fillStyle = EDGE_COLOURS[k];
      ctx.fillText(k ? "j" : "i", tx, ty);
    });
  }
  ctx.restore();
}

/**
 * A canvas over picture `img` (a border plot of `size` px whose map is `transform` {x: [a, b],
 * y: [a, b]}) on which `show(borders, cell)` marks a cell's edges.
 */
export function edgeOverlay(img) {
  const canvas = el("canvas", { className: "edge-mark" });
  canvas.setAttribute("aria-hidden", "true");
  const wrap = el("span", { className: "picture-stack" });
  img.replaceWith(wrap);
  wrap.append(img, canvas);
  return {
    canvas,
    show(borders, transform, size, c) {
      canvas.width = canvas.height = size;
      const ctx = canvas.getContext("2d");
      ctx.clearRect(0, 0, size, size);
      if (!c || !transform) return;
      const at = (p) => [transform.x[0] * p[0] + transform.x[1], transform.y[0] * p[1] + transform.y[1]];
      markEdges(ctx, borders, at, c, size / 480);
    },
  };
}
