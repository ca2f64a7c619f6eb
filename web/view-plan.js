// The Plan view: a goal fold on the fold circle, the plan from the cloth's current state,
// each step drawn (states, fold line, pick → place arrows) and said in words.

import * as api from "./api.js";
import * as store from "./store.js";
import * as router from "./router.js";
import { wrap } from "./fold.mjs";
import { AngleInputs, R, dragOnCircle, drawFoldCircle } from "./circle.js";
import { boundsOf, bowedArrow, cornerVertex, drawCloth, foldAll, labelCorners, line, made, polygon, textSize, viewport } from "./draw.js";
import { el, fmtDeg, fmtPoint } from "./format.js";

const $ = (sel) => document.querySelector(sel);
const ACTIONS = { fold: "Fold", unfold: "Unfold" };
const CASES = {
  fold: "The cloth is flat: one fold reaches the goal.",
  direct: "The goal folds the same corners as now: one step moves them straight there.",
  unfold_then_fold: "The goal folds other corners: unfold first, then fold the goal.",
  already_there: "The cloth is already folded as the goal asks: nothing to do.",
};
let showError = () => {};

const view = { cloth: null, goal: [Math.PI / 4, (5 * Math.PI) / 4], folds: [], corners: [], name: "" };
let inputs = null;

/** What a plan step does, in words; `cornerOf(vertex)` numbers a corner vertex. */
function stepText(step, cornerOf) {
  const moved = step.corners.length ? `moves corner${step.corners.length > 1 ? "s" : ""} ${step.corners.join(" and ")}` : "moves no corner";
  const picks = step.picks.map((p) => {
    const corner = cornerOf(p.vertex);
    const what = corner ? `corner ${corner} (vertex ${p.vertex})` : `vertex ${p.vertex}`;
    return step.action === "unfold" ? `grasp ${what} at ${fmtPoint(p.from)} and put it back at ${fmtPoint(p.to)}` : `grasp ${what} at ${fmtPoint(p.from)} and place it at ${fmtPoint(p.to)}`;
  });
  // Points are the sample's own (x, y) coordinates, in whatever unit its file uses.
  const where = picks.length ? ` (x, y in the sample's units)` : "";
  return `${ACTIONS[step.action] || step.action} along ${fmtDeg(step.fold)}: ${moved}; ${picks.join("; ") || "nothing to grasp"}${where}.`;
}

function fillCloths() {
  const select = $("#plan-sample");
  const value = view.cloth ? `${view.cloth.kind}:${view.cloth.id}` : select.value;
  select.replaceChildren(...store.cloths().map((c) => new Option(c.name, `${c.kind}:${c.id}`)));
  if (value) select.value = value;
}

/** The view's state as URL parameters: the cloth and the goal. */
function keepUrl() {
  if (!view.cloth) return;
  router.keep("plan", new URLSearchParams({ cloth: `${view.cloth.kind}:${view.cloth.id}`, goal: router.angleText(view.goal) }));
}

/** Load the current state of `cloth`; `takeGoal` starts the goal on a diagonal. */
async function load(cloth, takeGoal) {
  view.cloth = cloth;
  fillCloths();
  try {
    const result = cloth.kind === "upload" ? store.get().uploads.find((u) => u.key === cloth.id)?.result : await api.sample(cloth.id, "plan-cloth");
    if (!result) throw new Error("that upload is no longer in this page: upload it again");
    if (view.cloth !== cloth) return;
    view.folds = result.folds;
    view.corners = result.corners;
    view.name = $("#plan-sample").selectedOptions[0]?.textContent || result.name;
    $("#plan-now").textContent = `${view.name}: N = ${result.n}, ${result.corners.length} corners, now ${result.folds.length ? result.folds.map(fmtDeg).join(" then ") : "flat"}.`;
    if (takeGoal && result.corners.length >= 2) {
      // A diagonal through the first and third corners, a natural first goal.
      const c = result.corners;
      view.goal = [c[0], c[Math.min(2, c.length - 1)]];
    }
    $("#plan-list").replaceChildren();
    $("#plan-case").textContent = "";
    drawCircle();
    writeInputs();
    keepUrl();
    // Only while the view is on screen: Back may have left it during the load.
    if (!$("#view-plan").hidden) document.title = router.title("plan", view.name);
  } catch (e) {
    if (!api.isAbort(e)) showError(e.message);
  }
}

