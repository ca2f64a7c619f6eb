// CloSE web app: browse the built-in samples, upload one, interpolate folds.
// Plain ES module, no build step; talks to the JSON API of src/server.

import { TAU, wrap, foldAt, applyFold, foldLine, foldPath } from "./fold.mjs";

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
  $(".result-meta", node).textContent =
    `${result.category || "upload"} · N = ${result.n} vertices · frames ${result.start_frame} → ${result.end_frame}${reversed}`;
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
  $(".warnings", node).textContent = (result.warnings || []).join(" ");
  const button = $(".interp-this", node);
  button.hidden = result.folds.length === 0;
  button.addEventListener("click", () => {
    interp.useResult(result, "this result");
    showTab("interpolate");
  });
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
  files = [...files];
  if (files.length === 0) return;
  const form = new FormData();
  if (files.length === 2 && !files.some((f) => f.name.toLowerCase().endsWith(".json"))) {
    form.append("start", files[0], files[0].name);
    form.append("end", files[1], files[1].name);
    status.textContent = `Analysing ${files[0].name} → ${files[1].name}…`;
  } else {
    for (const f of files) form.append("sample", f, f.name);
    status.textContent = `Analysing ${files.map((f) => f.name).join(", ")}…`;
  }
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
    this.sampleJson = result.sample || null;
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
    let xs = [];
    let ys = [];
    for (const f of foldPath(this.from, this.to, 21)) {
      for (const p of applyFold(this.border, f)) {
        xs.push(p[0]);
        ys.push(p[1]);
      }
    }
    const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
    this.bounds = { x0, x1, y0, y1 };
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
    if (!$("#view-interpolate").hidden) this.disk.show(this.diskKey(), folded, this.border);
  },

  /** Names the state drawn: the cloth and the current fold. */
  diskKey() {
    const fold = this.current();
    return `${this.cloth}|${fold[0].toFixed(9)},${fold[1].toFixed(9)}`;
  },

  drawCanvas(fold, folded) {
    const canvas = $("#interp-canvas");
    const ctx = canvas.getContext("2d");
    const { width, height } = canvas;
    ctx.clearRect(0, 0, width, height);
    const b = this.bounds;
    const pad = 40;
    const scale = Math.min((width - 2 * pad) / (b.x1 - b.x0 || 1), (height - 2 * pad) / (b.y1 - b.y0 || 1));
    const ox = (width - scale * (b.x1 - b.x0)) / 2;
    const oy = (height - scale * (b.y1 - b.y0)) / 2;
    const X = (p) => ox + scale * (p[0] - b.x0);
    const Y = (p) => height - (oy + scale * (p[1] - b.y0));
    const poly = (pts, close = true) => {
      ctx.beginPath();
      pts.forEach((p, k) => (k ? ctx.lineTo(X(p), Y(p)) : ctx.moveTo(X(p), Y(p))));
      if (close) ctx.closePath();
    };

    // The flat cloth, dashed.
    poly(this.border);
    ctx.setLineDash([6, 6]);
    ctx.strokeStyle = "#9aa4b2";
    ctx.lineWidth = 1.5;
    ctx.stroke();
    ctx.setLineDash([]);

    // The folded border.
    poly(folded);
    ctx.fillStyle = "rgba(31, 111, 235, 0.12)";
    ctx.fill();
    ctx.strokeStyle = "#1f6feb";
    ctx.lineWidth = 2.5;
    ctx.stroke();

    // Corners (numbered in border order) where they are now.
    ctx.font = `${Math.round(width / 55)}px system-ui, sans-serif`;
    const n = this.border.length;
    this.corners.forEach((c, k) => {
      const v = Math.round((c * n) / TAU) % n;
      const p = folded[v];
      ctx.beginPath();
      ctx.arc(X(p), Y(p), 5, 0, TAU);
      ctx.fillStyle = "#111827";
      ctx.fill();
      ctx.fillText(String(k + 1), X(p) + 7, Y(p) - 7);
    });

    // The fold line.
    const [a, c] = foldLine(this.border, fold);
    ctx.beginPath();
    ctx.moveTo(X(a), Y(a));
    ctx.lineTo(X(c), Y(c));
    ctx.strokeStyle = "#d1495b";
    ctx.lineWidth = 3;
    ctx.stroke();
    for (const [p, label] of [[a, "f₁"], [c, "f₂"]]) {
      ctx.beginPath();
      ctx.arc(X(p), Y(p), 6, 0, TAU);
      ctx.fillStyle = "#d1495b";
      ctx.fill();
      ctx.fillText(label, X(p) + 8, Y(p) + 18);
    }

    // Plan arrows, when a plan is shown.
    for (const pick of this.picks || []) {
      const [p, q] = [pick.from, pick.to];
      ctx.beginPath();
      ctx.moveTo(X(p), Y(p));
      ctx.lineTo(X(q), Y(q));
      ctx.strokeStyle = "#2f855a";
      ctx.lineWidth = 2.5;
      ctx.stroke();
      const ang = Math.atan2(Y(q) - Y(p), X(q) - X(p));
      ctx.beginPath();
      ctx.moveTo(X(q), Y(q));
      ctx.lineTo(X(q) - 14 * Math.cos(ang - 0.4), Y(q) - 14 * Math.sin(ang - 0.4));
      ctx.lineTo(X(q) - 14 * Math.cos(ang + 0.4), Y(q) - 14 * Math.sin(ang + 0.4));
      ctx.closePath();
      ctx.fillStyle = "#2f855a";
      ctx.fill();
    }
  },

  drawCircle(fold) {
    const root = $("#fold-circle");
    root.replaceChildren();
    svg("circle", { cx: 0, cy: 0, r: R, fill: "none", stroke: "#cbd2dc", "stroke-width": 2 }, root);
    svg("line", { x1: R - 6, y1: 0, x2: R + 6, y2: 0, stroke: "#9aa4b2" }, root);
    svg("text", { x: R + 9, y: 4, "font-size": 10, fill: "#667085" }, root).textContent = "0";
    // The folded arc of the current fold, and its chord.
    if (wrap(fold[1] - fold[0]) > 1e-9) {
      svg("path", { d: arcPath(fold[0], fold[1], R), fill: "none", stroke: "#d1495b", "stroke-width": 7, "stroke-linecap": "round", opacity: 0.85 }, root);
    }
    const [ax, ay] = onCircle(fold[0]);
    const [bx, by] = onCircle(fold[1]);
    svg("line", { x1: ax, y1: ay, x2: bx, y2: by, stroke: "#d1495b", "stroke-dasharray": "4 4" }, root);
    this.corners.forEach((c, k) => {
      const [x, y] = onCircle(c);
      svg("circle", { cx: x, cy: y, r: 3.5, fill: "#111827" }, root);
      const [tx, ty] = onCircle(c, R - 13);
      svg("text", { x: tx, y: ty + 3.5, "font-size": 10, "text-anchor": "middle", fill: "#111827" }, root).textContent = k + 1;
    });
    const handle = (which, k, color) => {
      const [x, y] = onCircle(this[which][k], R + (which === "from" ? 14 : 26));
      const h = svg("circle", { cx: x, cy: y, r: 8, fill: color, stroke: "#fff", "stroke-width": 2, class: "handle" }, root);
      h.dataset.which = which;
      h.dataset.k = k;
      svg("text", { x, y: y + 3.5, "font-size": 9, "text-anchor": "middle", fill: "#fff", "pointer-events": "none" }, root).textContent = k + 1;
    };
    handle("from", 0, "#2b6cb0");
    handle("from", 1, "#2b6cb0");
    handle("to", 0, "#dd6b20");
    handle("to", 1, "#dd6b20");
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
    this.picks = null;
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

  /** Plan from the sample's current state to the "to" fold and draw pick → place arrows. */
  async plan() {
    const list = $("#plan-steps");
    const sample = this.sampleId || this.sampleJson;
    if (!sample) {
      showError("Planning needs a built-in sample: choose one above.");
      return;
    }
    try {
      const res = await api("/api/plan", {
        method: "POST",
        headers: { "content-type": "application/json" },
        body: JSON.stringify({ sample, goal: this.to }),
      });
      list.replaceChildren(
        ...res.steps.map((s) => {
          const li = document.createElement("li");
          const picks = s.picks.map((p) => `vertex ${p.vertex}`).join(", ") || "no corner";
          li.textContent = `${s.action} along ${fmtFold(s.fold)}: pick ${picks}`;
          return li;
        }),
      );
      $("#interp-check").textContent = `Plan case: ${res.case}`;
      this.picks = res.steps.flatMap((s) => s.picks);
      this.draw();
    } catch (e) {
      showError(e.message);
    }
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
    $("#plan-goal").addEventListener("click", () => this.plan());

    // Drag a handle round the circle.
    const root = $("#fold-circle");
    let drag = null;
    root.addEventListener("pointerdown", (e) => {
      if (!e.target.classList.contains("handle")) return;
      drag = { which: e.target.dataset.which, k: Number(e.target.dataset.k) };
      root.setPointerCapture(e.pointerId);
    });
    root.addEventListener("pointermove", (e) => {
      if (!drag) return;
      const pt = root.createSVGPoint();
      pt.x = e.clientX;
      pt.y = e.clientY;
      const p = pt.matrixTransform(root.getScreenCTM().inverse());
      this[drag.which][drag.k] = wrap(Math.atan2(-p.y, p.x));
      this.picks = null;
      this.changed();
    });
    const stop = () => (drag = null);
    root.addEventListener("pointerup", stop);
    root.addEventListener("pointercancel", stop);
  },
};

// ---------- start ----------

for (const tab of document.querySelectorAll(".tab")) tab.addEventListener("click", () => showTab(tab.dataset.tab));
setupUpload();
interp.setup();
loadSamples();
// For tests and the console.
window.closeApp = { interp, openSample, upload };
