// bvh-lab's lessons and Predict in the browser, as a student does them:
//
// 1. Keyboard only, at a laptop's 1280x720: Tab reaches the first lesson's button on a first
//    visit and Enter opens it; End reaches its goal; ] moves to the next step; R picks the ray's start and the arrow keys
//    move it (the report's ray changes); P switches Predict on, and the keys 1 and 2 answer
//    its questions, right and wrong (a wrong answer keeps the step and gives a hint, the
//    other answer then counts "after a hint"); the live region says the question and the
//    step in words.
// 2. By mouse: the same lesson's second step is done by dragging the ray with the mouse
//    until the goal is reached.
// 3. A course page receives the progress messages with Predict's exercise and score.
//
//   node tests/e2e/lesson.test.mjs http://127.0.0.1:PORT/
//
// Screenshots go to target/e2e/ (lesson-*.png).

import { mkdirSync, mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { BASE_ARGS, Failure, check, liveRegionSays, waitForReport } from './browser.mjs';

const url = process.argv[2] ?? process.env.LAB_URL;
if (!url) {
  console.error('usage: node tests/e2e/lesson.test.mjs http://127.0.0.1:PORT/');
  process.exit(2);
}
const repo = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const outDir = join(repo, 'target', 'e2e');
mkdirSync(outDir, { recursive: true });
const executablePath = process.env.CHROMIUM ?? '/usr/bin/chromium';
const TIMEOUT_MS = 60_000;

const report = (page) =>
  page.evaluate(() => JSON.parse(document.getElementById('lab-status').dataset.report ?? 'null'));

// Waits until the report satisfies `accept`; returns it.
const until = async (page, accept, timeoutMs, what) =>
  (await waitForReport(page, accept, timeoutMs, what)).report;

// Presses `key` and waits until the report satisfies `done`.
async function press(page, key, done, what) {
  await page.keyboard.press(key);
  return until(page, done, 10_000, what);
}

function watch(page, problems) {
  page.on('console', (m) => { if (m.type() === 'error') problems.push(m.text()); });
  page.on('pageerror', (e) => problems.push(e.message));
}

async function keyboardOnly(browser, summary) {
  const page = await browser.newPage({ viewport: { width: 1280, height: 720 } });
  const problems = [];
  watch(page, problems);
  await page.goto(new URL('index.html?fresh=1', url).href);
  let r = await until(page, (r) => r.ready, TIMEOUT_MS, 'the lab');
  check(!r.lesson, 'no lesson open on a first visit');
  // The page has the keyboard without a click: the lab's canvas takes the focus. Tab walks
  // the widgets in order (the panel's tabs, the Lessons header, ...); the sixth press is on
  // the first lesson's button (a visible focus ring: lesson-keyboard-focus.png), and Enter
  // presses it.
  // egui moves the focus once per frame whatever the number of Tab presses it sees in that
  // frame, so each press waits a few frames (a slow software-rendered page draws one every
  // 150-200 ms).
  await page.focus('canvas');
  const frameWait = Math.min(1000, Math.max(100, 3 * (r.frame_ms ?? 30)));
  for (let i = 0; i < 6; i++) {
    await page.keyboard.press('Tab');
    await page.waitForTimeout(frameWait);
  }
  await page.waitForTimeout(300);
  await page.screenshot({ path: join(outDir, 'lesson-keyboard-focus.png') });
  r = await press(page, 'Enter', (r) => r.lesson?.lesson === 'queries' && r.playback?.[0]?.steps > 0,
    'Tab and Enter open the first lesson');
  check(r.lesson.step === 1 && !r.lesson.goal_reached, `the step starts undone: ${JSON.stringify(r.lesson)}`);
  await page.screenshot({ path: join(outDir, 'lesson-keyboard-start.png') });
  r = await press(page, 'End', (r) => r.lesson?.goal_reached, 'End reaches the goal');
  summary.keyboardGoal = `step 1 done by End (${r.playback[0].steps} steps)`;
  r = await press(page, 'BracketRight', (r) => r.lesson?.step === 2, '] opens step 2');
  const before = r.query?.ray;
  check(before, `step 2 has a ray: ${JSON.stringify(r.query)}`);
  r = await press(page, 'KeyR', (r) => r.message?.includes('arrow keys move the ray'), 'R picks a handle');
  for (let i = 0; i < 3; i++) await page.keyboard.press('ArrowUp');
  r = await until(page, (r) => r.query?.ray && r.query.ray[1] !== before[1], 10_000, 'arrows move the ray');
  check(r.query.ray[1] > before[1], `the ray's start moved up: ${before} -> ${r.query.ray}`);
  // R again picks the ray's point s; the arrows aim the ray into the scene.
  r = await press(page, 'KeyR', (r) => r.message?.includes("ray's point s"), 'R picks s');
  for (let i = 0; i < 40; i++) await page.keyboard.press('ArrowRight');
  for (let i = 0; i < 10; i++) await page.keyboard.press('ArrowUp');
  r = await until(page, (r) => r.query?.hit, 10_000, 'a hit after aiming with the arrows');
  summary.keyboardRay = `ray start y ${before[1].toFixed(2)} -> ${r.query.ray[1].toFixed(2)} by 3 arrow presses; ` +
    `aimed with 50 presses: hits segment ${r.query.hit.primitive} at t = ${r.query.hit.t.toFixed(3)}`;

  // Predict, with the keys.
  r = await press(page, 'KeyP', (r) => r.predict && r.playback[0].step === 0, 'P switches Predict on at the start');
  let right = 0;
  let wrongThenRight = 0;
  let shown = 0;
  for (let i = 0; i < 80 && !(right >= 2 && wrongThenRight >= 1); i++) {
    r = await report(page);
    if (!r.predict.question) {
      if (r.playback[0].step >= r.playback[0].steps) break;
      r = await press(page, 'Period', (x) => x.playback[0].step > r.playback[0].step || x.predict.question, 'step on');
      continue;
    }
    const step = r.predict.question.step;
    await liveRegionSays(page, (t) => t.includes('Predict: ') && t.includes('1 '), 'the question');
    // Stepping past a question is refused.
    await page.keyboard.press('Period');
    await page.waitForTimeout(150);
    r = await report(page);
    check(r.playback[0].step === step, `"." does not skip the question: ${r.playback[0].step} vs ${step}`);
    r = await press(page, 'Digit1', (x) => x.predict.feedback, 'answer 1');
    if (r.predict.feedback.verdict === 'right') {
      right++;
      check(r.playback[0].step > step, 'a right answer shows the step');
    } else {
      check(r.predict.feedback.verdict === 'wrong' && r.playback[0].step === step,
        `a wrong answer keeps the step: ${JSON.stringify(r.predict.feedback)}`);
      check(r.predict.feedback.text.startsWith('Not quite. Hint:'), r.predict.feedback.text);
      r = await press(page, 'Digit2', (x) => x.playback[0].step > step, 'answer 2');
      if (r.predict.feedback.verdict === 'right after a hint') wrongThenRight++;
      else shown++;
    }
  }
  const score = r.predict.score;
  check(right > 0 && wrongThenRight > 0, `right ${right}, after a hint ${wrongThenRight}, shown ${shown}`);
  check(score.first_time === right && score.after_hint === wrongThenRight && score.shown === shown,
    `the score counts them: ${JSON.stringify(score)}`);
  summary.keyboardPredict = `${right} right first time, ${wrongThenRight} after a hint, ${shown} shown (${r.predict.exercise})`;
  await liveRegionSays(page, (t) => /Step \d+ of \d+: /.test(t), 'the step in words');
  await page.screenshot({ path: join(outDir, 'lesson-keyboard-predict.png') });
  check(problems.length === 0, `no errors: ${JSON.stringify(problems)}`);
  await page.close();
}

async function byMouse(browser, summary) {
  const page = await browser.newPage({ viewport: { width: 1600, height: 900 } });
  const problems = [];
  watch(page, problems);
  await page.goto(new URL('index.html?fresh=1&lesson=queries&step=2', url).href);
  let r = await until(page, (r) => r.ready && r.lesson?.step === 2, TIMEOUT_MS, 'step 2 open');
  const [x0, y0, x1, y1] = r.canvas;
  // Drags rays from the left edge towards points across the drawing area until one reaches the
  // goal (a hit with at most 6 segments tested by the tree), as a student tries.
  let tries = 0;
  for (const fy of [0.5, 0.4, 0.6, 0.3, 0.7]) {
    for (const fx of [0.5, 0.4, 0.6]) {
      tries++;
      const from = [x0 + 30, y0 + (y1 - y0) * fy];
      const to = [x0 + (x1 - x0) * fx, y0 + (y1 - y0) * (1 - fy)];
      await page.mouse.move(...from);
      await page.mouse.down();
      await page.mouse.move(...to, { steps: 8 });
      await page.mouse.up();
      await page.waitForTimeout(300);
      r = await report(page);
      if (r.lesson.goal_reached) break;
    }
    if (r.lesson.goal_reached) break;
  }
  check(r.lesson.goal_reached, `a dragged ray reached the goal: ${JSON.stringify(r.query)}`);
  summary.mouseGoal = `step 2 done by dragging the ray (${tries} drag(s)); ${r.query.primitive_tests} segments tested`;
  await page.screenshot({ path: join(outDir, 'lesson-mouse-done.png') });
  check(problems.length === 0, `no errors: ${JSON.stringify(problems)}`);
  await page.close();
}

async function coursePredict(browser, summary) {
  const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
  const problems = [];
  watch(page, problems);
  await page.goto(new URL('course.html', url).href);
  await page.waitForFunction(() => window.courseReady === true, null, { timeout: TIMEOUT_MS });
  const on = await page.evaluate(() => window.lab.predict(true));
  check(on.predict?.question, `Predict asks at once: ${JSON.stringify(on.predict)}`);
  await page.waitForFunction(() => window.progress.some((p) => p.exercise), null, { timeout: 10_000 });
  const answered = await page.evaluate(() => window.lab.answer(1));
  const settled = answered.predict.score.first_time + answered.predict.score.after_hint + answered.predict.score.shown;
  if (settled === 0) await page.evaluate(() => window.lab.answer(2));
  await page.waitForFunction(
    () => window.progress.some((p) => p.score && p.score.first_time + p.score.after_hint + p.score.shown > 0),
    null, { timeout: 10_000 });
  const last = await page.evaluate(() => window.progress.at(-1));
  check(last.lesson === 'slab-test' && last.exercise?.includes('first hit'),
    `the progress message has the lesson and the exercise: ${JSON.stringify(last)}`);
  const listed = await page.$$eval('#progress li', (items) => items.map((li) => li.textContent));
  check(listed.some((t) => t.includes('predicting ')), `the page lists the score: ${JSON.stringify(listed)}`);
  summary.course = listed.at(-1);
  await page.screenshot({ path: join(outDir, 'lesson-course-predict.png') });
  check(problems.length === 0, `no errors: ${JSON.stringify(problems)}`);
  await page.close();
}

const profile = mkdtempSync(join(tmpdir(), 'bvhlab-e2e-lesson-'));
const browser = await chromium.launchPersistentContext(profile, {
  executablePath,
  headless: true,
  args: BASE_ARGS,
  deviceScaleFactor: 1,
});
const summary = {};
let failed = 0;
const parts = [['keyboard only', keyboardOnly], ['by mouse', byMouse], ['course page', coursePredict]];
for (const [name, run] of parts) {
  try {
    await run(browser, summary);
    console.log(`ok ${name}`);
  } catch (error) {
    failed++;
    console.log(`FAILED ${name}: ${error instanceof Failure ? error.message : error.stack}`);
  }
}
await browser.close();
for (const [key, value] of Object.entries(summary)) console.log(`  ${key}: ${value}`);
console.log(`e2e lessons: ${parts.length - failed} passed, ${failed} failed`);
process.exit(failed === 0 ? 0 : 1);
