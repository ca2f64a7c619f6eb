// The Interpolate view: a cloth's flat border folded by reflection, any fold of its
// analysis (or the whole sequence) animated, the dGLI disk of each state beside it with one
// colour scale for the whole motion.

import * as api from "./api.js";
import * as store from "./store.js";
import * as router from "./router.js";
import { applyFold, foldAt, foldPath, turnPath, wrap, TAU } from "./fold.mjs";
import { AngleInputs, R, dragOnCircle, drawFoldCircle } from "./circle.js";
import { boundsOf, drawCloth, foldAll, labelCorners, line, made, stacked, textSize, viewport } from "./draw.js";
import { fmtFold } from "./format.js";
import { enlarge } from "./result.js";
import { condensedIndex, markEdges, readable } from "./readout.js";

const $ = (sel) => document.querySelector(sel);
const SEQUENCE = "all";
let showError = () => {};

/**
 * Keeps an <img> showing the dGLI disk of the latest border state asked for. One request is
 * in flight at a time and only the newest waiting state is kept, so dragging the slider
 * never queues up stale pictures. The colour scale is fixed per motion: the larger of the
 * scales of its two end states, so a colour means one value all the way through.
 */
class DiskFollower {
  constructor(img, status, size = 480) {
    Object.assign(this, { img, status, size, busy: false, next: null, shown: null, url: null, motion: null, scale: null, job: null, large: null, onShown: null });
  }

  /** The request for `job`'s disk at `size` px, in the motion's colour scale. */
  request(job, size) {
    return { border: job.border, reference: job.reference, size, scale: this.scale || undefined };
  }

  /** The state shown, at full resolution and in the same colour scale, in the shared dialog. */
  async enlarge(caption) {
    if (!this.job) return;
    try {
      const { url } = await api.disk(this.request(this.job, 1400), "disk-large");
      if (this.large) URL.revokeObjectURL(this.large);
      this.large = url;
      enlarge(url, caption);
    } catch (e) {
      if (!api.isAbort(e)) this.status.textContent = `(not drawn: ${e.message})`;
    }
  }

  /** Show the disk of `border` under `key`; `ends` are the motion's two end states. */
  show(key, border, reference, motion, ends) {
    this.next = { key, border, reference, motion, ends };
    if (!this.busy) this.pump();
  }

  async pump() {
    this.busy = true;
    while (this.next) {
      const job = this.next;
      this.next = null;
      if (job.key === this.shown) continue;
      try {
        if (job.motion !== this.motion) {
          this.status.textContent = "(fixing the colour scale…)";
          const scales = [];
          for (const border of job.ends) {
            const { url, scale } = await api.disk({ border, reference: job.reference, size: 64 }, "disk-scale");
            URL.revokeObjectURL(url);
            scales.push(scale);
          }
          this.scale = scales.every(Boolean) ? { s: Math.max(...scales.map((s) => s.s)), max: Math.max(...scales.map((s) => s.max)) } : null;
          this.motion = job.motion;
        }
        const { url } = await api.disk(this.request(job, this.size), "disk");
        this.img.src = url;
        await this.img.decode();
        if (this.url) URL.revokeObjectURL(this.url);
        this.url = url;
        this.shown = job.key;
        this.job = job;
        this.img.dataset.key = job.key;
        this.status.textContent = "";
        if (this.onShown) this.onShown();
      } catch (e) {
        if (!api.isAbort(e)) this.status.textContent = `(not drawn: ${e.message})`;
      }
    }
    this.busy = false;
  }
}

const view = {
  cloth: null,
  result: null,
  border: null,
  corners: [],
  /** Folds applied before the one animated. */
  prior: [],
  from: [0, 0],
  to: [Math.PI / 4, (5 * Math.PI) / 4],
  /** The step animated ("1", "2", …), SEQUENCE, or "free". */
  mode: "1",
  tau: 0,
  /** The disk cell read ({i, j, d}), whose edges are marked; null: none. */
  cell: null,
  bounds: null,
  playing: false,
  motion: 0,
};

/** A fold's two angles, whether it is [f1, f2] or made along a line (see draw.js `made`). */
const anglesOf = (f) => (Array.isArray(f) ? f : f.fold);

