// Time to first frame of a viewer page (issue #25: "opening (first frame drawn) in <= 3 s in
// headless Chromium on this machine"): check_page.mjs N times, each in a freshly started browser;
// prints readyMs (navigation start -> dataset.ready "1") of each run and their median, min and max.
//   node bench_first_frame.mjs PAGE.html EXPECT.json [N=5]
import { spawnSync } from 'node:child_process';
import { statSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const [page, expect, n = '5'] = process.argv.slice(2);
if (!page || !expect) {
  console.error('usage: node bench_first_frame.mjs PAGE.html EXPECT.json [N]');
  process.exit(2);
}
const times = [];
for (let i = 0; i < Number(n); ++i) {
  const r = spawnSync(process.execPath, [join(here, 'check_page.mjs'), page, expect], { encoding: 'utf8' });
  const result = JSON.parse(r.stdout);
  if (!result.ok) {
    console.error(JSON.stringify(result.failures));
    process.exit(1);
  }
  times.push(result.readyMs);
  console.log(`run ${i + 1}: ${result.readyMs} ms ${JSON.stringify(result.timings)}`);
}
const sorted = [...times].sort((a, b) => a - b);
console.log(JSON.stringify({
  page, bytes: statSync(page).size, runs: times.length,
  medianMs: sorted[Math.floor(sorted.length / 2)], minMs: sorted[0], maxMs: sorted[sorted.length - 1],
}));
