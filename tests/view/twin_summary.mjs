// Loads a .glb of `interfere simplify` with three.js's GLTFLoader (an independent glTF reader; issue
// #29, item 6) and prints, as JSON, every object it built: its name as written (userData.name, or
// the name three.js gave it), its parent's, whether it is a mesh, its material's name and its
// triangle count, and the node's extras (the product path). tests/cli/test_simplify.py compares
// this with the STEP assembly's instances and the simplify report.
// Usage: node twin_summary.mjs FILE.glb NODE_MODULES_DIR
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';

const [file, modules] = process.argv.slice(2);
await import(pathToFileURL(join(modules, 'three/build/three.module.js')).href);
const { GLTFLoader } = await import(pathToFileURL(join(modules, 'three/examples/jsm/loaders/GLTFLoader.js')).href);

const bytes = readFileSync(file);
const buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
const nameOf = (o) => (o && o.userData && o.userData.name !== undefined ? o.userData.name : o ? o.name : null);

new GLTFLoader().parse(buffer, '', (gltf) => {
  const objects = [];
  gltf.scene.traverse((o) => {
    const index = o.geometry && o.geometry.index;
    objects.push({
      name: nameOf(o),
      parent: nameOf(o.parent),
      mesh: !!o.isMesh,
      material: o.isMesh ? o.material.name : null,
      triangles: o.isMesh ? (index ? index.count / 3 : 0) : 0,
      path: o.userData && o.userData.path !== undefined ? o.userData.path : null,
    });
  });
  process.stdout.write(JSON.stringify({ objects }) + '\n');
}, (err) => {
  process.stderr.write(String(err) + '\n');
  process.exit(1);
});
