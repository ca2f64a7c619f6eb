// Hash URLs: #/samples/{id}, #/samples, #/upload, #/interpolate, #/plan. Back and Forward
// move between them; the page title names the view and the open sample.

export const VIEWS = ["samples", "upload", "interpolate", "plan"];
const NAMES = { samples: "Browse", upload: "Upload", interpolate: "Interpolate", plan: "Plan" };

/** The route of a hash: {view, id}. Unknown hashes are the sample browser. */
export function parse(hash) {
  const parts = hash.replace(/^#\/?/, "").split("/").filter(Boolean).map(decodeURIComponent);
  const view = VIEWS.includes(parts[0]) ? parts[0] : "samples";
  return { view, id: view === "samples" && parts[1] ? parts[1] : null };
}

/** The hash of a route. */
export function hashOf(view, id = null) {
  return id ? `#/${view}/${encodeURIComponent(id)}` : `#/${view}`;
}

/** Go to a route (a new history entry unless it is the current one). */
export function go(view, id = null) {
  const hash = hashOf(view, id);
  if (location.hash !== hash) location.hash = hash;
  else window.dispatchEvent(new HashChangeEvent("hashchange"));
}

/** Call `show(route)` now and on every hash change. */
export function start(show) {
  const run = () => show(parse(location.hash));
  window.addEventListener("hashchange", run);
  run();
}

/** The page title for a view and, in it, an open item's name. */
export function title(view, name = "") {
  return `${name ? `${name} · ` : ""}${NAMES[view] || "CloSE"} — CloSE cloth state explorer`;
}
