// The Compare view: #/compare/{a}/{b}, two cloth states side by side on one colour scale.
// A state is a sample id (its last analysed frame) or `id@k` (the state after step k;
// k = 0 is the start). A sample folded more than once also gets a frame scrubber: frame
// k − 1, frame k and the state the analysis predicts for frame k (its step k `predicted`:
// the start folded by the folds found in steps 1…k), again on one colour scale, so a colour
// means one value across the panels.

import * as api from "./api.js";
import * as router from "./router.js";
import { el } from "./format.js";
import { enlarge } from "./result.js";

const $ = (sel) => document.querySelector(sel);

/** "id" or "id@k" as {id, step} (step null: the last). */
export function parseState(text) {
  const at = text.lastIndexOf("@");
  const k = text.slice(at + 1);
  return at > 0 && /^\d+$/.test(k) ? { id: text.slice(0, at), step: Number(k) } : { id: text, step: null };
}

/** The border of analysed frame `k` of a listed sample's answer, in border order. */
function borderAt(result, k) {
  const frames = result.sample.mesh ? result.sample.mesh.frames : result.sample.frames;
  const raw = frames[result.start_frame + k];
  return result.border_indices.map((i) => raw[i]);
}

/** Steps of an answer (analysed frames − 1). */
const stepsOf = (result) => (result.steps || []).length;

/**
 * Draw `states` ({border, reference, caption}) into `slot` as disks of one colour scale:
 * the largest of their own scales. `channel` names the requests (a newer draw aborts them).
 */
async function drawShared(slot, states, channel) {
  const scales = [];
  for (const [k, s] of states.entries()) {
    const { url, scale } = await api.disk({ border: s.border, reference: s.reference, size: 64 }, `${channel}-scale-${k}`);
    URL.revokeObjectURL(url);
    scales.push(scale);
  }
  const scale = scales.every(Boolean) ? { s: Math.max(...scales.map((s) => s.s)), max: Math.max(...scales.map((s) => s.max)) } : undefined;
  const figures = [];
  for (const [k, s] of states.entries()) {
    const { url } = await api.disk({ border: s.border, reference: s.reference, size: 480, scale }, `${channel}-${k}`);
    const img = el("img", { src: url, alt: `dGLI disk: ${s.caption}`, width: 480, height: 480 });
    img.dataset.scale = scale ? `${scale.s} ${scale.max}` : "";
    const button = el("button", { type: "button", className: "zoom", title: "Open at full resolution" }, img);
    button.setAttribute("aria-label", `${s.caption}: open at full resolution`);
    button.addEventListener("click", async () => {
      const large = await api.disk({ border: s.border, reference: s.reference, size: 1400, scale }, `${channel}-large`);
      enlarge(large.url, s.caption);
    });
    figures.push(el("figure", {}, button, el("figcaption", { textContent: s.caption })));
  }
  for (const old of slot.querySelectorAll("img")) URL.revokeObjectURL(old.src);
  slot.replaceChildren(...figures);
  return scale;
}

/** The state {border, reference, caption} of `text` ("id" or "id@k") from its answer. */
function stateOf(text, result) {
  const { step } = parseState(text);
  const last = stepsOf(result);
  const k = step === null ? last : step;
  if (k > last) throw new Error(`${result.id} has steps 0…${last}: there is no state after step ${k}`);
  return { border: borderAt(result, k), reference: borderAt(result, 0), caption: `${result.name} · after step ${k} of ${last} (frame ${result.start_frame + k})` };
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
      { border: before, reference, caption: `frame ${result.start_frame + k - 1} (before step ${k})` },
      { border: after, reference, caption: `frame ${result.start_frame + k} (observed)` },
      { border: step.predicted, reference, caption: `predicted frame ${result.start_frame + k} (the analysis's: ${how})` },
    ];
    try {
      await drawShared(panels, states, "scrub");
    } catch (e) {
      if (!api.isAbort(e)) panels.replaceChildren(el("p", { className: "error-inline", textContent: e.message }));
    }
  };
  input.addEventListener("input", show);
  box.append(el("h2", { className: "card-title", textContent: "Frame scrubber" }), el("div", { className: "row" }, label, input, out), panels);
  show();
  return box;
}

/** Show `#/compare/{a}/{b}`. */
export async function shown(ids, showError) {
  const slot = $("#compare-result");
  const [a, b] = ids;
  $("#compare-a").value = a || "";
  $("#compare-b").value = b || "";
  if (!a || !b) {
    document.title = router.title("compare");
    slot.replaceChildren(el("p", { className: "hint", textContent: "Name two states to compare: a sample id, or id@k for the state after step k." }));
    return;
  }
  document.title = router.title("compare", `${a} vs ${b}`);
  slot.setAttribute("aria-busy", "true");
  try {
    const [ra, rb] = await Promise.all([api.sample(parseState(a).id, "compare-a"), api.sample(parseState(b).id, "compare-b")]);
    const pair = el("div", { className: "images compare-panels" });
    const parts = [el("p", { className: "muted", textContent: "One colour scale for both disks: the larger of their own scales." }), pair];
    slot.replaceChildren(...parts);
    await drawShared(pair, [stateOf(a, ra), stateOf(b, rb)], "compare");
    for (const r of [ra, rb].filter((r, k, all) => stepsOf(r) > 1 && all.findIndex((o) => o.id === r.id) === k)) slot.append(scrubber(r));
    showError("");
  } catch (e) {
    if (api.isAbort(e)) return;
    slot.replaceChildren(el("p", { className: "error-inline", textContent: `Could not compare ${a} and ${b}: ${e.message}` }));
    showError(e.message);
  } finally {
    slot.removeAttribute("aria-busy");
  }
}

export function setup() {
  $("#compare-form").addEventListener("submit", (e) => {
    e.preventDefault();
    router.go("compare", [$("#compare-a").value.trim(), $("#compare-b").value.trim()]);
  });
}
