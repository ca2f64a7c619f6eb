// The Interpolate view: a cloth's folds as the server moves them, the dGLI disk of each state
// beside it on one colour scale for the whole motion.
//
// Two motions, labelled on screen. A fold the analysis found turns its flap over about its
// line: t = 0 is the state before it (the flat cloth, or the earlier folds), t = 1 the
// analysis's prediction. Moving a handle, or the free mode, gives the paper's interpolation
// between two folds: each fold point moves along the border, and every state between is a
// fold of its own. Every state drawn is the server's (POST /api/interpolate at the fraction
// t: its border, layers, heights and fold line); the browser holds no fold geometry.
// One request is in flight at a time and only the newest state wanted is asked next, so a
// drag follows the pointer; a request left behind by a newer state for longer than
// STALE_MS is aborted.

import * as api from "./api.js";
import * as store from "./store.js";
import * as router from "./router.js";
import { AngleInputs, R, TAU, dragOnCircle, drawFoldCircle, wrap } from "./circle.js";
import { boundsOf, drawCloth, labelCorners, line, textSize, viewport } from "./draw.js";
import { fmtFold } from "./format.js";
import { enlarge } from "./result.js";
import { markEdges, readable } from "./readout.js";
import { notice } from "./view-upload.js";

const $ = (sel) => document.querySelector(sel);
const SEQUENCE = "all";
/** A request still unanswered this long after a newer state was wanted is given up. */
const STALE_MS = 100;
/** States asked for a motion's outline: its bounds and the colour scale's two ends. */
const OUTLINE_AT = [0, 0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 1];
let showError = () => {};

/**
 * Runs `run(job, signal)` for the newest job wanted, one at a time: a job wanted while
 * another runs waits (replacing any job waiting before it); the running one is aborted once
 * it has run STALE_MS past the moment a newer job was wanted. Jobs of one `key` run once.
 */
class Follower {
  constructor(run) {
    Object.assign(this, { run, next: null, running: null, done: null });
  }

  want(key, job) {
    if (key === this.done && !this.running) return;
    this.next = { key, job };
    if (!this.running) return void this.pump();
    const running = this.running;
    clearTimeout(running.timer);
    running.timer = setTimeout(() => running.controller.abort(), Math.max(0, running.started + STALE_MS - performance.now()));
  }

  async pump() {
    while (this.next) {
      const { key, job } = this.next;
      this.next = null;
      if (key === this.done) continue;
      const controller = new AbortController();
      this.running = { controller, started: performance.now(), timer: null };
      try {
        await this.run(job, controller.signal);
        this.done = key;
      } catch (e) {
        if (!api.isAbort(e)) showError(e.message);
      } finally {
        clearTimeout(this.running.timer);
        this.running = null;
      }
    }
  }
}

/**
 * Keeps an <img> showing the dGLI disk of the latest state asked for (one request at a
 * time, the newest waiting). The colour scale is fixed per motion: the larger of the scales
 * of its two end states, so a colour means one value all the way through.
 */
class DiskFollower {
  constructor(img, status, size = 480) {
    Object.assign(this, { img, status, size, busy: false, next: null, shown: null, url: null, motion: null, scale: null, job: null, onShown: null });
  }

  /** The request for `job`'s disk at `size` px, in the motion's colour scale. */
  request(job, size) {
    return { border: job.border, reference: job.reference, size, scale: this.scale || undefined };
  }

  /** The values of `job`'s disk cells (`{n, size, values(k)}`), for a readout. */
  async cells(job) {
    const r = await api.diskCells({ border: job.border, reference: job.reference, size: this.size });
    return { ...r, values: (k) => ({ value: r.values[k] }) };
  }

