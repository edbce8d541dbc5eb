// One browser test case (issue #25 item 4; registered in tests/CMakeLists.txt):
//   node run_case.mjs TEMPLATE.html WORK_DIR VARIANT [EXTRA EXPECTATIONS JSON]
// makes the VARIANT document with make_sample.mjs, injects it into the built template, and checks the
// page in headless Chromium with check_page.mjs (a screenshot lands in WORK_DIR/VARIANT.png).
// Extra expectations (e.g. '{"maxReadyMs": 8000, "maxBytes": 20000000}') are merged in.
import { spawnSync } from 'node:child_process';
import { readFileSync, statSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const [template, work, variant, extra] = process.argv.slice(2);
if (!template || !work || !variant) {
  console.error('usage: node run_case.mjs TEMPLATE.html WORK_DIR VARIANT [EXTRA_JSON]');
  process.exit(2);
}
const run = (script, args) => spawnSync(process.execPath, [join(here, script), ...args], { stdio: 'inherit' }).status;
if (run('make_sample.mjs', [template, work, variant]) !== 0) process.exit(1);
const expectPath = join(work, `${variant}.expect.json`);
const expect = { ...JSON.parse(readFileSync(expectPath, 'utf8')), ...(extra ? JSON.parse(extra) : {}) };
writeFileSync(expectPath, JSON.stringify(expect, null, 1));
const page = join(work, `${variant}.html`);
if (expect.maxBytes !== undefined && statSync(page).size > expect.maxBytes) {
  console.error(`${page}: ${statSync(page).size} bytes, expected at most ${expect.maxBytes}`);
  process.exit(1);
}
process.exit(run('check_page.mjs', [page, expectPath, '--screenshot', join(work, `${variant}.png`)]) === 0 ? 0 : 1);
