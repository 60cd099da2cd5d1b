// Where teachers put the lab, in the browser: the built page (dist/, served by web/server.mjs)
// in Debian's headless Chromium (WebGL2), one browser for every case.
//
//   node tests/e2e/hosting.test.mjs http://127.0.0.1:PORT/
//
// A page that cannot load its code says why within seconds (web/loader.js), never "Loading
// bvh-lab…" for ever:
// 1. opened from disk (file://);
// 2. its WebAssembly missing (HTTP 404), app.js sent as text/plain, no WebAssembly in the
//    browser, and a download that hangs (the page's clock is run forward to the 20 s notice);
//    the WebAssembly sent as application/octet-stream still starts (wasm-bindgen falls back);
// 3. in a frame sandboxed without allow-same-origin, from a server that does not send
//    Access-Control-Allow-Origin.
// Where it works:
// 4. sandboxed (`<iframe sandbox="allow-scripts">`) from web/server.mjs: the lab starts, says
//    once that it cannot save in this frame, and answers commands through bvhlab-embed.js;
// 5. the size message: bvhlab-embed.js's onSize hears the height the lab asks for, fitHeight
//    applies it to the iframe, and it follows the panels shown when the view switches;
// 6. served from a sub-folder (/course/lab/): the course page and its lab load, and nothing is
//    asked for outside the folder;
// 7. inside a slide scaled with transform: scale(0.6): a ray dragged in the scaled lab is the
//    same ray as one dragged at the same spot of an unscaled lab, and a click on its status
//    line's "Step through" toggle (a small target) shows that panel;
// 8. the single-file page (dist/bvh-lab-offline.html, web/offline.mjs) opened from disk:
//    it starts with the address's parameters, and a dragged ray is answered.
// Pages made up by the test are served by Playwright at the lab's origin, except in 3, where a
// plain static server started by the test serves dist/ and the page (Playwright adds
// Access-Control-Allow-Origin to the responses it fulfils, so it cannot take the header away).
// Screenshots: target/e2e/hosting-*.png.

import { mkdirSync, mkdtempSync, readFileSync } from 'node:fs';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { chromium } from 'playwright-core';
import { BASE_ARGS, Failure, check, seconds, waitForReport } from './browser.mjs';

const url = process.argv[2] ?? process.env.LAB_URL;
if (!url) {
  console.error('usage: node tests/e2e/hosting.test.mjs http://127.0.0.1:PORT/');
  process.exit(2);
}
const origin = new URL(url).origin;
const repo = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const outDir = join(repo, 'target', 'e2e');
mkdirSync(outDir, { recursive: true });
const executablePath = process.env.CHROMIUM ?? '/usr/bin/chromium';
const TIMEOUT_MS = 90_000;
const FAILED = 'The lab could not start: ';
// How soon a page that cannot load must say so.
const SAY_WITHIN_MS = 8_000;

/// Console errors, page errors and requests to other hosts on a page that should work.
function watch(page, problems) {
  page.on('console', (message) => {
    if (message.type() === 'error') problems.push(`console error: ${message.text()}`);
  });
  page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
  page.on('request', (request) => {
    const target = request.url();
    if (![origin, 'data:', 'blob:'].some((prefix) => target.startsWith(prefix))) {
      problems.push(`request to another host: ${target}`);
    }
  });
}

/// Waits for the loading line of `frame` to say the lab could not start; returns the text and
/// how long it took since `started`.
async function loadingLine(frame, started, expect = FAILED, timeoutMs = SAY_WITHIN_MS) {
  const handle = await frame.waitForFunction(
    (prefix) => {
      const text = document.getElementById('status')?.textContent ?? '';
      return text.startsWith(prefix) ? text : null;
    },
    expect,
    { timeout: timeoutMs, polling: 100 },
  ).catch(async () => {
    const text = await frame.evaluate(() => document.getElementById('status')?.textContent);
    throw new Failure(`no "${expect}…" within ${seconds(timeoutMs)}; the page says: ${text}`);
  });
  return { text: await handle.jsonValue(), ms: Date.now() - started };
}