/**
 * Fold k of the analysis as the analysis made it, turned the fraction `turn` of the way:
 * along the line it reports when the step's two fold points lie on top of each other (a fold
 * through stacked layers, where the line through them would point anywhere) or when it turns
 * several arcs (a multi-arc fold: only they turn, all about that line), so the motion ends
 * on the predicted state; otherwise on the fold circle from (f1, f1) to (f1, f2).
 */
function sampleFold(k, turn = 1) {
  const f = view.result.folds[k];
  const step = (view.result.steps || []).filter((s) => s.fold)[k];
  const arcs = step?.arcs?.length > 1 ? step.arcs : [f];
  if (step?.line && (step.synthesis?.direction || arcs.length > 1)) return { fold: f, arcs, line: step.line, turn };
  return turn >= 1 ? f : foldAt([f[0], f[0]], f, turn);
}

const sameFold = (a, b) => Math.abs(a[0] - wrap(b[0])) < 1e-12 && Math.abs(a[1] - wrap(b[1])) < 1e-12;

/** The folds of the state at the slider: prior folds and the animated one. */
function foldsNow() {
  if (view.mode === SEQUENCE) {
    const folds = view.result.folds;
    const x = view.tau * folds.length;
    const k = Math.min(Math.floor(x), folds.length - 1);
    return [...folds.slice(0, k).map((_, i) => sampleFold(i)), sampleFold(k, x - k)];
  }
  const k = Number(view.mode) - 1;
  // A step's own fold, its handles untouched, moves as the analysis made it.
  const own = view.result && Number.isInteger(k) && view.result.folds[k] && view.from[0] === view.from[1] && sameFold(view.to, view.result.folds[k]);
  return [...view.prior, own ? sampleFold(k, view.tau) : foldAt(view.from, view.to, view.tau)];
}

/** Every state of the motion, coarsely, for the drawing's bounds. */
function motionStates() {
  return Array.from({ length: 41 }, (_, k) => foldsAtTau(k / 40));
}

function foldsAtTau(t) {
  const keep = view.tau;
  view.tau = t;
  const folds = foldsNow();
  view.tau = keep;
  return folds;
}

function fillCloths() {
  const select = $("#interp-sample");
  const cloths = store.cloths();
  const value = view.cloth ? `${view.cloth.kind}:${view.cloth.id}` : select.value;
  select.replaceChildren(...cloths.map((c) => new Option(c.name, `${c.kind}:${c.id}`)));
  if (value) select.value = value;
}

function fillSteps() {
  const select = $("#interp-step");
  const folds = view.result ? view.result.folds : [];
  const options = folds.map((f, k) => new Option(`fold ${k + 1} of the sample${k ? ` (after fold${k > 1 ? "s" : ""} 1${k > 1 ? `–${k}` : ""})` : ""}`, String(k + 1)));
  if (folds.length > 1) options.push(new Option(`the whole sequence (${folds.length} folds)`, SEQUENCE));
  options.push(new Option("free: the folds below, on the flat cloth", "free"));
  select.replaceChildren(...options);
  select.value = view.mode;
}

/** Take cloth `cloth` ({kind, id}): load its analysis and start on its first fold, or on a link's state (`params`). */
async function useCloth(cloth, params = null) {
  view.cloth = cloth;
  fillCloths();
  // The previous cloth's messages do not speak of this one.
  $("#interp-check").textContent = "";
  $("#fold-input-status").textContent = "";
  try {
    let result;
    if (cloth.kind === "upload") {
      result = store.get().uploads.find((u) => u.key === cloth.id)?.result;
      if (!result) throw new Error("that upload is no longer in this page: upload it again");
    } else {
      result = await api.sample(cloth.id, "interp-cloth");
    }
    if (view.cloth !== cloth) return;
    view.result = result;
    view.border = result.start_border;
    view.corners = result.corners;
    view.mode = result.folds.length ? "1" : "free";
    fillSteps();
    setMode(view.mode);
    if (params) applyParams(params);
    // Only while the view is on screen: Back may have left it during the load.
    if (!$("#view-interpolate").hidden) document.title = router.title("interpolate", $("#interp-sample").selectedOptions[0]?.textContent || "");
  } catch (e) {
    if (!api.isAbort(e)) showError(e.message);
  }
}

