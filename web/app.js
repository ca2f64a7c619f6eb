// CloSE web app: browse the built-in samples, upload one, interpolate folds.
// Plain ES module, no build step; talks to the JSON API of src/server.

import { TAU, wrap, foldAt, applyFold, foldLine, foldPath, foldedVertices } from "./fold.mjs";

const $ = (sel, root = document) => root.querySelector(sel);
const PICTURES = [
  ["borders", "Borders: start, end, predicted"],
  ["close", "CloSE fold circle"],
  ["disk_start", "dGLI disk, start"],
  ["disk_end", "dGLI disk, end"],
  ["diff", "|diff| with fold curves"],
  ["signed_diff", "Signed diff"],
];

// ---------- errors and requests ----------

function showError(message) {
  const box = $("#error");
  box.textContent = message;
  box.hidden = !message;
}

/** fetch + JSON; a non-2xx answer throws the server's {"error"} text. */
async function api(url, options) {
  const res = await fetch(url, options);
  const text = await res.text();
  let body;
  try {
    body = JSON.parse(text);
  } catch {
    body = { error: text || res.statusText };
  }
  if (!res.ok) throw new Error(`${body.error || res.statusText} (HTTP ${res.status})`);
  return body;
}

// ---------- tabs ----------

function showTab(name) {
  for (const tab of document.querySelectorAll(".tab")) tab.classList.toggle("active", tab.dataset.tab === name);
  for (const view of document.querySelectorAll(".view")) view.hidden = view.id !== `view-${name}`;
  showError("");
  if (name === "interpolate") interp.draw();
  if (name === "plan") planner.shown();
}

// ---------- formatting ----------

const deg = (a) => (a * 180) / Math.PI;
const fmtAngle = (a) => `${a.toFixed(3)} rad (${deg(a).toFixed(1)}°)`;
const fmtFold = (f) => `(${fmtAngle(f[0])}, ${fmtAngle(f[1])})`;

function row(table, key, value) {
  const tr = table.insertRow();
  const th = document.createElement("th");
  th.textContent = key;
  tr.append(th);
  tr.insertCell().textContent = value;
}

/** The result view of one analysis (a sample's or an upload's). */
function renderResult(slot, result) {
  const node = $("#result-template").content.firstElementChild.cloneNode(true);
  $(".result-name", node).textContent = result.name || "(unnamed)";
  const reversed = result.reversed ? " · given clockwise, walked anticlockwise" : "";
  const source = result.border_source === "border" ? "border given" : `border from the ${result.border_source}`;
  $(".result-meta", node).textContent =
    `${result.category || "upload"} · N = ${result.n} vertices (${source}) · frames ${result.start_frame} → ${result.end_frame}${reversed}`;
  $(".result-label", node).textContent = result.label.text;

  const close = $(".close-table tbody", node);
  row(close, "corners", `${result.corners.length}: ${result.corners.map((c) => deg(c).toFixed(0) + "°").join(", ") || "none"}`);
  if (result.folds.length === 0) row(close, "folds", "none found");
  result.folds.forEach((f, k) => row(close, `fold ${k + 1} (f₁, f₂)`, fmtFold(f)));
  const truth = result.sample && result.sample.truth;
  if (truth && truth.folds) truth.folds.forEach((f, k) => row(close, `true fold ${k + 1}`, fmtFold(f)));

  const metrics = $(".metrics-table tbody", node);
  if (result.metrics) {
    row(metrics, "RMSE (XY, normalised)", result.metrics.rmse.toFixed(4));
    row(metrics, "Fréchet (XY, normalised)", result.metrics.frechet.toFixed(4));
  } else {
    row(metrics, "—", "one frame: nothing to compare");
  }

  const images = $(".images", node);
  for (const [key, caption] of PICTURES) {
    if (!result.images[key]) continue;
    const fig = document.createElement("figure");
    const img = document.createElement("img");
    img.src = result.images[key];
    img.alt = caption;
    img.dataset.picture = key;
    const cap = document.createElement("figcaption");
    cap.textContent = caption;
    fig.append(img, cap);
    images.append(fig);
  }
  if (result.recording) {
    const file = `${result.id || "sample"}.rrd`;
    $(".recording", node).hidden = false;
    $(".recording-link", node).href = result.recording;
    $(".recording-link", node).download = file;
    $(".recording-command", node).textContent = `rerun ${file}`;
  }
  $(".warnings", node).textContent = (result.warnings || []).join(" ");
  const button = $(".interp-this", node);
  button.hidden = result.folds.length === 0;
  button.addEventListener("click", () => {
    interp.useResult(result, "this result");
    showTab("interpolate");
  });
  $(".plan-this", node).addEventListener("click", () => planner.open(result.id || result.key));
  slot.replaceChildren(node);
}

