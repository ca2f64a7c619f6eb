// The view of one analysis (a built-in sample's or an upload's): its label, its CloSE, the
// evidence for each fold with a "low confidence" flag, and its pictures, per step for
// samples folded more than once. Any picture opens at full resolution on a click.

import { imageUrl, readout } from "./api.js";
import { deg, el, fmtFold, row } from "./format.js";
import { edgeOverlay, readable } from "./readout.js";

/**
 * The error a step's disks can answer for: the RMSE once the prediction is moved rigidly
 * onto the observed frame (`aligned_rmse`). CloSE does not change when the whole cloth
 * slides across the table, so a slide is no evidence against the fold.
 */
const shapeError = (metrics) => metrics.aligned_rmse ?? metrics.rmse;

const PICTURES = [
  ["disk_start", "dGLI disk, start frame"],
  ["disk_end", "dGLI disk, end frame"],
  ["diff", "|diff| with the fold's curves"],
  ["signed_diff", "Signed diff Δ"],
];
const BORDERS_CAPTION = "Borders: start, end, predicted";
const CIRCLE_CAPTION = "CloSE fold circle";
const MESH = ["mesh", "Mesh from above, by height, with its border loop"];

/** A file name made of `parts` (letters, digits, "_", "-" and "." kept). */
const fileName = (...parts) => parts.filter(Boolean).join("_").replace(/[^\w.-]+/g, "-");

/**
 * Links that download picture `name` as `file`.png/.svg: a PNG for the screen (1400 px), a PNG for
 * print (2048 px stating 300 dpi: 6.8 inches wide, a page's width) and an SVG (the same drawing,
 * its lines and text vector).
 */
function downloads(key, name, step, file) {
  const link = (kind, text, title, { format = kind, size = 1400, dpi = null } = {}) => {
    const href = imageUrl(key, name, { step, size, format, dpi });
    const a = el("a", { href, download: `${fileName(file, dpi && `${dpi}dpi`)}.${format}`, textContent: text, title, className: "download" });
    a.dataset.format = kind;
    return a;
  };
  return el(
    "span",
    { className: "downloads small" },
    link("png", "PNG", "1400 × 1400 px, for the screen"),
    " · ",
    link("png-print", "PNG 300 dpi", "2048 × 2048 px at 300 dpi: 6.8 inches wide in print", { format: "png", size: 2048, dpi: 300 }),
    " · ",
    link("svg", "SVG", "vector: lines and text stay sharp at any size"),
  );
}

/**
 * A picture that opens large in the shared dialog, with its download links; `enhance(button, img)`
 * adds to it, `readLarge(stage, img)` to the large one.
 */
function figure(key, name, caption, step, stem, enhance = null, readLarge = null) {
  const img = el("img", { src: imageUrl(key, name, { step }), alt: caption, width: 480, height: 480, loading: "lazy" });
  img.dataset.picture = name;
  const button = el("button", { type: "button", className: "zoom", title: "Open at full resolution" }, img);
  button.setAttribute("aria-label", `${caption}: open at full resolution`);
  const file = fileName(stem, name, step && `step${step}`);
  button.addEventListener("click", () => enlarge(imageUrl(key, name, { step, size: 1400 }), caption, { file: `${file}.png`, read: readLarge }));
  const node = el("figure", {}, button, el("figcaption", {}, caption, " ", downloads(key, name, step, file)));
  if (enhance) enhance(button, img);
  return node;
}

/** Where a result comes from, in words: built in, which dataset (its folder or store, and the sample's id there), or an upload. */
export function provenance(result) {
  if (result.source === "builtin") return "built-in sample";
  if (result.source === "upload" || !result.source) return "your upload";
  return `dataset ${result.source} (sample ${result.id})`;
}

/** `text` quoted for a POSIX shell. */
const shellQuote = (text) => `'${String(text).replace(/'/g, "'\\''")}'`;

/**
 * Calls that run as they are, from a shell (curl) and from Python (its standard library
 * alone): the analysis (a listed sample by its id; an upload from its files, `files`), a plan,
 * an interpolation and a picture of it.
 */
