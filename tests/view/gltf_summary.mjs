// Loads a .glb with three.js's GLTFLoader (an independent glTF reader; issue #25, item 2) and prints
// what it built as JSON, for tests/view/check_gltf.py to compare with the document:
//   objects: every object's type, original name (userData.name), parent, extras, material;
//   boxes: per body (a child of the "bodies" group) its world box in metres, over the meshes it
//   shows (a node scaled to 0 shows nothing), in the static view and at each key time of the
//   first animation (played by an AnimationMixer), with each clash node's world scale (0: hidden).
// Usage: node gltf_summary.mjs FILE.glb NODE_MODULES_DIR
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';

const [file, modules] = process.argv.slice(2);
const THREE = await import(pathToFileURL(join(modules, 'three/build/three.module.js')).href);
const { GLTFLoader } = await import(pathToFileURL(join(modules, 'three/examples/jsm/loaders/GLTFLoader.js')).href);

const bytes = readFileSync(file);
const buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);

function originalName(o) {
  return o.userData && o.userData.name !== undefined ? o.userData.name : o.name;
}

function groupChildren(scene, group) {
  const g = scene.getObjectByName(group);
  return g ? g.children : [];
}

function worldBox(object) {
  const box = new THREE.Box3();
  const v = new THREE.Vector3();
  object.traverse((o) => {
    if (!(o.isMesh || o.isLine) || !o.geometry) return;
    if (Math.abs(o.matrixWorld.determinant()) < 1e-30) return;  // scaled to nothing: hidden
    const p = o.geometry.attributes.position;
    for (let i = 0; i < p.count; ++i) box.expandByPoint(v.fromBufferAttribute(p, i).applyMatrix4(o.matrixWorld));
  });
  return box.isEmpty() ? null : [box.min.toArray(), box.max.toArray()];
}

function state(scene) {
  scene.updateMatrixWorld(true);
  const boxes = {};
  for (const b of groupChildren(scene, 'bodies')) boxes[b.userData.id] = worldBox(b);
  const clashScale = {};
  // (the length of the world matrix's first column: Matrix4.decompose is not meant for scale 0)
  for (const c of groupChildren(scene, 'clashes'))
    clashScale[c.userData.clash_id] = new THREE.Vector3().setFromMatrixColumn(c.matrixWorld, 0).length();
  return { boxes, clashScale };
}

new GLTFLoader().parse(buffer, '', (gltf) => {
  const scene = gltf.scene;
  const objects = [];
  scene.traverse((o) => {
    const entry = { type: o.type, name: originalName(o), parent: o.parent ? originalName(o.parent) : null, userData: o.userData };
    if (o.material) {
      const m = o.material;
      entry.material = { type: m.type, name: m.name, color: m.color ? m.color.getHexString() : null, opacity: m.opacity,
                         transparent: m.transparent, vertexColors: m.vertexColors, side: m.side };
      entry.vertices = o.geometry.attributes.position.count;
      entry.indices = o.geometry.index ? o.geometry.index.count : null;
      entry.hasColor = !!o.geometry.attributes.color;
    }
    objects.push(entry);
  });
  const summary = { sceneExtras: scene.userData, objects, static: state(scene), animations: [], frames: [] };
  for (const clip of gltf.animations)
    summary.animations.push({ name: clip.name, duration: clip.duration, tracks: clip.tracks.map((t) => t.name),
                              times: clip.tracks.length ? Array.from(clip.tracks[0].times) : [] });
  if (gltf.animations.length) {
    const clip = gltf.animations[0];
    const mixer = new THREE.AnimationMixer(scene);
    const action = mixer.clipAction(clip);
    action.setLoop(THREE.LoopOnce, 1);
    action.clampWhenFinished = true;
    action.play();
    for (const t of summary.animations[0].times) {
      mixer.setTime(Math.min(t + 1e-4, clip.duration));
      summary.frames.push({ time: t, ...state(scene) });
    }
  }
  process.stdout.write(JSON.stringify(summary));
}, (error) => {
  console.error('GLTFLoader error:', error && error.message ? error.message : error);
  process.exit(1);
});
