// The traversal-cost heat map: one invocation per pixel casts the pixel's ray through the
// flattened AABB tree exactly as the core's `Bvh::first_hit` does (bvhlab's
// structure/bvh/walk/ray.rs and walk/stack.rs, structure/bvh/volume/aabb.rs and mod.rs,
// primitive/triangle.rs) and counts the nodes it enters and the triangles it tests.
//
// `Node` and `Tri` are the core's `GpuNode` and `GpuTriangle` (structure/bvh/layout/gpu.rs),
// and `STACK` its MAX_DEPTH + 2: tests/shaders.rs fails when they drift apart.
//
// Agreement with the CPU, bit for bit, rests on four rules (heatmap/mod.rs explains them):
// every f32 operation is one the core performs, in the same order; a product that the core
// rounds before adding goes through `rounded`, so that no compiler fuses it into a
// multiply-add; divisions and the core's f64 steps use the exact integer arithmetic of
// exact.wgsl; and no infinity times zero is ever evaluated (the core's NaN cases are decided
// by explicit comparisons).

// The core's `GpuNode`.
struct Node {
    min: vec3<f32>,
    // Leaf: first triangle (leaf order). Inner node: second child.
    start: u32,
    max: vec3<f32>,
    // Leaf: triangle count. Inner node: 0.
    count: u32,
}

