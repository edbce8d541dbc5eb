// The 3D view (issue #25 item 1): WebGL renderer (preserveDrawingBuffer so that screenshots read the
// drawn frame), perspective camera, orbit controls, rendering on demand (a frame when something
// changed, not a continuous loop), and the camera flight.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { BACKGROUND_COLOR } from './colors.js';
import { addLights } from './scene.js';
import { fitClipping, makeFlight, standoff, stepFlight, viewDirection } from './camera.js';

export class View3D {
  constructor(container, scene) {
    this.container = container;
    this.scene = scene;
    scene.background = new THREE.Color(BACKGROUND_COLOR);
    // The selected clash: drawn after the scene over a cleared depth buffer.
    this.overlay = new THREE.Scene();
    this.headlights = [addLights(scene), addLights(this.overlay)];
    this.overlayRoot = new THREE.Group();
    this.overlay.add(this.overlayRoot);
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    container.append(this.renderer.domElement);
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 100);
    this.camera.up.set(0, 0, 1);  // engineering models are z-up
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener('change', () => this.requestRender());
    this.sceneRadius = 1;
    this.flight = null;
    this.pending = false;
    this.framesDrawn = 0;
    this.onFirstFrame = null;
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  resize() {
    const w = Math.max(1, this.container.clientWidth);
    const h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.requestRender();
  }

  requestRender() {
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame((now) => {
      this.pending = false;
      this.render(now);
    });
  }

  render(now) {
    if (this.flight) {
      if (stepFlight(this.flight, this.camera, this.controls, now)) this.flight = null;
      else this.requestRender();
    }
    this.controls.update();
    fitClipping(this.camera, this.controls, this.sceneRadius);
    for (const light of this.headlights) {
      // from over the viewer's shoulder (up and to the left of the camera)
      light.position.copy(this.camera.position).addScaledVector(this.camera.up, this.sceneRadius * 0.5);
      light.target.position.copy(this.controls.target);
      light.target.updateMatrixWorld();
    }
    this.renderer.render(this.scene, this.camera);
    if (this.overlayRoot.children.length) {
      this.renderer.autoClear = false;
      this.renderer.clearDepth();
      this.renderer.render(this.overlay, this.camera);
      this.renderer.autoClear = true;
    }
    ++this.framesDrawn;
    if (this.framesDrawn === 1) window.__interfereViewer.timings.rendered = performance.now();
    if (this.framesDrawn === 1 && this.onFirstFrame) {
      // The next animation frame comes after this one was composited.
      requestAnimationFrame(() => this.onFirstFrame());
    }
  }

  /** Looks at the whole box from the current direction (no animation). */
  fit(box) {
    const sphere = box.getBoundingSphere(new THREE.Sphere());
    this.sceneRadius = Math.max(sphere.radius, 1e-9);
    const dir = viewDirection(this.camera, this.controls.target);
    this.controls.target.copy(sphere.center);
    this.camera.position.copy(standoff(this.camera, sphere.center, this.sceneRadius, dir));
    this.camera.lookAt(sphere.center);
    this.requestRender();
  }

  /** Flies to a sphere (animated); `flying` is true until it arrives. */
  flyTo(center, radius) {
    this.flight = makeFlight(this.camera, this.controls, center, Math.max(radius, this.sceneRadius * 1e-4), performance.now());
    this.requestRender();
  }

  get flying() {
    return this.flight !== null;
  }

  /** Document coordinates -> CSS pixels in the page's viewport. */
  projectToScreen(p) {
    this.camera.updateMatrixWorld();
    const v = new THREE.Vector3(p[0], p[1], p[2]).project(this.camera);
    const r = this.renderer.domElement.getBoundingClientRect();
    return [r.left + ((v.x + 1) / 2) * r.width, r.top + ((1 - v.y) / 2) * r.height];
  }
}
