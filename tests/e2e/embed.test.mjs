// Embedding, hardening and nothing lost, in the browser: the built web page (dist/, served by
// web/server.mjs) in Debian's headless Chromium (WebGL2: two labs run in one page here).
//
//   node tests/e2e/embed.test.mjs http://127.0.0.1:PORT/
//
// 1. The example course page (web/embed.html) with two labs, driven through its JavaScript
//    API (bvhlab-embed.js): both answer, agree with brute force and with each other, step,
//    and refuse bad commands with a reason; the page's own buttons work.
// 2. The origin check: a page of another origin (localhost instead of 127.0.0.1) gets no
//    answer from a lab that does not name it, and answers from one whose address does.
// 3. A crash: the lab is made to panic (debug=panic); the overlay says what happened, and
//    "Reload with my saved work" brings back the ray set just before; a broken scene file
//    dropped then is refused with a message naming it, and the scene stays.
// 4. The 3D half across a reload: mesh, structure, ray and answer come back.
// 5. The example course page with a lesson (web/course.html): the lab posts its progress as
//    the lesson opens, as the student's ray reaches the step's goal, and as the page moves it
//    to the next step; the page lists it, and the lab's live region says the step and task.
// Every page runs under the lab's Content-Security-Policy: any violation, console error (but
// the panic's own) or request to another host fails the test. Screenshots: target/e2e/embed-*.png.