/** Animate step `mode` of the cloth's folds (or the sequence, or free folds). */
function setMode(mode) {
  view.mode = mode;
  const folds = view.result.folds;
  const k = Number(mode);
  if (Number.isInteger(k) && folds[k - 1]) {
    view.prior = folds.slice(0, k - 1).map((_, i) => sampleFold(i));
    view.to = [wrap(folds[k - 1][0]), wrap(folds[k - 1][1])];
    view.from = [view.to[0], view.to[0]];
  } else if (mode === "free") {
    view.prior = [];
  }
  const sequence = mode === SEQUENCE;
  for (const id of ["#from-1", "#from-2", "#to-1", "#to-2", "#swap-folds"]) $(id).disabled = sequence;
  changed();
  setTau(0);
  keepUrl();
}

/** The view's state as URL parameters: cloth, step, the free folds and t. */
function keepUrl() {
  if (!view.cloth || !view.result) return;
  const params = new URLSearchParams({ cloth: `${view.cloth.kind}:${view.cloth.id}`, step: view.mode });
  if (view.mode !== SEQUENCE) {
    params.set("from", router.angleText(view.from));
    params.set("to", router.angleText(view.to));
  }
  params.set("t", view.tau.toFixed(3));
  router.keep("interpolate", params);
}

/** Take a link's step, folds and t (once the cloth they belong to is loaded). */
function applyParams(params) {
  const step = params.get("step");
  if (step && [...$("#interp-step").options].some((o) => o.value === step)) {
    $("#interp-step").value = step;
    setMode(step);
  }
  if (view.mode !== SEQUENCE) {
    const [from, to] = [router.angles(params.get("from")), router.angles(params.get("to"))];
    if (from) view.from = from.map(wrap);
    if (to) view.to = to.map(wrap);
    if (from || to) changed();
  }
  const t = Number(params.get("t"));
  if (params.has("t") && Number.isFinite(t)) setTau(t);
}

/** After folds or the cloth changed: new motion, bounds, inputs, circle. */
function changed() {
  if (!view.border) return;
  // A check of another motion no longer holds.
  $("#interp-check").textContent = "";
  view.motion += 1;
  // The flat outline is drawn too: it must fit as well as every folded state.
  view.bounds = boundsOf([view.border, ...motionStates().map((folds) => foldAll(view.border, folds))]);
  inputs.write({ "from-1": view.from[0], "from-2": view.from[1], "to-1": view.to[0], "to-2": view.to[1] });
  draw();
}

function setTau(tau) {
  view.tau = Math.min(1, Math.max(0, tau));
  $("#interp-slider").value = Math.round(view.tau * 1000);
  draw();
  // While playing, the URL is written once the motion stops (not 60 times a second).
  if (!view.playing) keepUrl();
}

/** Names the state drawn: the cloth, the motion and the folds. */
export function diskKey() {
  const name = (f) => `${anglesOf(f).map((a) => a.toFixed(9)).join(",")}${Array.isArray(f) ? "" : `@${f.turn.toFixed(9)}`}`;
  return `${view.cloth?.id}|${view.motion}|${foldsNow().map(name).join(";")}`;
}

function draw() {
  if (!view.border || !view.bounds) return;
  const folds = foldsNow();
  const canvas = $("#interp-canvas");
  const ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  const v = viewport(canvas, view.bounds, 40);
  // The flat cloth dashed, then the layers of the folded one.
  ctx.setLineDash([6, 6]);
  ctx.strokeStyle = "#9aa4b2";
  ctx.lineWidth = 1.5;
  ctx.beginPath();
  view.border.forEach((p, k) => (k ? ctx.lineTo(v.X(p), v.Y(p)) : ctx.moveTo(v.X(p), v.Y(p))));
  ctx.closePath();
  ctx.stroke();
  ctx.setLineDash([]);
  const folded = drawCloth(ctx, v, view.border, folds);
  const size = textSize(canvas);
  labelCorners(ctx, v, folded, view.corners, size);
  // The edges of the disk cell read, on the state drawn.
  markEdges(ctx, [folded], (p) => [v.X(p), v.Y(p)], view.cell, size / 15);
  // The line of the fold animated, on the state it folds.
  const last = folds[folds.length - 1];
  const fold = anglesOf(last);
  const { a, b: c } = made(foldAll(view.border, folds.slice(0, -1)), last);
  line(ctx, v, a, c, "#d1495b", 3);
  // A fold along a reported line has its two fold points on top of each other: no tags.
  if (Array.isArray(last)) {
    ctx.font = `${size}px system-ui, sans-serif`;
    // A fold from flat starts with both points at one place: one tag, not two overprinted.
    const one = Math.hypot(v.X(a) - v.X(c), v.Y(a) - v.Y(c)) < size;
    for (const [p, label] of one ? [[a, "f₁·f₂"]] : [[a, "f₁"], [c, "f₂"]]) {
      ctx.beginPath();
      ctx.arc(v.X(p), v.Y(p), 6, 0, TAU);
      ctx.fillStyle = "#d1495b";
      ctx.fill();
      ctx.fillText(label, v.X(p) + 8, v.Y(p) + 18);
    }
  }
  drawCircle(fold);
  // In sequence mode the (disabled) inputs show the fold playing now.
  if (view.mode === SEQUENCE) inputs.write({ "from-1": fold[0], "from-2": fold[0], "to-1": fold[0], "to-2": fold[1] });
  const which = view.mode === SEQUENCE ? `fold ${folds.length} of ${view.result.folds.length}` : "fold";
  $("#interp-readout").textContent = `t = ${view.tau.toFixed(3)}   ${which} ${fmtFold(fold)}`;
  // The disk only while it is on screen; showing the view draws again.
  if (!$("#view-interpolate").hidden) {
    const ends = motionEnds();
    disk.show(diskKey(), stacked(view.border, folds), view.border, view.motion, ends);
  }
}