// ---------- browse ----------

let samples = [];

async function loadSamples() {
  const list = $("#sample-list");
  try {
    samples = (await api("/api/samples")).samples;
  } catch (e) {
    list.textContent = "";
    showError(`Could not load the samples: ${e.message}`);
    return;
  }
  const groups = new Map();
  for (const s of samples) {
    if (!groups.has(s.category)) groups.set(s.category, []);
    groups.get(s.category).push(s);
  }
  list.replaceChildren();
  for (const [category, members] of groups) {
    const h = document.createElement("h4");
    h.textContent = `${category} (${members.length})`;
    const cards = document.createElement("div");
    cards.className = "cards";
    for (const s of members) {
      const card = document.createElement("button");
      card.className = "sample-card";
      card.dataset.id = s.id;
      card.title = `${s.name} · N = ${s.n} · ${s.frames} frames`;
      const img = document.createElement("img");
      img.loading = "lazy";
      img.src = s.thumbnail;
      img.alt = "";
      const name = document.createElement("span");
      name.textContent = s.name;
      card.append(img, name);
      card.addEventListener("click", () => openSample(s.id));
      cards.append(card);
    }
    list.append(h, cards);
  }
  interp.fillSamples(samples);
  planner.fillSamples(samples);
  // Open the first sample so the page never starts empty (in a talk, the first click counts).
  if (samples.length && !$("#browse-result .result")) openSample(samples[0].id);
}

async function openSample(id) {
  for (const card of document.querySelectorAll(".sample-card")) card.classList.toggle("active", card.dataset.id === id);
  const slot = $("#browse-result");
  slot.setAttribute("aria-busy", "true");
  try {
    renderResult(slot, await api(`/api/samples/${encodeURIComponent(id)}`));
    showError("");
  } catch (e) {
    showError(e.message);
  } finally {
    slot.removeAttribute("aria-busy");
  }
}

// ---------- upload ----------

async function upload(files) {
  const status = $("#upload-status");
  const slot = $("#upload-result");
  // Frames go in file-name order, numbers compared as numbers (frame2 before frame10).
  files = [...files].sort((a, b) => a.name.localeCompare(b.name, undefined, { numeric: true }));
  if (files.length === 0) return;
  // The server reads every kind from "sample" files, by their names' extensions.
  const form = new FormData();
  for (const f of files) form.append("sample", f, f.name);
  status.textContent = `Analysing ${files.map((f) => f.name).join(" → ")}…`;
  try {
    const result = await api("/api/analyze", { method: "POST", body: form });
    renderResult(slot, result);
    status.textContent = `Done: ${files.map((f) => f.name).join(", ")}`;
    showError("");
  } catch (e) {
    slot.replaceChildren();
    status.textContent = "";
    showError(e.message);
  }
}

function setupUpload() {
  const zone = $("#dropzone");
  const input = $("#upload-input");
  input.addEventListener("change", () => upload(input.files));
  zone.addEventListener("dragover", (e) => {
    e.preventDefault();
    zone.classList.add("over");
  });
  zone.addEventListener("dragleave", () => zone.classList.remove("over"));
  zone.addEventListener("drop", (e) => {
    e.preventDefault();
    zone.classList.remove("over");
    upload(e.dataTransfer.files);
  });
}

// ---------- interpolate ----------

const SVG = "http://www.w3.org/2000/svg";
const R = 100;

function svg(tag, attrs, parent) {
  const el = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) el.setAttribute(k, v);
  if (parent) parent.append(el);
  return el;
}

/** Circle position of angle a (anticlockwise on screen: SVG's y points down). */
const onCircle = (a, r = R) => [r * Math.cos(a), -r * Math.sin(a)];

/** SVG path of the arc from a to b anticlockwise at radius r. */
function arcPath(a, b, r) {
  const span = wrap(b - a);
  const [x1, y1] = onCircle(a, r);
  const [x2, y2] = onCircle(b, r);
  return `M ${x1} ${y1} A ${r} ${r} 0 ${span > Math.PI ? 1 : 0} 0 ${x2} ${y2}`;
}

