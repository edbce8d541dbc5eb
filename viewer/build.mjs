// Builds the viewer template (issue #25 item 1; docs/viewer.md "How the page is built"):
//   node build.mjs [--node-modules DIR] OUT.html
// DIR holds three and esbuild (default: viewer/node_modules; the CMake build installs them with
// `npm ci` into <build>/viewer/node_modules, keeping the source tree clean). esbuild bundles src/main.js (three.js from node_modules) into one minified IIFE and the CSS, both
// inlined into src/page.html. The result holds exactly one /*INTERFERE_VIEWER_DATA*/ and one
// INTERFERE_VIEWER_TITLE placeholder, which the C++ writer (view/html.h) replaces. The build fails
// when the bundle could end its <script>/<style> element early or holds a placeholder itself.
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { createRequire } from 'node:module';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const args = process.argv.slice(2);
let nodeModules = join(here, 'node_modules');
if (args[0] === '--node-modules') {
  nodeModules = resolve(args[1]);
  args.splice(0, 2);
}
const out = args[0];
if (!out || args.length !== 1) {
  console.error('usage: node build.mjs [--node-modules DIR] OUT.html');
  process.exit(2);
}
const esbuild = createRequire(join(nodeModules, 'noop.js'))('esbuild');

function die(message) {
  console.error(`viewer build: ${message}`);
  process.exit(1);
}

function count(text, needle) {
  return text.split(needle).length - 1;
}

const js = await esbuild.build({
  entryPoints: [join(here, 'src/main.js')],
  bundle: true,
  minify: true,
  format: 'iife',
  target: ['es2020'],
  legalComments: 'eof',
  write: false,
  logLevel: 'warning',
  absWorkingDir: here,
  nodePaths: [nodeModules],
});
const bundle = js.outputFiles[0].text;
// (sources checked out with CRLF line ends still give the same page: LF only)
const readText = (f) => readFileSync(join(here, f), 'utf8').replace(/\r\n?/g, '\n');
const css = (await esbuild.transform(readText('src/style.css'), {
  loader: 'css', minify: true,
})).code;

// Inline content must not end or re-mode its element (HTML raw text rules).
if (/<\/script/i.test(bundle)) die('the bundle contains "</script": it would end the page\'s <script> early');
if (bundle.includes('<!--')) die('the bundle contains "<!--": it would change how the page\'s <script> ends');
if (/<script/i.test(bundle)) die('the bundle contains "<script": with a "<!--" before it, it would change how the page\'s <script> ends');
if (/<\/style/i.test(css)) die('the CSS contains "</style"');
for (const p of ['/*INTERFERE_VIEWER_DATA*/', 'INTERFERE_VIEWER_TITLE']) {
  if (bundle.includes(p) || css.includes(p)) die(`the bundle contains the placeholder ${p}`);
}

const shell = readText('src/page.html');
const page = shell.split('<!--BUILD:CSS-->').join(css).split('<!--BUILD:JS-->').join(bundle);
if (count(shell, '<!--BUILD:CSS-->') !== 1 || count(shell, '<!--BUILD:JS-->') !== 1) {
  die('src/page.html must hold <!--BUILD:CSS--> and <!--BUILD:JS--> once each');
}
for (const p of ['/*INTERFERE_VIEWER_DATA*/', 'INTERFERE_VIEWER_TITLE']) {
  if (count(page, p) !== 1) die(`the page holds the placeholder ${p} ${count(page, p)} times (expected once)`);
}
const target = resolve(out);
mkdirSync(dirname(target), { recursive: true });
writeFileSync(target, page);
console.log(`viewer build: ${target} (${page.length} bytes: script ${bundle.length}, style ${css.length})`);
