// Building the three.js scene from the decoded document (issue #25 item 1): bodies semi-transparent
// (face colours by legend entry when the mesh has them), clash and contact regions, intersection
// curves as thick lines, clearance witness segments. All coordinates are document coordinates
// (world minus "origin"). Geometry uses the decoded typed arrays directly.
import * as THREE from 'three';
import { LineSegments2 } from 'three/examples/jsm/lines/LineSegments2.js';
import { LineSegmentsGeometry } from 'three/examples/jsm/lines/LineSegmentsGeometry.js';
import { LineMaterial } from 'three/examples/jsm/lines/LineMaterial.js';
import {
  BODY_OPACITY, CURVE_COLOR, CURVE_OUTLINE_COLOR, WITNESS_COLOR, rgbToHex, verdictColor,
} from './colors.js';

// Triangles sorted by legend index into draw groups (one material per legend entry): keeps the
// mesh indexed, no per-vertex colours needed for per-triangle colouring.
function groupByFaceColor(geometry, indices, faceColors) {
  const counts = new Uint32Array(65536);
  let maxColor = 0;
  for (let t = 0; t < faceColors.length; ++t) {
    counts[faceColors[t]]++;
    if (faceColors[t] > maxColor) maxColor = faceColors[t];
  }
  const start = new Uint32Array(maxColor + 2);
  for (let c = 0; c <= maxColor; ++c) start[c + 1] = start[c] + counts[c];
  const sorted = new Uint32Array(indices.length);
  const next = start.slice(0, maxColor + 1);
  for (let t = 0; t < faceColors.length; ++t) {
    const o = next[faceColors[t]]++ * 3;
    sorted[o] = indices[t * 3];
    sorted[o + 1] = indices[t * 3 + 1];
    sorted[o + 2] = indices[t * 3 + 2];
  }
  for (let c = 0; c <= maxColor; ++c) {
    if (counts[c]) geometry.addGroup(start[c] * 3, counts[c] * 3, c);
  }
  return sorted;
}

function makeGeometry(mesh) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(mesh.positions, 3));
  const index = mesh.faceColors ? groupByFaceColor(g, mesh.indices, mesh.faceColors) : mesh.indices;
  g.setIndex(new THREE.BufferAttribute(index, 1));
  g.computeBoundingBox();
  g.computeBoundingSphere();
  return g;
}

function surfaceMaterial(color) {
  return new THREE.MeshLambertMaterial({ color, side: THREE.DoubleSide, flatShading: true });
}

/** Sets a body's materials translucent (ghost) or opaque (selected). */
export function setBodyOpaque(body, opaque) {
  for (const m of body.materials) {
    m.transparent = !opaque;
    m.opacity = opaque ? 1 : BODY_OPACITY;
    m.depthWrite = opaque;
    // one pass for both sides (three's default draws a transparent double-sided mesh twice, back
    // faces then front faces, with a shader program each): half the work for large bodies
    m.forceSinglePass = true;
    m.needsUpdate = true;
  }
  body.object.renderOrder = opaque ? 0 : 1;
}

function makeBody(doc, b, k, geometryOf) {
  const mesh = doc.meshes[b.mesh];
  let materials;
  if (mesh.faceColors) {
    materials = doc.legend.map((e) => surfaceMaterial(rgbToHex(e.color)));
  } else {
    materials = [surfaceMaterial(rgbToHex(b.color))];
  }
  const object = new THREE.Mesh(geometryOf(b.mesh), mesh.faceColors ? materials : materials[0]);
  object.name = b.name;
  object.matrixAutoUpdate = false;
  object.userData.body = k;
  const body = { index: k, object, materials, mesh: b.mesh, hasFaceColors: !!mesh.faceColors };
  setBodyOpaque(body, false);
  object.visible = b.visible;
  return body;
}

function lineMaterial(color, width) {
  return new LineMaterial({ color, linewidth: width, worldUnits: false });
}

// Segments (flat x,y,z pairs) as a thick line, drawn twice: a dark outline under the colour.
function thickSegments(segments, color, width, outlineColor) {
  const group = new THREE.Group();
  const geometry = new LineSegmentsGeometry();
  geometry.setPositions(segments);
  const layers = outlineColor === null
    ? [[color, width]]
    : [[outlineColor, width + 3], [color, width]];
  layers.forEach(([c, w], i) => {
    const line = new LineSegments2(geometry, lineMaterial(c, w));
    line.computeLineDistances();
    line.renderOrder = 2 + i;
    group.add(line);
  });
  return group;
}

function polylineSegments(curves) {
  let n = 0;
  for (const p of curves) n += Math.max(0, p.length / 3 - 1);
  const out = new Float32Array(n * 6);
  let o = 0;
  for (const p of curves) {
    for (let i = 0; i + 3 < p.length; i += 3) {
      for (let j = 0; j < 6; ++j) out[o++] = p[i + j];
    }
  }
  return out;
}

