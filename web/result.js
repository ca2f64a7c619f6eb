// The view of one analysis (a built-in sample's or an upload's): its label, its CloSE, the
// evidence for each fold with a "low confidence" flag, and its pictures, per step for
// samples folded more than once. Any picture opens at full resolution on a click.

import { imageUrl } from "./api.js";
import { deg, el, fmtFold, row } from "./format.js";

/**
 * Limits past which a fold's evidence is weak. The cut's same-to-cross ratio is 0 for an
 * exact fold and about 1 for change with no side (the detector gives up at 2.5); its
 * residual is the share of the change the cut leaves unexplained; the orientation's flip
 * scores say which side turned over, and close scores are a guess. The step's RMSE compares
 * the prediction with the frame observed after the step: the disks can agree with a wrong
 * fold, and the observed frame then says so. Measured on the built-in set (150 fold steps,
 * GET /api/samples/{id}): same-to-cross at most 0.38, residual at most 0.52 (noisy samples,
 * predictions still right, RMSE ≤ 0.03), flip margin at least 0.75, no tie-break; RMSE at
 * most 0.073 except `trousers__legs_up_then_half` step 2 (0.227, visibly wrong), the one
 * step these limits flag. On a stacked start (a step without an orientation) the synthesis's
 * mismatch over the unfolded state's says how much of the change the line it found explains:
 * measured at most 0.49 on the physics and MuJoCo second folds, 0.73 and more for the wrong
 * lines found before the stacked probe scale was mended (a step past 0.8 has no fold).
 */
export const WEAK = { sameToCross: 1.0, residual: 0.6, flipMargin: 0.25, rmse: 0.1, unexplained: 0.6 };

/** Why the fold of analysis step `step` is doubtful ([] when its evidence is strong). */
export function doubts(step) {
  const out = [];
  if (!step.fold) return out;
  const { cut, orientation, metrics, synthesis } = step;
  if (synthesis && !orientation && synthesis.unfolded_mismatch > 0) {
    const ratio = synthesis.mismatch / synthesis.unfolded_mismatch;
    if (ratio > WEAK.unexplained) out.push(`the synthesised fold leaves ${(100 * ratio).toFixed(0)}% of the disks' mismatch unexplained (> ${100 * WEAK.unexplained}%)`);
  }
  if (cut && cut.same_to_cross > WEAK.sameToCross) out.push(`same-to-cross ratio ${cut.same_to_cross.toFixed(2)} > ${WEAK.sameToCross}`);
  if (cut && cut.residual > WEAK.residual) out.push(`cut residual ${cut.residual.toFixed(2)} > ${WEAK.residual}`);
  if (orientation) {
    const margin = flipMargin(orientation);
    if (orientation.tie_break) out.push("orientation decided by the tie-break");
    else if (margin < WEAK.flipMargin) out.push(`orientation scores close (margin ${margin.toFixed(2)} < ${WEAK.flipMargin})`);
  }
  if (metrics && metrics.rmse > WEAK.rmse) out.push(`prediction ${metrics.rmse.toFixed(3)} RMSE from the frame observed after the step (> ${WEAK.rmse})`);
  return out;
}

/** Relative gap between the two orientation flip scores (0: a tie, 1: one side only). */
export function flipMargin(o) {
  const [a, b] = [Math.abs(o.flip_forward), Math.abs(o.flip_backward)];
  return Math.abs(a - b) / Math.max(a, b, 1e-12);
}

const PICTURES = [
  ["disk_start", "dGLI disk, start frame"],
  ["disk_end", "dGLI disk, end frame"],
  ["diff", "|diff| with the fold's curves"],
  ["signed_diff", "Signed diff Δ"],
];
const WHOLE = [
  ["borders", "Borders: start, end, predicted"],
  ["close", "CloSE fold circle"],
];

/** A picture that opens large in the shared dialog. */
function figure(key, name, caption, step) {
  const img = el("img", { src: imageUrl(key, name, { step }), alt: caption, width: 480, height: 480, loading: "lazy" });
  img.dataset.picture = name;
  const button = el("button", { type: "button", className: "zoom", title: "Open at full resolution" }, img);
  button.setAttribute("aria-label", `${caption}: open at full resolution`);
  button.addEventListener("click", () => enlarge(imageUrl(key, name, { step, size: 1400 }), caption));
  return el("figure", {}, button, el("figcaption", { textContent: caption }));
}

/** Show `url` in the full-resolution dialog. */
export function enlarge(url, caption) {
  const dialog = document.getElementById("lightbox");
  const img = dialog.querySelector("img");
  img.src = url;
  img.alt = caption;
  dialog.querySelector(".lightbox-caption").textContent = caption;
  dialog.showModal();
}

