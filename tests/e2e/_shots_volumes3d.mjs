// Ad-hoc screenshots of §2 in 3D (not part of the suite).
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
  await waitForReport(page, (r) => r.three?.ray || r.three?.agrees !== undefined, 120000, 'built');
  await page.waitForFunction(() => document.querySelectorAll('#lab-a11y *').length > 50, null, { timeout: 60000 });
  await page.waitForTimeout(1500);
}
async function press(role, text) {
  const ok = await page.evaluate(([role, text]) => {
    const all = [...document.querySelectorAll(`#lab-a11y [role="${role}"], #lab-a11y ${role}`)];
    const e = all.find((e) => e.textContent === text);
    if (!e) return all.map((e) => e.textContent).slice(0, 80);
    e.click(); return true;
  }, [role, text]);
  if (ok !== true) console.log('not found', role, text, JSON.stringify(ok));
  await page.waitForTimeout(800);
}
const shot = (name) => page.screenshot({ path: `/work/shots/${tag}-${name}-${w}.png` });
await open('?mesh=bunny&fresh=1');
await press('checkbox', 'Show the bounding volumes');
await page.waitForTimeout(1000);
await shot('1-mesh');
await press('checkbox', 'Slab test of the ray against the AABB (three slabs)');
await shot('2-slab');
await press('radio', 'the brush (triangles within r of q)');
await page.waitForTimeout(1000);
await shot('3-brush');
await open('?mesh=bunny&fresh=1&obbs=0,5,0,2,2,2,0,0,0,3.2,5,3.2,2,1,1,45,20,0');
await shot('4-sat');
for (let i = 0; i < 7; i++) await press('button', 'Next axis');
await shot('5-sat-edge');
await page.mouse.move(200, h - 150);
for (let i = 0; i < 2; i++) { await page.mouse.wheel(0, 400); await page.waitForTimeout(300); }
await page.waitForTimeout(800);
await shot('5b-sat-panel');
await open('?mesh=bunny&fresh=1&volumes=brush&point=2.1,5.3,-0.9');
await press('checkbox', 'Collision of two trees: the part (A) against a moved copy (B)');
await page.waitForTimeout(1000);
await shot('6-collision');
await press('button', 'First test');
for (let i = 0; i < 6; i++) await press('button', 'Next test');
await shot('7-collision-step');
await page.mouse.move(200, h - 150);
for (let i = 0; i < 3; i++) { await page.mouse.wheel(0, 400); await page.waitForTimeout(300); }
await page.waitForTimeout(800);
await shot('8-collision-panel');
await ctx.close();
