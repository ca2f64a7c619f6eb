// The fold circle of the Interpolate and Plan views, drawn as the paper draws CloSE: the
// border parameter as the unit circle (vertex 0 at angle 0, anticlockwise), corners as
// numbered dots, a fold (f1, f2) as the arc from f1 anticlockwise to f2 and its chord.
// Handles are dragged with a pointer or focused (Tab) and moved with the arrow keys.

export const TAU = 2 * Math.PI;
/** An angle taken into [0, 2π). */
export const wrap = (a) => ((a % TAU) + TAU) % TAU;

const SVG = "http://www.w3.org/2000/svg";
export const R = 100;
/** One arrow-key press moves a handle this far (Shift: ten times as far). */
const KEY_STEP = TAU / 360;

function svg(tag, attrs, parent) {
  const node = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  if (parent) parent.append(node);
  return node;
}

/** Position of angle a at radius r (anticlockwise on screen: SVG's y points down). */
const onCircle = (a, r = R) => [r * Math.cos(a), -r * Math.sin(a)];

/** SVG path of the arc from a to b anticlockwise at radius r. */
function arcPath(a, b, r) {
  const span = wrap(b - a);
  const [x1, y1] = onCircle(a, r);
  const [x2, y2] = onCircle(b, r);
  return `M ${x1} ${y1} A ${r} ${r} 0 ${span > Math.PI ? 1 : 0} 0 ${x2} ${y2}`;
}

/** A handle's radius, and the least distance between two handles' centres (SVG units). */
const HANDLE = 9;
const APART = 2 * HANDLE + 2;

/**
 * The angle each handle is drawn at: its own, except that handles on one ring closer than
 * APART (a fold from flat has both "from" points at one angle) are fanned out around their
 * middle, in order, so every handle stays visible and can be grabbed.
 */
function fanned(handles) {
  const at = new Map();
  for (const r of new Set(handles.map((h) => h.r))) {
    const step = APART / r;
    // Stable: handles at one angle keep their order (1 before 2, anticlockwise).
    const ring = handles.filter((h) => h.r === r).sort((a, b) => a.angle - b.angle);
    let fan = [];
    ring.forEach((h, k) => {
      fan.push(h);
      if (k + 1 < ring.length && ring[k + 1].angle - h.angle < step) return;
      const mid = (fan[0].angle + h.angle) / 2;
      fan.forEach((g, i) => at.set(g, fan.length > 1 ? mid + (i - (fan.length - 1) / 2) * step : g.angle));
      fan = [];
    });
  }
  return at;
}

/**
 * Draw into the SVG `root`: the circle, the corners (numbered outside it), each of `arcs`
 * ({fold, color}) as its folded arc and chord, and `handles` ({id, angle, color, label, r,
 * name}) as focusable dots outside the circle, at radius r.
 */
export function drawFoldCircle(root, corners, arcs, handles) {
  const focused = document.activeElement && root.contains(document.activeElement) ? document.activeElement.dataset.id : null;
  root.replaceChildren();
  svg("circle", { cx: 0, cy: 0, r: R, fill: "none", stroke: "#cbd2dc", "stroke-width": 2 }, root);
  svg("line", { x1: R - 6, y1: 0, x2: R + 6, y2: 0, stroke: "#6b7280" }, root);
  // Below the tick, clear of a corner number inside and the handles outside.
  svg("text", { x: R + 2, y: 16, "font-size": 9, fill: "#4b5563" }, root).textContent = "0";
  arcs.forEach(({ fold, color }, k) => {
    // Nested arcs stay apart when several folds are shown.
    const r = R - 5 * k;
    if (wrap(fold[1] - fold[0]) > 1e-9) {
      svg("path", { d: arcPath(fold[0], fold[1], r), fill: "none", stroke: color, "stroke-width": 7, "stroke-linecap": "round", opacity: 0.85 }, root);
    }
    const [ax, ay] = onCircle(fold[0]);
    const [bx, by] = onCircle(fold[1]);
    svg("line", { x1: ax, y1: ay, x2: bx, y2: by, stroke: color, "stroke-dasharray": "4 4" }, root);
  });
  corners.forEach((c, k) => {
    const [x, y] = onCircle(c);
    svg("circle", { cx: x, cy: y, r: 3.5, fill: "#111827" }, root);
    // Inside the circle, so the handles outside never cover the numbers.
    const [tx, ty] = onCircle(c, R - 14);
    svg("text", { x: tx, y: ty + 3.5, "font-size": 11, "text-anchor": "middle", fill: "#111827" }, root).textContent = k + 1;
  });
  const at = fanned(handles);
  // A handle fanned off its angle points at it; the pointers go under every handle.
  const pointers = svg("g", {}, root);
  for (const h of handles) {
    const [x, y] = onCircle(at.get(h), h.r);
    const [px, py] = onCircle(h.angle);
    if (at.get(h) !== h.angle) svg("line", { x1: px, y1: py, x2: x, y2: y, stroke: h.color, "stroke-width": 1.5 }, pointers);
    const group = svg("g", { class: "handle", tabindex: 0, role: "slider", "aria-label": h.name, "aria-valuemin": 0, "aria-valuemax": 360,
      "aria-valuenow": ((h.angle * 180) / Math.PI).toFixed(1), "aria-valuetext": `${((h.angle * 180) / Math.PI).toFixed(1)}°` }, root);
    group.dataset.id = h.id;
    // Arrow keys step from the exact angle, not from the rounded one said to screen readers.
    group.dataset.angle = h.angle;
    svg("circle", { cx: x, cy: y, r: HANDLE, fill: h.color, stroke: "#fff", "stroke-width": 2 }, group);
    svg("text", { x, y: y + 3.5, "font-size": 10, "text-anchor": "middle", fill: "#fff", "pointer-events": "none" }, group).textContent = h.label;
  }
  if (focused) root.querySelector(`.handle[data-id="${CSS.escape(focused)}"]`)?.focus();
}