import { mkdirSync, mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { BASE_ARGS, Failure, check, dropFile, liveRegionSays, seconds, waitForReport } from './browser.mjs';

const url = process.argv[2] ?? process.env.LAB_URL;
if (!url) {
  console.error('usage: node tests/e2e/embed.test.mjs http://127.0.0.1:PORT/');
  process.exit(2);
}
const origin = new URL(url).origin;
const otherOrigin = origin.replace('127.0.0.1', 'localhost');
const repo = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const outDir = join(repo, 'target', 'e2e');
mkdirSync(outDir, { recursive: true });
const executablePath = process.env.CHROMIUM ?? '/usr/bin/chromium';
const TIMEOUT_MS = 90_000;

/// Counts what must not happen on a page: console errors, page errors, CSP violations,
/// requests to other hosts. `allow(text)` lets expected console errors pass.
function watch(page, problems, allow = () => false) {
  page.on('console', (message) => {
    if (message.type() === 'error' && !allow(message.text())) {
      problems.push(`console error: ${message.text()}`);
    }
  });
  page.on('pageerror', (error) => {
    if (!allow(error.message)) problems.push(`page error: ${error.message}`);
  });
  page.on('request', (request) => {
    const target = request.url();
    const allowed = [origin, otherOrigin, 'data:', 'blob:'];
    if (!allowed.some((prefix) => target.startsWith(prefix))) {
      problems.push(`request to another host: ${target}`);
    }
  });
}

/// Records CSP violations in every frame of the page, for `violations(page)` to read.
async function recordViolations(context) {
  await context.addInitScript(() => {
    window.__cspViolations = [];
    document.addEventListener('securitypolicyviolation', (event) => {
      window.__cspViolations.push(`${event.violatedDirective}: ${event.blockedURI}`);
    });
  });
}

async function violations(page) {
  const all = [];
  for (const frame of page.frames()) {
    all.push(...(await frame.evaluate(() => window.__cspViolations ?? []).catch(() => [])));
  }
  return all;
}

/// Command ids as a page would make them with `Math.random()` (many digits, in [0, 1)), but
/// the same in every run: the golden ratio's multiples, modulo 1.
let idCount = 0;
function nextId() {
  idCount += 1;
  return (idCount * 0.6180339887498949) % 1;
}

/// Sends one command to the lab in this page (the page scripts itself: same origin).
async function command(page, body, timeoutMs = TIMEOUT_MS) {
  return page.evaluate(
    ({ body, timeoutMs, id }) =>
      new Promise((resolve) => {
        const timer = setTimeout(() => resolve({ timeout: true }), timeoutMs);
        window.addEventListener('message', function listen(event) {
          if (event.data?.bvhlab === 'reply' && event.data.id === id) {
            clearTimeout(timer);
            window.removeEventListener('message', listen);
            resolve(event.data);
          }
        });
        window.postMessage({ bvhlab: 'command', id, command: body }, location.origin);
      }),
    { body, timeoutMs, id: nextId() },
  );
}

async function twoLabs(context, summary) {
  const page = await context.newPage();
  const problems = [];
  watch(page, problems);
  const started = Date.now();
  await page.goto(new URL('embed.html', url).href);
  await page.waitForFunction(() => window.labsReady === true, null, { timeout: TIMEOUT_MS });
  summary.embedReady = seconds(Date.now() - started);
  const rows = await page.$$eval('tbody tr', (trs) => trs.map((tr) => [...tr.cells].map((c) => c.textContent)));
  check(rows.length === 2 && rows.every((r) => r.length === 8), `the table has a row per lab: ${JSON.stringify(rows)}`);
  check(rows[0][1] === 'k-d tree' && rows[1][1] === 'AABB tree', `the labs report their structures: ${JSON.stringify(rows)}`);

  const result = await page.evaluate(async () => {
    const { left, right } = window.labs;
    const [a, b] = await Promise.all([left.setRay([0, 4.5], [1, 0]), right.setRay([0, 4.5], [1, 0])]);
    const start = await left.goToStep(0);
    const two = await left.step(2);
    const refusals = [];
    for (const attempt of [() => right.setStructure('octopus'), () => left.setRay([0, 0], [0, 0]), () => left.send({ type: 'fly' })]) {
      try {
        await attempt();
        refusals.push(null);
      } catch (error) {
        refusals.push(error.message);
      }
    }
    const after = await right.report();
    return { a, b, start: start.playback[0], two: two.playback[0], refusals, after };
  });
  const { a, b } = result;
  check(a.query?.hit && b.query?.hit, `both labs hit: ${JSON.stringify([a.query, b.query])}`);
  check(a.query.hit.primitive === b.query.hit.primitive && a.query.hit.t === b.query.hit.t,
    `the same hit in both labs: ${JSON.stringify([a.query.hit, b.query.hit])}`);
  check(a.query.agrees && b.query.agrees, 'both agree with brute force');
  check(a.query.nodes_visited !== b.query.nodes_visited || a.structure !== b.structure, 'two structures');
  check(result.start.step === 0 && result.two.step === 2, `stepping: ${result.start.step} then ${result.two.step}`);
  check(result.two.so_far[1] > 0, `two steps test something: ${JSON.stringify(result.two.so_far)}`);
  const [octopus, zero, fly] = result.refusals;
  check(octopus?.includes('octopus') && octopus.includes('kd-tree'), `a bad structure is refused with the list: ${octopus}`);
  check(zero?.toLowerCase().includes('zero'), `a zero direction is refused: ${zero}`);
  check(fly?.includes('fly'), `an unknown command is refused: ${fly}`);
  check(result.after.structure === 'AABB tree', 'a refused command changes nothing');

  // The page's own button: step both labs, and the table follows.
  await page.evaluate(() => Promise.all([window.labs.left.goToStep(0), window.labs.right.goToStep(0)]));
  await page.click('#step');
  await page.waitForFunction(() => document.querySelector('#row-left td:nth-child(4)')?.textContent.startsWith('1 /'), null, { timeout: TIMEOUT_MS });
  await page.screenshot({ path: join(outDir, 'embed-two-labs.png') });
  problems.push(...(await violations(page)).map((v) => `CSP violation: ${v}`));
  check(problems.length === 0, `problems on the embed page:\n  ${problems.join('\n  ')}`);
  summary.embed = `same hit #${a.query.hit.primitive} at t = ${a.query.hit.t.toFixed(3)}; k-d tree ${a.query.nodes_visited} nodes, AABB tree ${b.query.nodes_visited}`;
  await page.close();
}

async function originCheck(context, summary) {
  const page = await context.newPage();
  const problems = [];
  watch(page, problems, (text) => text.includes('was ignored'));
  const lab = (extra) => `${origin}/index.html?lab=cross${extra}`;
  // A page of another origin, made up by the test (served by Playwright, not the lab's server).
  await page.route(`${otherOrigin}/course.html`, (route) =>
    route.fulfill({
      contentType: 'text/html',
      body: `<!DOCTYPE html><link rel="icon" href="data:,">
        <iframe id="strange" src="${lab('-strange')}" width="600" height="400"></iframe>
        <iframe id="friend" src="${lab(`-friend&origin=${encodeURIComponent(otherOrigin)}`)}" width="600" height="400"></iframe>`,
    }),
  );
  await page.goto(`${otherOrigin}/course.html`);
  for (const frame of page.frames().slice(1)) {
    await waitForReport(frame, (r) => r.ready, TIMEOUT_MS, 'a cross-origin lab');
  }
  const answers = await page.evaluate(async (labOrigin) => {
    let asked = 0;
    const ask = (frame) =>
      new Promise((resolve) => {
        asked += 1;
        const id = (asked * 0.6180339887498949) % 1;
        const timer = setTimeout(() => resolve('no answer'), 4000);
        window.addEventListener('message', (event) => {
          if (event.data?.bvhlab === 'reply' && event.data.id === id) {
            clearTimeout(timer);
            resolve(event.data.ok ? `answered: ${event.data.report.structure}` : event.data.error);
          }
        });
        frame.contentWindow.postMessage({ bvhlab: 'command', id, command: { type: 'set-structure', structure: 'grid' } }, labOrigin);
      });
    return {
      strange: await ask(document.getElementById('strange')),
      friend: await ask(document.getElementById('friend')),
    };
  }, origin);
  check(answers.strange === 'no answer', `a lab that does not name the page's origin ignores it: ${answers.strange}`);
  check(answers.friend === 'answered: uniform grid' || answers.friend.startsWith('answered:'), `a lab that names it answers: ${answers.friend}`);
  const strangeFrame = page.frames().find((f) => f.url().includes('cross-strange'));
  const { report } = await waitForReport(strangeFrame, (r) => r.ready, TIMEOUT_MS, 'the ignoring lab');
  check(report.structure !== 'uniform grid', `the ignored command changed nothing: ${report.structure}`);
  check(problems.length === 0, `problems on the cross-origin page:\n  ${problems.join('\n  ')}`);
  summary.origins = `another origin: ignored without origin=, ${answers.friend} with it`;
  await page.close();
}

async function crashAndReload(context, summary) {
  const page = await context.newPage();
  const problems = [];
  // The panic is logged as an error on purpose (by eframe's hook and the wasm trap).
  watch(page, problems, (text) => /panic|unreachable|RuntimeError/i.test(text));
  await page.goto(`${url}?lab=crash&preset=kd-tree&debug=panic`);
  await waitForReport(page, (r) => r.ready, TIMEOUT_MS, 'the lab');
  const set = await command(page, { type: 'set-ray', origin: [0.5, 4.5], direction: [1, 0.05] });
  check(set.ok, `set-ray: ${JSON.stringify(set)}`);
  const before = set.report;
  // The lab saves at most every half second.
  await page.waitForTimeout(1200);
  await command(page, { type: 'panic-for-test' }, 3000);
  await page.waitForSelector('#crash:not([hidden])', { timeout: 10_000 });
  const shown = await page.textContent('#crash');
  check(shown.includes('panic-for-test') && shown.includes('Reload'), `the overlay says what happened: ${shown}`);
  await page.screenshot({ path: join(outDir, 'embed-crash.png') });
  await page.click('#crash-reload');
  const { report: after } = await waitForReport(page, (r) => r.ready && r.query != null, TIMEOUT_MS, 'the state after the reload');
  const same = (a, b) => a.length === b.length && a.every((x, i) => Math.fround(x) === Math.fround(b[i]));
  check(same(after.query.ray, before.query.ray) && after.structure === before.structure,
    `the reload brought back the ray: ${JSON.stringify(after.query.ray)} (before ${JSON.stringify(before.query.ray)})`);
  // A broken scene file: refused, named, and the scene stays.
  await dropFile(page, 'broken-scene.json', Buffer.from('{"version": 1, "k": "many"'));
  const { report: refused } = await waitForReport(page, (r) => r.message?.includes('broken-scene.json'), TIMEOUT_MS, 'the broken file\'s message');
  check(refused.message.includes('kept'), `the message says the scene was kept: ${refused.message}`);
  check(same(refused.query.ray, before.query.ray) && refused.scene.shapes === before.scene.shapes,
    'the scene and ray stay after the broken file');
  await page.screenshot({ path: join(outDir, 'embed-broken-file.png') });
  problems.push(...(await violations(page)).map((v) => `CSP violation: ${v}`));
  check(problems.length === 0, `problems on the crash page:\n  ${problems.join('\n  ')}`);
  summary.crash = `overlay shown, reload restored the ray ${JSON.stringify(after.query.ray)}; broken file: "${refused.message}"`;
  await page.close();
}

async function reload3d(context, summary) {
  const page = await context.newPage();
  const problems = [];
  watch(page, problems);
  await page.goto(`${url}?lab=three&mesh=torus&structure=kd-tree`);
  await waitForReport(page, (r) => r.three?.triangles > 0 && r.three.building == null, TIMEOUT_MS, 'the torus built');
  const set = await command(page, { type: 'set-ray', origin: [0.1, 0.2, 4], direction: [0.05, -0.02, -1] });
  check(set.ok && set.report.three.hit, `the ray hits the torus: ${JSON.stringify(set)}`);
  await page.waitForTimeout(1200);
  await page.reload();
  const { report } = await waitForReport(page, (r) => r.three?.hit != null && r.three.building == null, TIMEOUT_MS, 'the 3D state after a reload');
  const keep = (t) => JSON.stringify([t.mesh, t.structure, t.ray, t.hit]);
  check(keep(report.three) === keep(set.report.three), `after a reload: ${keep(report.three)}; before: ${keep(set.report.three)}`);
  await page.screenshot({ path: join(outDir, 'embed-3d-reloaded.png') });
  problems.push(...(await violations(page)).map((v) => `CSP violation: ${v}`));
  check(problems.length === 0, `problems on the 3D page:\n  ${problems.join('\n  ')}`);
  summary.reload3d = `${report.three.mesh}, ${report.three.structure}, hit triangle ${report.three.hit.triangle} at t = ${report.three.hit.t.toFixed(4)} came back`;
  await page.close();
}

async function courseProgress(context, summary) {
  const page = await context.newPage();
  const problems = [];
  watch(page, problems);
  const started = Date.now();
  await page.goto(new URL('course.html', url).href);
  await page.waitForFunction(() => window.courseReady === true, null, { timeout: TIMEOUT_MS });
  await page.waitForFunction(() => window.progress.some((p) => p.lesson === 'slab-test' && p.step === 1),
    null, { timeout: 20_000 });
  summary.courseReady = seconds(Date.now() - started);
  const opened = await page.evaluate(() => window.progress.at(-1));
  check(!opened.goal_reached && opened.steps === 3 && opened.goals === 3 && opened.goals_reached === 0,
    `the lesson opened, nothing done yet: ${JSON.stringify(opened)}`);
  // What the student does (here through the scripting API): a ray straight up, x_d = 0,
  // through the triangle at the bottom left.
  const done = await page.evaluate(() => window.lab.setRay([2, -1], [0, 1]));
  check(done.lesson?.goal_reached === true && done.query?.hit && done.query.agrees,
    `the ray reaches the goal: ${JSON.stringify(done.lesson)} ${JSON.stringify(done.query)}`);
  await page.waitForFunction(() => window.progress.some((p) => p.step === 1 && p.goal_reached),
    null, { timeout: 10_000 });
  const next = await page.evaluate(() => window.lab.goToLesson('slab-test', 2));
  check(next.lesson?.step === 2 && !next.lesson.goal_reached && next.lesson.goals_reached === 1,
    `the page moves the lab to step 2: ${JSON.stringify(next.lesson)}`);
  await page.waitForFunction(() => window.progress.some((p) => p.step === 2), null, { timeout: 10_000 });
  // The same progress as xAPI statements (bvhlab-embed.js onStatement).
  const statements = await page.evaluate(() => window.statements);
  const verbs = statements.map((s) => `${s.verb.display['en-US']} ${s.object.id.split('/lessons/')[1]}`);
  const completed = statements.filter((s) => s.verb.id === 'http://adlnet.gov/expapi/verbs/completed');
  check(completed.length === 1 && completed[0].object.id.endsWith('/index.html/lessons/slab-test/steps/1') &&
    completed[0].result.success === true && completed[0].result.completion === true &&
    completed[0].result.score.raw === 1 && completed[0].result.score.max === 3 &&
    completed[0].actor?.account?.name === 'example-student' && !Number.isNaN(Date.parse(completed[0].timestamp)) &&
    completed[0].context.contextActivities.parent[0].id.endsWith('/lessons/slab-test'),
  `one xAPI statement completes step 1, with its score and actor: ${JSON.stringify(verbs)} ${JSON.stringify(completed)}`);
  check(verbs.includes('experienced slab-test/steps/1') && verbs.at(-1) === 'experienced slab-test/steps/2',
    `the steps opened are "experienced": ${JSON.stringify(verbs)}`);
  const refused = await page.evaluate(() => window.lab.goToLesson('slab-tset', 1).then(() => null, (e) => e.message));
  check(refused?.includes('slab-test'), `an unknown lesson is refused with the names: ${refused}`);
  const listed = await page.$$eval('#progress li', (items) => items.map((li) => li.textContent));
  check(listed.some((t) => t.includes('slab-test, step 1 of 3: done (1 of 3')), `the page lists the step done: ${JSON.stringify(listed)}`);
  await liveRegionSays(page.frames()[1], (t) => t.includes('step 2 of 3') && t.includes('Task:'), 'the step and its task');
  await page.screenshot({ path: join(outDir, 'embed-course.png') });
  const csp = await violations(page);
  check(csp.length === 0, `no CSP violations: ${JSON.stringify(csp)}`);
  check(problems.length === 0, `no errors: ${JSON.stringify(problems)}`);
  await page.close();
}

const profile = mkdtempSync(join(tmpdir(), 'bvhlab-e2e-embed-'));
const context = await chromium.launchPersistentContext(profile, {
  executablePath,
  headless: true,
  // The origin check's course page is made up by the test (Playwright serves it), so Chromium's
  // Local Network Access check would count it as a public page framing a local one.
  args: [...BASE_ARGS, '--disable-features=LocalNetworkAccessChecks'],
  viewport: { width: 1400, height: 900 },
  deviceScaleFactor: 1,
});
await recordViolations(context);
const summary = {};
let failed = 0;
for (const [name, run] of [['two labs', twoLabs], ['origin check', originCheck], ['crash', crashAndReload], ['3D reload', reload3d], ['course page', courseProgress]]) {
  try {
    await run(context, summary);
    console.log(`ok ${name}`);
  } catch (error) {
    failed++;
    console.log(`FAILED ${name}: ${error instanceof Failure ? error.message : error.stack}`);
  }
}
await context.close();
for (const [key, value] of Object.entries(summary)) console.log(`  ${key}: ${value}`);
console.log(`e2e embed: ${5 - failed} passed, ${failed} failed`);
process.exit(failed === 0 ? 0 : 1);
