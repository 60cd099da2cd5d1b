// The second WebAssembly peer (issue 19): parry3d inside @dimforge/rapier3d-compat, asked as a
// rapier user asks it: one trimesh collider in a World, `Collider.castRay` and
// `Collider.projectPoint` (not `Shape.castRay`, which rebuilds the mesh on every call).
//
// Each call crosses the JS-wasm boundary and allocates (then frees) a `RawVector` per vector
// argument, so part of rapier's time is the binding's, not parry's. `overheadPerCall` measures
// that part on a one-triangle collider, where the query itself is next to free, so that
// run.mjs can report a second rate with it subtracted.

import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { dirname, join } from 'node:path';
import RAPIER from '@dimforge/rapier3d-compat';

await RAPIER.init();

const require = createRequire(import.meta.url);
const distDir = dirname(require.resolve('@dimforge/rapier3d-compat'));

/** The parry3d version compiled into rapier's wasm module (its panic paths name the crate). */
export function parryVersion() {
	const bytes = readFileSync(join(distDir, 'rapier_wasm3d_bg.wasm')).toString('latin1');
	return bytes.match(/parry3d-(\d+\.\d+\.\d+)/)?.[1] ?? '?';
}

export const rapierVersion = RAPIER.version();

/**
 * An indexed mesh from a non-indexed position buffer (9 floats per triangle), equal corners
 * merged (compared bit for bit), as a rapier user would pass it and as the native comparison
 * gives parry3d.
 */
export function indexedMesh(positions) {
	const index = new Map();
	const vertices = [];
	const indices = new Uint32Array(positions.length / 3);
	for (let c = 0; c < indices.length; c++) {
		const x = positions[3 * c], y = positions[3 * c + 1], z = positions[3 * c + 2];
		const key = `${x},${y},${z}`;
		let i = index.get(key);
		if (i === undefined) {
			i = vertices.length / 3;
			index.set(key, i);
			vertices.push(x, y, z);
		}
		indices[c] = i;
	}
	return { vertices: new Float32Array(vertices), indices };
}

/** A World holding the trimesh colliders the queries are asked of. */
export class RapierScene {
	constructor() {
		this.world = new RAPIER.World({ x: 0, y: 0, z: 0 });
	}

	/** Creates a trimesh collider (parry builds its BVH here): the timed "build". */
	build(vertices, indices) {
		return this.world.createCollider(RAPIER.ColliderDesc.trimesh(vertices, indices));
	}

	remove(collider) {
		this.world.removeCollider(collider, false);
	}

	free() {
		this.world.free();
	}
}

/**
 * `Collider.castRay` for every ray (7 floats each: origin, unit direction, t_max), `solid`
 * false as the native comparison asks parry3d (for a mesh of triangles it changes nothing);
 * the time of impact along a unit direction is the distance, `-1` a miss.
 */
export function rapierFirstHits(collider, rays) {
	return eachRay(rays, new Float32Array(rays.length / 7), (ray, tMax) => collider.castRay(ray, tMax, false));
}

/**
 * `out[i] = ask(ray i, its t_max)` for every ray (7 floats each: origin, unit direction,
 * t_max), through one reused `RAPIER.Ray` as a rapier user would write the loop.
 */
function eachRay(rays, out, ask) {
	const ray = new RAPIER.Ray({ x: 0, y: 0, z: 0 }, { x: 0, y: 0, z: 1 });
	for (let i = 0; i < out.length; i++) {
		const k = 7 * i;
		ray.origin.x = rays[k];
		ray.origin.y = rays[k + 1];
		ray.origin.z = rays[k + 2];
		ray.dir.x = rays[k + 3];
		ray.dir.y = rays[k + 4];
		ray.dir.z = rays[k + 5];
		out[i] = ask(ray, rays[k + 6]);
	}
	return out;
}

/**
 * `Collider.intersectsRay` for every ray (occlusion: blocked within t_max or not), 1 or 0.
 */
export function rapierOccluded(collider, rays) {
	return eachRay(rays, new Uint8Array(rays.length / 7), (ray, tMax) => (collider.intersectsRay(ray, tMax) ? 1 : 0));
}

/**
 * `Collider.projectPoint` for every point, `solid` false so that a point inside the (closed)
 * mesh still projects onto its surface, as the distance to the nearest triangle asks.
 */
export function rapierClosest(collider, points) {
	const p = { x: 0, y: 0, z: 0 };
	const target = new RAPIER.PointProjection({ x: 0, y: 0, z: 0 }, false);
	const n = points.length / 3;
	const out = new Float32Array(n);
	for (let i = 0; i < n; i++) {
		p.x = points[3 * i];
		p.y = points[3 * i + 1];
		p.z = points[3 * i + 2];
		const hit = collider.projectPoint(p, false, target);
		out[i] = hit ? Math.hypot(hit.point.x - p.x, hit.point.y - p.y, hit.point.z - p.z) : -1;
	}
	return out;
}

/** A collider of the first triangle alone: the per-call overhead's yardstick. */
export function oneTriangle(scene, positions) {
	return scene.build(positions.slice(0, 9), new Uint32Array([0, 1, 2]));
}
