// The Upload view: files in, one analysis out, named by the files' names everywhere.

import * as api from "./api.js";
import * as store from "./store.js";
import * as router from "./router.js";
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

async function upload(fileList) {
  const status = $("#upload-status");
  const slot = $("#upload-result");
  // Frames go in file-name order, numbers compared as numbers (frame2 before frame10).
  const files = [...fileList].sort((a, b) => a.name.localeCompare(b.name, undefined, { numeric: true }));
  if (files.length === 0) return;
  // The server reads every kind from "sample" files, by their names' extensions.
  const form = new FormData();
  for (const f of files) form.append("sample", f, f.name);
  status.textContent = `Analysing ${files.map((f) => f.name).join(" → ")}…`;
  slot.setAttribute("aria-busy", "true");
  slot.classList.add("loading");
  try {
    const result = await api.analyze(form);
    const name = uploadName(files);
    store.addUpload(name, result);
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
    showError(nameFrames(e.message, files));
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
    slot.replaceChildren();
    showError(e.message);
  }
}
