// The Compare view: #/compare/{a}/{b}, two cloth states side by side. A state is a sample
// (by id or by name: its last analysed frame) or `sample@k` (the state after step k; k = 0
// is the start). Each side has its own title, disk and border; the two disks share one
// colour scale, and the difference disk A − B (the server's) shows where they differ (two
// cloths of other vertex counts have none: the view says so, and asks nothing). A sample
// folded more than once also gets a frame scrubber: frame k − 1, frame k and the
// state the analysis predicts for frame k (its step k `predicted`), on one colour scale.

import * as api from "./api.js";
import * as store from "./store.js";
import * as router from "./router.js";
import { boundsOf, polygon, viewport } from "./draw.js";
import { el } from "./format.js";
import { enlarge } from "./result.js";
import { notice } from "./view-upload.js";

const $ = (sel) => document.querySelector(sel);

/** "x" or "x@k" as {name, step} (step null: the last). */
export function parseState(text) {
  const at = text.lastIndexOf("@");
  const k = text.slice(at + 1);
  return at > 0 && /^\d+$/.test(k) ? { name: text.slice(0, at), step: Number(k) } : { name: text, step: null };
}

/**
 * The sample a state names: an id, else a name (exactly, then ignoring case). Gives its id,
 * or the name as given when the list does not hold it (store.answer then says so).
 */
function sampleId(name) {
  const samples = store.get().samples || [];
  const found = samples.find((s) => s.id === name) || samples.find((s) => s.name === name) || samples.find((s) => s.name.toLowerCase() === name.toLowerCase());
  return found ? found.id : name;
}

/** The border of analysed frame `k` of a listed sample's answer, in border order. */
function borderAt(result, k) {
  const frames = result.sample.mesh ? result.sample.mesh.frames : result.sample.frames;
  const raw = frames[result.start_frame + k];
  return result.border_indices.map((i) => raw[i]);
}

/** Steps of an answer (analysed frames − 1). */
const stepsOf = (result) => (result.steps || []).length;

/** A disk picture that opens large; `request` is what POST /api/disk drew it from. */
function diskFigure(url, caption, request, scale) {
  const img = el("img", { src: url, alt: `dGLI disk: ${caption}`, width: 480, height: 480 });
  img.dataset.scale = scale ? `${scale.s} ${scale.max}` : "";
  img.dataset.picture = "disk";
  const button = el("button", { type: "button", className: "zoom", title: "Open at full resolution" }, img);
  button.setAttribute("aria-label", `${caption}: open at full resolution`);
  button.addEventListener("click", async () => {
    const large = await api.disk({ ...request, size: 1400 }, "compare-large");
    enlarge(large.url, caption);
  });
  return el("figure", {}, button, el("figcaption", { textContent: caption }));
}

/**
 * Draw `states` ({border, reference, caption, title}) into `slot` as disks of one colour
 * scale (the largest of their own), then `extra` figures. `channel` names the requests (a
 * newer draw aborts them).
 */
async function drawShared(slot, states, channel, extra = []) {
  const scales = [];
  for (const [k, s] of states.entries()) {
    const { url, scale } = await api.disk({ border: s.border, reference: s.reference, size: 64 }, `${channel}-scale-${k}`);
    URL.revokeObjectURL(url);
    scales.push(scale);
  }
  const scale = scales.every(Boolean) ? { s: Math.max(...scales.map((s) => s.s)), max: Math.max(...scales.map((s) => s.max)) } : undefined;
  const figures = [];
  for (const [k, s] of states.entries()) {
    const request = { border: s.border, reference: s.reference, size: 480, scale, title: s.title };
    const { url } = await api.disk(request, `${channel}-${k}`);
    figures.push(diskFigure(url, s.caption, request, scale));
  }
  for (const make of extra) figures.push(await make());
  for (const old of slot.querySelectorAll("img")) URL.revokeObjectURL(old.src);
  slot.replaceChildren(...figures);
  return scale;
}

/** The state {border, reference, caption, title, name} of `text` ("x" or "x@k") from its answer. */
function stateOf(text, result, side) {
  const { step } = parseState(text);
  const last = stepsOf(result);
  const k = step === null ? last : step;
  if (k > last) throw new Error(`${result.name} has states 0…${last} (after each step): there is no state after step ${k}`);
  const what = `after step ${k} of ${last} (frame ${result.start_frame + k})`;
  return {
    border: borderAt(result, k),
    reference: borderAt(result, 0),
    caption: `${side}: ${result.name} · ${what}`,
    title: `${side} · ${result.name} · ${what}`.slice(0, 100),
    name: result.name,
  };
}

/** The two states' borders on one canvas: A blue, B orange, each as it lies. */
function bordersFigure(a, b) {
  const canvas = el("canvas", { width: 480, height: 480, className: "compare-borders" });
  canvas.setAttribute("role", "img");
  canvas.setAttribute("aria-label", `Borders: A (${a.name}) blue, B (${b.name}) orange`);
  const ctx = canvas.getContext("2d");
  const v = viewport(canvas, boundsOf([a.border, b.border]), 24);
  polygon(ctx, v, a.border, { stroke: "#1f6feb", width: 3 });
  polygon(ctx, v, b.border, { stroke: "#c05621", width: 2, dash: [6, 4] });
  return el("figure", {}, canvas, el("figcaption", { textContent: `Borders: A ${a.name} (blue), B ${b.name} (orange, dashed)` }));
}

/**
 * The difference disk A − B, from the server. It takes two states of one vertex count: for
 * two others, what it needs is said in its place, and nothing is asked.
 */