function codePanel(result, files) {
  const origin = location.origin;
  const listed = Boolean(result.id);
  const analysisUrl = listed ? `${origin}/api/samples/${encodeURIComponent(result.id)}` : `${origin}/api/analyses/${encodeURIComponent(result.key)}`;
  const goal = result.folds[0] || [0.5, 3.6];
  const goalText = `[${goal.map((g) => g.toFixed(4)).join(", ")}]`;
  const planBody = JSON.stringify({ sample: listed ? result.id : result.key, goal: goal.map((g) => Number(g.toFixed(4))) });
  const picture = `${origin}${imageUrl(result.key, "diff", { size: 1400 })}`;
  const upload = (files || []).map((f) => `-F sample=@${shellQuote(f)}`).join(" ");
  const curl = [
    "# The analysis (the JSON of `close analyze --json`, with its picture URLs)",
    listed || !files?.length ? `curl -s ${shellQuote(analysisUrl)}` : `curl -s ${upload} ${shellQuote(`${origin}/api/analyze`)}`,
    "# A plan to reach a goal fold (radians)",
    `curl -s -H 'content-type: application/json' -d ${shellQuote(planBody)} ${shellQuote(`${origin}/api/plan`)}`,
    "# A picture: the |diff| disk as PNG, and as SVG",
    `curl -s -o diff.png ${shellQuote(picture)}`,
    `curl -s -o diff.svg ${shellQuote(`${picture}&format=svg`)}`,
  ].join("\n");
  const python = [
    "import json, urllib.request",
    "",
    `BASE = ${JSON.stringify(origin)}`,
    "",
    "def call(path, body=None):",
    "    data = None if body is None else json.dumps(body).encode()",
    '    request = urllib.request.Request(BASE + path, data=data, headers={"content-type": "application/json"})',
    "    with urllib.request.urlopen(request) as answer:",
    "        return json.load(answer)",
    "",
    `analysis = call(${JSON.stringify(analysisUrl.slice(origin.length))})`,
    'print(analysis["label"]["text"], analysis["close"])',
    "# The first fold turning over about its line, in 5 states",
    'step = next((s for s in analysis["steps"] if s["fold"]), None)',
    "if step:",
    '    motion = call("/api/interpolate", {"border": analysis["start_border"], "arcs": step["arcs"], "line": step["line"], "steps": 5})',
    '    print(len(motion["borders"]), "states")',
    `plan = call("/api/plan", {"sample": analysis.get("id") or analysis["key"], "goal": ${goalText}})`,
    'print(plan["case"], len(plan["steps"]), "steps")',
    'urllib.request.urlretrieve(BASE + analysis["images"]["diff"], "diff.png")',
  ].join("\n");
  const block = (lang, text) => el("pre", { className: `code code-${lang}` }, el("code", { textContent: text }));
  const details = el("details", { className: "use-code" }, el("summary", { textContent: "Use from code" }));
  const where = listed ? "" : files?.length ? " (run the shell lines where your files are)" : "";
  details.append(
    el("p", { className: "muted small", textContent: `The same JSON as \`close analyze --json\`, a plan, an interpolation and a picture, from the running server${where}:` }),
    el("h3", { className: "code-title", textContent: "Shell (curl)" }),
    block("curl", curl),
    el("h3", { className: "code-title", textContent: "Python (standard library)" }),
    block("python", python),
  );
  return details;
}

/** The lightbox's zoom: scale over the fitted size, and the pan in CSS px. */
const zoom = { scale: 1, x: 0, y: 0 };

/** Zoom and pan the dialog's picture (its stage: the picture and any cell mark over it). */
function applyZoom(frame) {
  frame.firstElementChild.style.transform = `translate(${zoom.x}px, ${zoom.y}px) scale(${zoom.scale})`;
}

