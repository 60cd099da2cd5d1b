// A tiny static file server for the lab's web page (dist/ at the repository root), with no
// dependencies: `node web/server.mjs [PORT]` (or PORT in the environment; default 8080; 0 picks
// a free port). Listens on 127.0.0.1 only and prints the address once listening.
//
// The page must not fetch anything from elsewhere at run time, so every answer carries a strict
// Content-Security-Policy (the same as index.html's meta element): 'wasm-unsafe-eval' is what
// lets the page compile its WebAssembly; no inline script or style, no eval. An inline script
// in a served page would be allowed by its hash (computed here from the file as served), never
// by 'unsafe-inline'; the lab's pages have none.
//
// Scripts and WebAssembly also carry "Access-Control-Allow-Origin: *": a course page that embeds
// the lab in an <iframe sandbox="allow-scripts"> (without allow-same-origin) gives it the origin
// "null", so its module scripts and its WebAssembly fetch are cross-origin requests, which the
// browser completes only with that header. The files are public and no cookies go with them.

import { createHash } from 'node:crypto';
import { createServer } from 'node:http';
import { readFile, stat } from 'node:fs/promises';
import { extname, join, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = resolve(fileURLToPath(new URL('../dist', import.meta.url)));
const portText = process.argv[2] ?? process.env.PORT ?? '8080';
const port = Number(portText);
if (!Number.isInteger(port) || port < 0 || port > 65535) {
  console.error(`web/server.mjs: not a port: ${portText}`);
  process.exit(2);
}

const types = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.wasm': 'application/wasm',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json; charset=utf-8',
  '.png': 'image/png',
  '.svg': 'image/svg+xml',
  '.ico': 'image/x-icon',
  '.txt': 'text/plain; charset=utf-8',
  '.toml': 'application/toml; charset=utf-8',
};

function policyFor(inlineScripts = []) {
  const hashes = inlineScripts.map(
    (script) => `'sha256-${createHash('sha256').update(script).digest('base64')}'`,
  );
  return [
    "default-src 'self'",
    ["script-src 'self' 'wasm-unsafe-eval'", ...hashes].join(' '),
    "style-src 'self'",
    "img-src 'self' data: blob:",
    "connect-src 'self' https:",
    "object-src 'none'",
    "base-uri 'none'",
    "form-action 'none'",
  ].join('; ');
}
const policy = policyFor();

// The files a frame of origin "null" loads with CORS: module scripts and the WebAssembly.
const corsExtensions = new Set(['.js', '.mjs', '.wasm']);

// The bodies of the inline <script> elements of an HTML page (those without a src attribute).
function inlineScripts(html) {
  const scripts = [];
  for (const match of html.matchAll(/<script\b([^>]*)>([\s\S]*?)<\/script>/gi)) {
    if (!/\ssrc\s*=/i.test(match[1])) scripts.push(match[2]);
  }
  return scripts;
}

function send(response, status, body, type = 'text/plain; charset=utf-8') {
  response.writeHead(status, {
    'Content-Type': type,
    'Content-Length': Buffer.byteLength(body),
    'Content-Security-Policy': policy,
    'X-Content-Type-Options': 'nosniff',
    'Cache-Control': 'no-cache',
  });
  response.end(body);
}

const server = createServer(async (request, response) => {
  if (request.method !== 'GET' && request.method !== 'HEAD') {
    send(response, 405, 'Method not allowed\n');
    return;
  }
  let path;
  try {
    path = decodeURIComponent(new URL(request.url, 'http://localhost').pathname);
  } catch {
    send(response, 400, 'Bad request\n');
    return;
  }
  if (path.includes('\0')) {
    send(response, 400, 'Bad request\n');
    return;
  }
  if (path.endsWith('/')) path += 'index.html';
  // Resolve inside dist/ and refuse anything that lands outside it ("..", encoded or not).
  const file = resolve(join(root, path));
  if (file !== root && !file.startsWith(root + sep)) {
    send(response, 403, 'Forbidden\n');
    return;
  }
  try {
    const info = await stat(file);
    if (!info.isFile()) throw Object.assign(new Error('not a file'), { code: 'ENOENT' });
    const body = await readFile(file);
    const extension = extname(file).toLowerCase();
    response.writeHead(200, {
      ...(corsExtensions.has(extension) ? { 'Access-Control-Allow-Origin': '*' } : {}),
      'Content-Type': types[extension] ?? 'application/octet-stream',
      'Content-Length': body.length,
      'Content-Security-Policy':
        extension === '.html' ? policyFor(inlineScripts(body.toString('utf8'))) : policy,
      'X-Content-Type-Options': 'nosniff',
      'Cache-Control': 'no-cache',
    });
    response.end(request.method === 'HEAD' ? undefined : body);
  } catch (error) {
    if (error.code === 'ENOENT' || error.code === 'ENOTDIR') {
      send(response, 404, 'Not found\n');
    } else {
      send(response, 500, 'Internal error\n');
    }
  }
});

server.on('error', (error) => {
  console.error(`web/server.mjs: ${error.message}`);
  if (error.code === 'EADDRINUSE') {
    console.error('Another program uses that port: pass another one (0 picks a free one).');
  }
  process.exit(1);
});
server.listen(port, '127.0.0.1', () => {
  console.log(`bvh-lab is served at http://127.0.0.1:${server.address().port}/`);
});

for (const signal of ['SIGINT', 'SIGTERM']) {
  process.on(signal, () => server.close(() => process.exit(0)));
}
