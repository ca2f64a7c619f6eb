// The Browse view: the sample list (filter by name, by category, collapsible categories,
// paged so thousands of samples stay fast) and the open sample's result.

import * as api from "./api.js";
import * as store from "./store.js";
import * as router from "./router.js";
import { el } from "./format.js";
import { renderResult } from "./result.js";
import { notice } from "./view-upload.js";

/** Cards drawn per category before a "show more" button. */
const PAGE = 24;

const $ = (sel) => document.querySelector(sel);
/** Cards shown per category (grows with "show more"); categories the user closed. */
const shown = new Map();
const closed = new Set();
let openId = null;
/** The sample whose result is on screen (none after a failure, so a new click retries). */
let shownId = null;
let actions = null;

/** The samples matching the filter boxes (name, category, id or where it comes from). */
function matching(samples) {
  const words = $("#sample-filter").value.trim().toLowerCase().split(/\s+/).filter(Boolean);
  const category = $("#sample-category").value;
  return samples.filter((s) => (!category || s.category === category) && words.every((w) => `${s.name} ${s.category} ${s.id} ${origin(s)} ${s.source}`.toLowerCase().includes(w)));
}

/** A sample's name that wraps after its underscores ("napkin__half_" / "then_half"), not mid-word. */
function cardName(name) {
  const span = el("span", { className: "card-name" });
  name.split(/(?<=_)(?=[^_])/).forEach((part, k) => span.append(...(k ? [el("wbr"), part] : [part])));
  return span;
}

/** The path parts of a dataset's folder or store. */
const parts = (source) => String(source || "").split(/[\\/]/).filter(Boolean);

/**
 * Where a row comes from, shortly: "built-in", or the dataset folder's last parts, as many
 * as tell it from the other datasets listed ("physics/border", "physics-mujoco/border").
 */
export function origin(s) {
  if (s.source === "builtin") return "built-in";
  const mine = parts(s.source);
  const others = [...new Set((store.get().samples || []).map((r) => r.source))].filter((o) => o !== s.source && o !== "builtin").map(parts);
  let k = 1;
  while (k < mine.length && others.some((o) => o.slice(-k).join("/") === mine.slice(-k).join("/"))) k += 1;
  return `dataset ${mine.slice(-k).join("/") || "?"}`;
}

function card(s) {
  const n = s.n === null ? "N unknown" : `N = ${s.n}`;
  const button = el("button", { type: "button", className: "sample-card", title: `${s.name} · ${n} · ${s.frames} frames · ${s.source === "builtin" ? "built-in" : s.source}` });
  button.dataset.id = s.id;
  button.dataset.source = s.source;
  button.classList.toggle("active", s.id === openId);
  button.setAttribute("aria-pressed", String(s.id === openId));
  // A row that cannot be read has no picture: say why instead.
  const img = s.error
    ? el("span", { className: "card-error", textContent: s.error.slice(0, 120) })
    : el("img", { loading: "lazy", src: s.thumbnail, alt: "", width: 160, height: 160 });
  const folds = s.frames > 2 ? ` · ${s.frames - 1} folds` : "";
  button.append(img, cardName(s.name), el("span", { className: "card-meta", textContent: `${n}${folds}${s.mesh ? " · mesh" : ""} · ${origin(s)}` }));
  button.addEventListener("click", () => router.go("samples", s.id));
  return button;
}

/** Draw the list from the store's samples and the filter boxes. */
export function drawList() {
  const { samples, samplesError } = store.get();
  const list = $("#sample-list");
  if (samplesError) {
    list.replaceChildren(el("p", { className: "error-inline", textContent: `The sample list could not be loaded: ${samplesError}` }),
      Object.assign(el("button", { type: "button", className: "small-btn", textContent: "Try again" }), { onclick: () => loadSamples() }));
    $("#sample-count").textContent = "";
    return;
  }
  if (!samples) return;
  const found = matching(samples);
  $("#sample-count").textContent = `${found.length} of ${samples.length} samples`;
  const groups = new Map();
  for (const s of found) {
    if (!groups.has(s.category)) groups.set(s.category, []);
    groups.get(s.category).push(s);
  }
  const sections = [];
  for (const [category, members] of groups) {
    // A sample opened by a link is shown even past the first page of its category.
    const open = members.findIndex((s) => s.id === openId);
    const limit = Math.max(shown.get(category) || PAGE, open + 1);
    const details = el("details", { className: "category", open: !closed.has(category) });
    details.addEventListener("toggle", () => (details.open ? closed.delete(category) : closed.add(category)));
    details.append(el("summary", { textContent: `${category} (${members.length})` }));
    const cards = el("div", { className: "cards" }, ...members.slice(0, limit).map(card));
    details.append(cards);
    if (members.length > limit) {
      const more = el("button", { type: "button", className: "small-btn more", textContent: `Show ${Math.min(PAGE * 4, members.length - limit)} more of ${members.length - limit}` });
      more.addEventListener("click", () => {
        shown.set(category, limit + PAGE * 4);
        drawList();
      });
      details.append(more);
    }
    sections.push(details);
  }
  if (!sections.length) sections.push(el("p", { className: "muted", textContent: "No sample matches the filter." }));
  const first = !list.querySelector(".sample-card");
  list.replaceChildren(...sections);
  // A sample opened from its URL before the list came: show where it is.
  if (first) revealCard();
}

