// The WebAssembly half of the peer comparison (issue 7): bvhlab compiled to wasm32 with SIMD128
// (the module built by compare.sh with wasm-bindgen --target nodejs) against three-mesh-bvh
// (SAH strategy) and parry3d inside @dimforge/rapier3d-compat (issue 19; rapier.mjs) in this
// one node process, on the same triangles, rays and points, which the wasm module generates
// with the native comparison's workload code. The ray kinds are the module's (`kind_names`).
//
// Usage: node run.mjs --pkg DIR --meshes DIR --out FILE [--quick] [--scenes bunny,ogre]
//        [--clock cpu]
// Writes FILE (JSON) for the native comparison to merge into bench/RESULTS.md.
//
// `--clock cpu` times with the process's CPU time (user + system, every thread of node)
// instead of the wall clock: on a machine other jobs share, the wall clock counts their time
// slices too, while the CPU time of a process pinned to one core (taskset) counts what a
// quiet machine's wall clock would, less the other jobs' cache damage.

import { readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { join } from 'node:path';
import { performance } from 'node:perf_hooks';
import * as THREE from 'three';
import { MeshBVH, SAH } from 'three-mesh-bvh';
import {
	RapierScene,
	indexedMesh,
	oneTriangle,
	parryVersion,
	rapierClosest,
	rapierFirstHits,
	rapierOccluded,
	rapierVersion,
} from './rapier.mjs';

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
/** The column of the shadow rays asked as occlusion (any hit). */
const OCCLUSION = 'shadow as occlusion';
const ALL_SCENES = [['bunny', 'stanford-bunny.obj'], ['dragon', 'dragon.obj'], ['ogre', 'ogre.obj']];
const only = arg('--scenes')?.split(',');
const SCENES = only
	? ALL_SCENES.filter(([name]) => only.includes(name))
	: ALL_SCENES.slice(0, quick ? 1 : ALL_SCENES.length);

const CLOCK = arg('--clock') ?? 'wall';
if (CLOCK !== 'wall' && CLOCK !== 'cpu') throw new Error(`--clock ${CLOCK}: use wall or cpu`);
/** Milliseconds on the chosen clock. */
const now =
	CLOCK === 'cpu'
		? () => {
				const { user, system } = process.cpuUsage();
				return (user + system) / 1000;
			}
		: () => performance.now();

/**
 * Times each of `fs` REPEATS times, round robin, so that a change in the machine's load falls
 * on every library alike; returns, for each, its median time in seconds and its last result.
 */
function medians(fs) {
	const times = fs.map(() => []);
	const results = [];
	for (let i = 0; i < REPEATS; i++) {
		fs.forEach((f, j) => {
			const start = now();
			results[j] = f();
			times[j].push((now() - start) / 1000);
		});
	}
	return times.map((t, j) => {
		t.sort((a, b) => a - b);
		return [t[Math.floor(t.length / 2)], results[j]];
	});
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

/**
 * A rate as called (`count` queries in `seconds`) and with the binding's per-call overhead
 * subtracted (`yardstick`: the same calls on a one-triangle collider, in seconds); `net` is
 * null when the overhead is not below the time (nothing left to rate).
 */
function rates(count, seconds, yardstick) {
	const net = seconds - yardstick;
	return { gross: count / seconds, net: net > 0 ? count / net : null, overheadUs: (yardstick / count) * 1e6 };
}

/** The bounding box's half diagonal times 1e-6: the floor of the relative tolerance. */
function distanceFloor(positions) {
	const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
	for (let i = 0; i < positions.length; i++) {
		lo[i % 3] = Math.min(lo[i % 3], positions[i]);
		hi[i % 3] = Math.max(hi[i % 3], positions[i]);
	}
	return 1e-6 * 0.5 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
}

/** The three libraries' rows, before their numbers. */
function libraryRows() {
	const row = (library, extra = {}) => ({ library, is_bvhlab: false, mrays: {}, disagreements: {}, ...extra });
	return {
		ours: row('bvhlab 4-wide AABB tree (wasm32 + simd128)', { is_bvhlab: true }),
		three: row(`three-mesh-bvh ${version('three-mesh-bvh')} (SAH)`),
		rapier: row(`rapier3d-compat ${rapierVersion} (parry3d ${parryVersion()} trimesh collider)`, {
			mrays_net: {},
			overhead_us: {},
		}),
	};
}

/**
 * Builds each library's structure REPEATS times (interleaved) and returns what answers the
 * queries: three-mesh-bvh's MeshBVH and rapier's trimesh collider, with the one-triangle
 * collider whose calls measure rapier's per-call overhead.
 */
function buildAll(bench, positions, rapierScene, { ours, three, rapier }) {
	const geometries = Array.from({ length: REPEATS }, () => {
		const g = new THREE.BufferGeometry();
		g.setAttribute('position', new THREE.BufferAttribute(positions.slice(), 3));
		return g;
	});
	const { vertices, indices } = indexedMesh(positions);
	let g = 0;
	let bvh;
	// One collider per repeat, each timed from the descriptor to the collider in the World.
	const colliders = [];
	const [[tOurs], [tThree], [tRapier]] = medians([
		() => bench.build(),
		() => (bvh = new MeshBVH(geometries[g++], { strategy: SAH })),
		() => colliders.push(rapierScene.build(vertices, indices)),
	]);
	ours.build_ms = tOurs * 1000;
	three.build_ms = tThree * 1000;
	rapier.build_ms = tRapier * 1000;
	const collider = colliders.pop();
	for (const c of colliders) rapierScene.remove(c);
	return { bvh, collider, tiny: oneTriangle(rapierScene, positions) };
}

function runScene(name, file) {
	const bench = new WasmBench(readFileSync(join(meshes, file)), quick, MAX_POINTS);
	const kinds = WasmBench.kind_names();
	const positions = bench.positions();
	const points = bench.points();
	const floor = distanceFloor(positions);
	const rows = libraryRows();
	const { ours, three, rapier } = rows;
	const rapierScene = new RapierScene();
	const { bvh, collider, tiny } = buildAll(bench, positions, rapierScene, rows);

	// bvhlab's answers are the ones the peers' are checked against.
	kinds.forEach((kind, k) => {
		const rays = bench.rays(k);
		const n = rays.length / 7;
		const [[tOurs, want], [tThree, haveThree], [tRapier, haveRapier], [yardstick]] = medians([
			() => bench.first_hits(k),
			() => threeFirstHits(bvh, rays),
			() => rapierFirstHits(collider, rays),
			() => rapierFirstHits(tiny, rays),
		]);
		const r = rates(n, tRapier, yardstick);
		ours.mrays[kind] = n / tOurs / 1e6;
		three.mrays[kind] = n / tThree / 1e6;
		rapier.mrays[kind] = r.gross / 1e6;
		rapier.mrays_net[kind] = r.net === null ? null : r.net / 1e6;
		rapier.overhead_us[kind] = r.overheadUs;
		ours.disagreements[kind] = 0;
		three.disagreements[kind] = countDisagreements(want, haveThree, floor);
		rapier.disagreements[kind] = countDisagreements(want, haveRapier, floor);
	});
	// The shadow rays again as occlusion (any hit): bvhlab's any-hit walk and rapier's
	// `intersectsRay`; three-mesh-bvh has no such call. Verdicts are checked against
	// bvhlab's first hits.
	const shadow = kinds.indexOf('shadow');
	if (shadow >= 0) {
		const rays = bench.rays(shadow);
		const n = rays.length / 7;
		const first = bench.first_hits(shadow);
		// One untimed call each first: the other kinds warmed their first-hit calls up.
		bench.any_hits(shadow);
		rapierOccluded(collider, rays);
		rapierOccluded(tiny, rays);
		const [[tOurs, oursBlocked], [tRapier, rapierBlocked], [yardstick]] = medians([
			() => bench.any_hits(shadow),
			() => rapierOccluded(collider, rays),
			() => rapierOccluded(tiny, rays),
		]);
		const wrong = (blocked) => first.reduce((sum, t, i) => sum + ((t >= 0) !== (blocked[i] === 1) ? 1 : 0), 0);
		const r = rates(n, tRapier, yardstick);
		ours.mrays[OCCLUSION] = n / tOurs / 1e6;
		rapier.mrays[OCCLUSION] = r.gross / 1e6;
		rapier.mrays_net[OCCLUSION] = r.net === null ? null : r.net / 1e6;
		rapier.overhead_us[OCCLUSION] = r.overheadUs;
		ours.disagreements[OCCLUSION] = wrong(oursBlocked);
		rapier.disagreements[OCCLUSION] = wrong(rapierBlocked);
	}
	const m = points.length / 3;
	const [[cOurs, want], [cThree, haveThree], [cRapier, haveRapier], [yardstick]] = medians([
		() => bench.closest(),
		() => threeClosest(bvh, points),
		() => rapierClosest(collider, points),
		() => rapierClosest(tiny, points),
	]);
	const r = rates(m, cRapier, yardstick);
	ours.closest_per_s = m / cOurs;
	three.closest_per_s = m / cThree;
	rapier.closest_per_s = r.gross;
	rapier.closest_per_s_net = r.net;
	rapier.overhead_us.closest = r.overheadUs;
	ours.closest_disagreements = 0;
	three.closest_disagreements = countDisagreements(want, haveThree, floor);
	rapier.closest_disagreements = countDisagreements(want, haveRapier, floor);
	rapierScene.free();
	bench.free();
	printScene(name, kinds.concat(shadow >= 0 ? [OCCLUSION] : []), rows);
	return { scene: name, triangles: positions.length / 9, points: m, libraries: [ours, three, rapier] };
}

function printScene(name, kinds, { ours, three, rapier }) {
	const fixed = (x, d) => (x === null ? 'n/a' : x.toFixed(d));
	for (const lib of [ours, three, rapier]) {
		const rates = kinds.map((k) => `${k} ${fixed(lib.mrays[k] ?? null, 2)}`).join(', ');
		console.log(
			`${name}: ${lib.library}: build ${lib.build_ms.toFixed(1)} ms, Mrays/s ${rates}, ` +
				`closest ${(lib.closest_per_s / 1e3).toFixed(0)}k/s, disagreements ` +
				`${JSON.stringify(lib.disagreements)} closest ${lib.closest_disagreements}`,
		);
	}
	const overhead = Object.entries(rapier.overhead_us).map(([k, us]) => `${k} ${us.toFixed(2)}`);
	const net = kinds.map((k) => `${k} ${fixed(rapier.mrays_net[k], 2)}`);
	const closest = rapier.closest_per_s_net === null ? null : rapier.closest_per_s_net / 1e3;
	console.log(
		`${name}: rapier less its per-call overhead (µs per call: ${overhead.join(', ')}): ` +
			`Mrays/s ${net.join(', ')}, closest ${fixed(closest, 0)}k/s`,
	);
}

function version(pkg) {
	return JSON.parse(readFileSync(join(import.meta.dirname, 'node_modules', pkg, 'package.json'), 'utf8')).version;
}
const result = {
	node: process.version,
	three: version('three'),
	three_mesh_bvh: version('three-mesh-bvh'),
	rapier: rapierVersion,
	parry: parryVersion(),
	// The ray kinds, and the shadow rays asked as occlusion.
	kinds: WasmBench.kind_names().concat([OCCLUSION]),
	clock: CLOCK,
	repeats: REPEATS,
	max_points: MAX_POINTS,
	scenes: SCENES.map(([name, file]) => runScene(name, file)),
};
writeFileSync(out, JSON.stringify(result, null, 2));
console.log(`wrote ${out}`);