/**
 * Let the handles of the circle `root` be dragged round it or moved by arrow keys:
 * `move(id, angle)`; `end()` once a drag lets go.
 */
export function dragOnCircle(root, move, end = () => {}) {
  let id = null;
  root.addEventListener("pointerdown", (e) => {
    const handle = e.target.closest(".handle");
    if (!handle) return;
    id = handle.dataset.id;
    root.setPointerCapture(e.pointerId);
  });
  root.addEventListener("pointermove", (e) => {
    if (id === null) return;
    const pt = root.createSVGPoint();
    pt.x = e.clientX;
    pt.y = e.clientY;
    const p = pt.matrixTransform(root.getScreenCTM().inverse());
    move(id, wrap(Math.atan2(-p.y, p.x)));
  });
  const stop = () => {
    if (id !== null) end();
    id = null;
  };
  root.addEventListener("pointerup", stop);
  root.addEventListener("pointercancel", stop);
  root.addEventListener("keydown", (e) => {
    const handle = e.target.closest(".handle");
    if (!handle) return;
    // Up/Right turn anticlockwise (increasing angle), as on the circle.
    const sign = { ArrowUp: 1, ArrowRight: 1, ArrowDown: -1, ArrowLeft: -1 }[e.key];
    if (!sign) return;
    e.preventDefault();
    move(handle.dataset.id, wrap(Number(handle.dataset.angle) + sign * KEY_STEP * (e.shiftKey ? 10 : 1)));
  });
}

/**
 * Angle inputs that keep their exact values: a box shows its angle rounded, and only the
 * box the user edits is read back (the others keep their full precision). Typing that is
 * not a number is reported beside the box, not ignored.
 */
export class AngleInputs {
  /** `inputs`: {key: <input>}; `onChange(key, radians)`; `status`: element for messages. */
  constructor(inputs, status, onChange, degrees = () => true) {
    Object.assign(this, { inputs, status, onChange, degrees });
    for (const [key, input] of Object.entries(inputs)) {
      input.addEventListener("change", () => this.read(key));
    }
  }

  /** Show `values` ({key: radians}) in the boxes, except the one being typed in. */
  write(values) {
    const inDeg = this.degrees();
    for (const [key, input] of Object.entries(this.inputs)) {
      if (!(key in values) || document.activeElement === input) continue;
      input.value = inDeg ? ((values[key] * 180) / Math.PI).toFixed(1) : values[key].toFixed(4);
      input.step = inDeg ? "0.1" : "0.001";
      input.removeAttribute("aria-invalid");
    }
  }

  read(key) {
    const input = this.inputs[key];
    const value = Number(input.value.trim().replace(",", "."));
    if (input.value.trim() === "" || !Number.isFinite(value)) {
      input.setAttribute("aria-invalid", "true");
      this.status.textContent = `“${input.value}” is not a number: type an angle in ${this.degrees() ? "degrees" : "radians"}.`;
      return;
    }
    input.removeAttribute("aria-invalid");
    this.status.textContent = "";
    this.onChange(key, wrap(this.degrees() ? (value * Math.PI) / 180 : value));
  }
}