/** The two end states of the motion, as the disk sees them. */
function motionEnds() {
  return [foldsAtTau(0), foldsAtTau(1)].map((folds) => stacked(view.border, folds));
}

function drawCircle(fold) {
  const handles = [];
  // Rings 2 handle radii apart: a "from" and a "to" handle at one angle do not overlap.
  for (const [which, color, r, word] of [["from", "#2b6cb0", R + 12, "from"], ["to", "#c05621", R + 32, "to"]]) {
    view[which].forEach((angle, k) => handles.push({ id: `${which}:${k}`, angle, color, label: k + 1, r, name: `${word} fold point ${k + 1}` }));
  }
  const arcs = foldsNow().slice(0, -1).map((f) => ({ fold: anglesOf(f), color: "#9aa4b2" }));
  arcs.push({ fold, color: "#d1495b" });
  drawFoldCircle($("#fold-circle"), view.corners, arcs, view.mode === SEQUENCE ? [] : handles);
}

function play() {
  if (view.playing) {
    view.playing = false;
    return;
  }
  view.playing = true;
  $("#interp-play").textContent = "❚❚";
  $("#interp-play").setAttribute("aria-label", "Pause");
  if (view.tau >= 1) setTau(0);
  let last = performance.now();
  const seconds = 2.5 * (view.mode === SEQUENCE ? view.result.folds.length : 1);
  const tick = (now) => {
    if (!view.playing) {
      $("#interp-play").textContent = "▶";
      $("#interp-play").setAttribute("aria-label", "Play");
      return;
    }
    setTau(view.tau + (now - last) / (1000 * seconds));
    last = now;
    if (view.tau >= 1) {
      view.playing = false;
      keepUrl();
    }
    requestAnimationFrame(tick);
  };
  requestAnimationFrame(tick);
}

/** Ask the server for the same motion and report the largest difference. */
async function checkServer() {
  const out = $("#interp-check");
  const steps = 41;
  // The sequence is checked one fold at a time on the state before it: here, the current one.
  const folds = foldsNow();
  const prior = view.mode === SEQUENCE ? folds.slice(0, -1) : view.prior;
  const last = folds[folds.length - 1];
  const base = foldAll(view.border, prior);
  // A fold made along a line of its own turns its arcs about it; any other moves on the circle.
  const turned = !Array.isArray(last) && last.line;
  const [from, to] = view.mode === SEQUENCE ? (() => {
    const f = view.result.folds[folds.length - 1];
    return [[f[0], f[0]], f];
  })() : [view.from, view.to];
  const motion = turned ? { arcs: last.arcs, line: last.line } : { from, to };
  const path = turned ? null : foldPath(from, to, steps);
  const ours = turned ? turnPath(base, last.arcs, last.line, steps).borders : path.map((f) => applyFold(base, f));
  try {
    const res = await api.interpolate({ border: base, reference: view.border, ...motion, steps });
    let worst = 0;
    path?.forEach((f, k) => {
      worst = Math.max(worst, Math.abs(f[0] - res.folds[k][0]), Math.abs(f[1] - res.folds[k][1]));
    });
    ours.forEach((border, k) => {
      border.forEach((p, v) => {
        for (let c = 0; c < 3; c++) worst = Math.max(worst, Math.abs(p[c] - res.borders[k][v][c]));
      });
    });
    out.textContent = `Server and browser agree on ${steps} steps: largest difference ${worst.toExponential(1)}.`;
  } catch (e) {
    if (!api.isAbort(e)) showError(e.message);
  }
}

