// bvh-lab's browser end-to-end test: the built web page (dist/, served by web/server.mjs) in
// Debian's headless Chromium, driven by playwright-core, once on WebGPU and once on WebGL2.
//
//   node tests/e2e/lab.test.mjs http://127.0.0.1:PORT/
//
// (tests/e2e/run.sh installs, builds, serves and runs this.) For each renderer it opens the page,
// waits for the lab's JSON report (`#lab-status[data-report]`, see index.html) to say it is
// ready on the expected renderer, checks that the first picture is not blank, drags a ray across
// the drawing area with the mouse, and checks the report's answer (a hit, nodes visited, the same
// answer as brute force) and that the ray changed the picture along the drag line. Any console
// error, page error or request to another host fails the run. Screenshots go to target/e2e/.
// It also prints the page's frame rate while dragging (software rendering: informative only).
// Once more on WebGL2, it opens the drifting preset and checks that the report gives the
// refitted structure's and the rebuilt comparison's times frame by frame.

import { mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { deflateSync } from 'node:zlib';
import { chromium } from 'playwright-core';
import {
  BASE_ARGS,
  WEBGPU_ARGS,
  Failure,
  check,
  colourDistance,
  decode,
  frames,
  rgb,
  seconds,
  waitForReport,
} from './browser.mjs';

const url = process.argv[2] ?? process.env.LAB_URL;
if (!url) {
  console.error('usage: node tests/e2e/lab.test.mjs http://127.0.0.1:PORT/');
  process.exit(2);
}
const origin = new URL(url).origin;
const repo = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const outDir = join(repo, 'target', 'e2e');
mkdirSync(outDir, { recursive: true });
const executablePath = process.env.CHROMIUM ?? '/usr/bin/chromium';

const READY_TIMEOUT_MS = 60_000;
const QUERY_TIMEOUT_MS = 30_000;
const VIEWPORT = { width: 1600, height: 900 };

const RUNS = [
  { renderer: 'WebGPU', label: 'WebGPU', args: [...BASE_ARGS, ...WEBGPU_ARGS] },
  // Plain headless has no WebGPU adapter: the app falls back to WebGL2 by itself.
  { renderer: 'WebGL2', label: 'WebGL2', args: BASE_ARGS },
  // The 10,000-segment preset (issue 4's smoothness figure), opened through the address.
  { renderer: 'WebGPU', label: 'WebGPU-10k', search: '?preset=10k', primitives: 10000, args: [...BASE_ARGS, ...WEBGPU_ARGS] },
];

const show = (path) => relative(repo, path);

// The integer pixel rectangle of the report's drawing area, clipped to the screenshot.
function pixelRect(png, [x0, y0, x1, y1]) {
  return {
    x0: Math.max(0, Math.ceil(x0)),
    y0: Math.max(0, Math.ceil(y0)),
    x1: Math.min(png.width, Math.floor(x1)),
    y1: Math.min(png.height, Math.floor(y1)),
  };
}

// Distinct colours and the share of the most common one inside the drawing area.
function colourStats(png, rect) {
  const counts = new Map();
  for (let y = rect.y0; y < rect.y1; y++) {
    for (let x = rect.x0; x < rect.x1; x++) {
      const c = rgb(png, x, y);
      counts.set(c, (counts.get(c) ?? 0) + 1);
    }
  }
  const total = (rect.x1 - rect.x0) * (rect.y1 - rect.y0);
  const top = Math.max(...counts.values());
  return { distinct: counts.size, dominantShare: top / total };
}

// Samples the segment from `a` to `b` every 3 pixels; a sample counts as changed when some pixel
// within 2 pixels of it differs clearly between the two screenshots.
function changesAlong(before, after, a, b) {
  const length = Math.hypot(b.x - a.x, b.y - a.y);
  const samples = Math.max(1, Math.floor(length / 3));
  let changed = 0;
  for (let s = 0; s <= samples; s++) {
    const cx = Math.round(a.x + ((b.x - a.x) * s) / samples);
    const cy = Math.round(a.y + ((b.y - a.y) * s) / samples);
    let hit = false;
    for (let dy = -2; dy <= 2 && !hit; dy++) {
      for (let dx = -2; dx <= 2 && !hit; dx++) {
        const x = cx + dx;
        const y = cy + dy;
        if (x < 0 || y < 0 || x >= after.width || y >= after.height) continue;
        hit = colourDistance(rgb(before, x, y), rgb(after, x, y)) > 24;
      }
    }
    if (hit) changed++;
  }
  return { samples: samples + 1, changed };
}

async function screenshot(page, name) {
  const path = join(outDir, name);
  const buffer = await page.screenshot({ path });
  return { path, png: decode(buffer) };
}

async function runOne({ renderer, label, search = '', primitives, args }) {
  for (const stale of ['start', 'ray', 'step', 'failure']) {
    rmSync(join(outDir, `${label}-${stale}.png`), { force: true });
  }
  const profile = mkdtempSync(join(tmpdir(), 'bvhlab-e2e-'));
  const problems = [];
  const context = await chromium.launchPersistentContext(profile, {
    executablePath,
    headless: true,
    args,
    viewport: VIEWPORT,
    deviceScaleFactor: 1,
  });
  const summary = { renderer, label };
  try {
    const page = context.pages()[0] ?? (await context.newPage());
    page.setDefaultTimeout(READY_TIMEOUT_MS);
    page.on('console', (message) => {
      if (message.type() === 'error') problems.push(`console error: ${message.text()}`);
    });
    page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
    page.on('request', (request) => {
      const target = request.url();
      if (!target.startsWith(origin) && !target.startsWith('data:')) {
        problems.push(`request to another host: ${target}`);
      }
    });
    page.on('requestfailed', (request) =>
      problems.push(`request failed: ${request.url()} (${request.failure()?.errorText})`),
    );

    // 1. Start: the report says ready, on the expected renderer.
    const started = Date.now();
    await page.goto(url + search, { waitUntil: 'load' });
    const { report, text } = await waitForReport(page, (r) => r.ready === true, READY_TIMEOUT_MS, 'ready report');
    summary.readyMs = Date.now() - started;
    check(
      report.renderer === renderer,
      `renderer: expected ${renderer}, the report says ${JSON.stringify(report.renderer)}`,
    );
    check(Array.isArray(report.canvas) && report.canvas.length === 4, `canvas: ${JSON.stringify(report.canvas)}`);
    const [x0, y0, x1, y1] = report.canvas;
    check(
      x0 >= 0 && y0 >= 0 && x1 <= VIEWPORT.width + 1 && y1 <= VIEWPORT.height + 1 && x1 - x0 >= 200 && y1 - y0 >= 200,
      `the drawing area ${JSON.stringify(report.canvas)} is not a sizeable part of the ${VIEWPORT.width}x${VIEWPORT.height} page`,
    );
    check(report.scene?.primitives > 0, `the starting scene has no primitives: ${JSON.stringify(report.scene)}`);
    check(
      primitives === undefined || report.scene.primitives === primitives,
      `expected ${primitives} primitives for ${search}, the report says ${report.scene.primitives}`,
    );
    check(report.structure === 'AABB tree', `structure: expected "AABB tree", got ${JSON.stringify(report.structure)}`);
    check(text && text.trim().length > 0, '#lab-status has no text for screen readers');
    summary.scene = report.scene;
    summary.structure = report.structure;

    // 2. The first picture is not blank.
    await frames(page, 3);
    const start = await screenshot(page, `${label}-start.png`);
    const rect = pixelRect(start.png, report.canvas);
    const stats = colourStats(start.png, rect);
    summary.colours = stats.distinct;
    check(
      stats.distinct >= 8 && stats.dominantShare < 0.98,
      `the drawing area looks blank: ${stats.distinct} colours, the most common covers ` +
        `${(stats.dominantShare * 100).toFixed(1)}% (${show(start.path)})`,
    );

    // 3. Drag a ray across the middle of the drawing area, slowly (about 2 s of small moves),
    //    counting animation frames meanwhile.
    const w = x1 - x0;
    const h = y1 - y0;
    const a = { x: x0 + 0.12 * w, y: y0 + 0.46 * h };
    const b = { x: x0 + 0.88 * w, y: y0 + 0.54 * h };
    await page.mouse.move(a.x, a.y);
    await page.mouse.down();
    await page.evaluate(() => {
      window.__labFrames = { count: 0, since: performance.now(), counting: true };
      const tick = () => {
        if (!window.__labFrames.counting) return;
        window.__labFrames.count++;
        requestAnimationFrame(tick);
      };
      requestAnimationFrame(tick);
    });
    // Each move waits until the page has handled it, so on a slow renderer fewer moves fit in.
    const DRAG_MS = 2000;
    const dragStart = Date.now();
    let moves = 0;
    for (let elapsed = 0; elapsed < DRAG_MS && moves < 120; elapsed = Date.now() - dragStart) {
      const f = elapsed / DRAG_MS;
      await page.mouse.move(a.x + (b.x - a.x) * f, a.y + (b.y - a.y) * f);
      moves++;
      await page.waitForTimeout(16);
    }
    await page.mouse.move(b.x, b.y);
    moves++;
    const dragMs = Date.now() - dragStart;
    const counted = await page.evaluate(() => {
      window.__labFrames.counting = false;
      return { frames: window.__labFrames.count, ms: performance.now() - window.__labFrames.since };
    });
    await page.mouse.up();
    summary.fps = (counted.frames * 1000) / counted.ms;
    summary.dragMs = dragMs;
    summary.moves = moves;

    // 4. The report answers the ray: a hit, nodes visited, the same answer as brute force.
    await waitForReport(page, (r) => r.query?.hit != null, QUERY_TIMEOUT_MS, 'ray query with a hit');
    // Let a few frames pass so that the picture and the report both show the released ray.
    await frames(page, 3);
    const { report: answered } = await waitForReport(page, (r) => r.query?.hit != null, QUERY_TIMEOUT_MS, 'ray query');
    const q = answered.query;
    summary.query = q;
    summary.frameMs = answered.frame_ms;
    summary.cpuMs = answered.cpu_ms;
    check(q.kind === 'ray', `query.kind: expected "ray", got ${JSON.stringify(q.kind)}`);
    check(
      Number.isInteger(q.hit.primitive) && q.hit.primitive >= 0 && q.hit.primitive < answered.scene.primitives,
      `hit.primitive ${q.hit.primitive} is not one of the scene's ${answered.scene.primitives} primitives`,
    );
    check(Number.isFinite(q.hit.t) && q.hit.t >= 0, `hit.t is ${q.hit.t}`);
    check(q.nodes_visited > 0, `nodes_visited is ${q.nodes_visited}`);
    check(q.bound_tests > 0, `bound_tests is ${q.bound_tests}`);
    check(q.primitive_tests > 0, `primitive_tests is ${q.primitive_tests}`);
    check(q.brute_force_tests > 0, `brute_force_tests is ${q.brute_force_tests}`);
    check(q.agrees === true, `the AABB tree's answer differs from brute force's: ${JSON.stringify(q)}`);

    // 5. The ray is drawn: the picture changed along the drag line.
    const ray = await screenshot(page, `${label}-ray.png`);
    const along = changesAlong(start.png, ray.png, a, b);
    summary.changedAlongRay = along;
    check(
      along.changed >= 8,
      `the picture hardly changed along the drag line (${along.changed} of ${along.samples} samples; ` +
        `${show(start.path)} vs ${show(ray.path)})`,
    );
    summary.screenshots = [show(start.path), show(ray.path)];

    // 6. Step through the traversal with the keyboard: Home, then "." five times. The report's
    // playback section follows step by step; its counters never go down, and at the end
    // (End) they are the query's totals.
    await page.keyboard.press('Home');
    await waitForReport(page, (r) => r.playback?.[0]?.step === 0, QUERY_TIMEOUT_MS, 'playback at step 0');
    let previous = [0, 0, 0];
    for (let step = 1; step <= 5; step++) {
      await page.keyboard.press('Period');
      const { report: r } = await waitForReport(page, (r) => r.playback?.[0]?.step === step, QUERY_TIMEOUT_MS, `playback at step ${step}`);
      const p = r.playback[0];
      check(p.line != null && p.line >= 1, `step ${step}: no pseudocode line is highlighted (${JSON.stringify(p)})`);
      check(p.so_far.every((v, i) => v >= previous[i] && v <= p.total[i]), `step ${step}: counters ${JSON.stringify(p.so_far)} after ${JSON.stringify(previous)} (totals ${JSON.stringify(p.total)})`);
      previous = p.so_far;
    }
    summary.stepped = previous;
    const stepped = await screenshot(page, `${label}-step.png`);
    summary.screenshots.push(show(stepped.path));
    await page.keyboard.press('End');
    const { report: ended } = await waitForReport(page, (r) => r.playback?.[0] && r.playback[0].step === r.playback[0].steps, QUERY_TIMEOUT_MS, 'playback at the end');
    const end = ended.playback[0];
    check(JSON.stringify(end.so_far) === JSON.stringify(end.total) || end.structure === 'uniform grid',
      `at the end the counters ${JSON.stringify(end.so_far)} are not the totals ${JSON.stringify(end.total)}`);
    check(end.total[0] === q.nodes_visited && end.total[2] === q.primitive_tests, `playback totals ${JSON.stringify(end.total)} differ from the query's`);

    // 7. Nothing lost (first run only): step to 3, reload, and find the ray, the structure and
    // the step again; then open a share link built from the saved state in a fresh browser
    // profile and find the same state there.
    if (label === 'WebGPU') {
      summary.persistence = await reloadAndShare(page, args, answered);
    }

    check(problems.length === 0, `the page reported problems:\n  ${problems.join('\n  ')}`);
    return summary;
  } catch (error) {
    const pages = context.pages();
    if (pages.length > 0) {
      await pages[0].screenshot({ path: join(outDir, `${label}-failure.png`) }).catch(() => {});
    }
    if (problems.length > 0 && !(error instanceof Failure && error.message.startsWith('the page reported'))) {
      error.message += `\n  the page also reported:\n  ${problems.join('\n  ')}`;
    }
    error.summary = summary;
    throw error;
  } finally {
    await context.close().catch(() => {});
    rmSync(profile, { recursive: true, force: true });
  }
}

// The drifting preset (refit against rebuild, issue text "an animated preset shows refit
// against rebuild frame by frame with their times"): opened through the address, its shapes
// move every frame, the structure is refitted and the comparison rebuilt, and the report gives
// both lanes' times.
async function driftingRefit() {
  const label = 'WebGL2-drifting';
  const profile = mkdtempSync(join(tmpdir(), 'bvhlab-e2e-'));
  const problems = [];
  const context = await chromium.launchPersistentContext(profile, {
    executablePath,
    headless: true,
    args: BASE_ARGS,
    viewport: VIEWPORT,
    deviceScaleFactor: 1,
  });
  try {
    const page = context.pages()[0] ?? (await context.newPage());
    page.on('console', (message) => {
      if (message.type() === 'error') problems.push(`console error: ${message.text()}`);
    });
    page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
    await page.goto(`${url}?preset=drifting-shapes`, { waitUntil: 'load' });
    const { report } = await waitForReport(
      page,
      (r) => r.ready && r.updates?.length === 2 && r.updates[0].refits >= 10 && r.updates[1].rebuilds >= 10,
      READY_TIMEOUT_MS,
      'ten frames of refits beside rebuilds',
    );
    const [refitted, rebuilt] = report.updates;
    check(
      refitted.mode === 'refit' && refitted.last === 'refit' && Number.isFinite(refitted.refit_ms),
      `the structure is refitted every frame, with its time: ${JSON.stringify(refitted)}`,
    );
    check(
      rebuilt.mode === 'rebuild' && rebuilt.last === 'rebuild' && Number.isFinite(rebuilt.rebuild_ms),
      `the comparison is rebuilt every frame, with its time: ${JSON.stringify(rebuilt)}`,
    );
    check(
      refitted.structure.includes('refitted') && rebuilt.structure.includes('rebuilt'),
      `the lanes are named by how they update: ${refitted.structure}, ${rebuilt.structure}`,
    );
    const shot = await screenshot(page, `${label}.png`);
    check(problems.length === 0, `the page reported problems:\n  ${problems.join('\n  ')}`);
    return {
      label,
      refit: `${refitted.refits} refits, ${refitted.refit_ms.toFixed(3)} ms each on average, SAH cost ${refitted.cost_ratio?.toFixed(2)}x the last build's`,
      rebuild: `${rebuilt.rebuilds} rebuilds, ${rebuilt.rebuild_ms.toFixed(3)} ms each on average`,
      screenshot: show(shot.path),
    };
  } finally {
    await context.close().catch(() => {});
    rmSync(profile, { recursive: true, force: true });
  }
}

const STORAGE_KEY = 'bvh-lab/state/v1';

/// The lab's state as the report shows it: what must survive a reload or a link.
function essentials(r) {
  return JSON.stringify({
    structure: r.structure,
    primitives: r.scene.primitives,
    ray: r.query?.ray,
    hit: r.query?.hit?.primitive,
    step: r.playback?.[0]?.step,
    steps: r.playback?.[0]?.steps,
  });
}

async function reloadAndShare(page, args, answered) {
  await page.keyboard.press('Home');
  for (let i = 0; i < 3; i++) await page.keyboard.press('Period');
  const { report: before } = await waitForReport(page, (r) => r.playback?.[0]?.step === 3, QUERY_TIMEOUT_MS, 'playback at step 3');
  check(before.query?.ray?.join() === answered.query.ray.join(), 'the ray moved while stepping');
  // The autosave writes at most every 0.5 s.
  const saved = await page
    .waitForFunction((key) => {
      const s = localStorage.getItem(key);
      return s && JSON.parse(s).playback?.step === 3 ? s : null;
    }, STORAGE_KEY, { timeout: QUERY_TIMEOUT_MS })
    .then((h) => h.jsonValue());
  await page.reload({ waitUntil: 'load' });
  const { report: reloaded } = await waitForReport(page, (r) => r.ready && r.playback?.[0]?.step === 3 && r.query != null, READY_TIMEOUT_MS, 'the state after a reload');
  check(essentials(reloaded) === essentials(before), `after a reload: ${essentials(reloaded)}, before: ${essentials(before)}`);
  await screenshot(page, 'WebGPU-reloaded.png');

  // A share link, encoded as the lab encodes it (zlib, base64url, #s=), opened in a browser
  // with no saved state.
  const link = `${url.split('#')[0]}#s=${deflateSync(Buffer.from(saved)).toString('base64url')}`;
  const profile = mkdtempSync(join(tmpdir(), 'bvhlab-e2e-link-'));
  const other = await chromium.launchPersistentContext(profile, { executablePath, headless: true, args, viewport: VIEWPORT, deviceScaleFactor: 1 });
  try {
    const fresh = other.pages()[0] ?? (await other.newPage());
    await fresh.goto(link, { waitUntil: 'load' });
    const { report: shared } = await waitForReport(fresh, (r) => r.ready && r.playback?.[0]?.step === 3 && r.query != null, READY_TIMEOUT_MS, 'the state from the share link');
    check(essentials(shared) === essentials(before), `from the link: ${essentials(shared)}, shared: ${essentials(before)}`);
    await screenshot(fresh, 'WebGPU-shared.png');
  } finally {
    await other.close().catch(() => {});
    rmSync(profile, { recursive: true, force: true });
  }
  return { link: link.length, state: essentials(before) };
}

function describe(s) {
  const lines = [`${s.label} (${s.renderer}): ready in ${seconds(s.readyMs)}, ${s.scene.primitives} primitives, ${s.structure}, ${s.colours} colours at start`];
  const q = s.query;
  lines.push(
    `  ray: hit primitive ${q.hit.primitive} at t = ${q.hit.t.toFixed(3)}` +
      (q.hit.point ? ` (${q.hit.point.map((v) => v.toFixed(2)).join(', ')})` : '') +
      `, agrees with brute force: ${q.agrees}`,
  );
  lines.push(
    `  counters: ${q.nodes_visited} nodes visited, ${q.bound_tests} bound tests, ` +
      `${q.primitive_tests} primitive tests (brute force: ${q.brute_force_tests})`,
  );
  lines.push(
    `  frame rate while dragging: ${s.fps.toFixed(1)} frames/s over ${seconds(s.dragMs)} (${s.moves} mouse moves)` +
      (s.frameMs != null ? `; the lab's median frame time: ${Number(s.frameMs).toFixed(1)} ms` : '') +
      (s.cpuMs != null ? `, of which CPU (UI, tessellation, draw calls): ${Number(s.cpuMs).toFixed(1)} ms` : '') +
      ' (software rendering; not asserted)',
  );
  lines.push(`  ray drawn along ${s.changedAlongRay.changed} of ${s.changedAlongRay.samples} samples of the drag line`);
  lines.push(`  stepped 5 steps with the keyboard: counters so far ${JSON.stringify(s.stepped)} (nodes, bound tests, primitive tests)`);
  if (s.persistence) {
    lines.push(`  reload and a ${s.persistence.link}-character share link both gave back ${s.persistence.state} (target/e2e/WebGPU-reloaded.png, WebGPU-shared.png)`);
  }
  lines.push(`  screenshots: ${s.screenshots.join(', ')}`);
  return lines.join('\n');
}

let passed = 0;
let failed = 0;
const results = [];
for (const run of RUNS) {
  try {
    const summary = await runOne(run);
    passed++;
    results.push(summary);
    console.log(`ok ${run.label}`);
    console.log(describe(summary));
  } catch (error) {
    failed++;
    console.log(`FAILED ${run.label}: ${error instanceof Failure ? error.message : error.stack}`);
  }
}
try {
  const drifting = await driftingRefit();
  passed++;
  console.log(`ok ${drifting.label}: ${drifting.refit}; beside it ${drifting.rebuild} (${drifting.screenshot})`);
} catch (error) {
  failed++;
  console.log(`FAILED WebGL2-drifting: ${error instanceof Failure ? error.message : error.stack}`);
}
writeFileSync(join(outDir, 'summary.json'), `${JSON.stringify(results, null, 2)}\n`);
console.log(`e2e: ${passed} passed, ${failed} failed`);
process.exit(failed === 0 ? 0 : 1);
