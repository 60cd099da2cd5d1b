// Reports the web build's download size: each file of dist/ as served, gzip-compressed
// (level 9) and Brotli-compressed (quality 11), as a browser fetching it from a server that
// compresses would receive it. `node web/size.mjs [DIR]`; writes DIR/size.json as well.
import { readdirSync, readFileSync, writeFileSync, statSync } from 'node:fs';
import { join } from 'node:path';
import { brotliCompressSync, gzipSync, constants } from 'node:zlib';

const dir = process.argv[2] ?? 'dist';
const files = readdirSync(dir)
  .filter((name) => name !== 'size.json' && statSync(join(dir, name)).isFile())
  .sort();
const rows = files.map((name) => {
  const bytes = readFileSync(join(dir, name));
  return {
    name,
    bytes: bytes.length,
    gzip: gzipSync(bytes, { level: 9 }).length,
    brotli: brotliCompressSync(bytes, {
      params: { [constants.BROTLI_PARAM_QUALITY]: 11, [constants.BROTLI_PARAM_SIZE_HINT]: bytes.length },
    }).length,
  };
});
const lab = rows.filter((r) => ['index.html', 'loader.js', 'main.js', 'lab.css', 'app.js', 'app_bg.wasm'].includes(r.name));
const total = (key, list) => list.reduce((sum, r) => sum + r[key], 0);
const mb = (n) => (n >= 1e6 ? `${(n / 1e6).toFixed(2)} MB` : `${(n / 1e3).toFixed(1)} kB`);
for (const r of rows) {
  console.log(`  ${r.name.padEnd(18)} ${mb(r.bytes).padStart(9)}  gzip ${mb(r.gzip).padStart(9)}  brotli ${mb(r.brotli).padStart(9)}`);
}
const summary = {
  bytes: total('bytes', lab),
  gzip: total('gzip', lab),
  brotli: total('brotli', lab),
};
console.log(`The lab's page downloads ${mb(summary.bytes)} (${mb(summary.gzip)} gzip, ${mb(summary.brotli)} Brotli).`);
writeFileSync(join(dir, 'size.json'), JSON.stringify({ lab: summary, files: rows }, null, 2) + '\n');