let disk = null;
let inputs = null;

export function setup(errors, planGoal) {
  showError = errors;
  disk = new DiskFollower($("#interp-disk"), $("#interp-disk-status"));
  // The disk's cells read by hover, tap or arrow keys; their edges marked on the cloth.
  const cells = readable($("#interp-disk-zoom"), $("#interp-disk"), "state", async () => {
    if (!disk.job) throw new Error("no disk drawn yet");
    const r = await api.diskCells({ border: disk.job.border, reference: disk.job.reference, size: disk.size });
    return { ...r, values: (i, j) => ({ value: r.values[condensedIndex(r.n, i, j)] }) };
  }, (c) => {
    view.cell = c;
    draw();
  });
  $("#interp-disk-zoom").classList.add("readable");
  // A new state's disk: the cell read keeps its place, its value is the new state's.
  disk.onShown = () => cells.reset();
  inputs = new AngleInputs(
    Object.fromEntries(["from-1", "from-2", "to-1", "to-2"].map((id) => [id, $(`#${id}`)])),
    $("#fold-input-status"),
    (key, angle) => {
      const [which, k] = key.split("-");
      view[which] = view[which].map((a, i) => (i === Number(k) - 1 ? angle : a));
      changed();
      keepUrl();
    },
    () => $("#deg").checked,
  );
  const slider = $("#interp-slider");
  slider.addEventListener("input", () => {
    view.playing = false;
    setTau(slider.value / 1000);
  });
  $("#interp-play").addEventListener("click", play);
  $("#interp-sample").addEventListener("change", (e) => {
    const [kind, ...rest] = e.target.value.split(":");
    store.set({ cloth: { kind, id: rest.join(":") } });
    shown();
  });
  $("#interp-step").addEventListener("change", (e) => setMode(e.target.value));
  $("#deg").addEventListener("change", () => inputs.write({ "from-1": view.from[0], "from-2": view.from[1], "to-1": view.to[0], "to-2": view.to[1] }));
  $("#swap-folds").addEventListener("click", () => {
    [view.from, view.to] = [view.to, view.from];
    changed();
    keepUrl();
  });
  $("#interp-disk-zoom").addEventListener("click", () => disk.enlarge(`dGLI disk of the state drawn (${$("#interp-readout").textContent.replace(/\s+/g, " ").trim()})`));
  $("#check-server").addEventListener("click", checkServer);
  $("#plan-goal").addEventListener("click", () => planGoal(view.cloth, view.to));
  dragOnCircle($("#fold-circle"), (id, angle) => {
    const [which, k] = id.split(":");
    view[which] = view[which].map((a, i) => (i === Number(k) ? angle : a));
    changed();
    keepUrl();
  });
  store.subscribe(() => fillCloths());
}

/** A cloth named in a URL ("sample:ID" or "upload:KEY"), or null. */
export function clothParam(params) {
  const text = params && params.get("cloth");
  if (!text || !text.includes(":")) return null;
  const [kind, ...rest] = text.split(":");
  return ["sample", "upload"].includes(kind) ? { kind, id: rest.join(":") } : null;
}

/** The view came on screen: a link's cloth and state, else the store's cloth, else the first one. */
export function shown(params = null) {
  const linked = clothParam(params);
  if (linked) store.set({ cloth: linked });
  const { cloth } = store.get();
  const wanted = cloth || store.cloths()[0] || null;
  fillCloths();
  const same = view.cloth && wanted && view.cloth.kind === wanted.kind && view.cloth.id === wanted.id;
  if (wanted && !same) useCloth(wanted, linked ? params : null);
  else if (view.cloth) {
    document.title = router.title("interpolate", $("#interp-sample").selectedOptions[0]?.textContent || "");
    if (linked && view.result) applyParams(params);
    draw();
    keepUrl();
  } else document.title = router.title("interpolate");
}

// For tests and the console.
export const state = () => ({ ...view, folds: foldsNow(), drawn: foldAll(view.border, foldsNow()) });
export { setTau, setMode };