/// Serves `html` at `path` of the lab's origin (a page made up by the test).
async function servePage(page, path, html) {
  await page.route(`${origin}${path}`, (route) =>
    route.fulfill({ contentType: 'text/html; charset=utf-8', body: `<!DOCTYPE html><link rel="icon" href="data:,">${html}` }),
  );
}

async function fromDisk(context, summary) {
  const page = await context.newPage();
  const started = Date.now();
  await page.goto(pathToFileURL(join(repo, 'dist', 'index.html')).href);
  const { text, ms } = await loadingLine(page, started);
  check(text.includes('served over http(s)') && text.includes('bash web/serve.sh') && text.includes('python3 -m http.server') && text.includes('bvh-lab-offline.html'),
    `the file:// message says how to serve the folder: ${text}`);
  await page.screenshot({ path: join(outDir, 'hosting-file.png') });
  summary.file = `${seconds(ms)}: ${text}`;
  await page.close();
}

async function brokenServer(context, summary) {
  // The WebAssembly missing.
  let page = await context.newPage();
  await page.route('**/app_bg.wasm', (route) => route.fulfill({ status: 404, contentType: 'text/plain', body: 'Not found\n' }));
  let started = Date.now();
  await page.goto(`${url}index.html?lab=hosting-404&fresh=1`);
  let said = await loadingLine(page, started);
  check(said.text.includes('app_bg.wasm could not be downloaded (HTTP 404'), `a missing app_bg.wasm is named: ${said.text}`);
  await page.screenshot({ path: join(outDir, 'hosting-404.png') });
  summary.missingWasm = `${seconds(said.ms)}: ${said.text}`;
  await page.close();

  // A module script with the wrong MIME type (the server sends nosniff, as web/server.mjs does).
  page = await context.newPage();
  await page.route('**/app.js', async (route) => {
    const response = await route.fetch();
    route.fulfill({ response, headers: { ...response.headers(), 'content-type': 'text/plain' } });
  });
  started = Date.now();
  await page.goto(`${url}index.html?lab=hosting-mime&fresh=1`);
  said = await loadingLine(page, started);
  check(said.text.includes('sends app.js as "text/plain"') && said.text.includes('text/javascript'),
    `a script with the wrong type is named: ${said.text}`);
  summary.wrongType = `${seconds(said.ms)}: ${said.text}`;
  await page.close();

  // The WebAssembly with a generic type (as some servers send .wasm): slower, but it starts.
  page = await context.newPage();
  await page.route('**/app_bg.wasm', async (route) => {
    const response = await route.fetch();
    route.fulfill({ response, headers: { ...response.headers(), 'content-type': 'application/octet-stream' } });
  });
  started = Date.now();
  await page.goto(`${url}index.html?lab=hosting-wasm-type&panels=&fresh=1`);
  await waitForReport(page, (r) => r.ready, TIMEOUT_MS, 'the lab with its wasm as application/octet-stream');
  summary.wasmType = `app_bg.wasm as application/octet-stream: the lab started in ${seconds(Date.now() - started)}`;
  await page.close();

  // No WebAssembly in this browser.
  page = await context.newPage();
  await page.addInitScript(() => { delete globalThis.WebAssembly; });
  started = Date.now();
  await page.goto(`${url}index.html?lab=hosting-nowasm&fresh=1`);
  said = await loadingLine(page, started);
  check(said.text.includes('runs no WebAssembly'), `no WebAssembly is said: ${said.text}`);
  summary.noWasm = `${seconds(said.ms)}: ${said.text}`;
  await page.close();

  // A download that never ends: the page's clock is run forward past the 20 s notice.
  page = await context.newPage();
  await page.clock.install();
  const hung = [];
  await page.route('**/app_bg.wasm', (route) => { hung.push(route); });
  await page.goto(`${url}index.html?lab=hosting-hang&fresh=1`);
  await page.waitForFunction(() => document.getElementById('status')?.textContent.startsWith('Loading'));
  await page.clock.runFor(21_000);
  said = await loadingLine(page, Date.now(), 'bvh-lab is still loading after 20 s', 3000);
  check(said.text.includes('console'), `the notice says where to look: ${said.text}`);
  summary.hang = said.text;
  await page.close();
}