// The core's `GpuTriangle`.
struct Tri {
    a: vec3<f32>,
    // The triangle's input index.
    id: u32,
    b: vec3<f32>,
    // Bit 0: degenerate (zero area), never hit.
    flags: u32,
    c: vec3<f32>,
    pad: u32,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> nodes: array<Node>;
@group(0) @binding(2) var<storage, read> tris: array<Tri>;
@group(0) @binding(3) var<storage, read_write> traces: array<Trace>;
@group(0) @binding(4) var<storage, read_write> maxima: array<atomic<u32>, 2>;

const NO_HIT: u32 = 0xffffffffu;
// The core's stack capacity: MAX_DEPTH + 2.
const STACK: u32 = 66u;

// `x`, rounded to f32 as a value of its own: OR-ing the bits with a zero the compiler cannot
// see stops it from fusing the product that made `x` with the addition that uses it (an FMA
// rounds once, the core twice).
fn rounded(x: f32) -> f32 {
    return bitcast<f32>(bitcast<u32>(x) | params.zero);
}

// A pixel's ray with what the core's node and triangle tests precompute from it.
struct Ray {
    origin: vec3<f32>,
    dir: vec3<f32>,
    // 1 / dir per axis, where finite.
    inv: vec3<f32>,
    // Per axis: the direction's sign bit (the core's `PreparedRay::negative`).
    neg: vec3<bool>,
    // Per axis: 1 / dir is infinite (dir is ±0).
    flat: vec3<bool>,
    // The core's `origin_near` and `origin_far`.
    near_origin: vec3<f32>,
    far_origin: vec3<f32>,
    // The watertight test's axes and shear (`Triangle3::ray_hit`).
    kx: u32,
    ky: u32,
    kz: u32,
    sx: f32,
    sy: f32,
    sz: f32,
}

// The ray through pixel (x, y) of the frame (`RayFrame::direction`).
fn pixel_ray(x: u32, y: u32) -> Ray {
    let fx = f32(x) + 0.5;
    let fy = f32(y) + 0.5;
    let c = params.corner.xyz;
    let sx = params.step_x.xyz;
    let sy = params.step_y.xyz;
    let dir = vec3<f32>(
        (c.x + rounded(sx.x * fx)) + rounded(sy.x * fy),
        (c.y + rounded(sx.y * fx)) + rounded(sy.y * fy),
        (c.z + rounded(sx.z * fx)) + rounded(sy.z * fy),
    );
    return prepare_ray(params.origin.xyz, params.origin_plus.xyz, params.origin_minus.xyz, dir);
}

// What `Ray::new`, `PreparedRay::new` and `Triangle3::ray_hit` derive from a ray; `plus` and
// `minus` are the origin moved up and down by the query's slack.
fn prepare_ray(origin: vec3<f32>, plus: vec3<f32>, minus: vec3<f32>, dir: vec3<f32>) -> Ray {
    var r: Ray;
    r.origin = origin;
    r.dir = dir;
    for (var i = 0; i < 3; i++) {
        let d = r.dir[i];
        r.neg[i] = (bitcast<u32>(d) >> 31u) != 0u;
        var flat = (bitcast<u32>(d) & 0x7fffffffu) == 0u;
        if !flat {
            let q = f32_div(1.0, d);
            flat = !q.finite;
            r.inv[i] = bitcast<f32>(q.bits);
        }
        r.flat[i] = flat;
        r.near_origin[i] = select(plus[i], minus[i], r.neg[i]);
        r.far_origin[i] = select(minus[i], plus[i], r.neg[i]);
    }
    // kz: the dominant axis (first of equals); kx, ky follow it, swapped when dir[kz] < 0.
    let ad = abs(r.dir);
    var kz = 0u;
    var largest = ad.x;
    if ad.y > largest {
        largest = ad.y;
        kz = 1u;
    }
    if ad.z > largest {
        kz = 2u;
    }
    var kx = (kz + 1u) % 3u;
    var ky = (kx + 1u) % 3u;
    if r.dir[kz] < 0.0 {
        let swap = kx;
        kx = ky;
        ky = swap;
    }
    r.kx = kx;
    r.ky = ky;
    r.kz = kz;
    r.sx = bitcast<f32>(f32_div(r.dir[kx], r.dir[kz]).bits);
    r.sy = bitcast<f32>(f32_div(r.dir[ky], r.dir[kz]).bits);
    r.sz = bitcast<f32>(f32_div(1.0, r.dir[kz]).bits);
    return r;
}

// The core's slab test (`Aabb::ray_entry`): the entry t, or −1 for a miss.
fn box_entry(r: Ray, lo: vec3<f32>, hi: vec3<f32>) -> f32 {
    var t_enter = 0.0;
    var t_exit = params.inf;
    for (var i = 0; i < 3; i++) {
        let neg = r.neg[i];
        let near = select(lo[i], hi[i], neg);
        let far = select(hi[i], lo[i], neg);
        let dn = near - r.near_origin[i];
        let df = far - r.far_origin[i];
        if r.flat[i] {
            // dn · (±∞): +∞ when dn has the infinity's sign (the ray starts before the slab
            // and never reaches it), −∞ for the other sign, NaN for zero; only +∞ moves the
            // entry (to +∞). Likewise only −∞ moves the exit.
            if (dn > 0.0 && !neg) || (dn < 0.0 && neg) {
                t_enter = params.inf;
            }
            if (df < 0.0 && !neg) || (df > 0.0 && neg) {
                t_exit = -params.inf;
            }
        } else {
            let t_near = dn * r.inv[i];
            let t_far = df * r.inv[i];
            if t_near > t_enter {
                t_enter = t_near;
            }
            if t_far < t_exit {
                t_exit = t_far;
            }
        }
    }
    if t_enter <= t_exit * params.grow {
        return t_enter;
    }
    return -1.0;
}

// A corner relative to the origin in the ray's sheared frame.
fn shear(r: Ray, p: vec3<f32>) -> vec3<f32> {
    let q = p - r.origin;
    return vec3<f32>(
        q[r.kx] - rounded(r.sx * q[r.kz]),
        q[r.ky] - rounded(r.sy * q[r.kz]),
        r.sz * q[r.kz],
    );
}

// The core's edge function p.x · q.y − p.y · q.x, products exact, difference rounded to f64.
fn edge(p: vec3<f32>, q: vec3<f32>) -> F64 {
    let l = f64_mul(f64_from_f32(p.x), f64_from_f32(q.y));
    let r = f64_mul(f64_from_f32(p.y), f64_from_f32(q.x));
    return f64_sub(l, r);
}

// The sign (−1, 0 or 1) of the edge function, exactly. Rounding to f32 never reverses the
// order of two products (it is monotonic; so is flushing to zero), so two f32 products that
// differ decide it; only equal ones need the exact difference.
fn edge_sign(p: vec3<f32>, q: vec3<f32>) -> i32 {
    let l = p.x * q.y;
    let r = p.y * q.x;
    if l > r {
        return 1;
    }
    if l < r {
        return -1;
    }
    let e = edge(p, q);
    if f64_is_zero(e) {
        return 0;
    }
    return select(1, -1, e.neg);
}

struct TriHit {
    hit: bool,
    t: f32,
}

// `Triangle3::ray_hit` (Woop, Benthin and Wald, "Watertight Ray/Triangle Intersection",
// JCGT 2013, with the edge functions and t in f64).
fn ray_triangle(r: Ray, tri: Tri) -> TriHit {
    let miss = TriHit(false, 0.0);
    let a = shear(r, tri.a);
    let b = shear(r, tri.b);
    let c = shear(r, tri.c);
    let su = edge_sign(c, b);
    let sv = edge_sign(a, c);
    let sw = edge_sign(b, a);
    if (su < 0 || sv < 0 || sw < 0) && (su > 0 || sv > 0 || sw > 0) {
        return miss;
    }
    // All of one sign: det = u + v + w is zero exactly when all three are.
    if (su == 0 && sv == 0 && sw == 0) || (tri.flags & 1u) != 0u {
        return miss;
    }
    let u = edge(c, b);
    let v = edge(a, c);
    let w = edge(b, a);
    let det = f64_add(f64_add(u, v), w);
    let t_scaled = f64_add(
        f64_add(f64_mul(u, f64_from_f32(a.z)), f64_mul(v, f64_from_f32(b.z))),
        f64_mul(w, f64_from_f32(c.z)),
    );
    if (f64_positive(det) && f64_negative(t_scaled)) || (f64_negative(det) && f64_positive(t_scaled)) {
        return miss;
    }
    let t = f64_to_f32(f64_div(t_scaled, det));
    if !t.finite {
        return miss;
    }
    return TriHit(true, bitcast<f32>(t.bits));
}

@compute @workgroup_size(8, 8)
fn trace(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= params.size.x || gid.y >= params.size.y {
        return;
    }
    let r = pixel_ray(gid.x, gid.y);
    var visited = 0u;
    var tested = 0u;
    var best_id = NO_HIT;
    var best_t = 0.0;
    // The best hit's t, or t_max = +∞: nodes entered beyond it are skipped.
    var limit = params.inf;
    var stack_node: array<u32, STACK>;
    var stack_key: array<f32, STACK>;
    var len = 0u;
    if params.node_count > 0u {
        let root = nodes[0];
        let t = box_entry(r, root.min, root.max);
        if t >= 0.0 && !(t > limit * params.grow) {
            stack_node[0] = 0u;
            stack_key[0] = t;
            len = 1u;
        }
    }
    while len > 0u {
        len = len - 1u;
        let index = stack_node[len];
        let key = stack_key[len];
        let lim = limit;
        if key > lim * params.grow {
            continue;
        }
        visited = visited + 1u;
        let node = nodes[index];
        if node.count > 0u {
            for (var k = node.start; k < node.start + node.count; k++) {
                tested = tested + 1u;
                let tri = tris[k];
                let h = ray_triangle(r, tri);
                if !h.hit || !(h.t <= params.inf) {
                    continue;
                }
                // `HitTracker::offer`: nearer, or as near with a lower index.
                var better = h.t <= params.inf;
                if best_id != NO_HIT {
                    better = h.t < best_t || (h.t == best_t && tri.id < best_id);
                }
                if better && h.t >= 0.0 {
                    best_id = tri.id;
                    best_t = h.t;
                    limit = h.t;
                }
            }
            continue;
        }
        // Both children tested against the limit read when the node was popped; the nearer
        // one visited first, the first child on a tie (`Stack::push_pair`).
        let first = index + 1u;
        let second = node.start;
        let n1 = nodes[first];
        let n2 = nodes[second];
        let t1 = box_entry(r, n1.min, n1.max);
        let t2 = box_entry(r, n2.min, n2.max);
        let ok1 = t1 >= 0.0 && !(t1 > lim * params.grow);
        let ok2 = t2 >= 0.0 && !(t2 > lim * params.grow);
        if ok1 && ok2 {
            if t2 < t1 {
                stack_node[len] = first;
                stack_key[len] = t1;
                stack_node[len + 1u] = second;
                stack_key[len + 1u] = t2;
            } else {
                stack_node[len] = second;
                stack_key[len] = t2;
                stack_node[len + 1u] = first;
                stack_key[len + 1u] = t1;
            }
            len = len + 2u;
        } else if ok1 {
            stack_node[len] = first;
            stack_key[len] = t1;
            len = len + 1u;
        } else if ok2 {
            stack_node[len] = second;
            stack_key[len] = t2;
            len = len + 1u;
        }
    }
    traces[gid.y * params.size.x + gid.x] = Trace(visited, tested, best_id, bitcast<u32>(best_t));
    atomicMax(&maxima[0], visited);
    atomicMax(&maxima[1], tested);
}
