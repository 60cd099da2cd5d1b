// Helpers shared by the browser end-to-end tests (lab.test.mjs, view3d.test.mjs): Chromium's
// flags, failures, screenshots decoded to pixels, and the lab's JSON report polled from the
// page (`#lab-status[data-report]`, see index.html).

import pngjs from 'pngjs';

const { PNG } = pngjs;

// Flags from shared/SETUP.md. The background-networking ones keep Chromium from calling home
// (the network is closed); Playwright refuses --user-data-dir, hence launchPersistentContext.
export const BASE_ARGS = [
  '--no-sandbox',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
];
// WebGPU in headless Chromium without a GPU: SwiftShader's Vulkan under Dawn. With
// --enable-unsafe-webgpu alone the adapter exists but nothing is drawn. --enable-features
// replaces Playwright's own list, so its names are kept.
export const WEBGPU_ARGS = [
  '--enable-unsafe-webgpu',
  '--use-angle=swiftshader',
  '--use-vulkan=swiftshader',
  '--enable-features=Vulkan,CDPScreenshotNewSurface,SkipListAccountsWithoutGaiaCookies',
];


export class Failure extends Error {}

export function check(condition, message) {
  if (!condition) throw new Failure(message);
}

export const seconds = (ms) => `${(ms / 1000).toFixed(1)} s`;

export function decode(buffer) {
  return PNG.sync.read(buffer);
}

// The RGB colour at (x, y) of a decoded screenshot, as one number.
export function rgb(png, x, y) {
  const i = (png.width * y + x) * 4;
  return (png.data[i] << 16) | (png.data[i + 1] << 8) | png.data[i + 2];
}


// How far two colours are apart (largest channel difference).
export function colourDistance(a, b) {
  return Math.max(
    Math.abs(((a >> 16) & 255) - ((b >> 16) & 255)),
    Math.abs(((a >> 8) & 255) - ((b >> 8) & 255)),
    Math.abs((a & 255) - (b & 255)),
  );
}


// The lab's report, or an error text when the page says the lab could not start.
export async function readReport(page) {
  return page.evaluate(() => {
    const loading = document.getElementById('status');
    if (loading && loading.textContent.startsWith('The lab could not start')) {
      return { failed: loading.textContent };
    }
    const text = document.getElementById('lab-status')?.getAttribute('data-report');
    if (!text) return null;
    try {
      return { report: JSON.parse(text), text: document.getElementById('lab-status').textContent };
    } catch (error) {
      return { invalid: `${error.message}: ${text.slice(0, 200)}` };
    }
  });
}

// Polls the report until `accept(report)` holds; returns it, or throws with the last one seen.
export async function waitForReport(page, accept, timeoutMs, what) {
  const start = Date.now();
  let last = null;
  for (;;) {
    const state = await readReport(page);
    if (state?.failed) throw new Failure(`the page says: ${state.failed}`);
    if (state?.invalid) throw new Failure(`data-report is not JSON: ${state.invalid}`);
    if (state?.report) {
      last = state.report;
      if (accept(last)) return { report: last, text: state.text };
    }
    if (Date.now() - start > timeoutMs) {
      throw new Failure(
        `no ${what} after ${seconds(timeoutMs)}; last report: ${last ? JSON.stringify(last) : 'none'}`,
      );
    }
    await page.waitForTimeout(100);
  }
}

// Resolves after the page has shown `n` more animation frames.
export async function frames(page, n) {
  await page.evaluate(
    (count) =>
      new Promise((done) => {
        let left = count;
        const step = () => (--left <= 0 ? done() : requestAnimationFrame(step));
        requestAnimationFrame(step);
      }),
    n,
  );
}

// Drops a file with these bytes on the page's canvas, as a student dragging it from the desktop.
export async function dropFile(page, name, bytes) {
  await page.evaluate(
    ({ name, bytes }) => {
      const transfer = new DataTransfer();
      transfer.items.add(new File([new Uint8Array(bytes)], name));
      const canvas = document.querySelector('canvas');
      for (const type of ['dragenter', 'dragover', 'drop']) {
        canvas.dispatchEvent(new DragEvent(type, { dataTransfer: transfer, bubbles: true, cancelable: true }));
      }
    },
    { name, bytes: [...bytes] },
  );
}

/// What the live region (`#lab-status`) says, once `accept(text)` holds: it tells only the
/// news, at most every half second, so a change reaches it a moment after the report.
export async function liveRegionSays(pageOrFrame, accept, what, timeoutMs = 5_000) {
  const start = Date.now();
  for (;;) {
    const text = await pageOrFrame.evaluate(() => document.getElementById('lab-status')?.textContent ?? '');
    if (accept(text)) return text;
    if (Date.now() - start > timeoutMs) throw new Failure(`the live region never said ${what}; it says: ${text}`);
    await new Promise((done) => setTimeout(done, 100));
  }
}
