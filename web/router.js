// Hash URLs: #/samples/{id}, #/samples, #/upload, #/interpolate, #/plan, #/compare/{a}/{b}.
// A view keeps its state after a "?" (#/samples/{id}?step=2, #/interpolate?cloth=…&step=…
// &from=…&to=…&t=…, #/plan?cloth=…&goal=…), so a reload or a shared link shows the same
// thing. Back and Forward move between views; the page title names the view and the open
// sample.

export const VIEWS = ["samples", "upload", "interpolate", "plan", "compare"];
const NAMES = { samples: "Browse", upload: "Upload", interpolate: "Interpolate", plan: "Plan", compare: "Compare" };

/** The route of a hash: {view, id, ids, params}. Unknown hashes are the sample browser. */
export function parse(hash) {
  const [path, query = ""] = hash.replace(/^#\/?/, "").split("?");
  const parts = path.split("/").filter(Boolean).map((p) => {
    try {
      return decodeURIComponent(p);
    } catch {
      return p;
    }
  });
  const view = VIEWS.includes(parts[0]) ? parts[0] : "samples";
  return { view, id: view === "samples" && parts[1] ? parts[1] : null, ids: parts.slice(1), params: new URLSearchParams(query) };
}

/** The hash of a route: `id` one path part or several (compare). */
export function hashOf(view, id = null, params = null) {
  const ids = [id].flat().filter((p) => p !== null && p !== undefined && p !== "");
  const query = params && String(params) ? `?${params}` : "";
  return `#/${[view, ...ids.map(encodeURIComponent)].join("/")}${query}`;
}

/** Go to a route (a new history entry unless it is the current one). */
export function go(view, id = null, params = null) {
  const hash = hashOf(view, id, params);
  if (location.hash !== hash) location.hash = hash;
  else window.dispatchEvent(new HashChangeEvent("hashchange"));
}

/**
 * Write the state of the view on screen into its URL without a new history entry (and
 * without a hash change: nothing reloads). Only while `view` is the one shown.
 */
export function keep(view, params) {
  const route = parse(location.hash);
  if (route.view !== view) return;
  const hash = hashOf(view, route.ids, params);
  if (location.hash !== hash) history.replaceState(history.state, "", hash);
}

/** Two angles written in a URL ("0.785398,3.926991", radians), or null. */
export function angles(text) {
  const v = String(text || "").split(",").map(Number);
  return v.length === 2 && v.every(Number.isFinite) ? v : null;
}
export const angleText = (pair) => pair.map((a) => a.toFixed(6)).join(",");

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