function makeClash(doc, c, geometryOf) {
  const group = new THREE.Group();
  group.name = `clash ${c.id}`;
  const color = verdictColor(c.verdict);
  const parts = { region: null, curves: null, witness: null, box: null };
  if (c.regionMesh !== null && doc.meshes[c.regionMesh].triangles > 0) {
    const material = surfaceMaterial(color);
    // Regions lie on the bodies' surfaces: pull them forward in depth.
    material.polygonOffset = true;
    material.polygonOffsetFactor = -2;
    material.polygonOffsetUnits = -2;
    parts.region = new THREE.Mesh(geometryOf(c.regionMesh), material);
    group.add(parts.region);
  }
  const segments = polylineSegments(c.curves);
  if (segments.length) {
    parts.curves = thickSegments(segments, CURVE_COLOR, 3, CURVE_OUTLINE_COLOR);
    group.add(parts.curves);
  }
  if (c.witness) {
    const [a, b] = c.witness;
    const w = new THREE.Group();
    w.add(thickSegments(new Float32Array([...a, ...b]), WITNESS_COLOR, 3, null));
    const ends = new THREE.BufferGeometry();
    ends.setAttribute('position', new THREE.BufferAttribute(new Float32Array([...a, ...b]), 3));
    w.add(new THREE.Points(ends, new THREE.PointsMaterial({ color: WITNESS_COLOR, size: 9, sizeAttenuation: false })));
    parts.witness = w;
    group.add(w);
  }
  if (c.box) {
    const box = new THREE.Box3(new THREE.Vector3(...c.box[0]), new THREE.Vector3(...c.box[1]));
    parts.box = new THREE.Box3Helper(box, color);
    parts.box.visible = false;  // shown for the selected clash only
    group.add(parts.box);
  }
  return { index: c.index, group, parts };
}

/** Moves the selected clash into the overlay scene, drawn after a depth clear: its bodies are
 *  opaque and would hide the region (which lies on and inside their surfaces). */
export function setClashOnTop(built, clash, overlay, onTop) {
  (onTop ? overlay : built.clashRoot).add(clash.group);
  // curves and witness segments over the region (they lie on its edges)
  for (const part of [clash.parts.curves, clash.parts.witness]) {
    part?.traverse((o) => {
      if (!o.material) return;
      o.material.depthTest = !onTop;
      o.renderOrder = (o.renderOrder % 10) + (onTop ? 10 : 0);
    });
  }
  if (clash.parts.box) clash.parts.box.visible = onTop;
}

/** Lights for a scene: a sky/ground fill (z up) and a headlight that follows the camera. */
export function addLights(scene) {
  const fill = new THREE.HemisphereLight(0xffffff, 0x8a9099, 1.3);
  fill.position.set(0, 0, 1);
  scene.add(fill);
  const head = new THREE.DirectionalLight(0xffffff, 1.9);
  scene.add(head);
  scene.add(head.target);
  return head;
}

/** The scene for a decoded document: { scene, bodies, clashes, bounds }. */
export function buildScene(doc) {
  const scene = new THREE.Scene();

  const geometries = new Map();
  const geometryOf = (k) => {
    if (!geometries.has(k)) geometries.set(k, makeGeometry(doc.meshes[k]));
    return geometries.get(k);
  };
  const bodies = doc.bodies.map((b, k) => makeBody(doc, b, k, geometryOf));
  const bodyRoot = new THREE.Group();
  bodyRoot.name = 'bodies';
  for (const b of bodies) bodyRoot.add(b.object);
  scene.add(bodyRoot);
  const clashes = doc.clashes.map((c) => makeClash(doc, c, geometryOf));
  const clashRoot = new THREE.Group();
  clashRoot.name = 'clashes';
  for (const c of clashes) clashRoot.add(c.group);
  scene.add(clashRoot);
  return { scene, bodies, clashes, clashRoot, geometryOf };
}

/** Places the bodies for frame k (-1: the static pose) and returns the scene's bounds. */
export function poseBodies(doc, built, k) {
  const m = new THREE.Matrix4();
  for (const body of built.bodies) {
    const b = doc.bodies[body.index];
    const pose = k >= 0 && b.framePoses.length ? b.framePoses[k] : b.pose;
    if (pose) m.fromArray(pose); else m.identity();
    body.object.matrix.copy(m);
    body.object.matrixWorldNeedsUpdate = true;
    const meshIndex = k >= 0 && b.frameMeshes.length ? b.frameMeshes[k] : b.mesh;
    if (meshIndex !== body.mesh) {
      body.mesh = meshIndex;
      body.object.geometry = built.geometryOf(meshIndex);
    }
  }
}

/** Bounds of the visible bodies and clash geometry (document coordinates). */
export function sceneBounds(built) {
  const box = new THREE.Box3();
  built.scene.updateMatrixWorld(true);
  for (const body of built.bodies) {
    const g = body.object.geometry;
    if (!g.boundingBox || g.boundingBox.isEmpty()) continue;
    box.union(g.boundingBox.clone().applyMatrix4(body.object.matrixWorld));
  }
  for (const c of built.clashes) {
    if (c.parts.region) box.union(c.parts.region.geometry.boundingBox);
  }
  if (box.isEmpty()) box.set(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
  return box;
}
