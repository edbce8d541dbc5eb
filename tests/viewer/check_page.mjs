// Browser test of a viewer page (issue #25 item 4): Debian's Chromium, headless, driven by
// puppeteer-core (no browser download), WebGL through SwiftShader.
//   node check_page.mjs PAGE.html EXPECT.json [--screenshot OUT.png] [--timeout MS]
// EXPECT.json: { rows, clickRow, redAt: [x,y,z] (document coordinates), frames, marks, bodies,
//   hiddenBodies, filters: [{verdict, status, rows}], absent: [{frame, rows}], play, expectError, errorText,
//   screenshot, maxReadyMs }  (every key optional).
// Checks: the page loads with no console error, page error or request beyond the page itself; it
// becomes ready (dataset.ready "1", or "error" showing errorText when expectError); the clash list
// has `rows` rows; clicking row `clickRow` moves the camera; then the screenshot pixel where `redAt`
// projects (or one within 3 px) is red-dominant while the view's corner is not. Prints a JSON
// result; exits 1 on failure, 2 on bad usage.
// puppeteer-core comes from INTERFERE_VIEWER_NODE_MODULES (default: viewer/node_modules).
import { createRequire } from 'node:module';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { decodePng, pixel } from './png.mjs';

const here = dirname(fileURLToPath(import.meta.url));

function usage() {
  console.error('usage: node check_page.mjs PAGE.html EXPECT.json [--screenshot OUT.png] [--timeout MS]');
  process.exit(2);
}

const args = process.argv.slice(2);
const positional = [];
const opts = {};
for (let i = 0; i < args.length; ++i) {
  if (args[i].startsWith('--')) opts[args[i].slice(2)] = args[++i];
  else positional.push(args[i]);
}
if (positional.length !== 2) usage();
const pagePath = resolve(positional[0]);
const expect = JSON.parse(readFileSync(positional[1], 'utf8'));
const screenshotPath = opts.screenshot ?? expect.screenshot ?? null;
const timeoutMs = Number(opts.timeout ?? expect.timeoutMs ?? 30000);
const nodeModules = process.env.INTERFERE_VIEWER_NODE_MODULES || join(here, '../../viewer/node_modules');
const chromium = process.env.INTERFERE_CHROMIUM || '/usr/bin/chromium';

const require = createRequire(join(resolve(nodeModules), 'noop.js'));
const puppeteer = require('puppeteer-core');

/** Red-dominant: the clash colour (#e02020) under any lighting, not grey, orange or a body tint. */
export function isRed([r, g, b]) {
  return r >= 90 && r >= 1.8 * g && r >= 1.8 * b;
}

const result = { page: pagePath, ok: false, failures: [], consoleErrors: [], consoleWarnings: [], requests: [] };
const failIf = (cond, message) => {
  if (cond) result.failures.push(message);
};