/// An embedding page with a lab in `<iframe sandbox="allow-scripts">`, scripted with
/// bvhlab-embed.js (window.lab); `window.sizes` collects the size messages.
function sandboxPage(search) {
  return `<iframe id="lab" sandbox="allow-scripts" src="index.html?${search}" width="800" height="500"></iframe>
    <script type="module">
      import { BvhLab } from './bvhlab-embed.js';
      window.sizes = [];
      window.lab = new BvhLab(document.getElementById('lab'), { fitHeight: true });
      window.lab.onSize((size) => window.sizes.push(size.height));
    </script>`;
}

/// A plain static server for dist/, as teachers often have: the right types, no other headers.
/// `pages` maps paths to made-up HTML pages. Resolves with its address.
function plainServer(pages) {
  const types = { '.html': 'text/html', '.js': 'text/javascript', '.wasm': 'application/wasm', '.css': 'text/css' };
  const server = createServer((request, response) => {
    const path = new URL(request.url, 'http://localhost').pathname;
    if (pages[path]) {
      response.writeHead(200, { 'Content-Type': 'text/html' });
      response.end(pages[path]);
      return;
    }
    try {
      if (path.includes('..')) throw new Error('outside');
      const body = readFileSync(join(repo, 'dist', path));
      response.writeHead(200, { 'Content-Type': types[path.slice(path.lastIndexOf('.'))] ?? 'application/octet-stream' });
      response.end(body);
    } catch {
      response.writeHead(404);
      response.end();
    }
  });
  return new Promise((done) => server.listen(0, '127.0.0.1', () => done({ server, address: `http://127.0.0.1:${server.address().port}` })));
}

async function sandboxedWithoutHeader(context, summary) {
  const { server, address } = await plainServer({
    '/sandboxed.html': `<!DOCTYPE html><link rel="icon" href="data:,">
      <iframe sandbox="allow-scripts" src="index.html?lab=hosting-plain&fresh=1" width="800" height="500"></iframe>`,
  });
  const page = await context.newPage();
  try {
    const started = Date.now();
    await page.goto(`${address}/sandboxed.html`);
    const frame = page.frames()[1];
    const said = await loadingLine(frame, started);
    check(said.text.includes('Access-Control-Allow-Origin: *') && said.text.includes('allow-same-origin'),
      `the sandboxed frame says which header it needs: ${said.text}`);
    await page.screenshot({ path: join(outDir, 'hosting-sandbox-plain.png') });
    summary.sandboxPlain = `${seconds(said.ms)}: ${said.text}`;
  } finally {
    await page.close();
    server.close();
  }
}

async function sandboxed(context, summary) {
  const page = await context.newPage();
  const problems = [];
  watch(page, problems);
  await servePage(page, '/hosting-sandbox.html', sandboxPage('lab=hosting-sandbox&preset=kd-tree&structure=kd-tree&fresh=1'));
  const started = Date.now();
  await page.goto(`${origin}/hosting-sandbox.html`);
  const frame = page.frames()[1];
  check(await frame.evaluate(() => window.origin) === 'null', 'the frame has an opaque origin');
  const { report: first } = await waitForReport(frame, (r) => r.ready, TIMEOUT_MS, 'the sandboxed lab');
  summary.sandboxReady = seconds(Date.now() - started);
  const notice = 'This lab cannot save in this browser frame';
  check(first.message?.includes(notice), `the lab says it cannot save: ${first.message}`);
  // The embed API works: a ray through the kd-tree scene, answered like brute force.
  const answered = await page.evaluate(async () => {
    await window.lab.ready();
    const report = await window.lab.setRay([0, 4.5], [1, 0]);
    const stepped = await window.lab.step(1);
    return { query: report.query, step: stepped.playback[0].step, message: report.message };
  });
  check(answered.query?.hit && answered.query.agrees, `the sandboxed lab answers a ray: ${JSON.stringify(answered.query)}`);
  check(answered.step >= 0, 'and steps');
  // Past the autosave's half second: the lab tried no write, and said its notice only once.
  await page.waitForTimeout(1200);
  const { report: later } = await waitForReport(frame, (r) => r.ready, TIMEOUT_MS, 'the lab later');
  const times = (later.message ?? '').split(notice).length - 1;
  check(times <= 1 && !(later.message ?? '').includes('did not keep'),
    `the notice is said once, and no failed write is reported: ${later.message}`);
  const height = await page.evaluate(() => [window.sizes, document.getElementById('lab').style.height]);
  check(height[0][0] === 720 && height[1] === '720px', `fitHeight sized the sandboxed frame: ${JSON.stringify(height)}`);
  await page.screenshot({ path: join(outDir, 'hosting-sandbox.png') });
  check(problems.length === 0, `problems in the sandboxed lab:\n  ${problems.join('\n  ')}`);
  summary.sandbox = `"${first.message}"; a ray hit #${answered.query.hit.primitive} through bvhlab-embed.js`;
  await page.close();
}

