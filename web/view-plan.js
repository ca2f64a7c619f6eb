// The Plan view: a goal fold on the fold circle, the plan from the cloth's current state,
// each step drawn (states, fold line, pick → place arrows) and said in words.

import * as api from "./api.js";
import * as store from "./store.js";
import * as router from "./router.js";
import { AngleInputs, R, TAU, dragOnCircle, drawFoldCircle, wrap } from "./circle.js";
import { boundsOf, bowedArrow, drawCloth, labelCorners, line, polygon, textSize, viewport } from "./draw.js";
import { el, fmtDeg, fmtPoint } from "./format.js";
import { notice } from "./view-upload.js";

const $ = (sel) => document.querySelector(sel);
const ACTIONS = { fold: "Fold", unfold: "Unfold" };
const CASES = {
  fold: "The cloth is flat: one fold reaches the goal.",
  direct: "The goal folds the same corners as now: one step moves them straight there.",
  unfold_then_fold: "The goal folds other corners: unfold first, then fold the goal.",
  already_there: "The cloth is already folded as the goal asks: nothing to do.",
};
let showError = () => {};

const view = { cloth: null, missing: null, goal: [Math.PI / 4, (5 * Math.PI) / 4], folds: [], corners: [], cornerVertices: [], name: "", flat: null };
let inputs = null;

/** "a", "a and b", "a, b and c". */
const listed = (items) => (items.length > 1 ? `${items.slice(0, -1).join(", ")} and ${items[items.length - 1]}` : items.join(""));

/**
 * What a plan step does, in words; `cornerOf(vertex)` numbers a corner vertex, `size` is the
 * cloth's size (a grasp that moves a point less than 1 % of it moves nothing).
 */
function stepText(step, cornerOf, size) {
  const verb = ACTIONS[step.action] || step.action;
  const moves = (p) => Math.hypot(p.to[0] - p.from[0], p.to[1] - p.from[1]) > 0.01 * size;
  if (!step.corners.length && !step.picks.some(moves)) {
    return `${verb} along ${fmtDeg(step.fold)}: this fold turns no part of the cloth over (its two points lie together or along an edge): nothing to do.`;
  }
  const grasped = [];
  const picks = step.picks.map((p) => {
    const corner = cornerOf(p.vertex);
    if (corner) grasped.push(corner);
    const what = corner ? `corner ${corner} (vertex ${p.vertex})` : `vertex ${p.vertex}`;
    return step.action === "unfold" ? `grasp ${what} at ${fmtPoint(p.from)} and put it back at ${fmtPoint(p.to)}` : `grasp ${what} at ${fmtPoint(p.from)} and place it at ${fmtPoint(p.to)}`;
  });
  const followers = step.corners.filter((c) => !grasped.includes(c));
  const moved = step.corners.length ? `moves corner${step.corners.length > 1 ? "s" : ""} ${listed(step.corners)}` : "moves no corner";
  const follow = followers.length ? `; corner${followers.length > 1 ? "s" : ""} ${listed(followers)} ${followers.length > 1 ? "follow" : "follows"} with the cloth` : "";
  // Points are the sample's own (x, y) coordinates, in whatever unit its file uses.
  const where = picks.length ? ` (x, y in the sample's units)` : "";
  return `${verb} along ${fmtDeg(step.fold)}: ${moved}; ${picks.join("; ") || "nothing to grasp"}${follow}${where}.`;
}

/**
 * A first goal that folds the cloth in half along an axis of its outline, read off its corners
 * alone (border angles, `n` border vertices): two of its corners and side middles half the
 * border apart — the hem's and the neck's middles of a T-shirt, the waist's middle and the
 * crotch of trousers, opposite sides' middles of a napkin — the longest side's middle first.
 */
