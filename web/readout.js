// Reading values off a disk picture: hover, tap or the arrow keys pick a cell, which is
// outlined on the disk and named under it (edges i and j, their pair distance d, the value;
// for a diff also the start and end values), and the two edges are marked on a border
// drawing (the border plot's picture, or the cloth Interpolate draws).
//
// The pictures are the server's, and so is every cell: which cell a pixel of a disk picture
// shows is read off the server's cell picture (GET /api/cells.png, the painter's own rule),
// whose pixel holds 1 + the cell's index; the values come ring by ring (GET /api/readout,
// POST /api/disk/cells): index k = (d − 1)·N + a is the pair of edges (a, a + d mod N), d = 1
// at the rim. Nothing here knows where a cell lies on the disk.

import { cellMap } from "./api.js";
import { el } from "./format.js";

/** The cell of ring index `k` on a disk of `n` edges: {k, i, j, d}. */
function cell(n, k) {
  const [a, d] = [k % n, Math.floor(k / n) + 1];
  return { k, i: a, j: (a + d) % n, d };
}

/** The cell of ring `d` starting at edge `a` (any integer a: taken mod n). */
const cellOf = (n, a, d) => cell(n, (d - 1) * n + (((a % n) + n) % n));

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
 * `load()` resolves to {n, size, values(k)} (values of ring index k; called once, on first
 * use; may be called again after `reset`); `onCell(cell, loaded)` hears of the cell picked
 * ({k, i, j, d}; null: none); the readout goes into `slot`, or right after the button. Gives
 * {reset(), pick(cell)}: forget the loaded values (the picture changed), pick a cell.
 */
export function readable(button, img, kind, load, onCell = () => {}, slot = null) {
  const out = el("output", { className: "cell-readout mono small" });
  out.setAttribute("aria-live", "polite");
  const wrap = el("span", { className: "picture-stack" });
  img.replaceWith(wrap);
  const mark = el("canvas", { className: "cell-mark" });
  mark.setAttribute("aria-hidden", "true");
  wrap.append(img, mark);
  const hint = el("span", { className: "visually-hidden", textContent: "Arrow keys read the disk's cells." });
  hint.id = `hint-${Math.random().toString(36).slice(2)}`;
  if (slot) slot.append(out, hint);
  else button.after(out, hint);
  button.setAttribute("aria-describedby", hint.id);
  let data = null;
  let pending = null;
  let current = null;
  const ready = () => {
    if (data) return Promise.resolve(data);
    if (!pending) {
      pending = load()
        .then(async (d) => (data = { ...d, cells: await cellMap(d.n, d.size) }))
        .finally(() => (pending = null));
    }
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
    const shown = SHOWN[kind](data.values(c.k));
    out.textContent = `edges i = ${c.i}, j = ${c.j} · d = ${c.d} · ${shown.text}`;
    out.dataset.value = String(shown.value);
    outline(mark, data, c);
    onCell(c, data);
  };
  /** The cell under a pointer event: the cell picture's pixel there. */
  const under = async (e) => {
    const d = await ready();
    const r = img.getBoundingClientRect();
    const [x, y] = [Math.floor(((e.clientX - r.left) * d.size) / r.width), Math.floor(((e.clientY - r.top) * d.size) / r.height)];
    const code = x >= 0 && y >= 0 && x < d.size && y < d.size ? d.cells[y * d.size + x] : 0;
    return code ? cell(d.n, code - 1) : null;
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
  button.addEventListener("focus", () => ready().then(() => show(current || cell(data.n, 0)), fail));
  button.addEventListener("blur", () => show(null));
  button.addEventListener("keydown", (e) => {
    const step = { ArrowLeft: [1, 0], ArrowRight: [-1, 0], ArrowUp: [0, -1], ArrowDown: [0, 1] }[e.key];
    if (!step || !data) return;
    e.preventDefault();
    const c = current || cell(data.n, 0);
    const l = Math.floor(data.n / 2);
    // Left turns anticlockwise (as angles grow); up goes towards the rim (d = 1).
    show(cellOf(data.n, c.i + step[0], Math.min(l, Math.max(1, c.d + step[1]))));
  });
  return {
    reset() {
      data = null;
      if (current) ready().then(() => show(current), fail);
    },
    pick: (c) => ready().then(() => show(c)),
  };
}

/**
 * Outline cell `c` on the canvas over the picture: the pixels of the cell picture that show
 * it, within two pixels of another cell, dark, and the other cell's pixels there white.
 */
function outline(canvas, { size, cells }, c) {
  canvas.width = canvas.height = size;
  const ctx = canvas.getContext("2d");
  const code = c.k + 1;
  let [x0, y0, x1, y1] = [size, size, -1, -1];
  for (let p = 0; p < cells.length; p++) {
    if (cells[p] !== code) continue;
    const [x, y] = [p % size, Math.floor(p / size)];
    [x0, y0, x1, y1] = [Math.min(x0, x), Math.min(y0, y), Math.max(x1, x), Math.max(y1, y)];
  }
  if (x1 < 0) return;
  const reach = Math.max(2, Math.round((2 * size) / 480));
  const [bx0, by0, bx1, by1] = [Math.max(0, x0 - reach), Math.max(0, y0 - reach), Math.min(size - 1, x1 + reach), Math.min(size - 1, y1 + reach)];
  const [w, h] = [bx1 - bx0 + 1, by1 - by0 + 1];
  const image = ctx.createImageData(w, h);
  const inside = (x, y) => x >= 0 && y >= 0 && x < size && y < size && cells[y * size + x] === code;
  for (let y = by0; y <= by1; y++) {
    for (let x = bx0; x <= bx1; x++) {
      const own = inside(x, y);
      let near = false;
      for (let dy = -reach; dy <= reach && !near; dy++) for (let dx = -reach; dx <= reach && !near; dx++) near = inside(x + dx, y + dy) !== own;
      if (!near) continue;
      const q = 4 * ((y - by0) * w + (x - bx0));
      const v = own ? 17 : 255;
      image.data.set([v, v, v, 255], q);
    }
  }
  ctx.putImageData(image, bx0, by0);
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
