// The 3D view in the browser: the built web page (dist/, served by web/server.mjs) in Debian's
// headless Chromium, once on WebGPU and once on WebGL2.
//
//   node tests/e2e/view3d.test.mjs http://127.0.0.1:PORT/
//
// For each renderer it opens the page on the built-in bunny (`?mesh=bunny`), waits for the
// structure to be built, checks that the mesh is drawn, clicks on it and checks the report's
// hit (the same as brute force) and that the hit marker appears under the pointer, steps the
// query with the keyboard, shows the traversal-cost heat map (GPU on WebGPU, CPU on WebGL2)
// and waits for it to finish, then drops a broken STL file (refused, the bunny stays) and a
// good one (opened, through the binary read path), and opens the bunny again with two
// structures side by side and their tree diagrams (`compare=`, `panels=`). Screenshots go to
// target/e2e/3d-*.png.

import { mkdirSync } from 'node:fs';
import { dirname, join, relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import {
  BASE_ARGS,
  WEBGPU_ARGS,
  Failure,
  check,
  colourDistance,
  decode,
  dropFile,
  rgb,
  seconds,
  waitForReport,
} from './browser.mjs';

const url = process.argv[2] ?? process.env.LAB_URL;
if (!url) {
  console.error('usage: node tests/e2e/view3d.test.mjs http://127.0.0.1:PORT/');
  process.exit(2);
}
const repo = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const outDir = join(repo, 'target', 'e2e');
mkdirSync(outDir, { recursive: true });
const executablePath = process.env.CHROMIUM ?? '/usr/bin/chromium';
const VIEWPORT = { width: 1600, height: 900 };
const BUILD_TIMEOUT_MS = 120_000;
const QUERY_TIMEOUT_MS = 60_000;

const RUNS = [
  { renderer: 'WebGPU', heat: 'gpu', args: [...BASE_ARGS, ...WEBGPU_ARGS] },
  { renderer: 'WebGL2', heat: 'cpu', args: BASE_ARGS },
];

async function shoot(page, name) {
  const path = join(outDir, name);
  return { path: relative(repo, path), png: decode(await page.screenshot({ path })) };
}

// Pixels within `radius` of (x, y) that differ clearly between two screenshots.
function changedNear(before, after, x, y, radius) {
  let changed = 0;
  for (let dy = -radius; dy <= radius; dy++) {
    for (let dx = -radius; dx <= radius; dx++) {
      if (colourDistance(rgb(before, x + dx, y + dy), rgb(after, x + dx, y + dy)) > 40) changed++;
    }
  }
  return changed;
}

// A binary STL: an 80-byte header, a count, and 50 bytes per triangle.
function binaryStl(triangles, declared = triangles.length) {
  const buffer = Buffer.alloc(84 + 50 * triangles.length);
  buffer.writeUInt32LE(declared, 80);
  triangles.forEach((corners, i) => {
    const at = 84 + 50 * i + 12;
    corners.flat().forEach((v, j) => buffer.writeFloatLE(v, at + 4 * j));
  });
  return buffer;
}

async function runOne({ renderer, heat, args }) {
  const context = await chromium.launchPersistentContext('', { executablePath, headless: true, args, viewport: VIEWPORT, deviceScaleFactor: 1 });
  const problems = [];
  try {
    const page = context.pages()[0] ?? (await context.newPage());
    page.on('console', (m) => m.type() === 'error' && problems.push(`console: ${m.text()}`));
    page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
    const start = Date.now();
    await page.goto(`${url}?mesh=bunny`, { waitUntil: 'load' });
    const built = (r) => r.ready && r.three?.build_ms != null && r.three.building == null;
    const { report: ready } = await waitForReport(page, built, BUILD_TIMEOUT_MS, 'a built structure over the bunny');
    check(ready.renderer === renderer, `renderer ${ready.renderer}, expected ${renderer}`);
    check(ready.three.mesh === 'Stanford bunny' && ready.three.triangles > 3000, `mesh: ${JSON.stringify(ready.three)}`);
    const readyMs = Date.now() - start;
    await page.waitForTimeout(500);
    const first = await shoot(page, `3d-${renderer}-start.png`);
    const [x0, y0, x1, y1] = ready.three.view;
    const cx = Math.round((x0 + x1) / 2 + 3);
    const cy = Math.round((y0 + y1) / 2 - 7);
    const background = rgb(first.png, Math.round(x0) + 5, Math.round(y1) - 5);
    check(colourDistance(rgb(first.png, cx, cy), background) > 30, 'the mesh is drawn in the middle of the view');

    // Click the bunny: a ray from the camera through the pointer.
    await page.mouse.click(cx, cy);
    const { report: hit } = await waitForReport(
      page,
      (r) => r.three?.hit != null && r.three.ray?.join() !== ready.three.ray?.join(),
      QUERY_TIMEOUT_MS,
      'a hit after the click',
    );
    const t = hit.three;
    check(t.agrees === true, 'the hit is the same as brute force');
    check(t.cost[2] < t.brute_force_tests, `the tree tests fewer triangles (${t.cost[2]}) than brute force (${t.brute_force_tests})`);
    await page.waitForTimeout(500);
    const clicked = await shoot(page, `3d-${renderer}-hit.png`);
    const marker = changedNear(first.png, clicked.png, cx, cy, 6);
    check(marker > 20, `the hit marker appears under the pointer (${marker} pixels changed)`);

    // Step through the query with the keyboard.
    await page.keyboard.press('Home');
    for (let i = 0; i < 3; i++) await page.keyboard.press('Period');
    const { report: stepped } = await waitForReport(page, (r) => r.playback?.[0]?.step === 3, QUERY_TIMEOUT_MS, 'playback at step 3');
    check(stepped.playback[0].line != null, 'a pseudocode line is marked at step 3');
    await shoot(page, `3d-${renderer}-step3.png`);
    await page.keyboard.press('End');

    // The keyboard moves the clicked ray (issue 32): R picks its start, the arrows move it
    // along the camera's axes; R, R gives the arrows back to the camera.
    await page.keyboard.press('KeyR');
    for (const key of ['ArrowRight', 'ArrowRight', 'ArrowUp']) await page.keyboard.press(key);
    const { report: nudged } = await waitForReport(
      page,
      (r) => r.message?.includes("the ray's start e") && r.three?.ray?.join() !== hit.three.ray?.join(),
      QUERY_TIMEOUT_MS,
      "the ray's start moved by the arrow keys",
    );
    check(nudged.three.ray.slice(3).join() === hit.three.ray.slice(3).join(), 'the direction is kept');
    check(nudged.three.agrees === true, 'the moved ray is answered as brute force answers it');
    await shoot(page, `3d-${renderer}-keys.png`);
    await page.keyboard.press('KeyR');
    await page.keyboard.press('KeyR');
    await waitForReport(page, (r) => r.message?.includes('turn the camera'), QUERY_TIMEOUT_MS, 'the arrows back to the camera');

    // The heat map (H).
    await page.keyboard.press('KeyH');
    const { report: mapped } = await waitForReport(
      page,
      (r) => r.three?.heat_map?.device === heat && r.three.heat_map.progress === 1 && r.three.heat_map.max > 0,
      QUERY_TIMEOUT_MS,
      `a finished ${heat.toUpperCase()} heat map`,
    );
    await page.waitForTimeout(300);
    const map = await shoot(page, `3d-${renderer}-heat.png`);
    const mapChanged = changedNear(clicked.png, map.png, cx, cy, 40);
    check(mapChanged > 500, `the heat map replaces the view (${mapChanged} pixels changed near the middle)`);
    await page.keyboard.press('KeyH');

    // A broken file is refused and the bunny stays; a good binary STL opens.
    await dropFile(page, 'broken.stl', binaryStl([], 1200));
    const { report: refused } = await waitForReport(page, (r) => r.three?.message?.startsWith('broken.stl'), QUERY_TIMEOUT_MS, 'the refusal of broken.stl');
    check(refused.three.mesh === 'Stanford bunny', `the bunny stays open (${refused.three.mesh})`);
    check(refused.three.message.includes('stays open'), `the message says so: ${refused.three.message}`);
    await shoot(page, `3d-${renderer}-refused.png`);
    await dropFile(page, 'tri.stl', binaryStl([[[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 0, 0], [0, 1, 0], [0, 0, 1]]]));
    const { report: opened } = await waitForReport(page, (r) => r.three?.mesh === 'tri.stl' && built(r), QUERY_TIMEOUT_MS, 'tri.stl opened');
    check(opened.three.triangles === 2, `tri.stl has 2 triangles (${opened.three.triangles})`);

    // Two structures side by side in 3D, with their tree diagrams, from the address.
    await page.goto(`${url}?mesh=bunny&structure=aabb-tree&compare=kd-tree&panels=controls,stepper,tree`, { waitUntil: 'load' });
    const lanes = (r) => built(r) && r.playback?.length === 2 && r.playback.every((p) => p.steps > 0);
    const { report: compared } = await waitForReport(page, lanes, BUILD_TIMEOUT_MS, 'two structures over the bunny');
    const names = compared.playback.map((p) => p.structure).join(' and ');
    check(names === 'AABB tree and k-d tree', `the lanes are the AABB tree and the k-d tree (${names})`);
    check(compared.playback.every((p) => p.agrees), `both answer as brute force: ${JSON.stringify(compared.playback)}`);
    await page.waitForTimeout(500);
    await shoot(page, `3d-${renderer}-compare.png`);
    check(problems.length === 0, `the page reported: ${problems.join('; ')}`);
    return {
      renderer,
      readyMs,
      hit: t.hit,
      cost: t.cost,
      brute: t.brute_force_tests,
      heat: mapped.three.heat_map,
      heatPicture: map.png,
      view: ready.three.view,
      refused: refused.three.message,
    };
  } finally {
    await context.close().catch(() => {});
  }
}

// The share of pixels of `rect` that two pictures show alike (within 12 levels).
function alike(a, b, [x0, y0, x1, y1]) {
  let same = 0;
  let all = 0;
  for (let y = Math.ceil(y0); y < Math.floor(y1); y++) {
    for (let x = Math.ceil(x0); x < Math.floor(x1); x++) {
      all++;
      if (colourDistance(rgb(a, x, y), rgb(b, x, y)) <= 12) same++;
    }
  }
  return same / Math.max(1, all);
}

let failed = 0;
const maps = [];
for (const run of RUNS) {
  try {
    const s = await runOne(run);
    maps.push(s);
    console.log(`ok 3D ${run.renderer}: bunny built and shown in ${seconds(s.readyMs)}; click hit triangle ${s.hit.triangle} at t = ${s.hit.t.toFixed(3)} ` +
      `with ${s.cost[0]} nodes, ${s.cost[1]} bound tests, ${s.cost[2]} triangle tests (brute force: ${s.brute}); ` +
      `heat map on the ${s.heat.device.toUpperCase()}, largest count ${s.heat.max}; a broken STL: "${s.refused}"`);
  } catch (error) {
    failed++;
    console.log(`FAILED 3D ${run.renderer}: ${error instanceof Failure ? error.message : error.stack}`);
  }
}
// The GPU's map (WebGPU) and the CPU's (WebGL2) are the same picture: the same counts, the
// same colours, shown the same way.
if (maps.length === 2) {
  const share = alike(maps[0].heatPicture, maps[1].heatPicture, maps[0].view);
  if (share >= 0.99) {
    console.log(`ok 3D heat maps: the GPU's and the CPU's pictures agree on ${(share * 100).toFixed(2)}% of the view's pixels`);
  } else {
    failed++;
    console.log(`FAILED 3D heat maps: the GPU's and the CPU's pictures agree on only ${(share * 100).toFixed(2)}% of the view's pixels`);
  }
}
console.log(`e2e 3D: ${RUNS.length - failed} passed, ${failed} failed`);
process.exit(failed === 0 ? 0 : 1);