function halfGoal(corners, n) {
  const sides = corners.map((c, k) => [c, (k + 1 < corners.length ? corners[k + 1] : corners[0] + TAU) - c]);
  const points = [...sides.map(([c, span]) => ({ at: wrap(c + span / 2), span })), ...corners.map((c) => ({ at: c, span: 0 }))];
  const apart = (a, b) => Math.abs(wrap(b - a + Math.PI) - Math.PI);
  const candidates = points.map((p) => {
    const other = points.reduce((best, q) => (apart(q.at, p.at + Math.PI) < apart(best.at, p.at + Math.PI) ? q : best));
    return { goal: [p.at, other.at], off: apart(other.at, p.at + Math.PI), span: p.span };
  });
  // Within half an edge of the best pairing, the longest side's middle.
  const best = Math.min(...candidates.map((c) => c.off));
  return candidates.filter((c) => c.off <= best + TAU / (2 * n)).reduce((a, b) => (b.span > a.span ? b : a)).goal;
}

function fillCloths() {
  const select = $("#plan-sample");
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
 * Say that the cloth chosen is not on this server (`missing`, a store.Missing) in place of
 * its plan, and plan nothing for it; null: the notice goes.
 */
function setMissing(missing) {
  view.missing = missing;
  const slot = $("#plan-missing");
  slot.replaceChildren(...(missing ? [notice(missing, ({ result }) => {
    const cloth = { kind: "upload", id: result.key };
    store.set({ cloth });
    load(cloth, true);
  })] : []));
  slot.hidden = !missing;
  $("#plan-run").disabled = Boolean(missing);
  if (!missing) return;
  Object.assign(view, { folds: [], corners: [], cornerVertices: [], flat: null, name: "" });
  for (const id of ["#plan-now", "#plan-case", "#plan-preview-note"]) $(id).textContent = "";
  $("#plan-list").replaceChildren();
  $("#plan-json").hidden = true;
  $("#plan-preview").getContext("2d").clearRect(0, 0, $("#plan-preview").width, $("#plan-preview").height);
  fillCloths();
  drawCircle();
}

/** The view's state as URL parameters: the cloth and the goal. */
function keepUrl() {
  if (!view.cloth) return;
  router.keep("plan", new URLSearchParams({ cloth: `${view.cloth.kind}:${view.cloth.id}`, goal: router.angleText(view.goal) }));
}

/** Load the current state of `cloth`; `takeGoal` starts the goal on a diagonal. */
async function load(cloth, takeGoal) {
  view.cloth = cloth;
  setMissing(null);
  fillCloths();
  try {
    const result = await store.answer(cloth, "plan-cloth");
    if (view.cloth !== cloth) return;
    view.folds = result.folds;
    view.corners = result.corners;
    view.cornerVertices = result.corner_vertices;
    view.flat = result.start_border;
    view.name = $("#plan-sample").selectedOptions[0]?.textContent || result.name;
    $("#plan-now").textContent = `${view.name}: N = ${result.n}, ${result.corners.length} corners, now ${result.folds.length ? result.folds.map(fmtDeg).join(" then ") : "flat"}.`;
    if (takeGoal && result.corners.length >= 2) view.goal = halfGoal(result.corners, result.n);
    $("#plan-list").replaceChildren();
    $("#plan-case").textContent = "";
    drawCircle();
    writeInputs();
    keepUrl();
    // Only while the view is on screen: Back may have left it during the load.
    if (!$("#view-plan").hidden) document.title = router.title("plan", view.name);
  } catch (e) {
    if (view.cloth !== cloth) return;
    if (e instanceof store.Missing) setMissing(e);
    else if (!api.isAbort(e)) showError(e.message);
  }
}

function drawCircle() {
  const arcs = view.folds.map((fold) => ({ fold, color: "#2b6cb0" }));
  arcs.push({ fold: view.goal, color: "#c05621" });
  const handles = view.goal.map((angle, k) => ({ id: String(k), angle, color: "#c05621", label: k + 1, r: R + 18, name: `goal fold point ${k + 1}` }));
  drawFoldCircle($("#plan-circle"), view.corners, arcs, handles);
  preview();
}

/**
 * The goal made on the flat cloth, drawn under the circle as its handles move: the server's
 * state (`POST /api/interpolate` from the goal to itself, at its end), the newest goal asked
 * superseding any request still on its way.
 */
async function preview() {
  const canvas = $("#plan-preview");
  if (!view.flat) return;
  const goal = view.goal;
  try {
    const answer = await api.interpolate({ border: view.flat, from: goal, to: goal, at: [1], drawn: true }, "plan-preview");
    if (goal !== view.goal) return;
    const [state, border] = [answer.states[0], answer.borders[0]];
    const ctx = canvas.getContext("2d");
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    const v = viewport(canvas, boundsOf([view.flat, border]), 12);
    polygon(ctx, v, view.flat, { stroke: "#9aa4b2", width: 1.2, dash: [4, 4] });
    drawCloth(ctx, v, state.layers, border, { width: 1.8 });
    if (state.segment) line(ctx, v, state.segment[0], state.segment[1], "#d1495b", 2);
    canvas.setAttribute("aria-label", `The goal ${fmtDeg(goal)} made on the flat cloth`);
    $("#plan-preview-note").textContent = "The goal made on the flat cloth";
  } catch (e) {
    // A goal being dragged may pass through folds that cannot be made: said here, not as the page's error.
    if (!api.isAbort(e)) $("#plan-preview-note").textContent = `(no preview: ${e.message})`;
  }
}

const writeInputs = () => inputs.write({ "goal-1": view.goal[0], "goal-2": view.goal[1] });

/**
 * Whether the cloth's state reaches the goal, in the server's words (`POST /api/verify`'s
 * `text`: "goal reached …", or what is off and the grasp that corrects it), shown under the
 * plan's case; its own paragraph, made here, so the page's markup stays as it is.
 */
async function verdict() {
  let p = $("#plan-verdict");
  if (!p) {
    p = el("p", { id: "plan-verdict", className: "plan-case" });
    p.setAttribute("aria-live", "polite");
    $("#plan-case").after(p);
  }
  p.textContent = "";
  const res = await api.json("plan-verify", "/api/verify", { sample: view.cloth.id, goal: [view.goal] });
  p.textContent = res.text;
  p.dataset.reached = res.reached;
}

/** Ask the server for the plan and draw every step. */
async function plan() {
  if (!view.cloth || view.missing) return;
  const list = $("#plan-list");
  list.setAttribute("aria-busy", "true");
  $("#plan-case").textContent = "Planning…";
  $("#plan-json").hidden = true;
  try {
    const [res] = await Promise.all([api.plan({ sample: view.cloth.id, goal: view.goal }), verdict()]);
    Object.assign(view, { folds: res.folds, corners: res.corners });
    drawCircle();
    const count = res.steps.length;
    $("#plan-case").textContent = `${count} step${count === 1 ? "" : "s"} · ${CASES[res.case] || res.case}`;
    const download = $("#plan-json");
    if (download.href) URL.revokeObjectURL(download.href);
    download.href = URL.createObjectURL(new Blob([JSON.stringify(res, null, 1)], { type: "application/json" }));
    download.download = `plan_${view.cloth.id}.json`.replace(/[^\w.-]+/g, "-");
    download.hidden = false;
    list.replaceChildren();
    stepCards(res, list);
    showError("");
  } catch (e) {
    if (api.isAbort(e)) return;
    list.replaceChildren();
    $("#plan-case").textContent = "";
    showError(e.message);
  } finally {
    list.removeAttribute("aria-busy");
  }
}

/** Add a card per state of the plan (the server draws them: `res.states`) to `list`, each drawn once on the page: its labels sized for the width it is shown at. */
function stepCards(res, list) {
  const flat = res.start_border;
  const n = flat.length;
  const bounds = boundsOf([flat, ...res.states.flatMap((s) => [s.border, ...s.layers.map((l) => l.points)]), ...res.steps.flatMap((s) => s.picks.map((p) => [p.from, p.to]))]);
  const flatBounds = boundsOf([flat]);
  const extent = Math.hypot(flatBounds.x1 - flatBounds.x0, flatBounds.y1 - flatBounds.y0);
  // Input vertex (what picks name) → 1-based corner number.
  const cornerOf = (vertex) => {
    const border = res.border_indices ? res.border_indices.indexOf(vertex) : vertex;
    const i = view.cornerVertices.indexOf(border);
    return i >= 0 ? i + 1 : null;
  };
  res.states.forEach((state, k) => {
    const step = k ? res.steps[k - 1] : null;
    const canvas = el("canvas", { width: 520, height: 420 });
    canvas.setAttribute("role", "img");
    const title = el("h3", { textContent: step ? `Step ${k} · ${ACTIONS[step.action] || step.action}` : "Now" });
    const words = el("p", { textContent: step ? stepText(step, cornerOf, extent) : res.folds.length ? `Folded along ${res.folds.map(fmtDeg).join(", then ")}.` : "Flat." });
    canvas.setAttribute("aria-label", words.textContent);
    const li = el("li", { className: "plan-step" }, canvas, el("div", {}, title, words));
    if (step) li.dataset.picks = step.picks.length;
    list.append(li);
    const ctx = canvas.getContext("2d");
    const size = textSize(canvas);
    // Room round the cloth for the corner labels.
    const v = viewport(canvas, bounds, 28 + size);
    polygon(ctx, v, flat, { stroke: "#cbd2dc", width: 1.2, dash: [5, 5] });
    if (step) polygon(ctx, v, res.states[k - 1].border, { stroke: "#6b7280", width: 1.5, dash: [2, 4] });
    drawCloth(ctx, v, state.layers, state.border);
    labelCorners(ctx, v, state.border, view.cornerVertices, size);
    if (step) {
      // The line a fold step folds along, across the cloth it folds (an unfold's across the
      // state it goes back to).
      if (state.segment) line(ctx, v, state.segment[0], state.segment[1], "#d1495b", 2.5);
      // Bowed away from the cloth's middle, so an arrow along an edge is not hidden by it.
      const centre = [0, 1].map((c) => flat.reduce((sum, p) => sum + p[c], 0) / n);
      const mids = step.picks.map((pick) => bowedArrow(ctx, v, pick.from, pick.to, centre, "#2f855a"));
      canvas.dataset.arrows = JSON.stringify(step.picks.map((pick, k) => ({ from: [v.X(pick.from), v.Y(pick.from)], to: [v.X(pick.to), v.Y(pick.to)], mid: mids[k] })));
    }
  });
}

export function setup(errors) {
  showError = errors;
  inputs = new AngleInputs({ "goal-1": $("#goal-1"), "goal-2": $("#goal-2") }, $("#goal-input-status"), (key, angle) => {
    view.goal = view.goal.map((a, i) => (i === Number(key.slice(-1)) - 1 ? angle : a));
    drawCircle();
    keepUrl();
  });
  $("#plan-sample").addEventListener("change", (e) => {
    const [kind, ...rest] = e.target.value.split(":");
    const cloth = { kind, id: rest.join(":") };
    store.set({ cloth });
    load(cloth, true);
  });
  $("#plan-run").addEventListener("click", plan);
  dragOnCircle($("#plan-circle"), (id, angle) => {
    view.goal = view.goal.map((a, i) => (i === Number(id) ? angle : a));
    drawCircle();
    writeInputs();
    keepUrl();
  });
  store.subscribe(() => fillCloths());
}

/** The view came on screen, maybe with a goal to plan for (from Interpolate or the URL) and a link's cloth. */
export function shown(goal = null, linked = null) {
  if (linked) store.set({ cloth: linked });
  const { cloth } = store.get();
  const wanted = cloth || store.cloths()[0] || null;
  if (goal) view.goal = [wrap(goal[0]), wrap(goal[1])];
  let ready = Promise.resolve();
  if (wanted && (!view.cloth || view.cloth.kind !== wanted.kind || view.cloth.id !== wanted.id)) ready = load(wanted, !goal);
  else {
    fillCloths();
    if (view.cloth) {
      drawCircle();
      writeInputs();
      keepUrl();
    }
    document.title = router.title("plan", view.name);
  }
  // A goal given (a link, Interpolate's "to") is planned at once: the plan shows what it asks.
  if (goal) ready.then(() => view.cloth && plan());
}
