// The app's one store: a plain state object replaced (never mutated) on every change, and
// the views that listen to it. Server answers are kept as they came and never edited.

import * as api from "./api.js";

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
  /** Uploads the server said it no longer has (their keys): not asked for again. */
  gone: [],
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
 * A cloth this server does not have: an upload it no longer keeps, or a sample it does not
 * list. `detail` is the server's own account, when it gave one.
 */
export class Missing extends Error {
  constructor(cloth, detail = "") {
    super(cloth.kind === "upload" ? "That upload is no longer on this server: upload it again." : `There is no sample “${cloth.id}” on this server: pick one from the list.`);
    this.cloth = cloth;
    this.detail = detail;
  }
}

/** Resolves once the sample list came, or failed to. */
export function listed() {
  if (state.samples || state.samplesError) return Promise.resolve();
  return new Promise((resolve) => {
    const stop = subscribe((now) => {
      if (now.samples || now.samplesError) {
        stop();
        resolve();
      }
    });
  });
}

/**
 * The analysis of upload `key`: the one this page holds, else the server's (it keeps
 * uploads: a link to one works after a reload). An upload the server said it no longer has
 * is Missing, and not asked for again.
 */
export async function upload(key) {
  const held = state.uploads.find((u) => u.key === key);
  if (held) return held.result;
  const cloth = { kind: "upload", id: key };
  if (state.gone.includes(key)) throw new Missing(cloth);
  try {
    const result = await api.analysis(key);
    addUpload(result.name || key, result);
    return result;
  } catch (e) {
    if (e instanceof api.ApiError && e.status === 404) {
      set({ gone: [...state.gone, key] });
      throw new Missing(cloth, e.message);
    }
    throw e;
  }
}

/**
 * The answer for `cloth` ({kind, id}): an upload's analysis, or a sample's (on `channel`).
 * A sample the list does not hold is Missing without a request (the list is waited for;
 * when it failed, the server is asked).
 */
export async function answer(cloth, channel) {
  if (cloth.kind === "upload") return upload(cloth.id);
  await listed();
  if (state.samples && !state.samples.some((s) => s.id === cloth.id)) throw new Missing(cloth);
  return api.sample(cloth.id, channel);
}

/** The clothes Interpolate and Plan can use: every sample, then every upload. */
export function cloths() {
  const samples = (state.samples || []).map((s) => ({ kind: "sample", id: s.id, name: `${s.category} · ${s.name}` }));
  const uploads = state.uploads.map((u) => ({ kind: "upload", id: u.key, name: `upload · ${u.name}` }));
  return [...samples, ...uploads];
}
