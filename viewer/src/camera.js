// Camera placement (issue #25 item 1, "clicking a row flies the camera to it"): fitting a box, and a
// short animated flight that keeps the viewing direction and ends looking at the clash.
import * as THREE from 'three';

const FLIGHT_MS = 450;

/** Where the camera stands to see a sphere (centre, radius) from direction `dir` (unit, from target). */
export function standoff(camera, center, radius, dir) {
  const halfFov = THREE.MathUtils.degToRad(camera.fov) / 2;
  const fit = Math.min(halfFov, Math.atan(Math.tan(halfFov) * camera.aspect));
  const distance = (radius / Math.sin(fit)) * 1.15;
  return center.clone().addScaledVector(dir, distance);
}

/** The current viewing direction (target -> camera), or a default three-quarter view. */
export function viewDirection(camera, target) {
  const d = camera.position.clone().sub(target);
  if (d.lengthSq() < 1e-30) return new THREE.Vector3(1, -1.4, 1).normalize();
  return d.normalize();
}

/** A flight from the camera's pose to look at `center` from `radius`-fitting distance. */
export function makeFlight(camera, controls, center, radius, now) {
  const dir = viewDirection(camera, controls.target);
  return {
    t0: now,
    fromPos: camera.position.clone(),
    fromTarget: controls.target.clone(),
    toPos: standoff(camera, center, radius, dir),
    toTarget: center.clone(),
  };
}

/** Advances a flight; returns true once it has arrived. */
export function stepFlight(flight, camera, controls, now) {
  const t = Math.min(1, (now - flight.t0) / FLIGHT_MS);
  const s = t < 0.5 ? 4 * t * t * t : 1 - Math.pow(-2 * t + 2, 3) / 2;  // ease in-out
  camera.position.lerpVectors(flight.fromPos, flight.toPos, s);
  controls.target.lerpVectors(flight.fromTarget, flight.toTarget, s);
  camera.lookAt(controls.target);
  return t >= 1;
}

/** Near/far planes that fit the distance to the target and the scene's size. */
export function fitClipping(camera, controls, sceneRadius) {
  const d = camera.position.distanceTo(controls.target);
  camera.near = Math.max(d / 1000, sceneRadius * 1e-7);
  camera.far = d + sceneRadius * 4;
  camera.updateProjectionMatrix();
}
