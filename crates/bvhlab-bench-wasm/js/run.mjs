// The WebAssembly half of the peer comparison (issue 7): bvhlab compiled to wasm32 with SIMD128
// (the module built by compare.sh with wasm-bindgen --target nodejs) against three-mesh-bvh
// (SAH strategy) in this one node process, on the same triangles, rays and points, which the
// wasm module generates with the native comparison's workload code.
//
// Usage: node run.mjs --pkg DIR --meshes DIR --out FILE [--quick]
// Writes FILE (JSON) for the native comparison to merge into bench/RESULTS.md.

import { readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { join } from 'node:path';
import { performance } from 'node:perf_hooks';
import * as THREE from 'three';
import { MeshBVH, SAH } from 'three-mesh-bvh';

const require = createRequire(import.meta.url);
const args = process.argv.slice(2);
const arg = (name) => {
	const i = args.indexOf(name);
	return i >= 0 ? args[i + 1] : undefined;
};
const quick = args.includes('--quick');
const { WasmBench } = require(join(arg('--pkg'), 'bvhlab_bench_wasm.js'));
const meshes = arg('--meshes');
const out = arg('--out');

const REPEATS = quick ? 2 : 5;
// three-mesh-bvh answers about 40k closest-point queries a second: 100k points keep a scene's
// five repeats under a minute.
const MAX_POINTS = quick ? 20000 : 100000;
const TOLERANCE = 1e-5;
const SCENES = quick
	? [['bunny', 'stanford-bunny.obj']]
	: [['bunny', 'stanford-bunny.obj'], ['dragon', 'dragon.obj'], ['ogre', 'ogre.obj']];

/** The median of REPEATS timings of f, in seconds, and f's last result. */
function median(f) {
	const times = [];
	let result;
	for (let i = 0; i < REPEATS; i++) {
		const start = performance.now();
		result = f();
		times.push((performance.now() - start) / 1000);
	}
	times.sort((a, b) => a - b);
	return [times[Math.floor(times.length / 2)], result];
}

/** Same answer: both misses (-1), or distances within TOLERANCE relative (floor: `floor`). */
function agree(a, b, floor) {
	if (a < 0 || b < 0) return a < 0 && b < 0;
	return Math.abs(a - b) <= TOLERANCE * Math.max(Math.abs(a), Math.abs(b), floor);
}

function countDisagreements(want, have, floor) {
	let n = 0;
	for (let i = 0; i < want.length; i++) if (!agree(want[i], have[i], floor)) n++;
	return n;
}

/** three-mesh-bvh's first hits: `raycastFirst` on both sides, limited to each ray's t_max. */
function threeFirstHits(bvh, rays) {
	const ray = new THREE.Ray();
	const n = rays.length / 7;
	const out = new Float32Array(n);
	for (let i = 0; i < n; i++) {
		const k = 7 * i;
		ray.origin.set(rays[k], rays[k + 1], rays[k + 2]);
		ray.direction.set(rays[k + 3], rays[k + 4], rays[k + 5]);
		const hit = bvh.raycastFirst(ray, THREE.DoubleSide, 0, rays[k + 6]);
		out[i] = hit ? hit.distance : -1;
	}
	return out;
}

function threeClosest(bvh, points) {
	const p = new THREE.Vector3();
	const target = {};
	const n = points.length / 3;
	const out = new Float32Array(n);
	for (let i = 0; i < n; i++) {
		p.set(points[3 * i], points[3 * i + 1], points[3 * i + 2]);
		const hit = bvh.closestPointToPoint(p, target);
		out[i] = hit ? hit.distance : -1;
	}
	return out;
}

function runScene(name, file) {
	const bench = new WasmBench(readFileSync(join(meshes, file)), quick, MAX_POINTS);
	const kinds = WasmBench.kind_names();
	const positions = bench.positions();
	const points = bench.points();
	let lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
	for (let i = 0; i < positions.length; i++) {
		lo[i % 3] = Math.min(lo[i % 3], positions[i]);
		hi[i % 3] = Math.max(hi[i % 3], positions[i]);
	}
	const floor = 1e-6 * 0.5 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);

	const ours = { library: 'bvhlab 4-wide AABB tree (wasm32 + simd128)', is_bvhlab: true, mrays: {}, disagreements: {} };
	const three = { library: 'three-mesh-bvh 0.9.17 (SAH)', is_bvhlab: false, mrays: {}, disagreements: {} };

	const [ourBuild] = median(() => bench.build());
	ours.build_ms = ourBuild * 1000;
	const geometries = Array.from({ length: REPEATS }, () => {
		const g = new THREE.BufferGeometry();
		g.setAttribute('position', new THREE.BufferAttribute(positions.slice(), 3));
		return g;
	});
	let g = 0;
	let bvh;
	const [threeBuild] = median(() => (bvh = new MeshBVH(geometries[g++], { strategy: SAH })));
	three.build_ms = threeBuild * 1000;

	kinds.forEach((kind, k) => {
		const rays = bench.rays(k);
		const n = rays.length / 7;
		const [tOurs, want] = median(() => bench.first_hits(k));
		const [tThree, have] = median(() => threeFirstHits(bvh, rays));
		ours.mrays[kind] = n / tOurs / 1e6;
		three.mrays[kind] = n / tThree / 1e6;
		ours.disagreements[kind] = 0;
		three.disagreements[kind] = countDisagreements(want, have, floor);
	});
	const [cOurs, want] = median(() => bench.closest());
	const [cThree, have] = median(() => threeClosest(bvh, points));
	const m = points.length / 3;
	ours.closest_per_s = m / cOurs;
	three.closest_per_s = m / cThree;
	ours.closest_disagreements = 0;
	three.closest_disagreements = countDisagreements(want, have, floor);
	bench.free();
	for (const lib of [ours, three]) {
		const rates = kinds.map((k) => `${k} ${lib.mrays[k].toFixed(2)}`).join(', ');
		console.log(
			`${name}: ${lib.library}: build ${lib.build_ms.toFixed(1)} ms, Mrays/s ${rates}, ` +
				`closest ${(lib.closest_per_s / 1e3).toFixed(0)}k/s, disagreements ` +
				`${JSON.stringify(lib.disagreements)} closest ${lib.closest_disagreements}`,
		);
	}
	return { scene: name, triangles: positions.length / 9, points: m, libraries: [ours, three] };
}

const version = (pkg) =>
	JSON.parse(readFileSync(join(import.meta.dirname, 'node_modules', pkg, 'package.json'), 'utf8')).version;
const result = {
	node: process.version,
	three: version('three'),
	three_mesh_bvh: version('three-mesh-bvh'),
	repeats: REPEATS,
	max_points: MAX_POINTS,
	scenes: SCENES.map(([name, file]) => runScene(name, file)),
};
writeFileSync(out, JSON.stringify(result, null, 2));
console.log(`wrote ${out}`);