/**
 * Keeps an <img> showing the dGLI disk of the latest border state asked for. One request is
 * in flight at a time and only the newest waiting state is kept, so dragging the slider
 * never queues up stale pictures.
 */
class DiskFollower {
  constructor(img, status, size = 480) {
    Object.assign(this, { img, status, size, busy: false, next: null, shown: null, url: null });
  }

  /** Show the disk of `border` (normalised like `reference`, the flat start) under `key`. */
  show(key, border, reference) {
    this.next = { key, border, reference };
    if (!this.busy) this.pump();
  }

  async pump() {
    this.busy = true;
    while (this.next) {
      const job = this.next;
      this.next = null;
      if (job.key === this.shown) continue;
      try {
        const res = await fetch("/api/disk", {
          method: "POST",
          headers: { "content-type": "application/json" },
          body: JSON.stringify({ border: job.border, reference: job.reference, size: this.size }),
        });
        if (!res.ok) {
          const body = await res.json().catch(() => ({}));
          throw new Error(`${body.error || res.statusText} (HTTP ${res.status})`);
        }
        const url = URL.createObjectURL(await res.blob());
        this.img.src = url;
        await this.img.decode();
        if (this.url) URL.revokeObjectURL(this.url);
        this.url = url;
        this.shown = job.key;
        this.img.dataset.key = job.key;
        this.status.textContent = "";
      } catch (e) {
        this.status.textContent = `(not drawn: ${e.message})`;
      }
    }
    this.busy = false;
  }
}

/**
 * Draw a fold circle into the SVG `root`: the unit circle with angle 0 marked, the corners as
 * numbered dots, each of `arcs` ({fold, color}) as its folded arc and chord, and `handles`
 * ({id, angle, color, label, r}) as draggable dots outside the circle.
 */
function drawFoldCircle(root, corners, arcs, handles) {
  root.replaceChildren();
  svg("circle", { cx: 0, cy: 0, r: R, fill: "none", stroke: "#cbd2dc", "stroke-width": 2 }, root);
  svg("line", { x1: R - 6, y1: 0, x2: R + 6, y2: 0, stroke: "#9aa4b2" }, root);
  svg("text", { x: R + 9, y: 4, "font-size": 10, fill: "#667085" }, root).textContent = "0";
  arcs.forEach(({ fold, color }, k) => {
    // Nested arcs stay apart when several folds are shown.
    const r = R - 5 * k;
    if (wrap(fold[1] - fold[0]) > 1e-9) {
      svg("path", { d: arcPath(fold[0], fold[1], r), fill: "none", stroke: color, "stroke-width": 7, "stroke-linecap": "round", opacity: 0.85 }, root);
    }
    const [ax, ay] = onCircle(fold[0]);
    const [bx, by] = onCircle(fold[1]);
    svg("line", { x1: ax, y1: ay, x2: bx, y2: by, stroke: color, "stroke-dasharray": "4 4" }, root);
  });
  corners.forEach((c, k) => {
    const [x, y] = onCircle(c);
    svg("circle", { cx: x, cy: y, r: 3.5, fill: "#111827" }, root);
    const [tx, ty] = onCircle(c, R - 13);
    svg("text", { x: tx, y: ty + 3.5, "font-size": 10, "text-anchor": "middle", fill: "#111827" }, root).textContent = k + 1;
  });
  for (const h of handles) {
    const [x, y] = onCircle(h.angle, h.r);
    const dot = svg("circle", { cx: x, cy: y, r: 8, fill: h.color, stroke: "#fff", "stroke-width": 2, class: "handle" }, root);
    dot.dataset.id = h.id;
    svg("text", { x, y: y + 3.5, "font-size": 9, "text-anchor": "middle", fill: "#fff", "pointer-events": "none" }, root).textContent = h.label;
  }
}

/** Let the handles of the fold circle `root` be dragged round it: `move(id, angle)`. */
function dragOnCircle(root, move) {
  let id = null;
  root.addEventListener("pointerdown", (e) => {
    if (!e.target.classList.contains("handle")) return;
    id = e.target.dataset.id;
    root.setPointerCapture(e.pointerId);
  });
  root.addEventListener("pointermove", (e) => {
    if (id === null) return;
    const pt = root.createSVGPoint();
    pt.x = e.clientX;
    pt.y = e.clientY;
    const p = pt.matrixTransform(root.getScreenCTM().inverse());
    move(id, wrap(Math.atan2(-p.y, p.x)));
  });
  const stop = () => (id = null);
  root.addEventListener("pointerup", stop);
  root.addEventListener("pointercancel", stop);
}