/// Clicks the status line's "Step through" toggle of the lab in iframe `selector`: the status
/// line is the lab's last row, laid out from the right, so the toggle sits a fixed distance
/// from the frame's bottom right corner (in the lab's own pixels, times `scale`).
async function toggleStepper(page, selector, scale = 1) {
  const box = await page.locator(selector).boundingBox();
  await page.mouse.click(box.x + box.width - 55 * scale, box.y + box.height - 12 * scale);
}

async function sizeMessages(context, summary) {
  const page = await context.newPage();
  const problems = [];
  watch(page, problems);
  // Same origin, not sandboxed; the view alone (panels=).
  await servePage(page, '/hosting-size.html', sandboxPage('lab=hosting-size&preset=kd-tree&panels=&fresh=1')
    .replace(' sandbox="allow-scripts"', ''));
  await page.goto(`${origin}/hosting-size.html`);
  await page.waitForFunction(() => window.sizes?.length > 0, null, { timeout: TIMEOUT_MS });
  await page.evaluate(() => window.lab.ready());
  const heights = () => page.evaluate(() => ({ sizes: window.sizes, frame: document.getElementById('lab').style.height }));
  const seen = [await heights()];
  // The student shows "Step through", then hides it again: the lab asks for more room, then less.
  for (const n of [2, 3]) {
    await page.waitForTimeout(300);
    await toggleStepper(page, '#lab');
    const arrived = await page.waitForFunction((count) => window.sizes.length >= count, n, { timeout: 10_000 })
      .then(() => true, () => false);
    check(arrived, `no size message after clicking "Step through": ${JSON.stringify(await heights())}`);
    seen.push(await heights());
    if (n === 2) await page.screenshot({ path: join(outDir, 'hosting-size.png') });
  }
  const sizes = seen.at(-1).sizes;
  check(JSON.stringify(sizes) === '[480,720,480]', `the size messages: ${JSON.stringify(sizes)}`);
  check(JSON.stringify(seen.map((s) => s.frame)) === '["480px","720px","480px"]', `the iframe follows: ${JSON.stringify(seen)}`);
  check(problems.length === 0, `problems on the size page:\n  ${problems.join('\n  ')}`);
  summary.size = `panels=: ${sizes.join(' -> ')} px as "Step through" is shown and hidden; the iframe followed`;
  await page.close();
}

