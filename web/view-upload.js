// The Upload view: files in, one analysis out, named by the files' names everywhere. And
// the notice the other views give of a cloth this server does not have, whose upload
// control brings one as this view does.

import * as api from "./api.js";
import * as store from "./store.js";
import * as router from "./router.js";
import { el } from "./format.js";
import { renderResult } from "./result.js";

const $ = (sel) => document.querySelector(sel);
let actions = null;
let showError = () => {};

/** A name for an upload: its file, or its first and last files. */
export function uploadName(files) {
  if (files.length === 1) return files[0].name;
  return `${files[0].name} … ${files[files.length - 1].name} (${files.length} files)`;
}

/** "frame K" in a server error, with the file that frame came from (unless the server named it). */
export function nameFrames(message, files) {
  if (files.length < 2 || files.some((f) => message.includes(f.name))) return message;
  return message.replace(/\bframe (\d+)\b/g, (text, k) => (files[Number(k)] ? `${text} (${files[Number(k)].name})` : text));
}

/** Frames in file-name order, numbers compared as numbers (frame2 before frame10). */
export const inOrder = (fileList) => [...fileList].sort((a, b) => a.name.localeCompare(b.name, undefined, { numeric: true }));

/**
 * Analyse one sample made of `files` (in order) and keep it in the store: {result, name}.
 * A failure's message names the files its frames came from.
 */
export async function analyse(files) {
  // The server reads every kind from "sample" files, by their names' extensions.
  const form = new FormData();
  for (const f of files) form.append("sample", f, f.name);
  try {
    const result = await api.analyze(form);
    const name = uploadName(files);
    store.addUpload(name, result);
    return { result, name };
  } catch (e) {
    if (!api.isAbort(e)) e.message = nameFrames(e.message, files);
    throw e;
  }
}

/**
 * The notice of `missing` (a store.Missing: an upload the server no longer keeps, a sample
 * it does not list), to stay on screen where the cloth would be. With `onUpload`, it holds
 * an upload control: the files chosen are analysed as this view does, and
 * `onUpload({result, name})` goes on with them (a failure is said in the notice).
 */
export function notice(missing, onUpload = null) {
  const box = el("div", { className: "missing card", role: "alert" });
  box.dataset.cloth = `${missing.cloth.kind}:${missing.cloth.id}`;
  box.append(el("p", { className: "missing-text", textContent: missing.message }));
  if (missing.detail) box.append(el("p", { className: "muted small", textContent: missing.detail }));
  if (!onUpload) return box;
  const input = el("input", { type: "file", multiple: true, accept: $("#upload-input").accept });
  const status = el("p", { className: "small", role: "status" });
  input.addEventListener("change", async () => {
    const files = inOrder(input.files);
    if (!files.length) return;
    status.textContent = `Analysing ${files.map((f) => f.name).join(" → ")}…`;
    try {
      const uploaded = await analyse(files);
      status.textContent = "";
      onUpload(uploaded);
    } catch (e) {
      if (!api.isAbort(e)) status.textContent = `Could not analyse it: ${e.message}`;
    }
  });
  const ask = missing.cloth.kind === "upload" ? "Upload it again: " : "Or upload your own: ";
  box.append(el("label", { className: "block-label" }, el("strong", { textContent: ask }), input), status);
  return box;
}

async function upload(fileList) {
  const status = $("#upload-status");
  const slot = $("#upload-result");
  const files = inOrder(fileList);
  if (files.length === 0) return;
  status.textContent = `Analysing ${files.map((f) => f.name).join(" → ")}…`;
  slot.setAttribute("aria-busy", "true");
  slot.classList.add("loading");
  try {
    const { result, name } = await analyse(files);
    renderResult(slot, result, name, actions, { files: files.map((f) => f.name) });
    shownKey = result.key;
    // The upload's own URL: a reload (or a link) shows it again while the server keeps it.
    router.keep("upload", new URLSearchParams({ key: result.key }));
    document.title = router.title("upload", name);
    status.textContent = `Done: ${files.map((f) => f.name).join(", ")}`;
    showError("");
  } catch (e) {
    if (api.isAbort(e)) return;
    slot.replaceChildren();
    status.textContent = "";
    // The previous upload is no longer shown: the title must not name it.
    document.title = router.title("upload");
    showError(e.message);
  } finally {
    slot.removeAttribute("aria-busy");
    slot.classList.remove("loading");
  }
}

export function setup(resultActions, errors) {
  actions = resultActions;
  showError = errors;
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

/** The title of the view: the upload shown, if any. */
export function titleName() {
  return $("#upload-result .result-name")?.textContent || "";
}

/** The upload whose result is on screen (its key). */
let shownKey = null;

/** The view came on screen; a link's `key` shows that upload (the server's, after a reload). */
export async function shown(params) {
  const key = params.get("key");
  if (!key || key === shownKey) return void (document.title = router.title("upload", titleName()));
  const slot = $("#upload-result");
  const status = $("#upload-status");
  status.textContent = "Loading the upload…";
  try {
    const result = await store.upload(key);
    const name = store.get().uploads.find((u) => u.key === key)?.name || result.name;
    renderResult(slot, result, name, actions);
    shownKey = key;
    status.textContent = "";
    document.title = router.title("upload", name);
    showError("");
  } catch (e) {
    if (api.isAbort(e)) return;
    status.textContent = "";
    // A gone upload is said where it would be; the control to bring it again is above.
    slot.replaceChildren(...(e instanceof store.Missing ? [notice(e)] : []));
    showError(e instanceof store.Missing ? "" : e.message);
  }
}
