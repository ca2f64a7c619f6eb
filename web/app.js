// CloSE web app: browse the built-in samples, upload one, interpolate folds, plan a fold.
// Native ES modules, no build step; talks to the JSON API of src/server through api.js.
// One module per view, state in store.js, URLs in router.js.

import * as store from "./store.js";
import * as router from "./router.js";
import * as browse from "./view-browse.js";
import * as upload from "./view-upload.js";
import * as interpolate from "./view-interpolate.js";
import * as plan from "./view-plan.js";
import * as compare from "./view-compare.js";

const $ = (sel) => document.querySelector(sel);

/** Show `message` in the page's error box (empty: hide it). */
function showError(message) {
  const box = $("#error");
  box.textContent = message;
  box.hidden = !message;
}

/** Interpolate and Plan need a cloth: say why there is none. */
function noCloth() {
  const { samplesError, uploads } = store.get();
  if (store.cloths().length || !samplesError) return "";
  return uploads.length ? "" : `No cloth to work on: the sample list could not be loaded (${samplesError}). Upload a sample, or reload the page.`;
}

/** A result's cloth, for Interpolate and Plan. */
const clothOf = (result) => (result.id ? { kind: "sample", id: result.id } : { kind: "upload", id: result.key });

const resultActions = {
  /** Interpolate `result`'s fold `fold` (1-based, or "all": the sequence), as shown. */
  interpolate(result, fold) {
    const cloth = clothOf(result);
    store.set({ cloth });
    router.go("interpolate", null, new URLSearchParams({ cloth: `${cloth.kind}:${cloth.id}`, step: String(fold) }));
  },
  plan(result) {
    store.set({ cloth: clothOf(result) });
    router.go("plan");
  },
  /** Compare states `a` and `b` ("id", "name" or "…@k"). */
  compare(a, b) {
    router.go("compare", [a, b]);
  },
};

let pendingGoal = null;

function show({ view, id, ids, params }) {
  for (const name of router.VIEWS) {
    $(`#view-${name}`).hidden = name !== view;
    const tab = $(`#tab-${name}`);
    tab.classList.toggle("active", name === view);
    if (name === view) tab.setAttribute("aria-current", "page");
    else tab.removeAttribute("aria-current");
  }
  showError(noCloth());
  if (view === "samples") {
    const wanted = id || browse.opened() || browse.first();
    // The default sample replaces the bare URL rather than adding a history entry.
    if (!id && wanted) location.replace(router.hashOf("samples", wanted));
    else if (wanted && wanted !== browse.current()) browse.open(wanted, showError, params.get("step"));
    else {
      // The sample on screen: a link may still name another step.
      if (params.get("step")) browse.showStep(params.get("step"));
      document.title = router.title("samples", $("#browse-result .result-name")?.textContent || "");
    }
  } else if (view === "upload") {
    upload.shown(params);
  } else if (view === "interpolate") {
    interpolate.shown(params);
  } else if (view === "plan") {
    plan.shown(pendingGoal || router.angles(params.get("goal")), interpolate.clothParam(params));
    pendingGoal = null;
  } else if (view === "compare") {
    compare.shown(ids, showError);
  }
}

// The skip link moves the focus to the view on screen without touching the hash route.
document.querySelector(".skip-link").addEventListener("click", (e) => {
  e.preventDefault();
  const view = document.querySelector(".view:not([hidden])");
  const first = view?.querySelector("input, select, button, a[href], [tabindex='0']");
  (first || $("#main")).focus();
});

browse.setup(resultActions);
upload.setup(resultActions, showError);
interpolate.setup(showError, (cloth, goal) => {
  store.set({ cloth });
  pendingGoal = goal;
  router.go("plan");
});
plan.setup(showError);
compare.setup();

// The list first, then the route (a sample URL opens its sample at once either way).
const listed = browse.loadSamples();
router.start(show);
listed.then(() => {
  const route = router.parse(location.hash);
  // Views that waited for the list (a first sample, a cloth to fold) can start now.
  if (!route.id || route.view !== "samples") show(route);
});

// For tests and the console.
window.closeApp = { store, router, interpolate, diskKey: interpolate.diskKey };
