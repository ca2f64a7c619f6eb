// The API client: one function per route of src/server, every error a readable message.
//
// Requests go through channels: a new request on a channel aborts the one still running
// there (a click on sample B makes sample A's answer irrelevant), and an aborted request
// rejects with an AbortError that callers ignore (see `isAbort`). A channel's controller
// stays until the next request, so reading a superseded answer's body is aborted too.

const channels = new Map();

/** An error a person can read: the server's {"error"} text, or what went wrong. */
export class ApiError extends Error {
  constructor(message, status = 0) {
    super(message);
    this.status = status;
  }
}

/** True for the rejection of a superseded request, which is not an error to show. */
export const isAbort = (e) => e && e.name === "AbortError";

/** The message of a failed answer: its JSON "error", else its text without markup. */
export function errorText(status, statusText, body) {
  let message = "";
  try {
    const parsed = JSON.parse(body);
    message = (parsed && (parsed.error || parsed.message)) || "";
  } catch {
    // An HTML or plain text page from a proxy or an older server: keep its words only.
    const doc = new DOMParser().parseFromString(body || "", "text/html");
    // Block elements end a phrase: "503 Service Unavailable" and "upstream down" stay apart.
    for (const block of doc.querySelectorAll("h1, h2, h3, h4, h5, h6, p, div, li, br, tr, pre")) block.after(" ");
    message = (doc.body ? doc.body.textContent : body || "").replace(/\s+/g, " ").trim().slice(0, 300);
  }
  if (message) return `${message} (HTTP ${status})`;
  return `The server answered HTTP ${status}${statusText ? ` ${statusText}` : ""} without a message.`;
}

/**
 * fetch on `channel` (aborting its previous request), or with the caller's `options.signal`;
 * resolves to the Response if ok.
 */
async function send(channel, url, options = {}) {
  let signal = options.signal;
  if (channel) {
    if (channels.has(channel)) channels.get(channel).abort();
    const controller = new AbortController();
    channels.set(channel, controller);
    signal = controller.signal;
  }
  let res;
  try {
    res = await fetch(url, { ...options, signal });
  } catch (e) {
    if (isAbort(e)) throw e;
    throw new ApiError(`Could not reach the server (${url}): the network failed or the server stopped. Check that \`close serve\` is running, then try again.`);
  }
  if (!res.ok) {
    const body = await res.text().catch(() => "");
    throw new ApiError(errorText(res.status, res.statusText, body), res.status);
  }
  return res;
}

/** JSON of `url` (GET, or POST of `body` when given); `signal` aborts it (without a channel). */
export async function json(channel, url, body, signal) {
  const options = { ...(body === undefined ? {} : post(body)), signal };
  const res = await send(channel, url, options);
  const text = await res.text();
  try {
    return JSON.parse(text);
  } catch {
    throw new ApiError(`The server's answer to ${url} is not JSON: ${text.slice(0, 120)}`);
  }
}

function post(body) {
  if (body instanceof FormData) return { method: "POST", body };
  return { method: "POST", headers: { "content-type": "application/json" }, body: JSON.stringify(body) };
}

export const samples = () => json("samples", "/api/samples");
export const sample = (id, channel = "sample") => json(channel, `/api/samples/${encodeURIComponent(id)}`);
export const analyze = (form) => json("analyze", "/api/analyze", form);
/** An analysis by its `key` (an upload's, kept by the server). */
export const analysis = (key, channel = "analysis") => json(channel, `/api/analyses/${encodeURIComponent(key)}`);
/** The states of a motion ({…, states}); `channel` names it (a newer request on it aborts it). */
export const interpolate = (request, channel = "interpolate") => json(channel, "/api/interpolate", request);
export const plan = (request) => json("plan", "/api/plan", request);

/**
 * The dGLI disk PNG of one border state, as an object URL, and the colour scale it used
 * ({s, max}; send it back as `scale` to keep the colours fixed).
 */
export async function disk(request, channel = "disk") {
  const res = await send(channel, "/api/disk", post(request));
  const [s, max] = (res.headers.get("x-disk-scale") || "").split(" ").map(Number);
  const url = URL.createObjectURL(await res.blob());
  return { url, scale: Number.isFinite(s) && s > 0 ? { s, max } : null };
}

/** The cells of the disk `disk(request)` draws: {n, size, disk: {cx, cy, radius}, values} (ring by ring). */
export const diskCells = (request, channel = "disk-cells") => json(channel, "/api/disk/cells", request);

/**
 * What reading the disk pictures of analysis `key` at `step` (null: the whole span) takes:
 * {n, size, from_frame, to_frame, disk: {cx, cy, radius}, borders: {x, y}, start, end}.
 */
export function readout(key, step, size = 480) {
  const query = new URLSearchParams({ size: String(size) });
  if (step) query.set("step", String(step));
  return json(null, `/api/readout/${encodeURIComponent(key)}?${query}`);
}

/** The URL of picture `name` of an analysis, for `step` (1-based) or the whole, at `size` px, as PNG or SVG. */
export function imageUrl(key, name, { step = null, size = 480, format = "png", dpi = null } = {}) {
  const query = new URLSearchParams({ size: String(size) });
  if (step) query.set("step", String(step));
  if (format !== "png") query.set("format", format);
  if (dpi) query.set("dpi", String(dpi));
  return `/api/images/${encodeURIComponent(key)}/${name}.png?${query}`;
}

const cellMaps = new Map();

/**
 * Which cell each pixel of a `size` px disk picture of `n` edges shows, from the server's
 * cell picture (GET /api/cells.png): per pixel, row by row, 1 + the cell's ring index (0 off
 * the disk). One request per (n, size), kept.
 */
export function cellMap(n, size) {
  const key = `${n}/${size}`;
  if (!cellMaps.has(key)) {
    const got = send(null, `/api/cells.png?${new URLSearchParams({ n: String(n), size: String(size) })}`)
      .then((res) => res.blob())
      .then((blob) => createImageBitmap(blob, { colorSpaceConversion: "none", premultiplyAlpha: "none" }))
      .then((bitmap) => {
        const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
        const ctx = canvas.getContext("2d", { willReadFrequently: true });
        ctx.drawImage(bitmap, 0, 0);
        const rgba = ctx.getImageData(0, 0, bitmap.width, bitmap.height).data;
        const codes = new Int32Array(bitmap.width * bitmap.height);
        for (let p = 0; p < codes.length; p++) codes[p] = (rgba[4 * p] << 16) | (rgba[4 * p + 1] << 8) | rgba[4 * p + 2];
        return codes;
      });
    got.catch(() => cellMaps.delete(key));
    cellMaps.set(key, got);
  }
  return cellMaps.get(key);
}