/** The step-picture block: a choice of span and the four disk pictures of it. */
function stepPictures(result) {
  const block = el("div", { className: "step-pictures" });
  const grid = el("div", { className: "images" });
  const steps = result.steps || [];
  const show = (step) => {
    const suffix = step ? ` · step ${step} (frames ${steps[step - 1].from_frame}→${steps[step - 1].to_frame})` : "";
    grid.replaceChildren(...PICTURES.map(([name, caption]) => figure(result.key, name, caption + suffix, step)));
  };
  if (steps.length > 1) {
    const group = el("div", { className: "segmented", role: "radiogroup" });
    group.setAttribute("aria-label", "Which frames the disks compare");
    const choices = [[null, `All: frames ${result.start_frame}→${result.end_frame}`], ...steps.map((s, k) => [k + 1, `Step ${k + 1}: ${s.from_frame}→${s.to_frame}`])];
    choices.forEach(([step, text]) => {
      const id = `span-${result.key}-${step || 0}`.replace(/[^\w-]/g, "_");
      const input = el("input", { type: "radio", name: `span-${result.key}`, id, checked: step === 1 });
      input.dataset.step = step || 0;
      input.addEventListener("change", () => show(step));
      group.append(el("span", {}, input, el("label", { htmlFor: id, textContent: text })));
    });
    block.append(group);
    show(1);
  } else {
    show(null);
  }
  block.append(grid);
  return block;
}

/** Render `result` into `slot`; `actions` {interpolate(result), plan(result)} for its buttons. */
export function renderResult(slot, result, displayName, actions) {
  const node = document.getElementById("result-template").content.firstElementChild.cloneNode(true);
  const $ = (sel) => node.querySelector(sel);
  $(".result-name").textContent = displayName || result.name || "(unnamed)";
  const reversed = result.reversed ? " · given clockwise, walked anticlockwise" : "";
  const source = result.border_source === "border" ? "border given" : `border from the ${result.border_source}`;
  $(".result-meta").textContent = `${result.category || "upload"} · N = ${result.n} vertices (${source}) · frames ${result.start_frame} → ${result.end_frame}${reversed}`;
  $(".result-label").textContent = result.label.text;

  const close = $(".close-table tbody");
  row(close, "corners", `${result.corners.length}: ${result.corners.map((c) => deg(c).toFixed(0) + "°").join(", ") || "none"}`);
  if (result.folds.length === 0) row(close, "folds", "none found");
  result.folds.forEach((f, k) => row(close, `fold ${k + 1} (f₁, f₂)`, fmtFold(f)));
  const truth = result.sample && result.sample.truth;
  if (truth && truth.folds) truth.folds.forEach((f, k) => row(close, `true fold ${k + 1}`, fmtFold(f)));

  const metrics = $(".metrics-table tbody");
  if (result.metrics) {
    row(metrics, "RMSE (XY, normalised)", result.metrics.rmse.toFixed(4));
    row(metrics, "Fréchet (XY, normalised)", result.metrics.frechet.toFixed(4));
  } else {
    row(metrics, "—", "one frame: nothing to compare");
  }

  // The evidence of each step's fold, and the verdict.
  const evidence = $(".evidence-table tbody");
  const flagged = [];
  (result.steps || []).forEach((s, k) => {
    const name = `step ${k + 1} (${s.from_frame}→${s.to_frame})`;
    if (!s.fold) {
      row(evidence, name, "no fold");
      return;
    }
    const parts = [];
    if (s.cut) parts.push(`cut residual ${s.cut.residual.toFixed(3)}`, `same/cross ${s.cut.same_to_cross.toFixed(2)}`);
    if (s.orientation) parts.push(`flip scores ${s.orientation.flip_forward.toFixed(2)} / ${s.orientation.flip_backward.toFixed(2)}${s.orientation.tie_break ? " (tie-break)" : ""}`);
    if (s.metrics) parts.push(`RMSE ${s.metrics.rmse.toFixed(3)}`);
    const why = doubts(s);
    const tr = row(evidence, name, parts.join(" · ") || "—");
    if (why.length) {
      flagged.push(`step ${k + 1}: ${why.join("; ")}`);
      tr.cells[0].append(el("span", { className: "badge low", textContent: "low confidence" }));
    }
  });
  const verdict = $(".confidence");
  if (flagged.length) {
    verdict.hidden = false;
    verdict.textContent = `Low confidence — the disks give weak evidence for this fold (${flagged.join(" — ")}). The prediction may be wrong.`;
  }

  const images = $(".images-slot");
  images.append(stepPictures(result));
  images.append(el("div", { className: "images whole" }, ...WHOLE.map(([name, caption]) => figure(result.key, name, caption, null))));

  if (result.recording) {
    const file = `${result.id || "sample"}.rrd`;
    $(".recording").hidden = false;
    $(".recording-link").href = result.recording;
    $(".recording-link").download = file;
    $(".recording-command").textContent = `rerun ${file}`;
  }
  $(".warnings").textContent = (result.warnings || []).join(" ");
  const interp = $(".interp-this");
  interp.hidden = result.folds.length === 0;
  interp.addEventListener("click", () => actions.interpolate(result));
  $(".plan-this").addEventListener("click", () => actions.plan(result));
  slot.replaceChildren(node);
}
