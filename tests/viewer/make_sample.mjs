// Synthetic viewer documents for the browser tests (issue #25 item 4), injected into the built
// template the way the C++ writer does it (docs/viewer.md "Writing a page"):
//   node make_sample.mjs TEMPLATE.html OUT_DIR VARIANT [--triangles N]
// writes OUT_DIR/VARIANT.html and OUT_DIR/VARIANT.expect.json (the expectations check_page.mjs reads).
// Variants: sample (two overlapping boxes with a red region of the overlapping triangles, the
// intersection curve, 3 frames, a clearance and a contact), error ("error" set), schema (another
// schema_version), invalid (broken JSON), unescaped (data that ends its element wrongly), nodata
// (the template as built), large (about N triangles, default 300,000, decimated from 1,000,000 in
// source).
// The geometry is computed here from its construction (boxes, their overlap box), independently of
// the page's code.
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';

const DATA = '/*INTERFERE_VIEWER_DATA*/';
const TITLE = 'INTERFERE_VIEWER_TITLE';

// ---- the writer's side of the contract: escaping and placeholders ----
function escapeHtml(s) {
  return s.replace(/[&<>"']/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' })[c]);
}

/** JSON text safe inside <script type="application/json">: "</" -> "<\/", "<!--" -> "\u003c!--". */
export function scriptSafeJson(json) {
  return json.split('</').join('<\\/').split('<!--').join('\\u003c!--');
}

/** The page: the template with its two placeholders replaced (each found exactly once). */
export function inject(template, dataText, title) {
  const d = template.indexOf(DATA);
  const t = template.indexOf(TITLE);
  if (d < 0 || t < 0 || template.indexOf(DATA, d + 1) >= 0 || template.indexOf(TITLE, t + 1) >= 0) {
    throw new Error('the template must hold each placeholder exactly once');
  }
  if (t > d) throw new Error('the title placeholder is expected before the data placeholder');
  return template.slice(0, t) + escapeHtml(title) + template.slice(t + TITLE.length, d) + dataText +
         template.slice(d + DATA.length);
}

// ---- geometry ----
const b64 = (typed) => Buffer.from(typed.buffer, typed.byteOffset, typed.byteLength).toString('base64');

/** A box [lo, hi] with every face split into n x n squares (2 triangles each), outward winding. */
function boxMesh(lo, hi, n) {
  const pos = [];
  const idx = [];
  const faceOf = [];
  // each face: axis fixed at lo or hi, u and v axes, winding so that u x v points outward
  const faces = [];
  for (let axis = 0; axis < 3; ++axis) {
    const u = (axis + 1) % 3;
    const v = (axis + 2) % 3;
    faces.push([axis, 1, u, v], [axis, 0, v, u]);
  }
  faces.forEach(([axis, side, u, v], f) => {
    const base = pos.length / 3;
    for (let j = 0; j <= n; ++j) {
      for (let i = 0; i <= n; ++i) {
        const p = [0, 0, 0];
        p[axis] = side ? hi[axis] : lo[axis];
        p[u] = lo[u] + ((hi[u] - lo[u]) * i) / n;
        p[v] = lo[v] + ((hi[v] - lo[v]) * j) / n;
        pos.push(...p);
      }
    }
    for (let j = 0; j < n; ++j) {
      for (let i = 0; i < n; ++i) {
        const a = base + j * (n + 1) + i;
        idx.push(a, a + 1, a + n + 2, a, a + n + 2, a + n + 1);
        faceOf.push(f, f);
      }
    }
  });
  return { positions: new Float32Array(pos), indices: new Uint32Array(idx), faceOf };
}

function meshJson(m, extra = {}) {
  return {
    vertices: m.positions.length / 3,
    triangles: m.indices.length / 3,
    positions: b64(m.positions),
    indices: b64(m.indices),
    source_triangles: m.indices.length / 3,
    decimation_error: 0,
    ...extra,
  };
}

const translate = (t) => [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, t[0], t[1], t[2], 1];
const add = (a, b) => a.map((x, i) => x + b[i]);

/** The triangles of mesh `m` (placed at `offset`) whose three corners lie in the closed box [lo, hi]. */
function trianglesInside(m, offset, lo, hi, eps) {
  const out = [];
  const inside = (k) => [0, 1, 2].every((a) => {
    const x = m.positions[k * 3 + a] + offset[a];
    return x >= lo[a] - eps && x <= hi[a] + eps;
  });
  for (let t = 0; t < m.indices.length / 3; ++t) {
    const [a, b, c] = [m.indices[t * 3], m.indices[t * 3 + 1], m.indices[t * 3 + 2]];
    if (inside(a) && inside(b) && inside(c)) {
      for (const k of [a, b, c]) out.push(m.positions[k * 3] + offset[0], m.positions[k * 3 + 1] + offset[1], m.positions[k * 3 + 2] + offset[2]);
    }
  }
  return out;
}

/** A world mesh from triangle soups (flat x,y,z per corner), vertices not shared. */
function soupMesh(...soups) {
  const flat = soups.flat();
  const positions = new Float32Array(flat);
  const indices = new Uint32Array(positions.length / 3).map((_, i) => i);
  return { positions, indices };
}

/** The edges of the overlap box [lo, hi] where a face of box A meets a face of box B: the
 *  intersection curve of the two box surfaces (as 2-point polylines). */
function overlapCurves(lo, hi, aLo, aHi, eps) {
  // which box each face of the overlap box lies on: A when the bound is A's own, else B
  const faceOwner = (axis, side) => (Math.abs((side ? hi : lo)[axis] - (side ? aHi : aLo)[axis]) < eps ? 'A' : 'B');
  const curves = [];
  for (let axis = 0; axis < 3; ++axis) {
    const u = (axis + 1) % 3;
    const v = (axis + 2) % 3;
    for (const su of [0, 1]) {
      for (const sv of [0, 1]) {
        if (faceOwner(u, su) === faceOwner(v, sv)) continue;
        const p = [0, 0, 0];
        p[u] = (su ? hi : lo)[u];
        p[v] = (sv ? hi : lo)[v];
        const q = [...p];
        p[axis] = lo[axis];
        q[axis] = hi[axis];
        curves.push([...p, ...q]);
      }
    }
  }
  return curves;
}

function sampleDocument() {
  const eps = 1e-6;
  const n = 10;
  const unit2 = boxMesh([0, 0, 0], [2, 2, 2], n);  // A, B and the hidden original share it
  const unit1 = boxMesh([0, 0, 0], [1, 1, 1], 4);
  // C's faces coloured by two legend entries (x faces "planar", the others "hole")
  const faceColors = new Uint16Array(unit1.faceOf.map((f) => (f < 2 ? 0 : 1)));
  const bAt = [[3.0, 0.6, 0.4], [1.2, 0.6, 0.4], [2.6, 0.6, 0.4]];  // frame 1: overlapping A
  const cAt = [-2, 0, 0];
  const eAt = [-2, 1, 0];  // E sits on C: they share the face y = 1
  const aLo = [0, 0, 0];
  const aHi = [2, 2, 2];
  const bLo = bAt[1];
  const bHi = add(bAt[1], [2, 2, 2]);
  const oLo = aLo.map((x, i) => Math.max(x, bLo[i]));
  const oHi = aHi.map((x, i) => Math.min(x, bHi[i]));
  // the red region: A's triangles inside B and B's triangles inside A (the overlap box's surface,
  // since the overlap's bounds fall on the 0.2 grid of both boxes)
  const region = soupMesh(trianglesInside(unit2, [0, 0, 0], bLo, bHi, eps), trianglesInside(unit2, bAt[1], aLo, aHi, eps));
  const contact = soupMesh([-2, 1, 0, -1, 1, 0, -1, 1, 1, -2, 1, 0, -1, 1, 1, -2, 1, 1]);
  const center = oLo.map((x, i) => (x + oHi[i]) / 2);
  const depth = Math.min(...oLo.map((x, i) => oHi[i] - x));
  const body = (id, name, mesh, pose, extra = {}) => ({
    id, name, path: `/sample/${name}`, mesh, role: '', visible: true, tags: [], color: [0.62, 0.66, 0.72], pose, ...extra,
  });
  const doc = {
    schema: 'interfere.viewer',
    schema_version: 1,
    title: 'Sample <clash> & "quotes"',
    command: 'interfere clash a.stl b.stl --html sample.html',
    tool_version: 'test',
    units: 'mm',
    verdict: 'clash',
    notes: ['synthetic document of tests/viewer/make_sample.mjs', 'a note with </script> in it must not end the data element'],
    error: '',
    origin: [1000, -500, 250],
    legend: [{ label: 'planar face', color: [0.3, 0.7, 0.35] }, { label: 'hole', color: [0.55, 0.35, 0.8] }],
    meshes: [
      meshJson(unit2),
      meshJson(unit1, { face_colors: b64(faceColors) }),
      meshJson(region),
      meshJson(contact),
    ],
    bodies: [
      body('a', 'block A', 0, translate([0, 0, 0]), { color: [0.45, 0.6, 0.85] }),
      body('b', 'block B', 0, translate(bAt[1]), { frame_poses: bAt.map(translate), color: [0.75, 0.75, 0.5] }),
      body('c', 'part C', 1, translate(cAt)),
      body('e', 'part E', 1, translate(eAt), { color: [0.5, 0.7, 0.7] }),
      body('a0', 'block A (original)', 0, translate([0, 0, 0]), { visible: false, role: 'original' }),
    ],
    clashes: [
      {
        id: 'c1', verdict: 'clash', status: 'new', kind: 'crossing', bodies: [0, 1],
        depth, depth_bound: depth, distance: null, point: center, box: [oLo, oHi],
        curves: overlapCurves(oLo, oHi, aLo, aHi, eps), region_mesh: 2, witness: null, frames: [1],
        note: 'block B pushed into block A',
      },
      {
        id: 'c2', verdict: 'clearance', status: 'active', kind: 'clearance', bodies: [2, 0],
        depth: null, depth_bound: null, distance: 1.0, point: [-0.5, 0.5, 0.5], box: [[-1, 0, 0], [0, 1, 1]],
        curves: [], region_mesh: null, witness: [[-1, 0.5, 0.5], [0, 0.5, 0.5]], frames: [], note: '',
      },
      {
        id: 'c3', verdict: 'contact', status: 'resolved', kind: 'touching', bodies: [2, 3],
        depth: 0, depth_bound: 0, distance: 0, point: [-1.5, 1, 0.5], box: [[-2, 1, 0], [-1, 1, 1]],
        curves: [], region_mesh: 3, witness: null, frames: [], note: '',
      },
    ],
    frames: { labels: ['pose 0', 'pose 1', 'pose 2'], times: [0, 0.5, 1], verdicts: ['clear', 'clash', 'clear'] },
  };
  const expect = {
    rows: 3, clickRow: 0, redAt: center, frames: 3, marks: 1, bodies: 5, hiddenBodies: 1,
    filters: [{ verdict: 'clearance', rows: [1] }, { status: 'resolved', rows: [2] }, { verdict: 'clash', status: 'active', rows: [] }],
    absent: [{ frame: 0, rows: [0] }, { frame: 1, rows: [] }],
    play: true,
  };
  return { doc, expect };
}

/** About `triangles` display triangles: two overlapping finely split boxes and their red region,
 *  reported as decimated from 1,000,000 source triangles. */
function largeDocument(triangles) {
  // two boxes of 12 n^2 triangles each, plus the region (about 1/8 of each) -> ~ 27 n^2
  const n = Math.max(2, Math.round(Math.sqrt(triangles / 27)));
  const box = boxMesh([0, 0, 0], [2, 2, 2], n);
  const shift = [1, 1, 1].map((x) => Math.round(x * n / 2) * 2 / n);  // on the grid
  const region = soupMesh(trianglesInside(box, [0, 0, 0], shift, add(shift, [2, 2, 2]), 1e-6),
                          trianglesInside(box, shift, [0, 0, 0], [2, 2, 2], 1e-6));
  const oLo = shift;
  const oHi = [2, 2, 2];
  const center = oLo.map((x, i) => (x + oHi[i]) / 2);
  const half = 500000;
  const boxJson = meshJson(box, { source_triangles: half, decimation_error: 0.001 });
  const total = 2 * (box.indices.length / 3) + region.indices.length / 3;
  const doc = {
    schema: 'interfere.viewer', schema_version: 1, title: 'Large synthetic report', command: 'make_sample.mjs large',
    tool_version: 'test', units: 'mm', verdict: 'clash', error: '', origin: [0, 0, 0], legend: [],
    notes: [`bodies decimated for display: ${(2 * half).toLocaleString('en')} -> ${(total - region.indices.length / 3).toLocaleString('en')} triangles`],
    meshes: [boxJson, meshJson(region)],
    bodies: [
      { id: 'a', name: 'A', path: 'A', mesh: 0, role: '', visible: true, tags: [], color: [0.45, 0.6, 0.85], pose: translate([0, 0, 0]) },
      { id: 'b', name: 'B', path: 'B', mesh: 0, role: '', visible: true, tags: [], color: [0.75, 0.75, 0.5], pose: translate(shift) },
    ],
    clashes: [{
      id: 'c1', verdict: 'clash', status: '', kind: 'crossing', bodies: [0, 1], depth: 2 - shift[0], depth_bound: null,
      distance: null, point: center, box: [oLo, oHi], curves: [], region_mesh: 1, witness: null, frames: [], note: '',
    }],
    frames: { labels: [], times: [], verdicts: [] },
  };
  return { doc, expect: { rows: 1, clickRow: 0, redAt: center, frames: 0, triangles: total } };
}

function main() {
  const [templatePath, outDir, variant, ...rest] = process.argv.slice(2);
  if (!templatePath || !outDir || !variant) {
    console.error('usage: node make_sample.mjs TEMPLATE.html OUT_DIR sample|error|schema|invalid|unescaped|nodata|large [--triangles N]');
    process.exit(2);
  }
  const ti = rest.indexOf('--triangles');
  const triangles = ti >= 0 ? Number(rest[ti + 1]) : 300000;
  const template = readFileSync(templatePath, 'utf8');
  let page;
  let expect;
  if (variant === 'sample' || variant === 'large') {
    const made = variant === 'sample' ? sampleDocument() : largeDocument(triangles);
    page = inject(template, scriptSafeJson(JSON.stringify(made.doc)), made.doc.title);
    expect = made.expect;
  } else if (variant === 'error') {
    const doc = {
      schema: 'interfere.viewer', schema_version: 1, title: 'Failed report', command: 'interfere clash missing.stl b.stl',
      tool_version: 'test', units: 'mm', verdict: '', notes: [], origin: [0, 0, 0], legend: [], meshes: [], bodies: [],
      clashes: [], frames: { labels: [], times: [], verdicts: [] },
      error: 'cannot read missing.stl: no such file </script> (the report has no geometry)',
    };
    page = inject(template, scriptSafeJson(JSON.stringify(doc)), doc.title);
    expect = { expectError: true, errorText: 'cannot read missing.stl: no such file </script>' };
  } else if (variant === 'schema') {
    const { doc } = sampleDocument();
    doc.schema_version = 2;
    page = inject(template, scriptSafeJson(JSON.stringify(doc)), doc.title);
    expect = { expectError: true, errorText: 'schema_version 2' };
  } else if (variant === 'unescaped') {
    // a writer that escaped nothing: "<!--<script>" keeps the data element open to the end of the
    // page; the page must still show an error, not stay blank
    const { doc } = sampleDocument();
    doc.notes.push('x <!--<script> y');
    page = inject(template, JSON.stringify(doc), doc.title);
    expect = { expectError: true, errorText: 'not valid JSON' };
  } else if (variant === 'invalid') {
    page = inject(template, '{"schema": "interfere.viewer", "schema_version": 1, "bodies": [', 'broken');
    expect = { expectError: true, errorText: 'not valid JSON' };
  } else if (variant === 'nodata') {
    page = template;
    expect = { expectError: true, errorText: 'holds no data' };
  } else {
    console.error(`unknown variant ${variant}`);
    process.exit(2);
  }
  mkdirSync(outDir, { recursive: true });
  writeFileSync(join(outDir, `${variant}.html`), page);
  writeFileSync(join(outDir, `${variant}.expect.json`), JSON.stringify(expect, null, 1) + '\n');
  console.log(`${join(outDir, `${variant}.html`)}: ${page.length} bytes`);
}

main();
