//! The watertight ray-triangle test leaves as soon as two of its three edge values have
//! opposite signs (issue 19: it spares most missed triangles a third of the `f64` work).
//! That exit must change no answer: here `Triangle3::ray_hit` and `ray_barycentric` are
//! checked, bit for bit, against the test written out in full (all three edge values, then
//! the sign test: Woop, Benthin and Wald, JCGT 2013, as the crate computed it before), on
//! seeded random triangles and rays, rays aimed at corners, edge midpoints and inside
//! points, axis-parallel rays, rays in the triangle's plane, degenerate triangles, the
//! shared edges of a grid of integer triangles, and tiny and huge scales.

use bvhlab::glam::{DVec3, Vec3};
use bvhlab::{Ray3, Triangle3};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// What the full test computes: the barycentric `(u, v)` where the ray's line crosses the
/// triangle (`ray_barycentric`), and the hit's `t` when it is not behind the origin
/// (`ray_hit`).
fn reference(tri: &Triangle3, ray: &Ray3) -> (Option<(f32, f32)>, Option<f32>) {
    // The shear of `RayShear::of` for the ray's direction.
    let d = ray.dir().as_dvec3().as_vec3();
    let kz = d.abs().max_position();
    let (mut kx, mut ky) = ((kz + 1) % 3, (kz + 2) % 3);
    if d[kz] < 0.0 {
        std::mem::swap(&mut kx, &mut ky);
    }
    let (sx, sy, sz) = (d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]);
    let apply = |p: Vec3| {
        let p = p - ray.origin();
        (p[kx] - sx * p[kz], p[ky] - sy * p[kz], sz * p[kz])
    };
    let (a, b, c) = (apply(tri.a), apply(tri.b), apply(tri.c));
    let edge = |p: (f32, f32, f32), q: (f32, f32, f32)| {
        f64::from(p.0) * f64::from(q.1) - f64::from(p.1) * f64::from(q.0)
    };
    let (u, v, w) = (edge(c, b), edge(a, c), edge(b, a));
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return (None, None);
    }
    let det = u + v + w;
    let (ta, tb, tc) = (tri.a.as_dvec3(), tri.b.as_dvec3(), tri.c.as_dvec3());
    if det == 0.0 || (tb - ta).cross(tc - ta) == DVec3::ZERO {
        return (None, None);
    }
    let uv = Some(((v / det) as f32, (w / det) as f32));
    let t_scaled = u * f64::from(a.2) + v * f64::from(b.2) + w * f64::from(c.2);
    if (det > 0.0 && t_scaled < 0.0) || (det < 0.0 && t_scaled > 0.0) {
        return (uv, None);
    }
    let t = (t_scaled / det) as f32;
    (uv, t.is_finite().then_some(t))
}

/// Counts of what the checks met, so that a test can tell they were not all misses.
#[derive(Default)]
struct Seen {
    hits: usize,
    misses: usize,
}

/// Checks one triangle and ray against the full test, bit for bit.
fn check(tri: &Triangle3, ray: &Ray3, seen: &mut Seen) {
    let (want_uv, want_t) = reference(tri, ray);
    let bits = |x: Option<f32>| x.map(f32::to_bits);
    let uv_bits = |x: Option<(f32, f32)>| x.map(|(u, v)| (u.to_bits(), v.to_bits()));
    assert_eq!(
        bits(tri.ray_hit(ray)),
        bits(want_t),
        "t of {tri:?} and {ray:?}"
    );
    assert_eq!(
        uv_bits(tri.ray_barycentric(ray)),
        uv_bits(want_uv),
        "u, v of {tri:?} and {ray:?}"
    );
    if want_t.is_some() {
        seen.hits += 1;
    } else {
        seen.misses += 1;
    }
}

fn random_point(rng: &mut ChaCha8Rng, extent: f32) -> Vec3 {
    Vec3::from_array(std::array::from_fn(|_| rng.random_range(-extent..=extent)))
}

/// Rays from random origins towards the triangle's corners, edge midpoints, centroid and
/// random points near it, along random directions, and along the axes.
fn rays_at(rng: &mut ChaCha8Rng, tri: &Triangle3, extent: f32) -> Vec<Ray3> {
    let targets = [
        tri.a,
        tri.b,
        tri.c,
        (tri.a + tri.b) * 0.5,
        (tri.b + tri.c) * 0.5,
        (tri.c + tri.a) * 0.5,
        (tri.a + tri.b + tri.c) / 3.0,
        tri.a + random_point(rng, extent * 0.5),
    ];
    let mut rays = Vec::new();
    for target in targets {
        let origin = target + random_point(rng, extent);
        rays.extend(Ray3::through(origin, target));
        rays.extend(Ray3::new(origin, random_point(rng, 1.0)));
        let axis = rng.random_range(0..3);
        let mut along = Vec3::ZERO;
        along[axis] = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
        let mut on_axis = target;
        on_axis[axis] += extent * -along[axis];
        rays.extend(Ray3::new(on_axis, along));
        // In the triangle's plane: from one corner through another.
        rays.extend(Ray3::through(tri.a, tri.b));
    }
    rays
}

#[test]
fn random_triangles_answer_as_the_full_test() {
    let mut rng = ChaCha8Rng::seed_from_u64(0x7E57_0019);
    let mut seen = Seen::default();
    for scale in [1e-20f32, 1e-3, 1.0, 1e3, 1e20] {
        for _ in 0..2000 {
            let a = random_point(&mut rng, scale);
            let tri = Triangle3::new(
                a,
                a + random_point(&mut rng, scale * 0.3),
                a + random_point(&mut rng, scale * 0.3),
            );
            for ray in rays_at(&mut rng, &tri, scale) {
                check(&tri, &ray, &mut seen);
            }
        }
    }
    assert!(seen.hits > 10_000, "{} hits", seen.hits);
    assert!(seen.misses > 10_000, "{} misses", seen.misses);
}

#[test]
fn shared_edges_and_degenerate_triangles_answer_as_the_full_test() {
    let mut rng = ChaCha8Rng::seed_from_u64(0x5EED_0019);
    let mut seen = Seen::default();
    // A grid of integer triangles: rays through their shared edges and vertices.
    let mut tris = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            let p = |di: i32, dj: i32| Vec3::new((i + di) as f32, (j + dj) as f32, 0.0);
            tris.push(Triangle3::new(p(0, 0), p(1, 0), p(1, 1)));
            tris.push(Triangle3::new(p(0, 0), p(1, 1), p(0, 1)));
        }
    }
    // Degenerate ones: collinear corners, a repeated corner, all corners equal.
    tris.push(Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0));
    tris.push(Triangle3::new(Vec3::ZERO, Vec3::Y, Vec3::Y));
    tris.push(Triangle3::new(Vec3::ONE, Vec3::ONE, Vec3::ONE));
    for tri in &tris {
        for _ in 0..50 {
            for ray in rays_at(&mut rng, tri, 3.0) {
                check(tri, &ray, &mut seen);
            }
        }
        // Straight down through every grid vertex and edge midpoint.
        for i in 0..=8 {
            for j in 0..=8 {
                let at = Vec3::new(i as f32 * 0.5, j as f32 * 0.5, 2.0);
                check(tri, &Ray3::new(at, -Vec3::Z).expect("ray"), &mut seen);
            }
        }
    }
    assert!(seen.hits > 1000, "{} hits", seen.hits);
    assert!(seen.misses > 1000, "{} misses", seen.misses);
}