  /** The state shown, at full resolution and in the same colour scale, in the shared dialog, its cells readable. */
  async enlarge(caption) {
    const job = this.job;
    if (!job) return;
    try {
      const { url } = await api.disk(this.request(job, 1400), "disk-large");
      enlarge(url, caption, { read: (stage, img, slot) => readable(stage, img, "state", () => this.cells(job), undefined, slot) });
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
  /** Why the cloth chosen is not on this server (a store.Missing), or null. */
  missing: null,
  result: null,
  /** The flat border (the analysis's start border). */
  border: null,
  /** Corner vertices and angles. */
  corners: [],
  cornerAngles: [],
  from: [0, 0],
  to: [Math.PI / 4, (5 * Math.PI) / 4],
  /** The step animated ("1", "2", …), SEQUENCE, or "free". */
  mode: "1",
  tau: 0,
  /** The disk cell read ({k, i, j, d}), whose edges are marked; null: none. */
  cell: null,
  bounds: null,
  playing: false,
  /** Counts motions: a new one (new folds, cloth or mode) fixes a new colour scale. */
  motion: 0,
  /** The state drawn: {key, t, fold, border, state, now}. */
  frame: null,
  /** The motion's outline (OUTLINE_AT states), once it came: {motion, ends}. */
  outline: null,
  /** How the drag of a handle went: states wanted and drawn, each drawn one's wait (ms). */
  stats: { asked: 0, shown: 0, waits: [] },
};

/**
 * The analysis's folds in order, each as its step reports it ({fold, arcs, line}): fold k of
 * `result.folds` is `folded()[k]`. A step seen only flat and folded may hold a sequence
 * (`steps[k].folds`), played fold by fold.
 */
const folded = () => (view.result?.steps || []).flatMap((s) => (s.folds?.length ? s.folds : s.fold ? [s] : []));

/** Folds 1…k of the analysis as the server takes them before a motion (`prior`). */
const priorOf = (k) => folded().slice(0, k).map((s) => ({ arcs: s.arcs, line: s.line }));

const sameFold = (a, b) => Math.abs(wrap(a[0]) - wrap(b[0])) < 1e-12 && Math.abs(wrap(a[1]) - wrap(b[1])) < 1e-12;

/**
 * What moves now, and at which fraction: {motion (the request's fields but `at`), t, fold
 * (its number, 1-based, in sequence mode), kind ("turn" or "between")}.
 */
function current() {
  const steps = folded();
  if (view.mode === SEQUENCE) {
    const x = view.tau * steps.length;
    const k = Math.min(Math.floor(x), steps.length - 1);
    return { motion: { prior: priorOf(k), arcs: steps[k].arcs, line: steps[k].line }, t: x - k, fold: k + 1, kind: "turn" };
  }
  const k = Number(view.mode);
  if (Number.isInteger(k) && steps[k - 1]) {
    // The step's own fold, its handles untouched, turns over as the analysis made it.
    const own = view.from[0] === view.from[1] && sameFold(view.to, steps[k - 1].fold);
    const motion = own ? { arcs: steps[k - 1].arcs, line: steps[k - 1].line } : { from: view.from, to: view.to };
    return { motion: { prior: priorOf(k - 1), ...motion }, t: view.tau, fold: k, kind: own ? "turn" : "between" };
  }
  return { motion: { prior: [], from: view.from, to: view.to }, t: view.tau, fold: null, kind: "between" };
}

/** The request for the states at fractions `at` of `motion`. */
function request(motion, at) {
  const { prior, ...rest } = motion;
  return { border: view.border, ...(prior.length ? { prior } : {}), ...rest, at, drawn: true };
}

/** What the motion says it is, in words. */
function motionText({ kind, fold }) {
  if (kind === "turn") {
    const which = fold > 1 ? `Fold ${fold}` : "The fold";
    return `${which} as the analysis made it: its flap turns over about its line (t = 0 ${fold > 1 ? "the state before it" : "flat"}, t = 1 the analysis's prediction).`;
  }
  return "The paper's interpolation between two folds: each fold point moves along the border from “from” to “to”, and every state between is a fold of its own.";
}

function fillCloths() {
  const select = $("#interp-sample");
  const cloths = store.cloths();
  const value = view.cloth ? `${view.cloth.kind}:${view.cloth.id}` : select.value;
  const options = cloths.map((c) => new Option(c.name, `${c.kind}:${c.id}`));
  // A cloth the server does not have stays named in the box, as the notice says.
  if (view.missing && !cloths.some((c) => `${c.kind}:${c.id}` === value)) {
    options.unshift(Object.assign(new Option(`${view.cloth.kind} ${view.cloth.id} (not on this server)`, value), { disabled: true }));
  }
  select.replaceChildren(...options);
  if (value) select.value = value;
}

/**
 * Say that the cloth chosen is not on this server (`missing`, a store.Missing), in place of
 * its motion: nothing of another cloth stays drawn, and no request is made for it. Null:
 * the notice goes.
 */
function setMissing(missing) {
  view.missing = missing;
  const stage = $("#view-interpolate .interp-stage");
  stage.classList.toggle("gone", Boolean(missing));
  const slot = $("#interp-missing");
  slot.replaceChildren(...(missing ? [notice(missing, ({ result }) => {
    store.set({ cloth: { kind: "upload", id: result.key } });
    shown();
  })] : []));
  slot.hidden = !missing;
  if (!missing) return;
  Object.assign(view, { result: null, border: null, frame: null, outline: null, corners: [], cornerAngles: [] });
  $("#interp-step").replaceChildren();
  $("#interp-readout").textContent = "";
  $("#interp-motion").textContent = "";
  fillCloths();
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
  $("#fold-input-status").textContent = "";
  setMissing(null);
  try {
    const result = await store.answer(cloth, "interp-cloth");
    if (view.cloth !== cloth) return;
    view.result = result;
    view.border = result.start_border;
    view.corners = result.corner_vertices;
    view.cornerAngles = result.corners;
    view.mode = result.folds.length ? "1" : "free";
    fillSteps();
    setMode(view.mode);
    if (params) applyParams(params);
    // Only while the view is on screen: Back may have left it during the load.
    if (!$("#view-interpolate").hidden) document.title = router.title("interpolate", $("#interp-sample").selectedOptions[0]?.textContent || "");
  } catch (e) {
    if (view.cloth !== cloth) return;
    if (e instanceof store.Missing) setMissing(e);
    else if (!api.isAbort(e)) showError(e.message);
  }
}

/** Animate step `mode` of the cloth's folds (or the sequence, or free folds). */
function setMode(mode) {
  view.mode = mode;
  const steps = folded();
  const k = Number(mode);
  if (Number.isInteger(k) && steps[k - 1]) {
    view.to = steps[k - 1].fold.map(wrap);
    view.from = [view.to[0], view.to[0]];
  }
  const sequence = mode === SEQUENCE;
  for (const id of ["#from-1", "#from-2", "#to-1", "#to-2", "#swap-folds"]) $(id).disabled = sequence;
  view.bounds = null;
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

/** After folds, the cloth or the mode changed: a new motion; its outline is asked for. */
function changed() {
  if (!view.border) return;
  view.motion += 1;
  view.outline = null;
  inputs.write({ "from-1": view.from[0], "from-2": view.from[1], "to-1": view.to[0], "to-2": view.to[1] });
  $("#interp-motion").textContent = motionText(current());
  // The sequence's outline is each of its folds' in turn.
  const motions = view.mode === SEQUENCE ? folded().map((s, k) => ({ prior: priorOf(k), arcs: s.arcs, line: s.line })) : [current().motion];
  outlines.want(`${view.motion}|${motionKey()}`, { motions, count: view.motion });
  draw();
}

/** The motions' states at OUTLINE_AT: the drawing's bounds and the disk's colour-scale ends (the first state and the last). */
async function outlineOf({ motions, count }, signal) {
  const answers = [];
  for (const motion of motions) answers.push(await api.json(null, "/api/interpolate", request(motion, OUTLINE_AT), signal));
  if (count !== view.motion) return;
  for (const a of answers) grow(a.borders, a.states);
  const [first, last] = [answers[0], answers[answers.length - 1]];
  const end = last.borders.length - 1;
  view.outline = { motion: count, ends: [lifted(first.borders[0], first.states[0].heights), lifted(last.borders[end], last.states[end].heights)] };
  paint();
}

/** The border of a state as its disk sees it: each vertex at its height. */
const lifted = (border, heights) => border.map((p, v) => [p[0], p[1], heights[v]]);

/** Widen the drawing's bounds to hold `borders` and their `states`' layers (never narrowed within one motion's family). */
function grow(borders, states) {
  const shapes = [...borders, ...states.flatMap((s) => s.layers.map((l) => l.points))];
  const b = boundsOf(view.bounds ? [view.border, ...shapes, [[view.bounds.x0, view.bounds.y0], [view.bounds.x1, view.bounds.y1]]] : [view.border, ...shapes]);
  const same = view.bounds && ["x0", "x1", "y0", "y1"].every((k) => b[k] === view.bounds[k]);
  view.bounds = b;
  return !same;
}

/** Names the motion (not its t). */
const motionKey = () => `${view.cloth?.kind}:${view.cloth?.id}|${view.mode}|${JSON.stringify(current().motion)}`;

/** Names the state drawn: the cloth, the motion and t. */
export function diskKey() {
  return view.frame ? view.frame.key : "";
}

function setTau(tau) {
  view.tau = Math.min(1, Math.max(0, tau));
  $("#interp-slider").value = Math.round(view.tau * 1000);
  draw();
  // While playing, the URL is written once the motion stops (not 60 times a second).
  if (!view.playing) keepUrl();
}

/** Ask for the state now on screen (one request at a time: see Follower). */
function draw() {
  if (!view.border) return;
  const now = current();
  drawCircle(now);
  const key = `${motionKey()}|${now.t}`;
  view.stats.asked += 1;
  frames.want(key, { key, now, wanted: performance.now() });
}

/** Fetch the state `job` wants and draw it. */
async function fetchFrame({ key, now, wanted }, signal) {
  const answer = await api.json(null, "/api/interpolate", request(now.motion, [now.t]), signal);
  view.frame = { key, t: now.t, fold: answer.folds[0], border: answer.borders[0], state: answer.states[0], now };
  view.stats.shown += 1;
  view.stats.waits.push(performance.now() - wanted);
  paint();
}

/** Draw the frame fetched last: the flat cloth dashed, the state's layers and outline, its fold line, corners and the cell's edges. */
function paint() {
  const frame = view.frame;
  if (!frame) return;
  grow([frame.border], [frame.state]);
  const canvas = $("#interp-canvas");
  const ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  const v = viewport(canvas, view.bounds, 40);
  ctx.setLineDash([6, 6]);
  ctx.strokeStyle = "#9aa4b2";
  ctx.lineWidth = 1.5;
  ctx.beginPath();
  view.border.forEach((p, k) => (k ? ctx.lineTo(v.X(p), v.Y(p)) : ctx.moveTo(v.X(p), v.Y(p))));
  ctx.closePath();
  ctx.stroke();
  ctx.setLineDash([]);
  drawCloth(ctx, v, frame.state.layers, frame.border);
  const size = textSize(canvas);
  labelCorners(ctx, v, frame.border, view.corners, size);
  markEdges(ctx, [frame.border], (p) => [v.X(p), v.Y(p)], view.cell, size / 15);
  const segment = frame.state.segment;
  if (segment) line(ctx, v, segment[0], segment[1], "#d1495b", 3);
  const which = frame.now.fold && view.mode === SEQUENCE ? `fold ${frame.now.fold} of ${folded().length}` : "fold";
  $("#interp-readout").textContent = `t = ${view.tau.toFixed(3)}   ${which} ${fmtFold(frame.fold)}`;
  canvas.dataset.key = frame.key;
  // The disk only while it is on screen; showing the view draws again.
  if (!$("#view-interpolate").hidden && view.outline && view.outline.motion === view.motion) {
    disk.show(frame.key, lifted(frame.border, frame.state.heights), view.border, view.motion, view.outline.ends);
  }
}

function drawCircle(now) {
  const handles = [];
  // Rings 2 handle radii apart: a "from" and a "to" handle at one angle do not overlap.
  for (const [which, color, r, word] of [["from", "#2b6cb0", R + 12, "from"], ["to", "#c05621", R + 32, "to"]]) {
    view[which].forEach((angle, k) => handles.push({ id: `${which}:${k}`, angle, color, label: k + 1, r, name: `${word} fold point ${k + 1}` }));
  }
  const steps = folded();
  const before = now.motion.prior.length;
  const arcs = steps.slice(0, before).map((s) => ({ fold: s.fold, color: "#9aa4b2" }));
  const moving = now.kind === "turn" ? steps[(now.fold || 1) - 1].fold : view.frame?.fold || view.to;
  arcs.push({ fold: moving, color: "#d1495b" });
  drawFoldCircle($("#fold-circle"), view.cornerAngles, arcs, view.mode === SEQUENCE ? [] : handles);
  if (view.mode === SEQUENCE) inputs.write({ "from-1": moving[0], "from-2": moving[0], "to-1": moving[0], "to-2": moving[1] });
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
  const seconds = 2.5 * (view.mode === SEQUENCE ? folded().length : 1);
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

let disk = null;
let inputs = null;
let frames = null;
let outlines = null;

export function setup(errors, planGoal) {
  showError = errors;
  frames = new Follower(fetchFrame);
  outlines = new Follower(outlineOf);
  disk = new DiskFollower($("#interp-disk"), $("#interp-disk-status"));
  // The disk's cells read by hover, tap or arrow keys; their edges marked on the cloth.
  const cells = readable($("#interp-disk-zoom"), $("#interp-disk"), "state", async () => {
    if (!disk.job) throw new Error("no disk drawn yet");
    return disk.cells(disk.job);
  }, (c) => {
    view.cell = c;
    paint();
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
  $("#plan-goal").addEventListener("click", () => planGoal(view.cloth, view.to));
  dragOnCircle($("#fold-circle"), (id, angle) => {
    const [which, k] = id.split(":");
    view[which] = view[which].map((a, i) => (i === Number(k) ? angle : a));
    changed();
  }, keepUrl);
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
    paint();
    keepUrl();
  } else document.title = router.title("interpolate");
}

/**
 * How the view follows what is asked of it: the state wanted now and the one drawn (equal
 * once it caught up), and the counts since `reset`: states asked for, shown, and each shown
 * one's wait in ms.
 */
export function following(reset = false) {
  if (reset) view.stats = { asked: 0, shown: 0, waits: [] };
  const now = view.border ? `${motionKey()}|${current().t}` : null;
  return { wanted: now, drawn: view.frame?.key || null, ...view.stats };
}

// For tests and the console.
export const state = () => ({ ...view, drawn: view.frame?.border || null, disk: view.frame ? lifted(view.frame.border, view.frame.state.heights) : null });
export { setTau, setMode, TAU };
