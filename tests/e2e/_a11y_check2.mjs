import { chromium } from 'playwright-core';
import { BASE_ARGS } from './browser.mjs';
const url = process.argv[2];
const ctx = await chromium.launchPersistentContext('', { executablePath: '/usr/bin/chromium', headless: true, args: BASE_ARGS, viewport: { width: 1280, height: 720 } });
const page = await ctx.newPage();
await page.goto(url + '?mesh=bunny&fresh=1&volumes=brush');
await page.waitForFunction(() => document.querySelectorAll('#lab-a11y *').length > 50, null, { timeout: 60000 });
await page.waitForTimeout(2500);
const clicked = await page.evaluate(() => {
  const e = [...document.querySelectorAll('#lab-a11y [role="checkbox"]')].find((e) => e.textContent.startsWith('Collision of two trees'));
  e?.click(); return !!e;
});
await page.waitForTimeout(2500);
const cdp = await ctx.newCDPSession(page);
const { nodes } = await cdp.send('Accessibility.getFullAXTree');
const names = nodes.filter((n) => !n.ignored && ['spinbutton', 'button', 'checkbox', 'radio'].includes(n.role?.value)).map((n) => `${n.role.value}: ${n.name?.value ?? ''} ${n.value?.value ?? ''}`);
console.log('clicked', clicked);
console.log(names.filter((s) => /moved|turned|test|Collision|trees/.test(s)).join('\n'));
await ctx.close();
