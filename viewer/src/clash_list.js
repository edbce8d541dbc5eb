// The clash list (issue #25 item 1): id, bodies, verdict, depth/distance, status; filters by verdict
// and status; a click selects the clash (the page flies the camera to it). Rows of clashes that are
// not present in the current frame are dimmed. Also the selected clash's details.
import { hexToCss, verdictColor } from './colors.js';
import { el, formatLength, formatPoint } from './format.js';

/** The size column: depth (or its bound) for clashes, distance for clearances and contacts. */
export function clashSize(c, units) {
  const u = units ? ` ${units}` : '';
  if (c.verdict === 'contact' && !(c.distance > 0)) return 'touching';
  if (c.verdict === 'clearance' || (c.depth === null && c.distance !== null)) {
    return c.distance === null ? '—' : `gap ${formatLength(c.distance)}${u}`;
  }
  if (c.depth !== null && c.depth >= 0) return `depth ${formatLength(c.depth)}${u}`;
  if (c.depthBound !== null && c.depthBound >= 0) return `depth ≤ ${formatLength(c.depthBound)}${u}`;
  return '—';
}

function options(select, values, label) {
  select.append(el('option', { value: '*' }, `all ${label}`));
  for (const v of values) select.append(el('option', { value: v }, v === '' ? '(none)' : v));
}

/** Builds the list into `root`; returns { select(i), setFrame(k), rows }. */
export function buildClashList(root, doc, onSelect) {
  const verdicts = [...new Set(doc.clashes.map((c) => c.verdict))].sort();
  const statuses = [...new Set(doc.clashes.map((c) => c.status))].sort();
  const verdictFilter = el('select', { id: 'filter-verdict', title: 'Filter by verdict' });
  const statusFilter = el('select', { id: 'filter-status', title: 'Filter by status' });
  options(verdictFilter, verdicts, 'verdicts');
  options(statusFilter, statuses, 'statuses');
  const count = el('span', { className: 'count' });
  root.append(el('div', { className: 'filters' }, verdictFilter, statusFilter, count));

  const tbody = el('tbody');
  const head = el('thead', null, el('tr', null,
    el('th', null, 'id'), el('th', null, 'bodies'), el('th', null, 'verdict'),
    el('th', null, 'depth / gap'), el('th', null, 'status')));
  const table = el('table', { id: 'clash-table' }, head, tbody);
  root.append(el('div', { className: 'table-scroll' }, table));
  if (!doc.clashes.length) root.append(el('p', { className: 'empty' }, 'No clashes in this report.'));

  const name = (i) => doc.bodies[i].name;
  const rows = doc.clashes.map((c, i) => {
    const dot = el('span', { className: 'dot' });
    dot.style.background = hexToCss(verdictColor(c.verdict));
    const row = el('tr', null,
      el('td', { className: 'id', title: c.id }, c.id),
      el('td', { className: 'bodies', title: `${name(c.bodies[0])} ↔ ${name(c.bodies[1])}` },
        `${name(c.bodies[0])} ↔ ${name(c.bodies[1])}`),
      el('td', null, dot, c.verdict),
      el('td', { className: 'num' }, clashSize(c, doc.units)),
      el('td', null, c.status));
    row.dataset.index = String(i);
    row.dataset.verdict = c.verdict;
    row.addEventListener('click', () => onSelect(i));
    tbody.append(row);
    return row;
  });

  const applyFilters = () => {
    const v = verdictFilter.value;
    const s = statusFilter.value;
    let shown = 0;
    doc.clashes.forEach((c, i) => {
      const ok = (v === '*' || c.verdict === v) && (s === '*' || c.status === s);
      rows[i].hidden = !ok;
      if (ok) ++shown;
    });
    count.textContent = `${shown} of ${doc.clashes.length}`;
  };
  verdictFilter.addEventListener('change', applyFilters);
  statusFilter.addEventListener('change', applyFilters);
  applyFilters();

  return {
    rows,
    select(i) {
      rows.forEach((r, j) => r.classList.toggle('selected', j === i));
      if (i >= 0) rows[i].scrollIntoView({ block: 'nearest' });
    },
    setFrame(k) {
      doc.clashes.forEach((c, i) => {
        rows[i].classList.toggle('absent', k >= 0 && c.frames.length > 0 && !c.frames.includes(k));
      });
    },
  };
}

/** The selected clash's details (coordinates shown with the document's origin added back). */
export function showClashDetails(root, doc, c) {
  root.replaceChildren();
  if (!c) {
    root.append(el('p', { className: 'hint' }, 'Click a clash in the list to fly to it.'));
    return;
  }
  const add = (k, v) => {
    if (v === null || v === undefined || v === '') return;
    root.append(el('dt', null, k), el('dd', null, v));
  };
  const u = doc.units ? ` ${doc.units}` : '';
  const world = (p) => formatPoint(p.map((x, i) => x + doc.origin[i]));
  const body = (i) => {
    const b = doc.bodies[i];
    return b.path && b.path !== b.name ? `${b.name} (${b.path})` : b.name;
  };
  add('clash', c.id);
  add('verdict', c.kind ? `${c.verdict} (${c.kind})` : c.verdict);
  add('status', c.status);
  add('body A', body(c.bodies[0]));
  add('body B', body(c.bodies[1]));
  if (c.depth !== null && c.depth >= 0) add('depth', formatLength(c.depth) + u);
  if (c.depthBound !== null && c.depthBound >= 0) add('depth bound', formatLength(c.depthBound) + u);
  if (c.distance !== null && c.distance >= 0) add('distance', formatLength(c.distance) + u);
  if (c.point) add('point', world(c.point));
  if (c.box) add('box', `${world(c.box[0])} … ${world(c.box[1])}`);
  if (c.witness) add('witness', `${world(c.witness[0])} → ${world(c.witness[1])}`);
  if (c.curves.length) add('curves', `${c.curves.length} polyline${c.curves.length > 1 ? 's' : ''}`);
  if (c.frames.length) add('frames', c.frames.map((k) => doc.frames.labels[k]).join(', '));
  add('note', c.note);
}