/** Maps border points to a canvas, fitted to `bounds` {x0, x1, y0, y1} with `pad` pixels. */
function viewport(canvas, bounds, pad) {
  const { width, height } = canvas;
  const b = bounds;
  const scale = Math.min((width - 2 * pad) / (b.x1 - b.x0 || 1), (height - 2 * pad) / (b.y1 - b.y0 || 1));
  const ox = (width - scale * (b.x1 - b.x0)) / 2;
  const oy = (height - scale * (b.y1 - b.y0)) / 2;
  return { X: (p) => ox + scale * (p[0] - b.x0), Y: (p) => height - (oy + scale * (p[1] - b.y0)) };
}

/** XY bounds of several borders. */
function boundsOf(borders) {
  const xs = borders.flatMap((b) => b.map((p) => p[0]));
  const ys = borders.flatMap((b) => b.map((p) => p[1]));
  return { x0: Math.min(...xs), x1: Math.max(...xs), y0: Math.min(...ys), y1: Math.max(...ys) };
}

/** Stroke (and optionally fill) the closed polygon `pts` through the viewport `v`. */
function polygon(ctx, v, pts, { stroke, fill, width = 2, dash = [] }) {
  ctx.beginPath();
  pts.forEach((p, k) => (k ? ctx.lineTo(v.X(p), v.Y(p)) : ctx.moveTo(v.X(p), v.Y(p))));
  ctx.closePath();
  if (fill) {
    ctx.fillStyle = fill;
    ctx.fill();
  }
  ctx.setLineDash(dash);
  ctx.strokeStyle = stroke;
  ctx.lineWidth = width;
  ctx.stroke();
  ctx.setLineDash([]);
}

/** An arrow from p to q (border points) through the viewport `v`. */
function arrow(ctx, v, p, q, color) {
  const [x1, y1, x2, y2] = [v.X(p), v.Y(p), v.X(q), v.Y(q)];
  ctx.beginPath();
  ctx.moveTo(x1, y1);
  ctx.lineTo(x2, y2);
  ctx.strokeStyle = color;
  ctx.lineWidth = 2.5;
  ctx.stroke();
  const ang = Math.atan2(y2 - y1, x2 - x1);
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
}

/**
 * Dot and number the corners (angles) at their vertices of `points`; corners that a fold
 * stacked on one another share one label ("1·4") instead of overprinting.
 */
function labelCorners(ctx, v, points, corners, size) {
  const spots = new Map();
  corners.forEach((c, k) => {
    const p = points[cornerVertex(c, points.length)];
    const key = `${Math.round(v.X(p) / 4)},${Math.round(v.Y(p) / 4)}`;
    if (!spots.has(key)) spots.set(key, { p, labels: [] });
    spots.get(key).labels.push(k + 1);
  });
  ctx.font = `${size}px system-ui, sans-serif`;
  ctx.fillStyle = "#111827";
  for (const { p, labels } of spots.values()) {
    ctx.beginPath();
    ctx.arc(v.X(p), v.Y(p), size / 3, 0, TAU);
    ctx.fill();
    ctx.fillText(labels.join("·"), v.X(p) + size / 2, v.Y(p) - size / 2);
  }
}

/**
 * The folded border with the folded layer a cloth's thickness (1% of the cloth's radius)
 * above the flat one, turned over, as the built-in dataset folds: two layers at the same
 * height would give the disk near-singular values where they touch.
 */
function stacked(flat, folded, fold) {
  const n = flat.length;
  const centre = [0, 1].map((c) => flat.reduce((sum, p) => sum + p[c], 0) / n);
  const radius = Math.max(...flat.map((p) => Math.hypot(p[0] - centre[0], p[1] - centre[1])));
  const top = Math.max(...flat.map((p) => p[2]));
  const out = folded.map((p) => p.slice());
  for (const v of foldedVertices(n, fold)) out[v][2] = 2 * top + 0.01 * radius - flat[v][2];
  return out;
}

/** Vertex of a corner angle on a border of n vertices. */
const cornerVertex = (c, n) => Math.round((c * n) / TAU) % n;