/** Wheel or pinch (ctrl+wheel) zooms about the pointer, up to the picture's full resolution and beyond; drag pans. */
function setupZoom(dialog) {
  const frame = dialog.querySelector(".lightbox-frame");
  frame.addEventListener("wheel", (e) => {
    e.preventDefault();
    const r = frame.getBoundingClientRect();
    const [px, py] = [e.clientX - r.left, e.clientY - r.top];
    const next = Math.min(8, Math.max(1, zoom.scale * Math.exp(-e.deltaY / 300)));
    // Keep the point under the pointer where it is.
    zoom.x = px - ((px - zoom.x) * next) / zoom.scale;
    zoom.y = py - ((py - zoom.y) * next) / zoom.scale;
    zoom.scale = next;
    if (next === 1) Object.assign(zoom, { x: 0, y: 0 });
    applyZoom(frame);
  }, { passive: false });
  let drag = null;
  frame.addEventListener("pointerdown", (e) => {
    drag = { x: e.clientX - zoom.x, y: e.clientY - zoom.y };
    frame.setPointerCapture(e.pointerId);
  });
  frame.addEventListener("pointermove", (e) => {
    if (!drag) return;
    Object.assign(zoom, { x: e.clientX - drag.x, y: e.clientY - drag.y });
    applyZoom(frame);
  });
  frame.addEventListener("pointerup", () => (drag = null));
  dialog.dataset.zoom = "ready";
}

/**
 * Show `url` in the full-resolution dialog (fitted first; wheel, pinch and drag zoom and pan),
 * with a link that downloads it as `file`. `read(stage, img, slot)`, given, makes the picture
 * readable (a disk's cells, as on the small picture), its readout in `slot` under the picture.
 */
export function enlarge(url, caption, { file = `${fileName(caption)}.png`, read = null } = {}) {
  const dialog = document.getElementById("lightbox");
  if (!dialog.dataset.zoom) setupZoom(dialog);
  const frame = dialog.querySelector(".lightbox-frame");
  // A fresh picture each time: the last one's readout goes with it.
  const img = el("img", { src: url, alt: caption });
  const stage = el("div", { className: "lightbox-stage" }, img);
  frame.replaceChildren(stage);
  Object.assign(zoom, { scale: 1, x: 0, y: 0 });
  applyZoom(frame);
  const under = dialog.querySelector(".lightbox-readout");
  under.replaceChildren();
  if (read) {
    stage.tabIndex = 0;
    read(stage, img, under);
  }
  Object.assign(dialog.querySelector(".lightbox-download"), { href: url, download: file });
  dialog.querySelector(".lightbox-caption").textContent = caption;
  dialog.showModal();
}

/**
 * Reads cells off the disk pictures of `result` and marks their edges on its border plot:
 * one readout request per span, shared by the span's four pictures.
 */
function cellReader(result) {
  const spans = new Map();
  let plot = null;
  const load = (step) => {
    if (!spans.has(step)) {
      const got = readout(result.key, step).then((r) => ({ ...r, values: (k) => ({ start: r.start[k], end: r.end[k] }) }));
      got.catch(() => spans.delete(step));
      spans.set(step, got);
    }
    return spans.get(step);
  };
  return {
    /** Make disk picture `name` of span `step` readable; its cells' edges are marked on the border plot of the same span. */
    disk: (name, step) => (button, img) => {
      button.classList.add("readable");
      readable(button, img, name, () => load(step), (c, data) => plot && plot.show(data ? data.border_frames : [], data && data.borders, data ? data.size : 480, c));
    },
    /** The same for the full-resolution picture of disk `name` (its readout alone). */
    large: (name, step) => (stage, img, slot) => readable(stage, img, name, () => load(step), undefined, slot),
    /** The border plot, on which the edges are marked. */
    plot: (button, img) => (plot = edgeOverlay(img)),
  };
}

/**
 * The step-picture block: a choice of span, the four disk pictures of it, and into `plotSlot`
 * the border plot and the fold circle of the same span (one choice drives them all).
 */
