// The app's one store: a plain state object replaced (never mutated) on every change, and
// the views that listen to it. Server answers are kept as they came and never edited.

import { analysis } from "./api.js";

const listeners = new Set();

let state = Object.freeze({
  /** The sample list of GET /api/samples, or null until it arrives. */
  samples: null,
  /** Why the sample list could not be loaded, if it could not. */
  samplesError: "",
  /** Analyses the user brought, newest last: {key, name, result}. */
  uploads: [],
  /** What the Interpolate and Plan views work on: {kind: "sample"|"upload", id, name}. */
  cloth: null,
});

export const get = () => state;

/** Replace the fields of `patch` and tell every listener. */
export function set(patch) {
  state = Object.freeze({ ...state, ...patch });
  for (const listener of listeners) listener(state);
}

/** Call `listener(state)` after every change; returns the unsubscribe function. */
export function subscribe(listener) {
  listeners.add(listener);
  return () => listeners.delete(listener);
}

/** Remember an upload's analysis under its file names (a later one of the same key replaces it). */
export function addUpload(name, result) {
  const uploads = state.uploads.filter((u) => u.key !== result.key).concat([{ key: result.key, name, result }]);
  set({ uploads });
}

/**
 * The analysis of upload `key`: the one this page holds, else the server's (it keeps
 * uploads: a link to one works after a reload).
 */
export async function upload(key) {
  const held = state.uploads.find((u) => u.key === key);
  if (held) return held.result;
  const result = await analysis(key);
  addUpload(result.name || key, result);
  return result;
}

/** The clothes Interpolate and Plan can use: every sample, then every upload. */
export function cloths() {
  const samples = (state.samples || []).map((s) => ({ kind: "sample", id: s.id, name: `${s.category} · ${s.name}` }));
  const uploads = state.uploads.map((u) => ({ kind: "upload", id: u.key, name: `upload · ${u.name}` }));
  return [...samples, ...uploads];
}
