// bvh-lab for assistive technology, in the browser, as a screen reader and a keyboard meet it:
//
// 1. The page's own accessibility tree (Chromium's, read through the DevTools protocol:
//    Accessibility.getFullAXTree) holds every panel's controls with names and roles, the
//    drawing as a described application, and the tree diagram as a tree of items.
// 2. A lesson step done from that tree alone, with the keyboard: Tab until the tree says the
//    first lesson's button has the focus, Enter, read the task, do it with a key, and read
//    "met" in the tree and the live region. No mouse event reaches the canvas.
// 3. A mirrored control pressed by a DOM event (as a screen reader's "activate" does) changes
//    the lab.
// 4. Tab from a link before an embedded lab reaches the link after it; Shift+Tab comes back.
// 5. axe-core (WCAG 2.0 and 2.1, A and AA) finds no violation on the first screen, a lesson
//    step, the "Step through" panel, the 3D view and the embedding example page.
// 6. Stepping by the buttons is heard step by step; the 3D view is turned and cast by keys.
// 7. At 200% zoom on a laptop the view keeps room and the focused control is scrolled into
//    view.
//
//   node tests/e2e/a11y.test.mjs http://127.0.0.1:PORT/
//
// Screenshots go to target/e2e/ (a11y-*.png).

import { mkdirSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { BASE_ARGS, Failure, check, liveRegionSays, waitForReport } from './browser.mjs';

const url = process.argv[2] ?? process.env.LAB_URL;
if (!url) {
  console.error('usage: node tests/e2e/a11y.test.mjs http://127.0.0.1:PORT/');
  process.exit(2);
}
const here = dirname(fileURLToPath(import.meta.url));
const repo = resolve(here, '../..');
const outDir = join(repo, 'target', 'e2e');
mkdirSync(outDir, { recursive: true });
const executablePath = process.env.CHROMIUM ?? '/usr/bin/chromium';
const TIMEOUT_MS = 60_000;
const AXE = readFileSync(join(here, 'node_modules', 'axe-core', 'axe.min.js'), 'utf8');

/// The roles a person can operate.
const CONTROLS = new Set([
  'button', 'checkbox', 'radio', 'slider', 'spinbutton', 'combobox', 'textbox', 'separator',
  'application', 'link', 'tab', 'switch',
]);

/// The page's accessibility tree: its nodes that are not ignored, as {role, name, focused,
/// checked, expanded, description, node}.
async function axTree(page) {
  const cdp = await page.context().newCDPSession(page);
  const { nodes } = await cdp.send('Accessibility.getFullAXTree');
  await cdp.detach();
  const property = (n, name) => n.properties?.find((p) => p.name === name)?.value?.value;
  return nodes
    .filter((n) => !n.ignored)
    .map((n) => ({
      role: n.role?.value,
      name: n.name?.value ?? '',
      description: n.description?.value ?? '',
      focused: property(n, 'focused') === true,
      checked: property(n, 'checked'),
      expanded: property(n, 'expanded'),
      level: property(n, 'level'),
      id: n.backendDOMNodeId,
    }));
}

/// What a screen reader reads, in the page's order: each named node as "role: name", and the
/// description where there is one. Kept in target/e2e/a11y-read-<what>.txt for the notes.
function reading(tree, what) {
  const lines = tree
    .filter((n) => n.name.trim() && !['RootWebArea', 'StaticText', 'InlineTextBox'].includes(n.role))
    .map((n) => `${n.role}: ${n.name}${n.checked ? ` (checked: ${n.checked})` : ''}${n.expanded != null ? ` (expanded: ${n.expanded})` : ''}${n.description ? `\n    ${n.description}` : ''}`);
  writeFileSync(join(outDir, `a11y-read-${what}.txt`), `${lines.join('\n')}\n`);
  return lines;
}

const named = (tree, role, name) => tree.find((n) => n.role === role && n.name === name);
const report = (page) =>
  page.evaluate(() => JSON.parse(document.getElementById('lab-status').dataset.report ?? 'null'));

/// Waits until the mirror has made its elements.
async function mirrored(page) {
  await page.waitForFunction(() => document.querySelectorAll('#lab-a11y *').length > 50, null, {
    timeout: TIMEOUT_MS,
  });
  await page.waitForTimeout(500);
}

/// Presses Tab until the accessibility tree says `accept(node)` for the focused node; returns
/// it, or fails after `limit` presses.
async function tabTo(page, accept, what, limit = 200) {
  for (let i = 0; i < limit; i++) {
    await page.keyboard.press('Tab');
    await page.waitForTimeout(60);
    const focused = (await axTree(page)).filter((n) => n.focused && n.role !== 'RootWebArea').pop();
    if (focused && accept(focused)) return focused;
  }
  throw new Failure(`Tab never reached ${what} in ${limit} presses`);
}

/// Polls the accessibility tree until `accept(tree)` holds.
async function untilTree(page, accept, what, timeoutMs = 15_000) {
  const start = Date.now();
  for (;;) {
    const tree = await axTree(page);
    if (accept(tree)) return tree;
    if (Date.now() - start > timeoutMs) throw new Failure(`the accessibility tree never showed ${what}`);
    await page.waitForTimeout(200);
  }
}

/// axe-core's WCAG 2.0 and 2.1 A and AA violations on the page (and its frames).
async function axe(page) {
  for (const frame of page.frames()) {
    await frame.evaluate(AXE);
  }
  return page.evaluate(async () => {
    const result = await window.axe.run(document, {
      runOnly: { type: 'tag', values: ['wcag2a', 'wcag2aa', 'wcag21a', 'wcag21aa'] },
    });
    return result.violations.map((v) => ({
      id: v.id,
      help: v.help,
      nodes: v.nodes.slice(0, 3).map((n) => `${n.target.join(' ')}: ${n.failureSummary}`),
    }));
  });
}

async function checkAxe(page, what, summary) {
  const violations = await axe(page);
  check(
    violations.length === 0,
    `axe-core on ${what}: ${JSON.stringify(violations, null, 1).slice(0, 3000)}`,
  );
  summary.push(`axe: no violation on ${what}`);
}

async function theTree(context, summary) {
  const page = await context.newPage({ viewport: { width: 1280, height: 720 } });
  await page.goto(new URL('index.html?fresh=1', url).href);
  await mirrored(page);
  const expected = [
    ['button', 'Lessons'],
    ['button', '1. §1 Queries: why not test every primitive?'],
    ['checkbox', 'Show the bounding volumes'],
    ['radio', 'SAH'],
    ['slider', 'k nearest'],
    ['spinbutton', 'k nearest'],
    ['button', 'Undo'],
    ['tree', 'Tree diagram'],
  ];
  // The page is brought up to date every 200 ms at most: the lab may still be settling.
  let tree = await axTree(page);
  try {
    tree = await untilTree(page, (t) => expected.every(([role, name]) => named(t, role, name)), 'every control expected');
  } catch {
    // Fails below, naming what is missing.
  }
  const unnamed = tree.filter((n) => CONTROLS.has(n.role) && !n.name.trim());
  check(unnamed.length === 0, `controls without a name: ${JSON.stringify(unnamed)}`);
  for (const [role, name] of expected) {
    check(named(tree, role, name), `no ${role} named "${name}" in the accessibility tree`);
  }
  const combo = tree.find((n) => n.role === 'button' && n.name.startsWith('Preset'));
  check(combo, 'the preset chooser is named after its label and its choice');
  const drawing = tree.find((n) => n.role === 'application' && n.name.startsWith('2D view'));
  check(drawing?.description.includes('primitives'), `the drawing is described: ${JSON.stringify(drawing)}`);
  const items = tree.filter((n) => n.role === 'treeitem');
  check(items.length > 5 && items.every((n) => n.name.startsWith('node ')), `tree items: ${items.length}`);
  await page.screenshot({ path: join(outDir, 'a11y-first-screen.png') });
  reading(tree, 'first-screen');
  const controls = tree.filter((n) => CONTROLS.has(n.role)).length;
  summary.push(`accessibility tree: ${controls} named controls, ${items.length} tree items, the drawing described`);
  await checkAxe(page, 'the first screen', summary);
  await page.close();
}

async function aLessonFromTheTree(context, summary) {
  const page = await context.newPage({ viewport: { width: 1280, height: 720 } });
  let mouse = 0;
  await page.exposeFunction('countMouse', () => { mouse += 1; });
  await page.addInitScript(() => {
    for (const type of ['pointerdown', 'mousedown', 'click', 'wheel']) {
      window.addEventListener(type, (e) => {
        if (e.target?.tagName === 'CANVAS' && e.isTrusted) window.countMouse();
      }, true);
    }
  });
  await page.goto(new URL('index.html?fresh=1', url).href);
  await mirrored(page);
  const lesson = await tabTo(
    page,
    (n) => n.role === 'button' && n.name.startsWith('1. §1 Queries'),
    'the first lesson',
  );
  check(lesson, 'the first lesson button has the focus');
  await page.keyboard.press('Enter');
  let tree = await untilTree(page, (t) => t.some((n) => n.name.includes('Your task')), 'the task');
  const task = tree.find((n) => n.name.includes('press End'));
  check(task, `the task is read from the tree: ${tree.filter((n) => n.role === 'paragraph' || n.role === 'StaticText').map((n) => n.name).join(' | ').slice(0, 600)}`);
  await page.screenshot({ path: join(outDir, 'a11y-lesson.png') });
  reading(tree, 'lesson-step');
  await checkAxe(page, 'a lesson step', summary);
  // The task: step through the whole query (End). The focus is on one of the lesson's
  // buttons; End goes on to the lab.
  await page.keyboard.press('End');
  tree = await untilTree(page, (t) => t.some((n) => n.name.includes(': met)')), '"met"');
  const met = tree.filter((n) => n.name.includes(': met)')).map((n) => n.name);
  await liveRegionSays(page, (t) => t.includes('Done.'), 'the lesson step done');
  check(mouse === 0, `${mouse} mouse events reached the canvas`);
  summary.push(`lesson by keyboard from the tree: task read, End pressed, ${met.length} goal(s) met, no mouse`);

  // A mirrored control pressed by a DOM event, as a screen reader's activate.
  const toggled = await page.evaluate(() => {
    const box = [...document.querySelectorAll('#lab-a11y [role="checkbox"]')].find(
      (e) => e.textContent === 'Show the bounding volumes',
    );
    if (!box) return null;
    box.click();
    return box.id;
  });
  if (toggled) {
    tree = await untilTree(
      page,
      (t) => named(t, 'checkbox', 'Show the bounding volumes')?.checked === 'true',
      'the check box checked',
    );
    summary.push('a DOM click on the mirrored check box checked it in the lab');
  } else {
    // The lesson panel may hide the volumes' section; the step buttons are always there.
    const clicked = await page.evaluate(() => {
      const next = [...document.querySelectorAll('#lab-a11y button')].find((e) => e.textContent === 'Next');
      next?.click();
      return !!next;
    });
    check(clicked, 'a mirrored button to click');
    const r = await waitForReport(page, (r) => r.lesson?.step === 2, 10_000, 'the next step');
    summary.push(`a DOM click on the mirrored "Next" moved the lesson to step ${r.report.lesson.step}`);
  }
  await page.close();
}

async function steppingAnd3d(context, summary) {
  const page = await context.newPage({ viewport: { width: 1280, height: 720 } });
  await page.goto(new URL('index.html?fresh=1', url).href);
  await mirrored(page);
  // A ray from the keyboard: R on the drawing makes one across the middle of the view.
  await tabTo(page, (n) => n.role === 'application' && n.name.startsWith('2D view'), 'the 2D view');
  await page.keyboard.press('KeyR');
  await waitForReport(page, (r) => r.playback?.[0]?.steps > 0, 10_000, 'a ray made with R');
  // At 1280x720 the controls and "Step through" are tabs of one panel.
  await tabTo(page, (n) => n.role === 'button' && n.name === 'Step through', 'the Step through tab');
  await page.keyboard.press('Enter');
  await untilTree(page, (t) => named(t, 'button', 'next step'), 'the step buttons');
  await page.screenshot({ path: join(outDir, 'a11y-stepping.png') });
  await checkAxe(page, 'the Step through panel', summary);
  // Step the query with the "first step" and "next step" buttons, as a keyboard user does,
  // and keep what the live region and the drawing's description say at each step.
  await tabTo(page, (n) => n.role === 'button' && n.name === 'first step', 'the first step button');
  await page.keyboard.press('Enter');
  await tabTo(page, (n) => n.role === 'button' && n.name === 'next step', 'the next step button');
  const steps = [];
  for (let i = 1; i <= 3; i++) {
    await page.keyboard.press('Enter');
    await waitForReport(page, (r) => r.playback?.[0]?.step === i, 10_000, `step ${i}`);
    const tree = await untilTree(page, (t) => named(t, 'button', 'next step')?.focused, 'the focus kept on next step');
    const drawing = tree.find((n) => n.role === 'application');
    const said = await liveRegionSays(page, (t) => t.startsWith(`Step ${i} of `), `step ${i} alone`);
    check(drawing?.description.includes(`Step ${i} of `), `the drawing's description holds step ${i}: ${drawing?.description}`);
    steps.push(`step ${i}\n  live region: ${said}\n  the drawing: ${drawing?.description}`);
  }
  writeFileSync(join(outDir, 'a11y-read-stepping.txt'), `${steps.join('\n')}\n`);
  summary.push('stepped 3 steps with the next step button, the focus staying on it');

  // 3D by keyboard: Tab to the view, turn the camera with the arrows, cast with Enter.
  await page.goto(new URL('index.html?fresh=1&mesh=bunny', url).href);
  await mirrored(page);
  await untilTree(page, (t) => t.some((n) => n.role === 'application' && n.name.startsWith('3D view')), 'the 3D view');
  await waitForReport(page, (r) => r.three?.build_ms != null && r.three.building == null, TIMEOUT_MS, 'the bunny built');
  await tabTo(page, (n) => n.role === 'application' && n.name.startsWith('3D view'), 'the 3D view');
  const first = (await report(page)).three;
  for (let i = 0; i < 2; i++) await page.keyboard.press('ArrowRight');
  await page.keyboard.press('Enter');
  const { report: cast } = await waitForReport(
    page,
    (r) => r.three?.ray != null && r.three.ray.join() !== first.ray?.join(),
    10_000,
    'a ray cast with Enter after turning the camera',
  );
  check(cast.three.hit != null && cast.three.agrees === true, `the ray hits the bunny as brute force says: ${JSON.stringify(cast.three.hit)}`);
  await page.screenshot({ path: join(outDir, 'a11y-3d.png') });
  reading(await axTree(page), '3d');
  summary.push(`3D by keyboard: turned with the arrows, Enter cast a ray that hit triangle ${cast.three.hit.triangle}`);
  await checkAxe(page, 'the 3D view', summary);
  await page.close();
}

async function tabThroughAnEmbeddedLab(context, summary) {
  const page = await context.newPage({ viewport: { width: 1280, height: 900 } });
  const course = new URL('a11y-course.html', url).href;
  await page.route(course, (route) =>
    route.fulfill({
      contentType: 'text/html',
      body: `<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>A course page</title></head>
        <body><main><h1>Notes</h1><p><a id="before" href="#before">Before the lab</a></p>
        <iframe id="lab" title="bvh-lab" src="index.html?fresh=1&amp;panels=stepper" width="900" height="600"></iframe>
        <p><a id="after" href="#after">After the lab</a></p></main></body></html>`,
    }),
  );
  await page.goto(course);
  const frame = page.frameLocator('#lab');
  await frame.locator('#lab-a11y button').first().waitFor({ timeout: TIMEOUT_MS });
  await page.focus('#before');
  let presses = 0;
  let inside = 0;
  for (; presses < 300; presses++) {
    await page.keyboard.press('Tab');
    const where = await page.evaluate(() => document.activeElement?.id);
    if (where === 'lab') inside += 1;
    if (where === 'after') break;
  }
  check(presses < 300, 'Tab never left the embedded lab');
  check(inside > 3, `Tab went through the lab's controls (${inside} stops inside)`);
  await page.keyboard.press('Shift+Tab');
  const back = await page.evaluate(() => document.activeElement?.id);
  check(back === 'lab', `Shift+Tab from the link after went back into the lab (${back})`);
  summary.push(`embedded: Tab from the link before reached the link after in ${presses + 1} presses (${inside} inside the lab); Shift+Tab came back`);
  await page.goto(new URL('embed.html', url).href);
  await page.frameLocator('#left').locator('#lab-a11y button').first().waitFor({ timeout: TIMEOUT_MS });
  await page.waitForTimeout(1000);
  await checkAxe(page, 'the embedding example page', summary);
  await page.close();
}

/// A 1280x720 laptop at 200% zoom: a window of 640x360 CSS pixels at two device pixels each
/// (Chromium's own scale factor: the DevTools protocol's emulated one gives the canvas the
/// wrong size). The view and the panels keep room, and Tab brings each focused control into
/// its panel's view.
async function atTwiceTheZoom(_, summary) {
  const zoomed = await chromium.launchPersistentContext(mkdtempSync(join(tmpdir(), 'bvhlab-zoom-')), {
    executablePath,
    headless: true,
    // The window's height holds the headless browser's bars (87 px) above the page's 360.
    args: [...BASE_ARGS, '--window-size=640,447', '--force-device-scale-factor=2'],
    viewport: null,
  });
  try {
    const page = zoomed.pages()[0] ?? (await zoomed.newPage());
    await page.goto(new URL('index.html?fresh=1', url).href);
    await mirrored(page);
    const size = await page.evaluate(() => [innerWidth, innerHeight, devicePixelRatio]);
    check(size.join() === '640,360,2', `a 640x360 window at 2 device pixels per CSS pixel: ${size}`);
    const { report: r } = await waitForReport(page, (x) => x.ready, TIMEOUT_MS, 'ready');
    const [x0, y0, x1, y1] = r.canvas;
    check(x1 - x0 >= 640 * 0.45 && y1 - y0 >= 120, `the view keeps room: ${r.canvas}`);
    // The fifth lesson's button is below the panel's fold at first.
    await tabTo(page, (n) => n.role === 'button' && n.name.startsWith('5. '), 'the fifth lesson');
    await page.waitForTimeout(600);
    const shown = await page.evaluate(() => {
      const b = document.activeElement.getBoundingClientRect();
      return [b.top, b.bottom];
    });
    check(shown[0] >= 0 && shown[1] <= 360 - 40, `the focused lesson button is in view, above the status line: ${shown}`);
    await page.screenshot({ path: join(outDir, 'a11y-zoom-200.png') });
    summary.push(`200% zoom (640x360 CSS px): the view ${Math.round(x1 - x0)}x${Math.round(y1 - y0)}, the focused fifth lesson scrolled into view`);
  } finally {
    await zoomed.close();
  }
}

const context = await chromium.launchPersistentContext(mkdtempSync(join(tmpdir(), 'bvhlab-a11y-')), {
  executablePath,
  headless: true,
  args: BASE_ARGS,
  // axe-core is added to the page as a script: the lab's CSP would refuse it.
  bypassCSP: true,
});
const summary = [];
const failures = [];
for (const [name, test] of [
  ['the accessibility tree', theTree],
  ['a lesson from the tree', aLessonFromTheTree],
  ['stepping and 3D', steppingAnd3d],
  ['embedded', tabThroughAnEmbeddedLab],
  ['200% zoom', atTwiceTheZoom],
]) {
  try {
    await test(context, summary);
    console.log(`ok ${name}`);
  } catch (error) {
    failures.push(name);
    console.log(`FAILED ${name}: ${error instanceof Failure ? error.message : error.stack}`);
  }
}
await context.close();
for (const line of summary) console.log(`  ${line}`);
console.log(`e2e a11y: ${5 - failures.length} passed, ${failures.length} failed`);
process.exit(failures.length ? 1 : 0);