function stepPictures(result, stem, cells, plotSlot, { step: wanted = null, onStep = null } = {}) {
  const block = el("div", { className: "step-pictures" });
  const grid = el("div", { className: "images" });
  const steps = result.steps || [];
  const show = (step) => {
    const suffix = step ? ` · step ${step} (frames ${steps[step - 1].from_frame}→${steps[step - 1].to_frame})` : "";
    // Over several steps the curves are fitted per step: the whole span shows none.
    const captionOf = (name, caption) => (name === "diff" && !step && steps.length > 1 ? "|diff| (the fold curves: see each step)" : caption);
    grid.replaceChildren(...PICTURES.map(([name, caption]) => figure(result.key, name, captionOf(name, caption) + suffix, step, stem, cells.disk(name, step), cells.large(name, step))));
    const plot = figure(result.key, "borders", BORDERS_CAPTION + suffix, step, stem, cells.plot);
    plot.classList.add("instrument-borders");
    plotSlot.replaceChildren(plot, figure(result.key, "close", CIRCLE_CAPTION + suffix, step, stem));
  };
  if (steps.length > 1) {
    const group = el("div", { className: "segmented", role: "radiogroup" });
    group.setAttribute("aria-label", "Which frames the disks compare");
    const choices = [[null, `All: frames ${result.start_frame}→${result.end_frame}`], ...steps.map((s, k) => [k + 1, `Step ${k + 1}: ${s.from_frame}→${s.to_frame}`])];
    // A link's step ("all" or 1…), else step 1.
    const first = wanted === "all" ? null : Number(wanted) >= 1 && Number(wanted) <= steps.length ? Number(wanted) : 1;
    choices.forEach(([step, text]) => {
      const id = `span-${result.key}-${step || 0}`.replace(/[^\w-]/g, "_");
      const input = el("input", { type: "radio", name: `span-${result.key}`, id, checked: step === first });
      input.dataset.step = step || 0;
      input.addEventListener("change", () => {
        show(step);
        if (onStep) onStep(step || "all");
      });
      group.append(el("span", {}, input, el("label", { htmlFor: id, textContent: text })));
    });
    block.append(group);
    show(first);
  } else {
    show(null);
  }
  block.append(grid);
  return block;
}

/**
 * Render `result` into `slot`; `actions` {interpolate(result, fold), plan(result), compare(a, b)}
 * for its buttons;
 * `options` {step, onStep(step), files}: the step pictures to show first, who hears of a
 * change, and an upload's file names (for its snippets).
 */
