// Reading the document embedded in the page (issue #25 viewer contract; docs/viewer.md "Embedded data"):
// JSON of schema "interfere.viewer", schema_version 1, inside <script id="interfere-data">. Meshes are
// base64 of little-endian arrays, decoded straight into typed arrays (no per-vertex objects) so that a
// 300k-triangle document opens quickly. Every problem is a DocumentError whose message names the field.

export const SCHEMA = 'interfere.viewer';
export const SCHEMA_VERSION = 1;

export class DocumentError extends Error {
  /** @param doc the parsed document when the header can still be shown (error reports) */
  constructor(message, doc = null) {
    super(message);
    this.doc = doc;
  }
}

/** The text of the data element; throws when the page holds no data. */
export function readEmbeddedText(dom) {
  const node = dom.getElementById('interfere-data');
  if (!node) throw new DocumentError('this page holds no data: it has no data element (id "interfere-data")');
  const text = node.textContent.trim();
  if (text === '') throw new DocumentError('this page holds no data: its data element is empty');
  // JSON never starts with a comment: this is the template's placeholder, never replaced.
  if (text.startsWith('/*')) {
    throw new DocumentError('this page holds no data: it is the viewer template, its data placeholder was never replaced');
  }
  return text;
}

const LITTLE_ENDIAN = new Uint8Array(new Uint16Array([1]).buffer)[0] === 1;

function fail(message, doc) {
  throw new DocumentError(message, doc);
}

function decodeBase64(text, field) {
  if (typeof text !== 'string') fail(`${field}: expected a base64 string`);
  try {
    if (typeof Uint8Array.fromBase64 === 'function') return Uint8Array.fromBase64(text);
    const bin = atob(text);
    const out = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; ++i) out[i] = bin.charCodeAt(i);
    return out;
  } catch (e) {
    return fail(`${field}: not valid base64 (${e.message})`);
  }
}

// A typed array of `count` elements of `Type` from base64 little-endian bytes.
function decodeArray(text, Type, count, field) {
  const bytes = decodeBase64(text, field);
  const expected = count * Type.BYTES_PER_ELEMENT;
  if (bytes.length !== expected) {
    fail(`${field}: ${bytes.length} bytes, expected ${expected} (${count} values of ${Type.BYTES_PER_ELEMENT} bytes)`);
  }
  if (LITTLE_ENDIAN || Type.BYTES_PER_ELEMENT === 1) return new Type(bytes.buffer, bytes.byteOffset, count);
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.length);
  const out = new Type(count);
  const get = { 2: 'getUint16', 4: Type === Float32Array ? 'getFloat32' : 'getUint32' }[Type.BYTES_PER_ELEMENT];
  for (let i = 0; i < count; ++i) out[i] = view[get](i * Type.BYTES_PER_ELEMENT, true);
  return out;
}

function isCount(v) {
  return Number.isInteger(v) && v >= 0;
}

function checkVec3(v, field) {
  if (!Array.isArray(v) || v.length !== 3 || !v.every(Number.isFinite)) fail(`${field}: expected [x, y, z] numbers`);
  return v;
}

function checkMatrix(m, field) {
  if (!Array.isArray(m) || m.length !== 16 || !m.every(Number.isFinite)) {
    fail(`${field}: expected 16 numbers (a column-major 4x4 matrix)`);
  }
  return m;
}

function checkIndex(i, n, field, what) {
  if (!Number.isInteger(i) || i < 0 || i >= n) fail(`${field}: ${i} is not a ${what} index (there are ${n})`);
  return i;
}

function optNumber(v, field) {
  if (v === null || v === undefined) return null;
  if (!Number.isFinite(v)) fail(`${field}: expected a number or null`);
  return v;
}

function strings(v, field) {
  if (v === undefined || v === null) return [];
  if (!Array.isArray(v) || !v.every((s) => typeof s === 'string')) fail(`${field}: expected an array of strings`);
  return v;
}

