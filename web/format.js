// Number formatting shared by the views.

export const deg = (a) => (a * 180) / Math.PI;
export const fmtAngle = (a) => `${a.toFixed(3)} rad (${deg(a).toFixed(1)}°)`;
export const fmtFold = (f) => `(${fmtAngle(f[0])}, ${fmtAngle(f[1])})`;
export const fmtDeg = (f) => `(${deg(f[0]).toFixed(1)}°, ${deg(f[1]).toFixed(1)}°)`;
export const fmtPoint = (p) => `(${p[0].toFixed(2)}, ${p[1].toFixed(2)})`;

/** A new element with `props` (className, textContent, …) and children. */
export function el(tag, props = {}, ...children) {
  const node = Object.assign(document.createElement(tag), props);
  node.append(...children.filter((c) => c !== null && c !== undefined));
  return node;
}

/** A table row: a header cell and a value cell. */
export function row(table, key, value) {
  const tr = table.insertRow();
  tr.append(el("th", { scope: "row", textContent: key }));
  tr.insertCell().textContent = value;
  return tr;
}