export function renderResult(slot, result, displayName, actions, options = {}) {
  // The previous result's JSON download is no longer reachable.
  for (const a of slot.querySelectorAll("a.download-analysis")) URL.revokeObjectURL(a.href);
  const node = document.getElementById("result-template").content.firstElementChild.cloneNode(true);
  const $ = (sel) => node.querySelector(sel);
  // A long name wraps after its underscores and dots, never inside a word.
  const name = displayName || result.name || "(unnamed)";
  name.split(/(?<=[_.])(?=[^_.])/).forEach((part, k) => $(".result-name").append(...(k ? [el("wbr"), part] : [part])));
  const reversed = result.reversed ? " · given clockwise, walked anticlockwise" : "";
  const source = result.border_source === "border" ? "border given" : `border from the ${result.border_source}`;
  $(".result-meta").textContent = `${provenance(result)} · ${result.category || "upload"} · N = ${result.n} vertices (${source}) · frames ${result.start_frame} → ${result.end_frame}${reversed}`;
  $(".result-label").textContent = result.label.text;

  const close = $(".close-table tbody");
  row(close, "corners", `${result.corners.length}: ${result.corners.map((c) => deg(c).toFixed(0) + "°").join(", ") || "none"}`);
  if (result.folds.length === 0) row(close, "folds", "none found");
  result.folds.forEach((f, k) => row(close, `fold ${k + 1} (f₁, f₂)`, fmtFold(f)));
  const truth = result.truth;
  if (truth && truth.folds) truth.folds.forEach((f, k) => row(close, `true fold ${k + 1}`, fmtFold(f)));

  const metrics = $(".metrics-table tbody");
  if (result.metrics) {
    row(metrics, "RMSE (XY, normalised)", result.metrics.rmse.toFixed(4));
    row(metrics, "Fréchet (XY, normalised)", result.metrics.frechet.toFixed(4));
    row(metrics, "RMSE once moved rigidly onto the end (what the disks can see)", result.metrics.aligned_rmse.toFixed(4));
  } else {
    row(metrics, "—", "one frame: nothing to compare");
  }

  // The evidence of each step's fold, and the verdict.
  const evidence = $(".evidence-table tbody");
  const flagged = [];
  (result.steps || []).forEach((s, k) => {
    const name = `step ${k + 1} (${s.from_frame}→${s.to_frame})`;
    const parts = [];
    if (!s.fold) parts.push("no fold");
    // A step seen only flat and folded: the sequence read from its end disk, in order.
    if (s.folds?.length > 1) parts.push(`${s.folds.length} folds: ${s.folds.map((f) => fmtFold(f.fold)).join(", then ")}`);
    if (s.alternatives?.length) parts.push(`${s.alternatives.length} other order${s.alternatives.length > 1 ? "s" : ""} explain${s.alternatives.length > 1 ? "" : "s"} it about as well`);
    if (s.cut) parts.push(`cut residual ${s.cut.residual.toFixed(3)}`, `same/cross ${s.cut.same_to_cross.toFixed(2)}`);
    if (s.orientation) parts.push(`flip scores ${s.orientation.flip_forward.toFixed(2)} / ${s.orientation.flip_backward.toFixed(2)}${s.orientation.tie_break ? " (tie-break)" : ""}`);
    if (s.metrics) parts.push(`RMSE ${s.metrics.rmse.toFixed(3)} (aligned ${shapeError(s.metrics).toFixed(3)})`);
    // The server judges each step (close_core::confidence): its doubts, in words.
    const why = (s.confidence?.doubts || []).map((d) => d.text);
    const tr = row(evidence, name, parts.join(" · ") || "—");
    if (s.confidence?.level === "low") {
      flagged.push(`step ${k + 1}: ${why.join("; ")}`);
      tr.cells[0].append(el("span", { className: "badge low", textContent: "low confidence" }));
    }
  });
  const verdict = $(".confidence");
  if (flagged.length) {
    verdict.hidden = false;
    const what = result.folds.length ? "the disks give weak evidence for this fold" : "the cloth changed, but no fold was found";
    verdict.textContent = `Low confidence — ${what} (${flagged.join(" — ")}). The prediction may be wrong.`;
  }

  const images = $(".images-slot");
  const stem = fileName(result.id || displayName || result.name);
  const cells = cellReader(result);
  // One instrument: the border plot beside the disks (on a wide screen), so the edges a
  // hover on a disk marks on the plot are in view.
  const plotSlot = el("div", { className: "instrument-plot" });
  images.append(el("div", { className: "instrument" }, stepPictures(result, stem, cells, plotSlot, options), plotSlot));
  // The mesh picture is listed for mesh samples alone.
  if (result.images && result.images.mesh) images.append(el("div", { className: "images whole" }, figure(result.key, ...MESH, null, stem)));
  const json = URL.createObjectURL(new Blob([JSON.stringify(result, null, 1)], { type: "application/json" }));
  const jsonLink = el("a", { href: json, download: `${stem || "analysis"}.json`, className: "download download-analysis", textContent: "Download the analysis (JSON)" });
  images.append(el("p", { className: "small" }, jsonLink), codePanel(result, options.files));

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
  // The fold of the step whose pictures are shown (the sequence for all of them).
  interp.addEventListener("click", () => {
    const shown = Number(node.querySelector(".segmented input:checked")?.dataset.step || 1);
    const steps = result.steps || [];
    // A step holds a sequence of folds when its end was seen only folded: play them all.
    const folds = steps.slice(0, shown || steps.length).reduce((n, s) => n + (s.folds?.length || (s.fold ? 1 : 0)), 0);
    const whole = shown === 0 || steps.length === 1;
    actions.interpolate(result, whole && result.folds.length > 1 ? "all" : Math.max(1, folds));
  });
  $(".plan-this").addEventListener("click", () => actions.plan(result));
  // Compare with another sample: this one's state after the step shown (or its last).
  const compareWith = $(".compare-with");
  const compareThis = $(".compare-this");
  compareThis.hidden = !result.id;
  compareThis.addEventListener("click", () => {
    compareWith.hidden = !compareWith.hidden;
    compareThis.setAttribute("aria-expanded", String(!compareWith.hidden));
    if (!compareWith.hidden) compareWith.querySelector("input").focus();
  });
  compareWith.addEventListener("submit", (e) => {
    e.preventDefault();
    const shown = Number(node.querySelector(".segmented input:checked")?.dataset.step || 0);
    actions.compare(shown ? `${result.id}@${shown}` : result.id, compareWith.querySelector("input").value.trim());
  });
  slot.replaceChildren(node);
}