function decodeMesh(m, k, legendCount) {
  const f = `meshes[${k}]`;
  if (!m || typeof m !== 'object') fail(`${f}: expected an object`);
  if (!isCount(m.vertices)) fail(`${f}.vertices: expected a count`);
  if (!isCount(m.triangles)) fail(`${f}.triangles: expected a count`);
  const positions = decodeArray(m.positions, Float32Array, m.vertices * 3, `${f}.positions`);
  const indices = decodeArray(m.indices, Uint32Array, m.triangles * 3, `${f}.indices`);
  for (let i = 0; i < indices.length; ++i) {
    if (indices[i] >= m.vertices) {
      fail(`${f}.indices: triangle ${Math.floor(i / 3)} uses vertex ${indices[i]}, the mesh has ${m.vertices}`);
    }
  }
  let faceColors = null;
  if (m.face_colors !== undefined && m.face_colors !== null && m.face_colors !== '') {
    faceColors = decodeArray(m.face_colors, Uint16Array, m.triangles, `${f}.face_colors`);
    for (let t = 0; t < faceColors.length; ++t) {
      if (faceColors[t] >= legendCount) {
        fail(`${f}.face_colors: triangle ${t} has legend index ${faceColors[t]}, the legend has ${legendCount} entries`);
      }
    }
  }
  let clashFlags = null;
  if (m.clash_flags !== undefined && m.clash_flags !== null && m.clash_flags !== '') {
    clashFlags = decodeArray(m.clash_flags, Uint8Array, m.triangles, `${f}.clash_flags`);
  }
  return {
    vertices: m.vertices,
    triangles: m.triangles,
    positions,
    indices,
    faceColors,
    clashFlags,
    sourceTriangles: isCount(m.source_triangles) ? m.source_triangles : m.triangles,
    decimationError: Number.isFinite(m.decimation_error) ? m.decimation_error : 0,
  };
}

function decodeBody(b, k, meshCount, frameCount) {
  const f = `bodies[${k}]`;
  if (!b || typeof b !== 'object') fail(`${f}: expected an object`);
  const framePoses = b.frame_poses ?? [];
  const frameMeshes = b.frame_meshes ?? [];
  if (!Array.isArray(framePoses)) fail(`${f}.frame_poses: expected an array`);
  if (!Array.isArray(frameMeshes)) fail(`${f}.frame_meshes: expected an array`);
  if (framePoses.length && framePoses.length !== frameCount) {
    fail(`${f}.frame_poses: ${framePoses.length} poses, the document has ${frameCount} frames`);
  }
  if (frameMeshes.length && frameMeshes.length !== frameCount) {
    fail(`${f}.frame_meshes: ${frameMeshes.length} meshes, the document has ${frameCount} frames`);
  }
  return {
    id: String(b.id ?? k),
    name: String(b.name ?? b.id ?? `body ${k}`),
    path: String(b.path ?? ''),
    role: String(b.role ?? ''),
    mesh: checkIndex(b.mesh, meshCount, `${f}.mesh`, 'mesh'),
    visible: b.visible !== false,
    tags: strings(b.tags, `${f}.tags`),
    color: b.color === undefined ? [0.62, 0.66, 0.72] : checkVec3(b.color, `${f}.color`),
    pose: b.pose === undefined ? null : checkMatrix(b.pose, `${f}.pose`),
    framePoses: framePoses.map((p, i) => checkMatrix(p, `${f}.frame_poses[${i}]`)),
    frameMeshes: frameMeshes.map((m, i) => checkIndex(m, meshCount, `${f}.frame_meshes[${i}]`, 'mesh')),
  };
}

