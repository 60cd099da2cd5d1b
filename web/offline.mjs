// Writes the single-file lab for classrooms without a server: DIR/bvh-lab-offline.html, the
// lab's page with its style, scripts and WebAssembly (as base64) inside, which runs when opened
// from disk (file://), where browsers load no module scripts and fetch no WebAssembly.
//
//   node web/offline.mjs [DIR]      (DIR: the built page, dist/ by default; web/build.sh runs it)
//
// The page keeps the lab's Content-Security-Policy, with the hashes of its own inline style and
// scripts in place of 'self' (no 'unsafe-inline', no eval; 'wasm-unsafe-eval' compiles the
// WebAssembly). The WebAssembly sits in a <script type="application/octet-stream">, which the
// browser never runs. What the student saves stays in this browser's storage for file:// pages.
import { createHash } from 'node:crypto';
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';

const dir = process.argv[2] ?? 'dist';
const read = (name) => readFileSync(join(dir, name), 'utf8');

/// `text` with `from` replaced by `to`, which must occur exactly once (the build's files
/// changed otherwise, and this script with them).
function replaceOnce(text, from, to, file) {
  const at = text.indexOf(from);
  if (at < 0 || text.indexOf(from, at + 1) >= 0) {
    throw new Error(`web/offline.mjs: expected one ${JSON.stringify(from)} in ${file}`);
  }
  return text.slice(0, at) + to + text.slice(at + from.length);
}

// wasm-bindgen's module, without its export line: the inline module below calls its init.
const bindings = replaceOnce(read('app.js'), 'export { initSync, __wbg_init as default };', '', 'app.js');
// main.js, starting the lab from the bytes inside the page instead of fetching app.js and
// app_bg.wasm.
const main = replaceOnce(
  read('main.js'),
  "const app = await import('./app.js');\n  await app.default();",
  `const base64 = document.getElementById('bvhlab-wasm').textContent.trim();
  const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
  await __wbg_init({ module_or_path: bytes });`,
  'main.js',
);
const module = `${bindings}\n${main}`;
const loader = read('loader.js');
for (const [name, text] of [['app.js and main.js', module], ['loader.js', loader]]) {
  if (/<\/script/i.test(text)) throw new Error(`web/offline.mjs: ${name} contains "</script", which would end it early`);
}
const style = read('lab.css');
const wasm = readFileSync(join(dir, 'app_bg.wasm')).toString('base64');

const hash = (text) => `'sha256-${createHash('sha256').update(text).digest('base64')}'`;
const policy = [
  "default-src 'none'",
  `script-src ${hash(loader)} ${hash(module)} 'wasm-unsafe-eval'`,
  `style-src ${hash(style)}`,
  "img-src data: blob:",
  "object-src 'none'",
  "base-uri 'none'",
  "form-action 'none'",
].join('; ');

let page = read('index.html');
page = replaceOnce(page, '<html lang="en">', '<html lang="en" data-offline>', 'index.html');
page = page.replace(
  /<meta http-equiv="Content-Security-Policy" content="[^"]*">/,
  `<meta http-equiv="Content-Security-Policy" content="${policy}">`,
);
page = replaceOnce(page, '<link rel="stylesheet" href="lab.css">', `<style>${style}</style>`, 'index.html');
page = replaceOnce(page, '<script src="loader.js"></script>', `<script>${loader}</script>`, 'index.html');
page = replaceOnce(
  page,
  '<script type="module" src="main.js"></script>',
  `<script id="bvhlab-wasm" type="application/octet-stream">${wasm}</script>\n  <script type="module">${module}</script>`,
  'index.html',
);
if (!page.includes(policy)) throw new Error('web/offline.mjs: index.html has no Content-Security-Policy to replace');
writeFileSync(join(dir, 'bvh-lab-offline.html'), page);
console.log(`Wrote ${join(dir, 'bvh-lab-offline.html')} (${(page.length / 1e6).toFixed(1)} MB): the lab in one file, for opening from disk.`);