function drawCircle() {
  const arcs = view.folds.map((fold) => ({ fold, color: "#2b6cb0" }));
  arcs.push({ fold: view.goal, color: "#c05621" });
  const handles = view.goal.map((angle, k) => ({ id: String(k), angle, color: "#c05621", label: k + 1, r: R + 18, name: `goal fold point ${k + 1}` }));
  drawFoldCircle($("#plan-circle"), view.corners, arcs, handles);
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
  if (!view.cloth) return;
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

/**
 * The states the plan goes through, from now, as fold lists: an unfold takes the last fold
 * off, a fold folds the flat cloth ("direct" replaces the current folds by the goal at once).
 */
function states(res) {
  // The current folds along the lines the analysis made them along (a fold through stacked
  // layers has no line of its own through its two points).
  let applied = res.folds.map((fold, k) => (res.lines?.[k] ? { fold, line: res.lines[k] } : fold));
  const out = [{ folds: applied }];
  for (const step of res.steps) {
    const before = applied;
    if (step.action === "unfold") applied = applied.slice(0, -1);
    else applied = res.case === "direct" ? [step.fold] : [...applied, step.fold];
    out.push({ step, before, folds: applied });
  }
  return out;
}

/** Add a card per state of the plan to `list`, each drawn once on the page: its labels sized for the width it is shown at. */
function stepCards(res, list) {
  const flat = res.start_border;
  const n = flat.length;
  const at = (folds) => foldAll(flat, folds);
  const all = states(res);
  const bounds = boundsOf([flat, ...all.map((s) => at(s.folds)), ...res.steps.flatMap((s) => s.picks.map((p) => [p.from, p.to]))]);
  // Input vertex (what picks name) → 1-based corner number.
  const cornerVertices = res.corners.map((c) => cornerVertex(c, n));
  const cornerOf = (vertex) => {
    const border = res.border_indices ? res.border_indices.indexOf(vertex) : vertex;
    const i = cornerVertices.indexOf(border);
    return i >= 0 ? i + 1 : null;
  };
  all.forEach(({ step, before, folds }, k) => {
    const canvas = el("canvas", { width: 520, height: 420 });
    canvas.setAttribute("role", "img");
    const title = el("h3", { textContent: step ? `Step ${k} · ${ACTIONS[step.action] || step.action}` : "Now" });
    const words = el("p", { textContent: step ? stepText(step, cornerOf) : res.folds.length ? `Folded along ${res.folds.map(fmtDeg).join(", then ")}.` : "Flat." });
    canvas.setAttribute("aria-label", words.textContent);
    const li = el("li", { className: "plan-step" }, canvas, el("div", {}, title, words));
    if (step) li.dataset.picks = step.picks.length;
    list.append(li);
    const ctx = canvas.getContext("2d");
    const size = textSize(canvas);
    // Room round the cloth for the corner labels.
    const v = viewport(canvas, bounds, 28 + size);
    polygon(ctx, v, flat, { stroke: "#cbd2dc", width: 1.2, dash: [5, 5] });
    if (before) polygon(ctx, v, at(before), { stroke: "#6b7280", width: 1.5, dash: [2, 4] });
    const state = drawCloth(ctx, v, flat, folds);
    labelCorners(ctx, v, state, res.corners, size);
    if (step) {
      // The line a fold step folds along lies on the border it folds (the flat cloth); an
      // unfold's on the state it goes back to.
      const undone = before[before.length - 1];
      const { a, b } = step.action === "unfold" ? made(state, undone) : made(flat, step.fold);
      line(ctx, v, a, b, "#d1495b", 2.5);
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
  if (wanted && (!view.cloth || view.cloth.kind !== wanted.kind || view.cloth.id !== wanted.id)) load(wanted, !goal);
  else {
    fillCloths();
    if (view.cloth) {
      drawCircle();
      writeInputs();
      keepUrl();
    }
    document.title = router.title("plan", view.name);
  }
}