async function differenceFigure(a, b, channel) {
  if (a.border.length !== b.border.length) {
    const why = `A − B needs two cloths with as many border vertices: ${a.border.length} and ${b.border.length}.`;
    const figure = el("figure", {}, el("p", { className: "no-picture", textContent: why }));
    figure.dataset.picture = "no-difference";
    return figure;
  }
  const request = { border: a.border, reference: a.reference, minus: { border: b.border, reference: b.reference }, size: 480, title: "A − B: the difference of the two disks" };
  try {
    const { url } = await api.disk(request, `${channel}-difference`);
    const figure = diskFigure(url, "A − B: where the two disks differ (own colour scale)", request, null);
    figure.querySelector("img").dataset.picture = "difference";
    return figure;
  } catch (e) {
    if (api.isAbort(e)) throw e;
    return el("figure", {}, el("p", { className: "error-inline", textContent: `No difference disk: ${e.message}` }));
  }
}

/** The scrubber of a sequence: frame k − 1, frame k and predicted k, for k = 1…steps. */
function scrubber(result) {
  const steps = stepsOf(result);
  const box = el("div", { className: "scrubber card" });
  const id = `scrub-${result.id}`.replace(/[^\w-]/g, "_");
  const input = el("input", { type: "range", min: 1, max: steps, value: 1, step: 1, id });
  const label = el("label", { htmlFor: id, textContent: `${result.name}: step` });
  const out = el("output", { className: "mono", textContent: "1" });
  const panels = el("div", { className: "images compare-panels" });
  const show = async () => {
    const k = Number(input.value);
    out.textContent = `${k} of ${steps}`;
    const [before, after] = [borderAt(result, k - 1), borderAt(result, k)];
    const step = result.steps[k - 1];
    const reference = borderAt(result, 0);
    const folds = result.steps.slice(0, k).filter((s) => s.fold).length;
    const how = folds ? `the start folded by the ${folds === 1 ? "fold" : `${folds} folds`} found in steps 1…${k}` : "no fold found yet: the start";
    const states = [
      { border: before, reference, caption: `frame ${result.start_frame + k - 1} (before step ${k})`, title: `${result.name} · frame ${result.start_frame + k - 1}` },
      { border: after, reference, caption: `frame ${result.start_frame + k} (observed)`, title: `${result.name} · frame ${result.start_frame + k} observed` },
      { border: step.predicted, reference, caption: `predicted frame ${result.start_frame + k} (the analysis's: ${how})`, title: `${result.name} · frame ${result.start_frame + k} predicted` },
    ];
    try {
      // Each scrubber on its own channel: one does not abort the other's pictures.
      await drawShared(panels, states, `scrub-${id}`);
    } catch (e) {
      if (!api.isAbort(e)) panels.replaceChildren(el("p", { className: "error-inline", textContent: e.message }));
    }
  };
  input.addEventListener("input", show);
  box.append(el("h2", { className: "card-title", textContent: `Frame scrubber: ${result.name}` }), el("div", { className: "row" }, label, input, out), panels);
  show();
  return box;
}

/** Show `#/compare/{a}/{b}`. */
export async function shown(ids, showError) {
  const slot = $("#compare-result");
  const [a, b] = ids;
  fillNames();
  $("#compare-a").value = a || "";
  $("#compare-b").value = b || "";
  if (!a || !b) {
    document.title = router.title("compare");
    slot.replaceChildren(el("p", { className: "hint", textContent: "Name two states to compare: a sample (its id or its name), or sample@k for the state after step k. Or open a sample in Browse and choose “Compare with…”." }));
    return;
  }
  document.title = router.title("compare", `${a} vs ${b}`);
  slot.setAttribute("aria-busy", "true");
  try {
    // Names are read against the list, and a name it does not hold is not asked for.
    await store.listed();
    const [ra, rb] = await Promise.all([a, b].map((text, k) => store.answer({ kind: "sample", id: sampleId(parseState(text).name) }, `compare-${"ab"[k]}`)));
    const [sa, sb] = [stateOf(a, ra, "A"), stateOf(b, rb, "B")];
    const pair = el("div", { className: "images compare-panels" });
    const own = sa.border.length === sb.border.length ? " The difference A − B has its own." : "";
    const parts = [el("p", { className: "muted", textContent: `One colour scale for A and B: the larger of their own scales.${own}` }), pair];
    slot.replaceChildren(...parts);
    await drawShared(pair, [sa, sb], "compare", [() => differenceFigure(sa, sb, "compare"), async () => bordersFigure(sa, sb)]);
    for (const r of [ra, rb].filter((r, k, all) => stepsOf(r) > 1 && all.findIndex((o) => o.id === r.id) === k)) slot.append(scrubber(r));
    showError("");
  } catch (e) {
    if (api.isAbort(e)) return;
    if (e instanceof store.Missing) {
      slot.replaceChildren(notice(e));
      showError("");
      return;
    }
    slot.replaceChildren(el("p", { className: "error-inline", textContent: `Could not compare ${a} and ${b}: ${e.message}` }));
    showError(e.message);
  } finally {
    slot.removeAttribute("aria-busy");
  }
}

/** The sample names the boxes suggest. */
function fillNames() {
  const list = $("#compare-names");
  const samples = store.get().samples || [];
  if (list.options.length === samples.length) return;
  list.replaceChildren(...samples.map((s) => new Option(`${s.category} · ${s.id}`, s.name)));
}

export function setup() {
  $("#compare-form").addEventListener("submit", (e) => {
    e.preventDefault();
    router.go("compare", [$("#compare-a").value.trim(), $("#compare-b").value.trim()]);
  });
  store.subscribe(fillNames);
}