const userDataDir = mkdtempSync(join(tmpdir(), 'interfere-chromium-'));
let browser;
try {
  browser = await puppeteer.launch({
    executablePath: chromium,
    headless: true,
    userDataDir,
    args: [
      '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
      '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run',
      '--disable-quic', '--disable-default-apps', '--disable-extensions', '--disable-dev-shm-usage',
      '--window-size=1280,800',
    ],
    defaultViewport: { width: 1280, height: 800, deviceScaleFactor: 1 },
  });
  const page = await browser.newPage();
  const pageUrl = pathToFileURL(pagePath).href;
  page.on('console', (m) => {
    if (m.type() === 'error') result.consoleErrors.push(m.text());
    else if (m.type() === 'warn' || m.type() === 'warning') result.consoleWarnings.push(m.text());
  });
  page.on('pageerror', (e) => result.consoleErrors.push(`page error: ${e.message}`));
  page.on('request', (r) => {
    if (r.url() !== pageUrl && !r.url().startsWith('data:') && !r.url().startsWith('blob:')) result.requests.push(r.url());
  });
  page.on('requestfailed', (r) => result.requests.push(`failed: ${r.url()} ${r.failure()?.errorText ?? ''}`));

  const t0 = Date.now();
  await page.goto(pageUrl, { waitUntil: 'load', timeout: timeoutMs });
  await page.waitForFunction(() => ['1', 'error'].includes(document.body.dataset.ready), { timeout: timeoutMs, polling: 20 });
  result.wallMs = Date.now() - t0;
  const state = await page.evaluate(() => {
    const v = window.__interfereViewer;
    const box = document.getElementById('error');
    return {
      ready: document.body.dataset.ready,
      error: v ? v.error : 'window.__interfereViewer missing',
      errorShown: box && !box.hidden ? box.innerText : '',
      readyMs: v ? v.readyMs : null,
      timings: v && v.timings ? Object.fromEntries(Object.entries(v.timings).map(([k, x]) => [k, Math.round(x)])) : null,
      clashCount: v ? v.clashCount : null,
      frameCount: v ? v.frameCount : null,
      rows: document.querySelectorAll('#clash-table tbody tr').length,
      marks: document.querySelectorAll('#timeline .mark').length,
      slider: document.getElementById('frame-slider') ? Number(document.getElementById('frame-slider').max) + 1 : 0,
      bodies: document.querySelectorAll('#body-list input').length,
      hiddenBodies: document.querySelectorAll('#body-list input:not(:checked)').length,
      title: document.title,
      htmlBytes: document.documentElement.outerHTML.length,
    };
  });
  Object.assign(result, { ready: state.ready, readyMs: state.readyMs && Math.round(state.readyMs), timings: state.timings, error: state.error });

  if (expect.expectError) {
    failIf(state.ready !== 'error', `expected the error page, dataset.ready is "${state.ready}"`);
    failIf(!state.errorShown.includes(expect.errorText ?? ''), `the page shows "${state.errorShown}", expected it to contain "${expect.errorText}"`);
    failIf(!state.error, 'window.__interfereViewer.error is not set');
  } else {
    failIf(state.ready !== '1', `dataset.ready is "${state.ready}" (error: ${state.error})`);
    if (expect.rows !== undefined) {
      failIf(state.rows !== expect.rows, `the clash list has ${state.rows} rows, expected ${expect.rows}`);
      failIf(state.clashCount !== expect.rows, `clashCount is ${state.clashCount}, expected ${expect.rows}`);
    }
    if (expect.frames !== undefined) {
      failIf(state.frameCount !== expect.frames, `frameCount is ${state.frameCount}, expected ${expect.frames}`);
      failIf(expect.frames > 0 && state.slider !== expect.frames, `the slider has ${state.slider} positions, expected ${expect.frames}`);
    }
    if (expect.marks !== undefined) failIf(state.marks !== expect.marks, `the slider has ${state.marks} marks, expected ${expect.marks}`);
    if (expect.bodies !== undefined) failIf(state.bodies !== expect.bodies, `the body list has ${state.bodies} entries, expected ${expect.bodies}`);
    if (expect.hiddenBodies !== undefined) {
      failIf(state.hiddenBodies !== expect.hiddenBodies, `${state.hiddenBodies} bodies start hidden, expected ${expect.hiddenBodies}`);
    }
    if (expect.maxReadyMs !== undefined) {
      failIf(state.readyMs > expect.maxReadyMs, `first frame after ${Math.round(state.readyMs)} ms, expected at most ${expect.maxReadyMs}`);
    }
    if (expect.clickRow !== undefined && state.ready === '1') {
      const i = expect.clickRow;
      const before = await page.evaluate(() => window.__interfereViewer.camera.position.toArray());
      await page.click(`#clash-table tbody tr[data-index="${i}"]`);
      await page.waitForFunction((k) => window.__interfereViewer.selected === k && !window.__interfereViewer.flying,
        { timeout: timeoutMs, polling: 20 }, i);
      // two more animation frames: the last flight frame is drawn and composited
      await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
      const after = await page.evaluate(() => window.__interfereViewer.camera.position.toArray());
      const moved = Math.hypot(...after.map((x, k) => x - before[k]));
      result.camera = { before, after, moved };
      failIf(!(moved > 1e-6), `clicking row ${i} did not move the camera (${JSON.stringify(before)})`);
      failIf(!(await page.$eval(`#clash-table tbody tr[data-index="${i}"]`, (r) => r.classList.contains('selected'))),
        `row ${i} is not marked selected after the click`);
    }
    if (expect.redAt !== undefined && state.ready === '1') {
      const [px, py] = await page.evaluate((p) => window.__interfereViewer.projectToScreen(p), expect.redAt);
      const shot = await page.screenshot({ type: 'png' });
      if (screenshotPath) writeFileSync(screenshotPath, shot);
      const img = decodePng(shot);
      const x0 = Math.round(px);
      const y0 = Math.round(py);
      let found = null;
      for (let r = 0; r <= 3 && !found; ++r) {
        for (let dy = -r; dy <= r && !found; ++dy) {
          for (let dx = -r; dx <= r && !found; ++dx) {
            const x = x0 + dx;
            const y = y0 + dy;
            if (x < 0 || y < 0 || x >= img.width || y >= img.height) continue;
            if (isRed(pixel(img, x, y))) found = [x, y, pixel(img, x, y)];
          }
        }
      }
      const inside = x0 >= 0 && y0 >= 0 && x0 < img.width && y0 < img.height;
      result.redPixel = { at: [px, py], rgb: inside ? pixel(img, x0, y0) : null, found };
      failIf(!inside, `redAt projects to (${px}, ${py}), outside the ${img.width}x${img.height} screenshot`);
      failIf(inside && !found, `no red pixel within 3 px of (${x0}, ${y0}): rgb there ${JSON.stringify(pixel(img, Math.min(Math.max(x0, 0), img.width - 1), Math.min(Math.max(y0, 0), img.height - 1)))}`);
      // control: the view is not red all over (its top-right corner shows the background)
      const corner = await page.evaluate(() => {
        const r = document.querySelector('#view canvas').getBoundingClientRect();
        return [Math.round(r.right - 4), Math.round(r.top + 4)];
      });
      const cornerRgb = pixel(img, corner[0], corner[1]);
      result.cornerPixel = { at: corner, rgb: cornerRgb };
      failIf(isRed(cornerRgb), `the view's corner is red too (${JSON.stringify(cornerRgb)}): the red check proves nothing`);
    }
  }
  if (!expect.expectError && state.ready === '1') {
    // filters: the rows left visible (by data-index) for a verdict/status choice
    for (const f of expect.filters ?? []) {
      const shown = await page.evaluate(async (f) => {
        const set = (id, v) => {
          const s = document.getElementById(id);
          s.value = v;
          s.dispatchEvent(new Event('change'));
        };
        set('filter-verdict', f.verdict ?? '*');
        set('filter-status', f.status ?? '*');
        const rows = [...document.querySelectorAll('#clash-table tbody tr')].filter((r) => !r.hidden).map((r) => Number(r.dataset.index));
        set('filter-verdict', '*');
        set('filter-status', '*');
        return rows;
      }, f);
      failIf(JSON.stringify(shown) !== JSON.stringify(f.rows), `filter ${JSON.stringify(f)} shows rows ${JSON.stringify(shown)}`);
    }
    // frames: the rows marked absent at a frame (clashes with "frames" that do not hold it)
    for (const a of expect.absent ?? []) {
      const absent = await page.evaluate((k) => {
        window.__interfereViewer.setFrame(k);
        return [...document.querySelectorAll('#clash-table tbody tr.absent')].map((r) => Number(r.dataset.index));
      }, a.frame);
      failIf(JSON.stringify(absent) !== JSON.stringify(a.rows), `at frame ${a.frame} rows ${JSON.stringify(absent)} are absent, expected ${JSON.stringify(a.rows)}`);
    }
  }
  if (!expect.expectError && state.ready === '1' && expect.play) {
    // play advances the frame by itself; pause stops it
    const f0 = await page.evaluate(() => window.__interfereViewer.frame);
    await page.click('#play');
    await page.waitForFunction((f) => window.__interfereViewer.frame !== f, { timeout: 5000, polling: 50 }, f0).catch(() => {});
    await page.click('#play');
    const f1 = await page.evaluate(() => window.__interfereViewer.frame);
    failIf(f1 === f0, `play did not advance the frame (still ${f0})`);
    await new Promise((r) => setTimeout(r, 1000));
    const f2 = await page.evaluate(() => window.__interfereViewer.frame);
    failIf(f2 !== f1, `pause did not stop the frames (${f1} -> ${f2})`);
  }
  if (screenshotPath && !(expect.redAt !== undefined && state.ready === '1')) {
    writeFileSync(screenshotPath, await page.screenshot({ type: 'png' }));
  }
  failIf(result.consoleErrors.length > 0, `console errors: ${JSON.stringify(result.consoleErrors)}`);
  failIf(result.requests.length > 0, `requests beyond the page: ${JSON.stringify(result.requests)}`);
  result.ok = result.failures.length === 0;
} catch (e) {
  result.failures.push(`harness: ${e.message}`);
} finally {
  if (browser) await browser.close().catch(() => {});
  rmSync(userDataDir, { recursive: true, force: true });
}
console.log(JSON.stringify(result, null, 1));
process.exit(result.ok ? 0 : 1);
