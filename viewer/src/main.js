// The interfere clash viewer page (issue #25 item 1; docs/viewer.md): reads the embedded document,
// builds the 3D view, clash list, bodies, legend and time slider, and exposes
// window.__interfereViewer for browser tests. Any failure shows its text in the page and sets
// document.body.dataset.ready = "error": never a blank page.
import * as THREE from 'three';
import { DocumentError, parseDocument, readEmbeddedText } from './data.js';
import { buildScene, poseBodies, sceneBounds, setBodyOpaque, setClashOnTop } from './scene.js';
import { View3D } from './view3d.js';
import { buildClashList, showClashDetails } from './clash_list.js';
import { buildBodiesPanel } from './bodies_panel.js';
import { buildTimeline } from './timeline.js';
import { buildHeader, buildLegend, buildNotes } from './header.js';
import { el } from './format.js';
import { warmUpGpu } from './warmup.js';

warmUpGpu();

const api = {
  ready: false,
  error: null,
  clashCount: 0,
  frameCount: 0,
  frame: -1,
  selected: -1,
  camera: null,
  flying: false,
  readyMs: null,
  selectClash: () => {},
  setFrame: () => {},
  projectToScreen: () => [NaN, NaN],
};
window.__interfereViewer = api;
api.timings = { bundle: performance.now() };

const $ = (id) => document.getElementById(id);

function showError(message, header) {
  if (document.body.dataset.ready === 'error') return;
  api.ready = false;
  api.error = message;
  if (header) buildHeader($('header'), header);
  document.body.classList.add('has-error');
  // data that ended its element early leaves its rest as stray page content
  const data = $('interfere-data');
  while (data && data.nextSibling) data.nextSibling.remove();
  const box = $('error');
  box.replaceChildren(el('h2', null, 'This report cannot be shown'), el('pre', null, message));
  box.hidden = false;
  document.body.dataset.ready = 'error';
}

function start(doc) {
  buildHeader($('header'), doc);
  document.title = doc.title || document.title;
  const t = api.timings;
  const built = buildScene(doc);
  t.scene = performance.now();
  let view;
  try {
    view = new View3D($('view'), built.scene);
    t.renderer = performance.now();
  } catch (e) {
    throw new DocumentError(`WebGL is not available in this browser, the 3D view cannot be drawn (${e.message})`, doc);
  }
  api.camera = view.camera;
  Object.defineProperty(api, 'flying', { get: () => view.flying });

  let frame = doc.frameCount > 0 ? 0 : -1;
  let selected = -1;

  const clashPresent = (c) => frame < 0 || c.frames.length === 0 || c.frames.includes(frame);
  const updateClashVisibility = () => {
    for (const c of built.clashes) c.group.visible = clashPresent(doc.clashes[c.index]);
  };

  const list = buildClashList($('clash-list'), doc, (i) => selectClash(i));
  buildBodiesPanel($('body-panel'), doc, (i, on) => {
    built.bodies[i].object.visible = on;
    view.requestRender();
  });
  buildLegend($('legend'), doc);
  buildNotes($('notes'), doc.notes);

  let timeline = null;
  const setFrame = (k) => {
    if (doc.frameCount === 0) return;
    frame = Math.max(0, Math.min(doc.frameCount - 1, Math.trunc(k)));
    api.frame = frame;
    poseBodies(doc, built, frame);
    updateClashVisibility();
    list.setFrame(frame);
    timeline.show(frame);
    view.requestRender();
  };
  if (doc.frameCount > 0) timeline = buildTimeline($('timeline'), doc.frames, (k) => setFrame(k));

  function selectClash(i) {
    if (!Number.isInteger(i) || i < -1 || i >= doc.clashes.length) return;
    if (selected >= 0) {
      setClashOnTop(built, built.clashes[selected], view.overlayRoot, false);
      for (const b of doc.clashes[selected].bodies) setBodyOpaque(built.bodies[b], false);
    }
    selected = i;
    api.selected = i;
    list.select(i);
    showClashDetails($('details'), doc, i >= 0 ? doc.clashes[i] : null);
    if (i < 0) return view.requestRender();
    const c = doc.clashes[i];
    if (frame >= 0 && c.frames.length && !c.frames.includes(frame)) setFrame(c.frames[0]);
    for (const b of c.bodies) {
      setBodyOpaque(built.bodies[b], true);
      built.bodies[b].object.visible = true;
      const box = document.querySelector(`#body-list input[data-index="${b}"]`);
      if (box) box.checked = true;
    }
    setClashOnTop(built, built.clashes[i], view.overlayRoot, true);
    // Fly to the clash's box (or its point, sized by its region or a bit of the scene).
    let center;
    let radius;
    if (c.box) {
      const box = new THREE.Box3(new THREE.Vector3(...c.box[0]), new THREE.Vector3(...c.box[1]));
      const s = box.getBoundingSphere(new THREE.Sphere());
      center = c.point ? new THREE.Vector3(...c.point) : s.center;
      radius = s.radius + (c.point ? center.distanceTo(s.center) : 0);
    } else if (c.point) {
      center = new THREE.Vector3(...c.point);
      radius = 0;
    } else {
      const region = built.clashes[i].parts.region;
      const s = region ? region.geometry.boundingSphere : new THREE.Sphere(new THREE.Vector3(), view.sceneRadius);
      center = s.center.clone();
      radius = s.radius;
    }
    view.flyTo(center, Math.max(radius * 1.6, view.sceneRadius * 0.05));
  }

  // fit every frame's bodies, not only the static poses
  poseBodies(doc, built, -1);
  const bounds = sceneBounds(built);
  for (let k = 0; k < doc.frameCount; ++k) {
    poseBodies(doc, built, k);
    bounds.union(sceneBounds(built));
  }
  view.fit(bounds);
  if (frame >= 0) setFrame(frame);
  updateClashVisibility();
  showClashDetails($('details'), doc, null);

  Object.assign(api, {
    clashCount: doc.clashes.length,
    frameCount: doc.frameCount,
    frame,
    selectClash,
    setFrame,
    projectToScreen: (p) => view.projectToScreen(p),
    view,
  });
  view.onFirstFrame = () => {
    api.ready = true;
    api.readyMs = performance.now();
    document.body.dataset.ready = '1';
  };
  view.requestRender();
}

window.addEventListener('error', (e) => {
  if (!api.ready) showError(`the viewer failed: ${e.message}`);
});

// The page's script comes before the data element and runs once the document is parsed: data that
// ends its element early or never (a writer that did not escape "</" or "<!--") still gets the error
// page instead of a blank one.
function run() {
  try {
    api.timings.script = performance.now();
    const doc = parseDocument(readEmbeddedText(document));
    api.timings.decoded = performance.now();
    start(doc);
    api.timings.built = performance.now();
  } catch (e) {
    if (e instanceof DocumentError) showError(e.message, e.doc);
    else showError(`the viewer failed: ${e && e.stack ? e.stack : e}`);
  }
}

if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', run);
else run();
