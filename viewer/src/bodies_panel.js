// Body visibility toggles (issue #25 item 1): one checkbox per body; bodies with visible=false
// (e.g. the original beside a simplification) start hidden.
import { hexToCss, rgbToHex } from './colors.js';
import { el } from './format.js';

export function buildBodiesPanel(root, doc, onToggle) {
  const list = el('ul', { id: 'body-list' });
  doc.bodies.forEach((b, i) => {
    const box = el('input', { type: 'checkbox', checked: b.visible });
    box.dataset.index = String(i);
    box.addEventListener('change', () => onToggle(i, box.checked));
    const swatch = el('span', { className: 'swatch' });
    swatch.style.background = hexToCss(rgbToHex(b.color));
    const mesh = doc.meshes[b.mesh];
    const extra = [];
    if (b.role) extra.push(b.role);
    if (mesh.triangles === 0) extra.push('no geometry');
    else if (mesh.sourceTriangles > mesh.triangles) {
      extra.push(`${mesh.triangles.toLocaleString('en')} of ${mesh.sourceTriangles.toLocaleString('en')} triangles`);
    }
    const label = el('label', { title: b.path || b.name }, box, swatch, b.name,
      extra.length ? el('span', { className: 'muted' }, ` (${extra.join(', ')})`) : null);
    list.append(el('li', null, label));
  });
  root.append(list);
}