const interp = {
  border: null,
  corners: [],
  from: [0, 0],
  to: [Math.PI / 4, (5 * Math.PI) / 4],
  tau: 0,
  bounds: null,
  playing: false,
  sampleFold: null,

  fillSamples(list) {
    const select = $("#interp-sample");
    select.replaceChildren(...list.map((s) => new Option(`${s.category} · ${s.name}`, s.id)));
    if (list.length) this.loadSample(list[0].id);
  },

  async loadSample(id) {
    try {
      this.useResult(await api(`/api/samples/${encodeURIComponent(id)}`), id);
    } catch (e) {
      showError(e.message);
    }
  },

  /** Fold the start border of an analysis; start unfolded at its first fold's f1. */
  useResult(result, id) {
    this.border = result.start_border;
    this.cloth = (this.cloth || 0) + 1;
    this.corners = result.corners;
    this.sampleId = result.id || null;
    this.sampleKey = result.key || null;
    this.sampleFold = result.folds[0] || (result.sample && result.sample.truth && result.sample.truth.folds[0]) || null;
    const goal = this.sampleFold || [Math.PI / 4, (5 * Math.PI) / 4];
    this.to = [wrap(goal[0]), wrap(goal[1])];
    this.from = [this.to[0], this.to[0]];
    const select = $("#interp-sample");
    if (result.id) select.value = result.id;
    else if (id && !select.querySelector(`option[value="${CSS.escape(id)}"]`)) select.append(new Option(result.name || id, id));
    this.changed();
    this.setTau(0);
  },

  /** After folds or border changed: new view bounds, inputs, circle. */
  changed() {
    if (!this.border) return;
    this.bounds = boundsOf(foldPath(this.from, this.to, 21).map((f) => applyFold(this.border, f)));
    this.writeInputs();
    this.draw();
  },

  setTau(tau) {
    this.tau = Math.min(1, Math.max(0, tau));
    $("#interp-slider").value = Math.round(this.tau * 1000);
    this.draw();
  },

  current() {
    return foldAt(this.from, this.to, this.tau);
  },

  draw() {
    if (!this.border || !this.bounds) return;
    const fold = this.current();
    const folded = applyFold(this.border, fold);
    this.drawCanvas(fold, folded);
    this.drawCircle(fold);
    $("#interp-readout").textContent = `t = ${this.tau.toFixed(3)}   fold ${fmtFold(fold)}`;
    // The disk only while it is on screen; showing the tab draws again.
    if (!$("#view-interpolate").hidden) this.disk.show(this.diskKey(), stacked(this.border, folded, fold), this.border);
  },

  /** Names the state drawn: the cloth and the current fold. */
  diskKey() {
    const fold = this.current();
    return `${this.cloth}|${fold[0].toFixed(9)},${fold[1].toFixed(9)}`;
  },

  drawCanvas(fold, folded) {
    const canvas = $("#interp-canvas");
    const ctx = canvas.getContext("2d");
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    const v = viewport(canvas, this.bounds, 40);
    polygon(ctx, v, this.border, { stroke: "#9aa4b2", width: 1.5, dash: [6, 6] });
    polygon(ctx, v, folded, { stroke: "#1f6feb", fill: "rgba(31, 111, 235, 0.12)", width: 2.5 });

    // Corners (numbered in border order) where they are now.
    labelCorners(ctx, v, folded, this.corners, Math.round(canvas.width / 55));
    ctx.font = `${Math.round(canvas.width / 55)}px system-ui, sans-serif`;

    // The fold line.
    const [a, c] = foldLine(this.border, fold);
    ctx.beginPath();
    ctx.moveTo(v.X(a), v.Y(a));
    ctx.lineTo(v.X(c), v.Y(c));
    ctx.strokeStyle = "#d1495b";
    ctx.lineWidth = 3;
    ctx.stroke();
    for (const [p, label] of [[a, "f₁"], [c, "f₂"]]) {
      ctx.beginPath();
      ctx.arc(v.X(p), v.Y(p), 6, 0, TAU);
      ctx.fillStyle = "#d1495b";
      ctx.fill();
      ctx.fillText(label, v.X(p) + 8, v.Y(p) + 18);
    }
  },

  drawCircle(fold) {
    const handles = [];
    for (const [which, color, r] of [["from", "#2b6cb0", R + 14], ["to", "#dd6b20", R + 26]]) {
      this[which].forEach((angle, k) => handles.push({ id: `${which}:${k}`, angle, color, label: k + 1, r }));
    }
    drawFoldCircle($("#fold-circle"), this.corners, [{ fold, color: "#d1495b" }], handles);
  },

  writeInputs() {
    const inDeg = $("#deg").checked;
    const show = (a) => (inDeg ? deg(a).toFixed(1) : a.toFixed(4));
    $("#from-1").value = show(this.from[0]);
    $("#from-2").value = show(this.from[1]);
    $("#to-1").value = show(this.to[0]);
    $("#to-2").value = show(this.to[1]);
    for (const id of ["#from-1", "#from-2", "#to-1", "#to-2"]) $(id).step = inDeg ? "1" : "0.01";
  },

  readInputs() {
    const unit = $("#deg").checked ? Math.PI / 180 : 1;
    const read = (id, old) => {
      const v = parseFloat($(id).value);
      return Number.isFinite(v) ? wrap(v * unit) : old;
    };
    this.from = [read("#from-1", this.from[0]), read("#from-2", this.from[1])];
    this.to = [read("#to-1", this.to[0]), read("#to-2", this.to[1])];
    this.changed();
  },

  play() {
    if (this.playing) {
      this.playing = false;
      return;
    }
    this.playing = true;
    $("#interp-play").textContent = "❚❚";
    if (this.tau >= 1) this.setTau(0);
    let last = performance.now();
    const tick = (now) => {
      if (!this.playing) {
        $("#interp-play").textContent = "▶";
        return;
      }
      this.setTau(this.tau + (now - last) / 2500);
      last = now;
      if (this.tau >= 1) this.playing = false;
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  },

  /** Ask the server for the same motion and report the largest difference. */
  async checkServer() {
    const out = $("#interp-check");
    const steps = 41;
    try {
      const res = await api("/api/interpolate", {
        method: "POST",
        headers: { "content-type": "application/json" },
        body: JSON.stringify({ border: this.border, from: this.from, to: this.to, steps }),
      });
      let worst = 0;
      foldPath(this.from, this.to, steps).forEach((f, k) => {
        worst = Math.max(worst, Math.abs(f[0] - res.folds[k][0]), Math.abs(f[1] - res.folds[k][1]));
        applyFold(this.border, f).forEach((p, v) => {
          for (let c = 0; c < 3; c++) worst = Math.max(worst, Math.abs(p[c] - res.borders[k][v][c]));
        });
      });
      out.textContent = `Server and browser agree on ${steps} steps: largest difference ${worst.toExponential(1)}.`;
    } catch (e) {
      showError(e.message);
    }
  },

  /** Open the plan view on this cloth with the "to" fold as the goal. */
  planGoal() {
    const sample = this.sampleId || this.sampleKey;
    if (!sample) {
      showError("Planning needs a sample: choose one above.");
      return;
    }
    planner.open(sample, this.to);
  },

  setup() {
    this.disk = new DiskFollower($("#interp-disk"), $("#interp-disk-status"));
    const slider = $("#interp-slider");
    slider.addEventListener("input", () => {
      this.playing = false;
      this.setTau(slider.value / 1000);
    });
    $("#interp-play").addEventListener("click", () => this.play());
    $("#interp-sample").addEventListener("change", (e) => this.loadSample(e.target.value));
    for (const id of ["#from-1", "#from-2", "#to-1", "#to-2"]) $(id).addEventListener("change", () => this.readInputs());
    $("#deg").addEventListener("change", () => this.writeInputs());
    $("#take-fold").addEventListener("click", () => {
      if (this.sampleFold) {
        this.to = [wrap(this.sampleFold[0]), wrap(this.sampleFold[1])];
        this.changed();
      }
    });
    $("#swap-folds").addEventListener("click", () => {
      [this.from, this.to] = [this.to, this.from];
      this.changed();
    });
    $("#check-server").addEventListener("click", () => this.checkServer());
    $("#plan-goal").addEventListener("click", () => this.planGoal());

    dragOnCircle($("#fold-circle"), (id, angle) => {
      const [which, k] = id.split(":");
      this[which][Number(k)] = angle;
      this.changed();
    });
  },
};

// ---------- plan ----------

const fmtPoint = (p) => `(${p[0].toFixed(2)}, ${p[1].toFixed(2)})`;
const fmtDeg = (f) => `(${deg(f[0]).toFixed(1)}°, ${deg(f[1]).toFixed(1)}°)`;
const ACTIONS = { fold: "Fold", unfold: "Unfold" };
const CASES = {
  fold: "The cloth is flat: one fold reaches the goal.",
  direct: "The goal folds the same corners as now: one step moves them straight there.",
  unfold_then_fold: "The goal folds other corners: unfold first, then fold the goal.",
};

/** What a plan step does, in words. */
function stepText(step) {
  const moved = step.corners.length ? `moves corner${step.corners.length > 1 ? "s" : ""} ${step.corners.join(" and ")}` : "moves no corner";
  const picks = step.picks.map((p) => {
    const corner = step.cornerOf(p.vertex);
    const what = corner ? `corner ${corner} (vertex ${p.vertex})` : `vertex ${p.vertex}`;
    return step.action === "unfold" ? `grasp ${what} at ${fmtPoint(p.from)} and put it back at ${fmtPoint(p.to)}` : `grasp ${what} at ${fmtPoint(p.from)} and place it at ${fmtPoint(p.to)}`;
  });
  return `${ACTIONS[step.action] || step.action} along ${fmtDeg(step.fold)}: ${moved}; ${picks.join("; ") || "nothing to grasp"}.`;
}

const planner = {
  sample: null,
  goal: [Math.PI / 4, (5 * Math.PI) / 4],
  folds: [],
  corners: [],

  fillSamples(list) {
    $("#plan-sample").replaceChildren(...list.map((s) => new Option(`${s.category} · ${s.name}`, s.id)));
  },

  /** Show the plan view for `sample` (an id or an analysis key), goal `goal` if given. */
  async open(sample, goal) {
    const select = $("#plan-sample");
    if (!select.querySelector(`option[value="${CSS.escape(sample)}"]`)) select.append(new Option(`upload · ${sample.slice(0, 12)}`, sample));
    select.value = sample;
    if (goal) this.goal = [wrap(goal[0]), wrap(goal[1])];
    this.sample = sample;
    showTab("plan");
    await this.load(sample, !goal);
  },

  /** The view came on screen: start on the chosen sample if none is loaded. */
  shown() {
    const id = $("#plan-sample").value;
    if (!this.sample && id) this.load(id, true);
  },

  /** Load the current state of `sample`; `takeGoal` starts the goal on a diagonal. */
  async load(sample, takeGoal) {
    this.sample = sample;
    try {
      // An upload's state comes back with its plan; a built-in sample's is shown now.
      const builtin = samples.some((s) => s.id === sample);
      const res = builtin ? await api(`/api/samples/${encodeURIComponent(sample)}`) : null;
      if (res) {
        this.folds = res.folds;
        this.corners = res.corners;
        $("#plan-now").textContent = `${res.name}: N = ${res.n}, ${res.corners.length} corners, now ${
          res.folds.length ? res.folds.map(fmtDeg).join(" then ") : "flat"
        }.`;
        if (takeGoal && res.corners.length >= 2) {
          // A diagonal through the first and third corners, a natural first goal.
          const c = res.corners;
          this.goal = [c[0], c[Math.min(2, c.length - 1)]];
        }
      } else {
        [this.folds, this.corners] = [[], []];
        $("#plan-now").textContent = "An uploaded sample: its state is shown with the plan.";
      }
      $("#plan-list").replaceChildren();
      $("#plan-case").textContent = "";
      this.drawCircle();
      this.writeInputs();
    } catch (e) {
      showError(e.message);
    }
  },

  drawCircle() {
    const arcs = this.folds.map((fold) => ({ fold, color: "#2b6cb0" }));
    arcs.push({ fold: this.goal, color: "#dd6b20" });
    const handles = this.goal.map((angle, k) => ({ id: String(k), angle, color: "#dd6b20", label: k + 1, r: R + 18 }));
    drawFoldCircle($("#plan-circle"), this.corners, arcs, handles);
  },

  writeInputs() {
    $("#goal-1").value = deg(this.goal[0]).toFixed(1);
    $("#goal-2").value = deg(this.goal[1]).toFixed(1);
  },

  readInputs() {
    const read = (id, old) => {
      const v = parseFloat($(id).value);
      return Number.isFinite(v) ? wrap((v * Math.PI) / 180) : old;
    };
    this.goal = [read("#goal-1", this.goal[0]), read("#goal-2", this.goal[1])];
    this.drawCircle();
  },

  /** Ask the server for the plan and draw every step. */
  async plan() {
    if (!this.sample) return;
    const list = $("#plan-list");
    try {
      const res = await api("/api/plan", {
        method: "POST",
        headers: { "content-type": "application/json" },
        body: JSON.stringify({ sample: this.sample, goal: this.goal }),
      });
      Object.assign(this, { folds: res.folds, corners: res.corners });
      this.drawCircle();
      $("#plan-case").textContent = `${res.steps.length} step${res.steps.length > 1 ? "s" : ""} · ${CASES[res.case] || res.case}`;
      list.replaceChildren(...this.stepCards(res));
      showError("");
    } catch (e) {
      list.replaceChildren();
      $("#plan-case").textContent = "";
      showError(e.message);
    }
  },

  /**
   * The states the plan goes through, from now: an unfold takes the last fold off, a fold
   * folds the flat cloth ("direct" replaces the current folds by the goal at once).
   */
  states(res) {
    const flat = res.start_border;
    let applied = [...res.folds];
    const at = (folds) => folds.reduce((b, f) => applyFold(b, f), flat);
    const out = [{ state: at(applied) }];
    for (const step of res.steps) {
      const before = at(applied);
      if (step.action === "unfold") applied = applied.slice(0, -1);
      else applied = res.case === "direct" ? [step.fold] : [...applied, step.fold];
      const after = at(applied);
      // The line a fold step folds along lies on the border it folds (plan.rs: the flat
      // cloth); an unfold's on the state it goes back to.
      out.push({ step, before, state: after, line: foldLine(step.action === "unfold" ? after : flat, step.fold) });
    }
    return out;
  },

  stepCards(res) {
    const flat = res.start_border;
    const n = flat.length;
    const states = this.states(res);
    const bounds = boundsOf([flat, ...states.map((s) => s.state), ...res.steps.flatMap((s) => s.picks.map((p) => [p.from, p.to]))]);
    // Input vertex (what picks name) → 1-based corner number.
    const cornerVertices = res.corners.map((c) => cornerVertex(c, n));
    const inputIndex = res.border_indices || null;
    return states.map(({ step, before, state, line }, k) => {
      const li = document.createElement("li");
      li.className = "plan-step";
      const canvas = document.createElement("canvas");
      canvas.width = 520;
      canvas.height = 420;
      const ctx = canvas.getContext("2d");
      const v = viewport(canvas, bounds, 28);
      // Outlines only: a folded border overlaps itself, so a fill would cancel out.
      polygon(ctx, v, flat, { stroke: "#cbd2dc", width: 1.2, dash: [5, 5] });
      if (before) polygon(ctx, v, before, { stroke: "#9aa4b2", width: 1.5, dash: [2, 4] });
      polygon(ctx, v, state, { stroke: "#1f6feb", width: 2.5 });
      labelCorners(ctx, v, state, res.corners, 15);
      if (line) {
        ctx.beginPath();
        ctx.moveTo(v.X(line[0]), v.Y(line[0]));
        ctx.lineTo(v.X(line[1]), v.Y(line[1]));
        ctx.strokeStyle = "#d1495b";
        ctx.lineWidth = 2.5;
        ctx.stroke();
      }
      for (const pick of step ? step.picks : []) arrow(ctx, v, pick.from, pick.to, "#2f855a");
      const text = document.createElement("div");
      const title = document.createElement("h4");
      const words = document.createElement("p");
      if (step) {
        title.textContent = `Step ${k} · ${ACTIONS[step.action] || step.action}`;
        // Picks name input vertices; a border vertex that is a corner gets its number.
        step.cornerOf = (vertex) => {
          const border = inputIndex ? inputIndex.indexOf(vertex) : vertex;
          const i = cornerVertices.indexOf(border);
          return i >= 0 ? i + 1 : null;
        };
        words.textContent = stepText(step);
        li.dataset.picks = step.picks.length;
      } else {
        title.textContent = "Now";
        words.textContent = res.folds.length ? `Folded along ${res.folds.map(fmtDeg).join(", then ")}.` : "Flat.";
      }
      text.append(title, words);
      li.append(canvas, text);
      return li;
    });
  },

  setup() {
    $("#plan-sample").addEventListener("change", (e) => this.load(e.target.value, true));
    for (const id of ["#goal-1", "#goal-2"]) $(id).addEventListener("change", () => this.readInputs());
    $("#plan-run").addEventListener("click", () => this.plan());
    dragOnCircle($("#plan-circle"), (id, angle) => {
      this.goal[Number(id)] = angle;
      this.drawCircle();
      this.writeInputs();
    });
  },
};

// ---------- start ----------

for (const tab of document.querySelectorAll(".tab")) tab.addEventListener("click", () => showTab(tab.dataset.tab));
setupUpload();
interp.setup();
planner.setup();
loadSamples();
// For tests and the console.
window.closeApp = { interp, planner, openSample, upload };
