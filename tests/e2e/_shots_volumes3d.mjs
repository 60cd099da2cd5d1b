// Ad-hoc screenshots of §2 in 3D (not part of the suite).
import { chromium } from 'playwright-core';
import { BASE_ARGS, WEBGPU_ARGS, waitForReport } from './browser.mjs';
const url = process.argv[2];
const [w, h] = (process.argv[3] ?? '1280x720').split('x').map(Number);
const tag = process.argv[4] ?? 'a';
const ctx = await chromium.launchPersistentContext('', { executablePath: '/usr/bin/chromium', headless: true, args: [...BASE_ARGS, ...WEBGPU_ARGS], viewport: { width: w, height: h }, deviceScaleFactor: 1 });
const page = await ctx.newPage();
page.on('console', (m) => { if (m.type() === 'error') console.log('console:', m.text()); });
await page.goto(url + '?mesh=bunny');
await waitForReport(page, (r) => r.three?.ray || r.three?.agrees !== undefined, 120000, 'built');
await page.waitForFunction(() => document.querySelectorAll('#lab-a11y *').length > 50, null, { timeout: 60000 });
await page.waitForTimeout(1000);
async function press(role, text) {
  const ok = await page.evaluate(([role, text]) => {
    const e = [...document.querySelectorAll(`#lab-a11y [role="${role}"], #lab-a11y ${role}`)].find((e) => e.textContent === text);
    if (!e) return [...document.querySelectorAll(`#lab-a11y [role="${role}"], #lab-a11y ${role}`)].map((e) => e.textContent).slice(0, 80);
    e.click(); return true;
  }, [role, text]);
  if (ok !== true) console.log('not found', role, text, JSON.stringify(ok));
  await page.waitForTimeout(800);
}
await press('checkbox', 'Show the bounding volumes');
await page.waitForTimeout(1500);
await page.screenshot({ path: `/work/shots/${tag}-1-mesh-${w}.png` });
await press('checkbox', 'Slab test of the ray against the AABB (three slabs)');
await page.screenshot({ path: `/work/shots/${tag}-2-slab-${w}.png` });
await press('radio', 'the brush (triangles within r of q)');
await page.waitForTimeout(1500);
await page.screenshot({ path: `/work/shots/${tag}-3-brush-${w}.png` });
await press('checkbox', 'Separating-axis test of two OBBs (15 axes)');
await page.waitForTimeout(1500);
await page.screenshot({ path: `/work/shots/${tag}-4-sat-${w}.png` });
for (let i = 0; i < 7; i++) await press('button', 'Next axis');
await page.screenshot({ path: `/work/shots/${tag}-5-sat-edge-${w}.png` });
await ctx.close();
