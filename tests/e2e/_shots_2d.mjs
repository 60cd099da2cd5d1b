// Ad-hoc screenshots: 2D collision and the 3D lesson steps (not part of the suite).
import { chromium } from 'playwright-core';
import { BASE_ARGS, WEBGPU_ARGS, waitForReport } from './browser.mjs';
const url = process.argv[2];
const [w, h] = (process.argv[3] ?? '1280x720').split('x').map(Number);
const tag = process.argv[4] ?? 'a';
const ctx = await chromium.launchPersistentContext('', { executablePath: '/usr/bin/chromium', headless: true, args: [...BASE_ARGS, ...WEBGPU_ARGS], viewport: { width: w, height: h }, deviceScaleFactor: 1 });
const page = await ctx.newPage();
page.on('console', (m) => { if (m.type() === 'error') console.log('console:', m.text()); });
async function open(search) {
  await page.goto(url + search);
  await page.waitForFunction(() => document.querySelectorAll('#lab-a11y *').length > 50, null, { timeout: 60000 });
  await page.waitForTimeout(2500);
}
async function press(role, text) {
  const ok = await page.evaluate(([role, text]) => {
    const all = [...document.querySelectorAll(`#lab-a11y [role="${role}"], #lab-a11y ${role}`)];
    const e = all.find((e) => e.textContent === text);
    if (!e) return all.map((e) => e.textContent).slice(0, 80);
    e.click(); return true;
  }, [role, text]);
  if (ok !== true) console.log('not found', role, text, JSON.stringify(ok).slice(0, 400));
  await page.waitForTimeout(800);
}
const shot = (name) => page.screenshot({ path: `/work/shots/${tag}-${name}-${w}.png` });
await open('?preset=random-segments&fresh=1&polygon=2,2,6,2,6,5,2,5');
await press('checkbox', 'Collision of two trees: the selection (A) against the other shapes (B)');
await press('button', 'First test');
for (let i = 0; i < 5; i++) await press('button', 'Next test');
await shot('2d-collision-step');
await press('button', 'All tests (the answer)');
await shot('2d-collision-all');
await open('?lesson=bounding-volumes&step=5&fresh=1');
await shot('lesson5');
await open('?lesson=bounding-volumes&step=6&fresh=1');
await shot('lesson6');
await open('?lesson=bounding-volumes&step=7&fresh=1');
await shot('lesson7');
await open('?lesson=bsp&step=2&fresh=1');
await shot('bsp2');
await ctx.close();