async function subFolder(context, summary) {
  const page = await context.newPage();
  const problems = [];
  watch(page, problems);
  const prefix = '/course/lab/';
  const outside = [];
  page.on('request', (request) => {
    const target = new URL(request.url());
    if (target.origin === origin && !target.pathname.startsWith(prefix)) outside.push(target.pathname);
  });
  // The built folder served under /course/lab/ (the requests are answered from dist/).
  await page.route(`${origin}${prefix}**`, async (route) => {
    const inner = new URL(route.request().url());
    inner.pathname = `/${inner.pathname.slice(prefix.length)}`;
    route.fulfill({ response: await route.fetch({ url: inner.href }) });
  });
  const started = Date.now();
  await page.goto(`${origin}${prefix}course.html`);
  await page.waitForFunction(() => window.courseReady === true, null, { timeout: TIMEOUT_MS });
  summary.subFolderReady = seconds(Date.now() - started);
  const done = await page.evaluate(() => window.lab.setRay([2, -1], [0, 1]));
  check(done.query?.hit && done.lesson?.goal_reached, `the lab in the sub-folder answers: ${JSON.stringify(done.query)}`);
  await page.screenshot({ path: join(outDir, 'hosting-subfolder.png') });
  check(outside.length === 0, `requests outside ${prefix}: ${JSON.stringify(outside)}`);
  check(problems.length === 0, `problems in the sub-folder:\n  ${problems.join('\n  ')}`);
  summary.subFolder = `${prefix}course.html and its lab load; no request outside ${prefix}`;
  await page.close();
}

async function scaledSlide(context, summary) {
  const page = await context.newPage();
  const problems = [];
  watch(page, problems);
  const lab = (name) => `index.html?lab=hosting-${name}&preset=kd-tree&panels=&fresh=1`;
  // As reveal.js scales a slide: a CSS transform on an ancestor of the iframe.
  await servePage(page, '/hosting-slides.html', `
    <style>body { margin: 0 } iframe { border: 0; width: 800px; height: 500px; display: block }
      .slide { transform: scale(0.6); transform-origin: 0 0; position: absolute; left: 40px; top: 30px }
      .plain { position: absolute; left: 600px; top: 30px }</style>
    <div class="slide"><iframe id="scaled" src="${lab('scaled')}"></iframe></div>
    <div class="plain"><iframe id="plain" src="${lab('plain')}"></iframe></div>`);
  await page.goto(`${origin}/hosting-slides.html`);
  const frameOf = (id) => page.frames().find((f) => f.url().includes(`hosting-${id}`));
  const rays = {};
  for (const [id, scale] of [['scaled', 0.6], ['plain', 1]]) {
    const frame = frameOf(id);
    const { report } = await waitForReport(frame, (r) => r.ready, TIMEOUT_MS, `the ${id} lab`);
    const [x0, y0, x1, y1] = report.canvas;
    const box = await page.locator(`#${id}`).boundingBox();
    // The same spots of each lab's own (unscaled) drawing area, in the page's pixels.
    const at = (fx, fy) => ({
      x: box.x + (x0 + fx * (x1 - x0)) * scale,
      y: box.y + (y0 + fy * (y1 - y0)) * scale,
    });
    const a = at(0.2, 0.4);
    const b = at(0.8, 0.6);
    await page.mouse.move(a.x, a.y);
    await page.mouse.down();
    // Few moves: each one redraws the lab in software (about a second under load).
    for (let i = 1; i <= 3; i++) {
      await page.mouse.move(a.x + ((b.x - a.x) * i) / 3, a.y + ((b.y - a.y) * i) / 3);
    }
    await page.mouse.up();
    const { report: after } = await waitForReport(frame, (r) => r.query != null, TIMEOUT_MS, `a ray in the ${id} lab`);
    rays[id] = after.query.ray;
  }
  // A click on a small target: the scaled lab's "Step through" toggle brings its panel, so its
  // drawing area narrows.
  const scaledFrame = frameOf('scaled');
  const { report: before } = await waitForReport(scaledFrame, (r) => r.ready, TIMEOUT_MS, 'the scaled lab');
  await toggleStepper(page, '#scaled', 0.6);
  const { report: narrowed } = await waitForReport(scaledFrame, (r) => r.canvas[2] < before.canvas[2] - 100,
    10_000, 'the "Step through" panel in the scaled lab');
  await page.screenshot({ path: join(outDir, 'hosting-slides.png') });
  // The scaled lab's pointer moves 1/0.6 as far per page pixel: allow a page pixel's slack.
  const [s, p] = [rays.scaled, rays.plain];
  const origins = Math.hypot(s[0] - p[0], s[1] - p[1]);
  const turn = Math.abs(Math.atan2(s[3], s[2]) - Math.atan2(p[3], p[2]));
  check(origins < 0.15 && turn < 0.02,
    `the ray dragged in the scaled slide is the unscaled one: ${JSON.stringify(s)} vs ${JSON.stringify(p)}`);
  check(problems.length === 0, `problems on the slide:\n  ${problems.join('\n  ')}`);
  summary.slides = `scale(0.6): "Step through" clicked, drawing area ${before.canvas[2]} -> ${narrowed.canvas[2]} px wide; ray ${JSON.stringify(s.map((x) => +x.toFixed(3)))}, unscaled ${JSON.stringify(p.map((x) => +x.toFixed(3)))}`;
  await page.close();
}

