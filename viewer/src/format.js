// Number and text formatting shared by the clash list, details and header (issue #25).

/** A length for display: 4 significant digits, "—" when not known (null or negative). */
export function formatLength(x) {
  if (x === null || x === undefined || !Number.isFinite(x) || x < 0) return '—';
  if (x === 0) return '0';
  const a = Math.abs(x);
  if (a >= 1e6 || a < 1e-4) return x.toExponential(3);
  return String(Number(x.toPrecision(4)));
}

/** A coordinate triple for display. */
export function formatPoint(p) {
  return p.map((v) => String(Number(v.toPrecision(7)))).join(', ');
}

/** Element helper: el('td', {className: 'x'}, 'text', child, ...). */
export function el(tag, props, ...children) {
  const e = document.createElement(tag);
  if (props) Object.assign(e, props);
  for (const c of children) {
    if (c === null || c === undefined) continue;
    e.append(c instanceof Node ? c : String(c));
  }
  return e;
}
