// GPU warm-up (issue #25, "first frame in <= 3 s"): in a freshly started browser the first WebGL
// context waits for the GPU process to start (0.4-1.3 s with SwiftShader on a 2-core machine). A
// worker asks for a throwaway OffscreenCanvas context as soon as the page's script runs, so that the
// GPU process starts while the main thread still parses and decodes the embedded data. Best effort:
// without Worker/OffscreenCanvas nothing happens.
export function warmUpGpu() {
  try {
    if (typeof Worker !== 'function' || typeof OffscreenCanvas !== 'function') return;
    const source = "try { new OffscreenCanvas(1, 1).getContext('webgl2'); } catch (e) {} postMessage(0);";
    const url = URL.createObjectURL(new Blob([source], { type: 'text/javascript' }));
    const worker = new Worker(url);
    const done = () => {
      worker.terminate();
      URL.revokeObjectURL(url);
    };
    worker.onmessage = done;
    worker.onerror = (e) => {
      e.preventDefault();
      done();
    };
  } catch (e) {
    // no warm-up: the first frame just comes later
  }
}