function decodeClash(c, k, bodyCount, meshCount, frameCount) {
  const f = `clashes[${k}]`;
  if (!c || typeof c !== 'object') fail(`${f}: expected an object`);
  if (!Array.isArray(c.bodies) || c.bodies.length !== 2) fail(`${f}.bodies: expected [a, b] body indices`);
  const bodies = c.bodies.map((b, i) => checkIndex(b, bodyCount, `${f}.bodies[${i}]`, 'body'));
  const box = c.box ?? null;
  if (box !== null && (!Array.isArray(box) || box.length !== 2)) fail(`${f}.box: expected [[min], [max]]`);
  const curves = c.curves ?? [];
  if (!Array.isArray(curves)) fail(`${f}.curves: expected an array of flat polylines`);
  curves.forEach((p, i) => {
    if (!Array.isArray(p) || p.length % 3 !== 0 || !p.every(Number.isFinite)) {
      fail(`${f}.curves[${i}]: expected a flat array of x, y, z numbers`);
    }
  });
  const witness = c.witness ?? null;
  if (witness !== null && (!Array.isArray(witness) || witness.length !== 2)) fail(`${f}.witness: expected [[a], [b]] or null`);
  const frames = c.frames ?? [];
  if (!Array.isArray(frames)) fail(`${f}.frames: expected an array of frame indices`);
  const regionMesh = c.region_mesh ?? null;
  return {
    index: k,
    id: String(c.id ?? k),
    verdict: String(c.verdict ?? 'undecided'),
    status: String(c.status ?? ''),
    kind: String(c.kind ?? ''),
    bodies,
    depth: optNumber(c.depth, `${f}.depth`),
    depthBound: optNumber(c.depth_bound, `${f}.depth_bound`),
    distance: optNumber(c.distance, `${f}.distance`),
    point: c.point === undefined || c.point === null ? null : checkVec3(c.point, `${f}.point`),
    box: box && [checkVec3(box[0], `${f}.box[0]`), checkVec3(box[1], `${f}.box[1]`)],
    curves,
    regionMesh: regionMesh === null || regionMesh < 0 ? null : checkIndex(regionMesh, meshCount, `${f}.region_mesh`, 'mesh'),
    witness: witness && [checkVec3(witness[0], `${f}.witness[0]`), checkVec3(witness[1], `${f}.witness[1]`)],
    frames: frames.map((i, j) => checkIndex(i, frameCount, `${f}.frames[${j}]`, 'frame')),
    note: String(c.note ?? ''),
  };
}

/** Parses and checks the document; returns the decoded model the page draws. */
export function parseDocument(text) {
  let raw;
  try {
    raw = JSON.parse(text);
  } catch (e) {
    return fail(`the embedded data is not valid JSON: ${e.message}`);
  }
  if (!raw || typeof raw !== 'object' || Array.isArray(raw)) fail('the embedded data is not a JSON object');
  if (raw.schema !== SCHEMA) {
    fail(`the embedded data is of schema ${JSON.stringify(raw.schema ?? null)}; this viewer reads "${SCHEMA}"`);
  }
  if (raw.schema_version !== SCHEMA_VERSION) {
    fail(`the embedded data is of ${SCHEMA} schema_version ${JSON.stringify(raw.schema_version ?? null)}; ` +
         `this viewer reads version ${SCHEMA_VERSION} (write the page again with a matching interfere)`);
  }
  const header = {
    title: String(raw.title ?? ''),
    command: String(raw.command ?? ''),
    toolVersion: String(raw.tool_version ?? ''),
    units: String(raw.units ?? ''),
    verdict: String(raw.verdict ?? ''),
    notes: strings(raw.notes, 'notes'),
  };
  if (typeof raw.error === 'string' && raw.error !== '') fail(raw.error, header);
  if (raw.error !== undefined && typeof raw.error !== 'string') fail('error: expected a string', header);

  const origin = raw.origin === undefined ? [0, 0, 0] : checkVec3(raw.origin, 'origin');
  const legend = raw.legend ?? [];
  if (!Array.isArray(legend)) fail('legend: expected an array');
  legend.forEach((e, i) => {
    if (!e || typeof e.label !== 'string') fail(`legend[${i}].label: expected a string`);
    checkVec3(e.color, `legend[${i}].color`);
  });

  const frameData = raw.frames ?? {};
  const labels = strings(frameData.labels, 'frames.labels');
  const frames = {
    labels,
    times: Array.isArray(frameData.times) ? frameData.times : [],
    verdicts: strings(frameData.verdicts, 'frames.verdicts'),
  };
  const frameCount = labels.length;

  for (const key of ['meshes', 'bodies', 'clashes']) {
    if (raw[key] !== undefined && !Array.isArray(raw[key])) fail(`${key}: expected an array`);
  }
  const meshes = (raw.meshes ?? []).map((m, k) => decodeMesh(m, k, legend.length));
  const bodies = (raw.bodies ?? []).map((b, k) => decodeBody(b, k, meshes.length, frameCount));
  const clashes = (raw.clashes ?? []).map((c, k) => decodeClash(c, k, bodies.length, meshes.length, frameCount));
  return { ...header, origin, legend, frames, frameCount, meshes, bodies, clashes };
}
