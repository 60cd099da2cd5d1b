// Converts the Stanford bunny of the npm package `bunny` (public domain) into bunny.obj, the
// asset compiled into bvhlab-meshio. Run once; see README.md beside this file.
//
//   cd "$(mktemp -d)" && npm pack bunny && tar xzf bunny-1.0.1.tgz
//   node /path/to/convert-bunny.mjs package/index.js > /path/to/bunny.obj
//
// The package's index.js is a CommonJS module exporting `positions` ([x, y, z] arrays) and
// `cells` (triangles as 0-based index triples). The output is plain OBJ: one `v` line per
// position, written exactly as the package has it, and one `f` line per cell (1-based).

import { createRequire } from "node:module";
import { resolve } from "node:path";

const source = process.argv[2];
if (!source) {
  console.error("usage: node convert-bunny.mjs <path to the bunny package's index.js>");
  process.exit(2);
}
const require = createRequire(import.meta.url);
const { positions, cells } = require(resolve(source));

const lines = [
  "# The Stanford bunny (Stanford 3D Scanning Repository), as the npm package `bunny` 1.0.1",
  "# (public domain) has it; converted by convert-bunny.mjs.",
  `# ${positions.length} vertices, ${cells.length} triangles.`,
];
for (const [x, y, z] of positions) lines.push(`v ${x} ${y} ${z}`);
for (const [a, b, c] of cells) lines.push(`f ${a + 1} ${b + 1} ${c + 1}`);
process.stdout.write(lines.join("\n") + "\n");