/** Fill the category box once the list is there. */
function fillCategories(samples) {
  const select = $("#sample-category");
  const categories = [...new Set(samples.map((s) => s.category))];
  select.replaceChildren(new Option("all", ""), ...categories.map((c) => new Option(c, c)));
}

/** GET /api/samples into the store. */
export async function loadSamples() {
  try {
    const { samples } = await api.samples();
    fillCategories(samples);
    store.set({ samples, samplesError: "" });
  } catch (e) {
    if (!api.isAbort(e)) store.set({ samplesError: e.message });
  }
}

/** Scroll the open sample's card into view inside the list (the list alone: the page stays). */
function revealCard() {
  const active = document.querySelector(".sample-card.active");
  const list = $("#sample-list");
  if (!active) return;
  const [card, box] = [active.getBoundingClientRect(), list.getBoundingClientRect()];
  if (card.top < box.top || card.bottom > box.bottom) list.scrollTop += card.top - box.top - (box.height - card.height) / 2;
}

/** Show the pictures of step `step` ("all", "1", …) of the sample on screen, as a link to it asks. */
export function showStep(step) {
  const input = document.querySelector(`#browse-result .segmented input[data-step="${step === "all" ? 0 : Number(step)}"]`);
  if (input && !input.checked) input.click();
}

/** Open sample `id` (from the URL, with its `step` pictures): highlight its card, load it, show it; a newer open wins. */
export async function open(id, showError, step = null) {
  openId = id;
  for (const c of document.querySelectorAll(".sample-card")) {
    c.classList.toggle("active", c.dataset.id === id);
    c.setAttribute("aria-pressed", String(c.dataset.id === id));
  }
  revealCard();
  const slot = $("#browse-result");
  slot.setAttribute("aria-busy", "true");
  slot.classList.add("loading");
  let status = slot.querySelector(".loading-note");
  if (!status) {
    status = el("p", { className: "loading-note", role: "status" });
    slot.prepend(status);
  }
  status.textContent = `Loading ${id}…`;
  // On a phone the result sits above the list: bring it into view.
  if (window.matchMedia("(max-width: 900px)").matches) slot.scrollIntoView({ block: "start" });
  try {
    const result = await store.answer({ kind: "sample", id }, "sample");
    if (openId !== id) return;
    const onStep = (k) => router.keep("samples", new URLSearchParams({ step: String(k) }));
    renderResult(slot, result, null, actions, { step, onStep });
    shownId = id;
    document.title = router.title("samples", result.name);
    showError("");
  } catch (e) {
    if (api.isAbort(e) || openId !== id) return;
    // The old result must not pass for the new one.
    shownId = null;
    if (e instanceof store.Missing) {
      // The upload of one's own sample is shown where uploads are.
      slot.replaceChildren(notice(e, ({ result }) => router.go("upload", null, new URLSearchParams({ key: result.key }))));
      document.title = router.title("samples");
      showError("");
      return;
    }
    slot.replaceChildren(el("p", { className: "error-inline", textContent: `Sample ${id} could not be shown: ${e.message}` }));
    showError(e.message);
  } finally {
    if (openId === id) {
      slot.removeAttribute("aria-busy");
      slot.classList.remove("loading");
    }
  }
}

export function setup(resultActions) {
  actions = resultActions;
  let timer = null;
  $("#sample-filter").addEventListener("input", () => {
    clearTimeout(timer);
    timer = setTimeout(drawList, 120);
  });
  $("#sample-category").addEventListener("change", drawList);
  let seen = null;
  store.subscribe((state) => {
    if (seen && seen.samples === state.samples && seen.samplesError === state.samplesError) return;
    seen = state;
    drawList();
  });
}

/** The id of the first sample, to open when the view has none. */
export const first = () => (store.get().samples || [])[0]?.id || null;
export const current = () => shownId;
/** The sample last asked for, shown or not. */
export const opened = () => openId;
