// Header, legend and notes (issue #25 item 1): title, the run's verdict, units, the command line that
// produced the page, the legend (the document's entries plus the fixed verdict colours), notes.
import { CURVE_COLOR, VERDICT_COLORS, WITNESS_COLOR, hexToCss, rgbToHex } from './colors.js';
import { el } from './format.js';

export function buildHeader(root, doc) {
  root.replaceChildren();
  root.append(el('h1', null, doc.title || 'interfere report'));
  if (doc.verdict) {
    const badge = el('span', { className: 'verdict', id: 'run-verdict' }, doc.verdict);
    if (VERDICT_COLORS[doc.verdict] !== undefined) badge.style.background = hexToCss(VERDICT_COLORS[doc.verdict]);
    root.append(badge);
  }
  const facts = [];
  if (doc.units) facts.push(`units: ${doc.units}`);
  if (doc.toolVersion) facts.push(`interfere ${doc.toolVersion}`);
  if (facts.length) root.append(el('span', { className: 'facts' }, facts.join(' · ')));
  if (doc.command) root.append(el('code', { id: 'command', title: 'The command line that produced this page' }, doc.command));
}

function legendRow(color, label, line) {
  const sw = el('span', { className: line ? 'swatch line' : 'swatch' });
  sw.style.background = hexToCss(color);
  return el('li', null, sw, label);
}

export function buildLegend(root, doc) {
  const list = el('ul', { id: 'legend-list' });
  for (const e of doc.legend) list.append(legendRow(rgbToHex(e.color), e.label, false));
  const used = new Set(doc.clashes.map((c) => c.verdict));
  if (used.has('clash') || !doc.clashes.length) list.append(legendRow(VERDICT_COLORS.clash, 'clash region', false));
  if (used.has('contact')) list.append(legendRow(VERDICT_COLORS.contact, 'contact region', false));
  if (used.has('undecided')) list.append(legendRow(VERDICT_COLORS.undecided, 'undecided', false));
  if (doc.clashes.some((c) => c.curves.length)) list.append(legendRow(CURVE_COLOR, 'intersection curve', true));
  if (doc.clashes.some((c) => c.witness)) list.append(legendRow(WITNESS_COLOR, 'clearance witness (closest points)', true));
  root.append(list);
}

export function buildNotes(root, notes) {
  if (!notes.length) {
    root.hidden = true;
    return;
  }
  const list = el('ul', { id: 'notes-list' });
  for (const n of notes) list.append(el('li', null, n));
  root.append(list);
}
