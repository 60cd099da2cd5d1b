// A student's walk through every lesson, for a person to look at (issue 29); not a gate, so
// `check.sh` does not run it. Each step of each lesson, one after the other in one page, as
// the lesson panel's Next does: the step as it opens (screenshot `...-open.png`), then its
// solution done through the embed API where it is a ray, a point or a structure, played to
// the end (`...-done.png`). It runs at 1280x720 and 1600x900 with the lab filling the
// window, and in an 800x500 iframe inside a 1280x720 page, and writes `walk.md`: per step,
// whether the goal showed reached on arrival (it must not) and after the solution.
//
//   node tests/e2e/walk.mjs http://127.0.0.1:PORT/ [OUT_DIR]
//
// OUT_DIR defaults to target/e2e/walk.

import { mkdirSync, readFileSync, readdirSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { BASE_ARGS, WEBGPU_ARGS } from './browser.mjs';

const url = process.argv[2] ?? process.env.LAB_URL;
if (!url) {
  console.error('usage: node tests/e2e/walk.mjs http://127.0.0.1:PORT/ [OUT_DIR]');
  process.exit(2);
}
const repo = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const outDir = process.argv[3] ?? join(repo, 'target', 'e2e', 'walk');
mkdirSync(outDir, { recursive: true });

// The lessons, in order, each with its steps' solutions (the lesson files' `solution`
// lines, read as the address's words).
function lessons() {
  const folder = join(repo, 'crates', 'bvhlab-app', 'lessons');
  return readdirSync(folder)
    .filter((f) => f.endsWith('.toml'))
    .sort()
    .map((file) => {
      const text = readFileSync(join(folder, file), 'utf8');
      const steps = text.split(/^\[\[step\]\]$/m).slice(1).map((step) => {
        const solution = step.match(/^solution = "(.*)"$/m)?.[1];
        // Predict's answers are given by hand (or by lesson.test.mjs), not here.
        if (solution === undefined || /^goal = .*predicted/m.test(step)) return null;
        return Object.fromEntries(new URLSearchParams(solution));
      });
      return { name: file.replace(/^\d+-/, '').replace(/\.toml$/, ''), steps };
    });
}

// The embed API's commands that do `solution`, or null when it needs more than they offer
// (a polygon, the demo's boxes, a split method, Predict's answers).
function commands(solution) {
  if (!solution) return null;
  const out = [];
  for (const [key, value] of Object.entries(solution)) {
    const n = value.split(',').map(Number);
    if (key === 'ray') {
      const half = n.length / 2;
      out.push({ type: 'set-ray', origin: n.slice(0, half), direction: n.slice(half) });
    } else if (key === 'point') out.push({ type: 'set-point', point: n });
    else if (key === 'structure') out.push({ type: 'set-structure', structure: value });
    else return null;
  }
  return out;
}

const host = (width, height) => `<!DOCTYPE html><html><head><style>
  body { margin: 0; background: #ddd; font: 14px sans-serif; }
  iframe { border: 0; display: block; width: ${width}; height: ${height}; }
  p { margin: 8px; }
</style></head><body>
${width === '100vw' ? '' : '<p>A course page with the lab in an 800x500 frame:</p>'}
<iframe id="lab" src="index.html?fresh=1&lab=walk" title="bvh-lab"></iframe>
<script type="module">
  import { BvhLab } from './bvhlab-embed.js';
  window.lab = new BvhLab(document.getElementById('lab'));
</script></body></html>`;

const cases = [
  { name: '1280x720', viewport: { width: 1280, height: 720 }, frame: ['100vw', '100vh'] },
  { name: '1600x900', viewport: { width: 1600, height: 900 }, frame: ['100vw', '100vh'] },
  { name: 'iframe-800x500', viewport: { width: 1280, height: 720 }, frame: ['800px', '500px'] },
];

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
  args: [...BASE_ARGS, ...WEBGPU_ARGS],
});
const lines = ['# The walk', ''];
const problems = [];
for (const c of cases) {
  const page = await browser.newPage({ viewport: c.viewport });
  page.on('pageerror', (e) => problems.push(`${c.name}: page error: ${e.message}`));
  const hostUrl = new URL('walk-host.html', url).href;
  await page.route(hostUrl, (route) =>
    route.fulfill({ contentType: 'text/html', body: host(...c.frame) }));
  await page.goto(hostUrl);
  await page.waitForFunction(() => window.lab);
  await page.evaluate(() => window.lab.ready(120000));
  const send = (command) => page.evaluate((cmd) => window.lab.send(cmd), command);
  const settle = () => page.waitForTimeout(1500);
  lines.push(`## ${c.name}`, '', '| lesson | step | open: reached? | solution | after: reached? |', '| --- | --- | --- | --- | --- |');
  for (const lesson of lessons()) {
    for (const [index, solution] of lesson.steps.entries()) {
      const base = join(outDir, `${c.name}-${lesson.name}-s${index + 1}`);
      let report = await send({ type: 'go-to-lesson', lesson: lesson.name, step: index + 1 });
      await settle();
      report = await send({ type: 'report' });
      await page.screenshot({ path: `${base}-open.png` });
      const open = report.lesson?.goal_reached;
      const todo = commands(solution);
      let after = 'not done here';
      if (todo) {
        for (const command of todo) await send(command);
        await send({ type: 'go-to-step', step: 1e9 });
        await settle();
        report = await send({ type: 'report' });
        after = String(report.lesson?.goal_reached);
        await page.screenshot({ path: `${base}-done.png` });
      }
      if (open) problems.push(`${c.name}: ${lesson.name} step ${index + 1} shows reached on arrival`);
      if (after === 'false') problems.push(`${c.name}: ${lesson.name} step ${index + 1}: its solution does not reach it`);
      lines.push(`| ${lesson.name} | ${index + 1} | ${open} | ${todo ? 'done by the embed API' : 'by hand'} | ${after} |`);
    }
  }
  lines.push('');
  await page.close();
}
await browser.close();
lines.push('## Problems', '', ...(problems.length ? problems.map((p) => `- ${p}`) : ['none']));
writeFileSync(join(outDir, 'walk.md'), `${lines.join('\n')}\n`);
console.log(lines.join('\n'));
process.exit(problems.length ? 1 : 0);