async function offlineFile(context, summary) {
  const page = await context.newPage();
  const problems = [];
  page.on('console', (message) => {
    if (message.type() === 'error') problems.push(`console error: ${message.text()}`);
  });
  page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
  // A small window: the lab redraws in software on every mouse move.
  await page.setViewportSize({ width: 900, height: 600 });
  const started = Date.now();
  await page.goto(`${pathToFileURL(join(repo, 'dist', 'bvh-lab-offline.html')).href}?preset=kd-tree&panels=&fresh=1`);
  const { report } = await waitForReport(page, (r) => r.ready, TIMEOUT_MS, 'the offline lab');
  check(report.scene.shapes === 8, `the address's preset applies: ${JSON.stringify(report.scene)}`);
  summary.offlineReady = seconds(Date.now() - started);
  const [x0, y0, x1, y1] = report.canvas;
  await page.mouse.move(x0 + 0.1 * (x1 - x0), y0 + 0.45 * (y1 - y0));
  await page.mouse.down();
  for (let i = 1; i <= 3; i++) {
    await page.mouse.move(x0 + (0.1 + 0.25 * i) * (x1 - x0), y0 + (0.45 + 0.03 * i) * (y1 - y0));
  }
  await page.mouse.up();
  const { report: answered } = await waitForReport(page, (r) => r.query?.hit != null, TIMEOUT_MS, 'a ray in the offline lab');
  check(answered.query.agrees, `the offline lab answers like brute force: ${JSON.stringify(answered.query)}`);
  await page.screenshot({ path: join(outDir, 'hosting-offline.png') });
  check(problems.length === 0, `problems in the offline file:\n  ${problems.join('\n  ')}`);
  summary.offline = `file://…/bvh-lab-offline.html: ${answered.renderer}, a ray hit #${answered.query.hit.primitive}`;
  await page.close();
}

const profile = mkdtempSync(join(tmpdir(), 'bvhlab-e2e-hosting-'));
const context = await chromium.launchPersistentContext(profile, {
  executablePath,
  headless: true,
  // Pages made up by the test (Playwright serves them) would count as public pages framing a
  // local one under Chromium's Local Network Access check.
  args: [...BASE_ARGS, '--disable-features=LocalNetworkAccessChecks'],
  viewport: { width: 1400, height: 900 },
  deviceScaleFactor: 1,
});
const summary = {};
const cases = [
  ['file://', fromDisk],
  ['broken server', brokenServer],
  ['sandboxed, no CORS header', sandboxedWithoutHeader],
  ['sandboxed', sandboxed],
  ['size message', sizeMessages],
  ['sub-folder', subFolder],
  ['scaled slide', scaledSlide],
  ['single file from disk', offlineFile],
];
let failed = 0;
const began = Date.now();
for (const [name, run] of cases) {
  const started = Date.now();
  try {
    await run(context, summary);
    console.log(`ok ${name} (${seconds(Date.now() - started)})`);
  } catch (error) {
    failed++;
    console.log(`FAILED ${name}: ${error instanceof Failure ? error.message : error.stack}`);
  }
}
await context.close();
for (const [key, value] of Object.entries(summary)) console.log(`  ${key}: ${value}`);
console.log(`e2e hosting: ${cases.length - failed} passed, ${failed} failed in ${seconds(Date.now() - began)}`);
process.exit(failed === 0 ? 0 : 1);
