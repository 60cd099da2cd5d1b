// A teacher's lesson in the browser, from the lesson writer to the student:
//
// 1. The writer ("Write a lesson" in the Lessons pane), driven through the page's mirror for
//    screen readers (#lab-a11y) as a screen reader would: title, text (with markup and a
//    script in it), task and file name typed; two goals added from the offers; "Check the
//    step" says the step is not ready without a solution; the task done in the lab's Queries
//    fields and recorded as the solution; the check passes; the step is saved; "Save the
//    lesson file" downloads the .toml, which is read; "Try step 1" shows it as a student
//    sees it.
// 2. That file opened again: from disk with "Open a lesson file…" (the file chooser), from
//    the address (?lesson-url=e2e-written.toml, the file put in dist/ for the run), and from a
//    course page (web/course.html) with bvhlab-embed.js's loadLesson. Each time the lesson
//    opens and doing its solution reaches the goal.
// 3. A broken lesson (a TOML slip on line 5), one over 256 KiB and a missing one (404), by
//    the file chooser, a drop, the address and loadLesson: the status line says
//    `file:line: why` or the limit, and the student's ray and open lesson stay as they were.
// 4. The lesson's markup is shown as text: no dialog opens, no element is made of it, and
//    the mirror holds the characters `<script>`.
// 5. A reload keeps the teacher's lesson and its reached goal; `fresh=1` starts it over.
// 6. Heard by screen readers: the live region (#lab-status) says the writer's verdict and a
//    refused file, as the status line at the bottom of the lab shows them.
//
//   node tests/e2e/teacher.test.mjs http://127.0.0.1:PORT/
//
// Screenshots at 1280x720 go to target/e2e/teacher-*.png. Any console error (but the 404's
// own), page error or dialog fails the part it happens in.

import { mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { BASE_ARGS, Failure, check, dropFile, liveRegionSays, seconds, waitForReport } from './browser.mjs';

const url = process.argv[2] ?? process.env.LAB_URL;
if (!url) {
  console.error('usage: node tests/e2e/teacher.test.mjs http://127.0.0.1:PORT/');
  process.exit(2);
}
const repo = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const outDir = join(repo, 'target', 'e2e');
const dist = join(repo, 'dist');
mkdirSync(outDir, { recursive: true });
const executablePath = process.env.CHROMIUM ?? '/usr/bin/chromium';
const TIMEOUT_MS = 60_000;
const started = Date.now();

// What the teacher writes. The setup's ray starts left of the k-d tree scene pointing away
// from it (a miss); the solution turns it right, through the scene (the ray the embedding
// test casts, a hit).
const SETUP = 'preset=kd-tree&structure=aabb-tree&task=first-hit&ray=-1,4.5,-1,0';
const SOLVED_RAY = [-1, 4.5, 1, 0];
const SCRIPT = '<b>bold</b><script>alert(1)</script>';
const WRITTEN = 'e2e-written.toml';
const LESSON = 'e2e-written';
const BAD = 'e2e-bad.toml';
const BIG = 'e2e-big.toml';
// A lesson whose line 5 opens a string that never closes.
const BAD_TEXT = [
  'title = "A lesson with a slip"',
  'section = "§1"',
  '',
  '[[step]]',
  'title = "The quote is never closed',
  `setup = "${SETUP}"`,
  'text = "Nothing to see."',
  '',
].join('\n');

const report = (page) =>
  page.evaluate(() => JSON.parse(document.getElementById('lab-status').dataset.report ?? 'null'));
const until = async (page, accept, what, timeoutMs = 15_000) =>
  (await waitForReport(page, accept, timeoutMs, what)).report;
const sameRay = (a, b) => Array.isArray(a) && a.length === b.length && a.every((v, i) => Math.abs(v - b[i]) < 1e-3);

/// What the status line (at the bottom of the lab) says, once `accept(text)` holds: the
/// report's message, and the same text on screen (in the mirror).
async function statusSays(page, accept, what) {
  const r = await until(page, (r) => r.message && accept(r.message), `the status line saying ${what}`);
  await mirrorShows(page, r.message);
  return r.message;
}

/// Whether the live region (#lab-status, what a screen reader announces by itself) says
/// `text` too; what it did not say fails the part "heard by screen readers".
const unheard = [];
async function heard(page, text) {
  try {
    await liveRegionSays(page, (t) => t.includes(text), `"${text}"`, 5_000);
  } catch (error) {
    unheard.push(error.message);
  }
}

/// Fails the part on console errors, page errors and dialogs (an alert from a lesson's text).
function watch(page, problems, allow = () => false) {
  page.on('console', (m) => { if (m.type() === 'error' && !allow(m.text())) problems.push(`console error: ${m.text()}`); });
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  page.on('dialog', (d) => { problems.push(`a dialog opened: ${d.type()} "${d.message()}"`); d.dismiss().catch(() => {}); });
}

async function open(context, address, problems, allow) {
  const page = await context.newPage();
  watch(page, problems, allow);
  await page.goto(new URL(address, url).href);
  return page;
}

/// The id of the mirror's button whose text is `text`, if there is one.
const buttonId = (page, text) => page.evaluate((text) =>
  [...document.querySelectorAll('#lab-a11y button')].find((e) => e.textContent.trim() === text)?.id ?? null, text);

/// Presses the mirror's button `text` (as a screen reader's "activate" does).
async function press(page, text) {
  const id = await buttonId(page, text);
  check(id, `the lab's mirror has a button "${text}"`);
  await page.evaluate((id) => document.getElementById(id).click(), id);
}

/// Waits until the mirror has an element whose own text is `text`.
async function mirrorShows(page, text, timeoutMs = 15_000) {
  await page.waitForFunction((text) =>
    [...document.querySelectorAll('#lab-a11y *')].some((e) => !e.children.length && e.textContent.trim() === text),
  text, { timeout: timeoutMs }).catch(() => { throw new Failure(`the mirror never showed "${text}"`); });
}

/// Types `text` into the mirror's field named by the label `name`.
async function fill(page, name, text) {
  const id = await page.evaluate((name) => {
    const label = [...document.querySelectorAll('#lab-a11y *')]
      .find((e) => !e.children.length && e.textContent.trim() === name);
    if (!label) return null;
    return [...document.querySelectorAll('#lab-a11y input, #lab-a11y textarea')]
      .find((e) => (e.getAttribute('aria-labelledby') ?? '').split(' ').includes(label.id))?.id ?? null;
  }, name);
  check(id, `the lab's mirror has a field "${name}"`);
  await page.fill(`#${id}`, text);
}

/// Types `x` as the x of the ray's point s in the Queries panel (as a student could); returns
/// the report once the ray has changed.
async function typeRayS(page, x) {
  const before = (await report(page)).query?.ray;
  const id = await page.evaluate(() => {
    const all = [...document.querySelectorAll('#lab-a11y *')];
    const at = all.findIndex((e) => !e.children.length && e.textContent.trim() === 'ray s');
    return at < 0 ? null : all.slice(at).find((e) => e.tagName === 'INPUT')?.id ?? null;
  });
  check(id, 'the Queries panel has the ray\'s point s to type');
  await page.fill(`#${id}`, String(x));
  return until(page, (r) => r.query?.ray && !sameRay(r.query.ray, before), 'the typed ray');
}

/// Does the lesson's task by typing: s at x = 0 points the ray right along y = 4.5.
async function solveByTyping(page) {
  const r = await typeRayS(page, 0);
  check(sameRay(r.query.ray, SOLVED_RAY), `the typed ray: ${r.query.ray}`);
  return r;
}

/// The mirror's text, and whether the lesson's markup became elements.
const mirrorText = (page) => page.evaluate(() => {
  const mirror = document.getElementById('lab-a11y');
  return { text: mirror.textContent, elements: mirror.querySelectorAll('script, b, i').length };
});

/// The lab's saved states (localStorage), as one text.
const saved = (page) => page.evaluate(() => JSON.stringify({ ...localStorage }));

/// Waits until the lab has saved a state other than `before` (it writes at most every half
/// second, on a frame).
async function savedAgain(page, before) {
  await page.waitForFunction((before) => JSON.stringify({ ...localStorage }) !== before, before, { timeout: 15_000 })
    .catch(() => { throw new Failure('the lab never saved its state'); });
}

/// Chooses `files` in the dialog of "Open a lesson file…".
async function chooseFile(page, file) {
  const chooser = page.waitForEvent('filechooser', { timeout: 15_000 });
  await press(page, 'Open a lesson file…');
  await (await chooser).setFiles(file);
}

const state = {};
const summary = {};

async function writer(context) {
  const problems = [];
  const page = await open(context, `index.html?fresh=1&${SETUP}`, problems);
  let r = await until(page, (r) => r.ready && r.query, 'the lab', TIMEOUT_MS);
  check(!r.query.hit && !r.lesson, `the lab starts with the ray missing, no lesson: ${JSON.stringify(r.query)}`);
  await mirrorShows(page, 'Write a lesson', TIMEOUT_MS);
  await press(page, 'Write a lesson');
  await mirrorShows(page, 'Writing a lesson');
  await page.screenshot({ path: join(outDir, 'teacher-writer-start.png') });
  const setup = await page.evaluate(() => {
    const label = [...document.querySelectorAll('#lab-a11y p')].find((e) => e.textContent === "Setup (the address's words)");
    return document.querySelector(`#lab-a11y [aria-labelledby~="${label?.id}"]`)?.value;
  });
  for (const word of SETUP.split('&')) check(setup?.includes(word), `the setup is what the lab shows: ${setup}`);

  await fill(page, 'Lesson title', 'Hit it <i>from the left</i>');
  await fill(page, 'File name', LESSON);
  await fill(page, 'Step title', 'Turn the ray');
  await fill(page, 'Text', `The ray points away from the scene. ${SCRIPT}`);
  await fill(page, 'Task (what the student does)', 'Turn the ray so that it hits a segment.');
  await press(page, 'Add a goal from what the lab shows now');
  await mirrorShows(page, 'answer != miss');
  await press(page, 'answer != miss');
  await mirrorShows(page, 'Goals (all must hold): 1');
  await press(page, 'nodes-visited > 0');
  await mirrorShows(page, 'Goals (all must hold): 2');
  await press(page, 'Check the step');
  const notReady = await statusSays(page, (t) => t.includes('not ready'), 'the step is not ready');
  check(/solution/.test(notReady), `without a solution the check says why: ${notReady}`);
  await heard(page, 'The step is not ready');
  // Only a step that passed its check is saved.
  await press(page, 'Save the step');
  await page.waitForTimeout(1000);
  await mirrorShows(page, 'Saved steps: 0');

  // The teacher does the task in the lab and records it.
  r = await solveByTyping(page);
  check(r.query.hit && !r.lesson, `the typed ray hits: ${JSON.stringify(r.query)}`);
  await press(page, 'Record what is on screen as the solution');
  await page.waitForFunction(() => {
    const label = [...document.querySelectorAll('#lab-a11y p')].find((e) => e.textContent === "Solution (the address's words)");
    return document.querySelector(`#lab-a11y [aria-labelledby~="${label?.id}"]`)?.value.includes('ray=');
  }, null, { timeout: 15_000 }).catch(() => { throw new Failure('the solution field never showed the ray'); });
  await press(page, 'Check the step');
  const passed = await statusSays(page, (t) => t.includes('passed its check'), 'the step passed');
  await page.screenshot({ path: join(outDir, 'teacher-writer-checked.png') });
  await press(page, 'Save the step');
  await statusSays(page, (t) => t.includes('Step saved: the lesson has 1 step'), 'the step saved');
  await mirrorShows(page, 'Saved steps: 1');

  const [download] = await Promise.all([
    page.waitForEvent('download', { timeout: 15_000 }),
    press(page, 'Save the lesson file'),
  ]);
  check(download.suggestedFilename() === WRITTEN, `the file is named as typed: ${download.suggestedFilename()}`);
  const toml = readFileSync(await download.path(), 'utf8');
  await statusSays(page, (t) => t.includes('Lesson saved'), 'the lesson saved');
  await page.screenshot({ path: join(outDir, 'teacher-writer-saved.png') });
  for (const part of ['title = "Hit it <i>from the left</i>"', 'title = "Turn the ray"', SCRIPT,
    'Turn the ray so that it hits a segment.', '"answer != miss"', '"nodes-visited > 0"', 'preset=kd-tree', 'ray=-1,4.5,1,0']) {
    check(toml.includes(part), `the lesson file has ${part}:\n${toml}`);
  }
  check(/^solution = ".*ray=-1,4\.5,1,0.*"$/m.test(toml), `the solution is the recorded ray:\n${toml}`);
  state.toml = toml;
  summary.written = `${toml.length} bytes, ${toml.split('\n').length} lines; check: "${notReady.slice(0, 90)}…", then "${passed.slice(0, 60)}…"`;

  // As a student sees it: the setup's ray again, the task to do, the markup as characters.
  await press(page, 'Try step 1');
  r = await until(page, (r) => r.lesson?.lesson === LESSON, 'the step tried');
  check(r.lesson.step === 1 && r.lesson.steps === 1 && !r.lesson.goal_reached && sameRay(r.query.ray, [-1, 4.5, -1, 0]),
    `the step opens where it starts: ${JSON.stringify(r.lesson)} ${JSON.stringify(r.query.ray)}`);
  await mirrorShows(page, 'Back to the lesson writer');
  const shown = await mirrorText(page);
  check(shown.text.includes(SCRIPT) && shown.elements === 0, `the text is shown as characters: ${shown.elements} elements`);
  await page.screenshot({ path: join(outDir, 'teacher-writer-try.png') });
  check(problems.length === 0, `no errors: ${JSON.stringify(problems)}`);
  await page.close();
}

const needFile = () => check(state.toml, 'the written lesson file (the writer part failed)');

/// Opened from disk, after a broken and a too large file that change nothing; then a broken
/// file dropped on the lab with the teacher's lesson open changes nothing either.
async function fromDisk(context) {
  needFile();
  const problems = [];
  const page = await open(context, `index.html?fresh=1&${SETUP}`, problems);
  let r = await until(page, (r) => r.ready && r.query, 'the lab', TIMEOUT_MS);
  await mirrorShows(page, 'Open a lesson file…', TIMEOUT_MS);
  // The student's work: a ray typed in.
  const ray = (await solveByTyping(page)).query.ray;
  await chooseFile(page, { name: BAD, mimeType: 'application/toml', buffer: Buffer.from(BAD_TEXT) });
  const bad = await statusSays(page, (t) => t.includes(`${BAD}:`), 'the broken file refused');
  check(bad.includes(`${BAD}:5:`), `the status line names the line: ${bad}`);
  await heard(page, `${BAD}:5:`);
  r = await report(page);
  check(!r.lesson && sameRay(r.query.ray, ray), `nothing changed: ${JSON.stringify(r.lesson)} ${r.query.ray}`);
  await chooseFile(page, { name: BIG, mimeType: 'application/toml', buffer: Buffer.from(bigLesson()) });
  const big = await statusSays(page, (t) => t.includes(BIG), 'the large file refused');
  check(/256(\.0)? KiB/.test(big), `the status line says the limit: ${big}`);
  r = await report(page);
  check(!r.lesson && sameRay(r.query.ray, ray), `nothing changed: ${JSON.stringify(r.lesson)} ${r.query.ray}`);

  await chooseFile(page, { name: WRITTEN, mimeType: 'application/toml', buffer: Buffer.from(state.toml) });
  r = await until(page, (r) => r.lesson?.lesson === LESSON, 'the lesson opened');
  check(r.lesson.step === 1 && !r.lesson.goal_reached && !r.query.hit, `it opens at its start: ${JSON.stringify(r.lesson)}`);
  await statusSays(page, (t) => t.includes(`from ${WRITTEN}`), 'whose lesson it is');
  await mirrorShows(page, `A teacher's lesson, from ${WRITTEN}`);
  r = await solveByTyping(page);
  r = await until(page, (r) => r.lesson?.goal_reached, 'the goal reached');
  summary.fromDisk = `refused "${bad}" and "${big}"; opened, goal reached by typing s = (0, 4.5)`;

  await dropFile(page, BAD, Buffer.from(BAD_TEXT));
  const dropped = await statusSays(page, (t) => t.includes(`${BAD}:5:`), 'the dropped broken file refused');
  const after = await report(page);
  check(JSON.stringify(after.lesson) === JSON.stringify(r.lesson) && sameRay(after.query.ray, r.query.ray),
    `the open lesson and the ray stay: ${JSON.stringify(after.lesson)} ${after.query.ray}`);
  summary.dropped = dropped;
  check(problems.length === 0, `no errors: ${JSON.stringify(problems)}`);
  await page.close();
}

/// A valid lesson over 256 KiB (a long comment).
function bigLesson() {
  return `${state.toml}\n${`# ${'x'.repeat(98)}\n`.repeat(2700)}`;
}

/// ?lesson-url=: opened, done, reloaded (kept), and opened fresh (started over).
async function fromAddress(context) {
  needFile();
  const problems = [];
  let fetched = 0;
  const page = await open(context, `index.html?fresh=1&lesson-url=${WRITTEN}`, problems);
  page.on('request', (q) => { if (new URL(q.url()).pathname.endsWith(`/${WRITTEN}`)) fetched++; });
  let r = await until(page, (r) => r.ready && r.lesson, 'the lesson from the address', TIMEOUT_MS);
  check(r.lesson.lesson === LESSON && r.lesson.step === 1 && !r.lesson.goal_reached && !r.query.hit,
    `the lesson opens at its start: ${JSON.stringify(r.lesson)}`);
  await mirrorShows(page, `A teacher's lesson, from ${WRITTEN}`);
  const shown = await mirrorText(page);
  check(shown.text.includes(SCRIPT) && shown.text.includes('Hit it <i>from the left</i>') && shown.elements === 0,
    `the title and text are shown as characters (${shown.elements} elements made)`);
  await page.waitForTimeout(300);
  await page.screenshot({ path: join(outDir, 'teacher-lesson-open.png') });
  const unsolved = await saved(page);
  r = await solveByTyping(page);
  r = await until(page, (r) => r.lesson?.goal_reached, 'the goal reached');
  check(r.lesson.goals_reached === 1 && r.lesson.goals === 1, `one goal of one: ${JSON.stringify(r.lesson)}`);
  await liveRegionSays(page, (t) => t.includes('Done'), 'the step done', 15_000);
  await page.screenshot({ path: join(outDir, 'teacher-lesson-done.png') });
  await savedAgain(page, unsolved);
  check(!page.url().includes('fresh=1'), `fresh=1 leaves the address once used: ${page.url()}`);
  const before = fetched;
  await page.reload();
  r = await until(page, (r) => r.ready && r.lesson, 'the lesson after a reload', TIMEOUT_MS);
  check(r.lesson.lesson === LESSON && r.lesson.goal_reached && r.lesson.goals_reached === 1 && sameRay(r.query.ray, SOLVED_RAY),
    `the reload keeps the lesson, its reached goal and the ray: ${JSON.stringify(r.lesson)} ${r.query.ray}`);
  await mirrorShows(page, `A teacher's lesson, from ${WRITTEN}`);
  // Fetching the file again would open the lesson over the saved progress.
  await page.waitForTimeout(1000);
  r = await report(page);
  check(fetched === before && r.lesson.goal_reached && sameRay(r.query.ray, SOLVED_RAY),
    `the file is not fetched again (${fetched - before} times): ${JSON.stringify(r.lesson)} ${r.query.ray}`);
  summary.reload = `kept ${LESSON} with its goal reached and the ray; fresh=1 starts it over`;
  await page.goto(new URL(`index.html?fresh=1&lesson-url=${WRITTEN}`, url).href);
  r = await until(page, (r) => r.ready && r.lesson, 'the lesson opened fresh', TIMEOUT_MS);
  check(r.lesson.lesson === LESSON && !r.lesson.goal_reached && r.lesson.goals_reached === 0 && !r.query.hit,
    `fresh=1 starts the lesson over: ${JSON.stringify(r.lesson)} ${r.query.ray}`);
  check(problems.length === 0, `no errors: ${JSON.stringify(problems)}`);
  await page.close();
}

/// A broken, a too large and a missing ?lesson-url= leave the student's saved work as it was.
async function badAddress(context) {
  needFile();
  const problems = [];
  const page = await open(context, 'index.html?lab=e2e-teacher-keep&fresh=1&lesson=queries&step=2', problems,
    (t) => t.includes('404'));
  await until(page, (r) => r.ready && r.lesson?.step === 2 && r.query, 'the queries lesson, step 2', TIMEOUT_MS);
  const before = await saved(page);
  const kept = await typeRayS(page, 3);
  await savedAgain(page, before);
  for (const [file, says] of [[BAD, (t) => t.includes(`${BAD}:5:`)], [BIG, (t) => t.includes(BIG) && /256(\.0)? KiB/.test(t)]]) {
    await page.goto(new URL(`index.html?lab=e2e-teacher-keep&lesson-url=${file}`, url).href);
    await until(page, (r) => r.ready, `the lab with ${file}`, TIMEOUT_MS);
    const said = await statusSays(page, says, `${file} refused`);
    const r = await report(page);
    check(JSON.stringify(r.lesson) === JSON.stringify(kept.lesson) && sameRay(r.query.ray, kept.query.ray),
      `${file}: the lesson and the ray stay: ${JSON.stringify(r.lesson)} ${r.query.ray}`);
    summary[`address ${file}`] = said;
  }
  await page.goto(new URL('index.html?fresh=1&lesson-url=e2e-missing.toml', url).href);
  await until(page, (r) => r.ready, 'the lab with a missing lesson', TIMEOUT_MS);
  const missing = await statusSays(page, (t) => t.includes('e2e-missing.toml'), 'the missing file');
  check(missing.includes('404'), `the status line says the server has no such file: ${missing}`);
  check(!(await report(page)).lesson, 'no lesson opens');
  summary.missing = missing;
  check(problems.length === 0, `no errors: ${JSON.stringify(problems)}`);
  await page.close();
}

/// A course page sends the file with loadLesson; the student's ray reaches the goal.
async function fromEmbed(context) {
  needFile();
  const problems = [];
  const page = await open(context, 'course.html', problems);
  await page.waitForFunction(() => window.courseReady === true, null, { timeout: TIMEOUT_MS });
  const opened = await page.evaluate((text) => window.lab.loadLesson(text, 'e2e-written.toml'), state.toml);
  check(opened.lesson?.lesson === LESSON && opened.lesson.step === 1 && !opened.lesson.goal_reached,
    `loadLesson opens the lesson: ${JSON.stringify(opened.lesson)}`);
  const done = await page.evaluate(([o, d]) => window.lab.setRay(o, d), [SOLVED_RAY.slice(0, 2), SOLVED_RAY.slice(2)]);
  check(done.lesson?.goal_reached && done.query.hit, `the ray reaches the goal: ${JSON.stringify(done.lesson)}`);
  await page.waitForFunction((name) => window.progress.some((p) => p.lesson === name && p.goal_reached), LESSON,
    { timeout: 10_000 }).catch(() => { throw new Failure('the page heard no progress with the goal reached'); });
  const refused = await page.evaluate((text) => window.lab.loadLesson(text, 'e2e-bad.toml').then(() => null, (e) => e.message), BAD_TEXT);
  check(refused?.startsWith(`${BAD}:5:`), `loadLesson refuses the broken file with its line: ${refused}`);
  const tooBig = await page.evaluate((text) => window.lab.loadLesson(text, 'e2e-big.toml').then(() => null, (e) => e.message), bigLesson());
  check(/256(\.0)? KiB/.test(tooBig ?? ''), `loadLesson refuses the large file: ${tooBig}`);
  const after = await page.evaluate(() => window.lab.report());
  check(JSON.stringify(after.lesson) === JSON.stringify(done.lesson) && sameRay(after.query.ray, SOLVED_RAY),
    `the lesson and the ray stay: ${JSON.stringify(after.lesson)}`);
  summary.embed = `opened, goal reached by setRay; refused "${refused}" and "${tooBig}"`;
  await page.screenshot({ path: join(outDir, 'teacher-course.png') });
  check(problems.length === 0, `no errors: ${JSON.stringify(problems)}`);
  await page.close();
}

/// The writer's verdict and a refused file, heard without looking for them: the live region
/// says them as the status line does (checked along the way by `heard`).
async function screenReaders() {
  check(unheard.length === 0, `the live region did not say what the status line said:\n  ${unheard.join('\n  ')}`);
}

const browser = await chromium.launch({ executablePath, headless: true, args: BASE_ARGS });
const context = await browser.newContext({ viewport: { width: 1280, height: 720 }, deviceScaleFactor: 1, acceptDownloads: true });
let failed = 0;
const parts = [['the writer', writer], ['from disk', fromDisk], ['from the address', fromAddress],
  ['bad addresses', badAddress], ['from a course page', fromEmbed], ['heard by screen readers', screenReaders]];
try {
  for (const [name, run] of parts) {
    const t = Date.now();
    try {
      if (name === 'from the address' || name === 'bad addresses') {
        needFile();
        writeFileSync(join(dist, WRITTEN), state.toml);
        writeFileSync(join(dist, BAD), BAD_TEXT);
        writeFileSync(join(dist, BIG), bigLesson());
      }
      await run(context);
      console.log(`ok ${name} (${seconds(Date.now() - t)})`);
    } catch (error) {
      failed++;
      console.log(`FAILED ${name} (${seconds(Date.now() - t)}): ${error instanceof Failure ? error.message : error.stack}`);
    }
  }
} finally {
  for (const file of [WRITTEN, BAD, BIG]) rmSync(join(dist, file), { force: true });
  await browser.close();
}
for (const [key, value] of Object.entries(summary)) console.log(`  ${key}: ${value}`);
console.log(`e2e teacher's lessons: ${parts.length - failed} passed, ${failed} failed, in ${seconds(Date.now() - started)}`);
process.exit(failed === 0 ? 0 : 1);
