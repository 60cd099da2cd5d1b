//! Segments and triangles: ray hits and closest points against independent methods, and the
//! watertightness of the ray-triangle test on a closed mesh.

use bvhlab::glam::{DVec3, Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab_tests::{closed_sphere_mesh, random_vector, rng};
use rand::RngExt;

/// Plane intersection and barycentric coordinates in `f64`: a different method from the
/// watertight shear test. Returns `(t, min barycentric)` or `None` when parallel.
fn reference_triangle_hit(tri: &Triangle3, ray: &Ray3) -> Option<(f64, f64)> {
    let (a, b, c) = (tri.a.as_dvec3(), tri.b.as_dvec3(), tri.c.as_dvec3());
    let (o, d) = (ray.origin().as_dvec3(), ray.dir().as_dvec3());
    let n = (b - a).cross(c - a);
    let denom = n.dot(d);
    if denom.abs() < 1e-9 * n.length() * d.length() {
        return None;
    }
    let t = n.dot(a - o) / denom;
    let p = o + d * t;
    let area = n.length_squared();
    let bary = |u: DVec3, v: DVec3| (v - u).cross(p - u).dot(n) / area;
    let min_bary = bary(b, c).min(bary(c, a)).min(bary(a, b));
    Some((t, min_bary))
}

#[test]
fn triangle_ray_hits_agree_with_plane_and_barycentric_reference() {
    let mut rng = rng(1);
    let (mut hits, mut checked) = (0, 0);
    for _ in 0..20_000 {
        let tri = Triangle3::new(
            random_vector(&mut rng, 2.0),
            random_vector(&mut rng, 2.0),
            random_vector(&mut rng, 2.0),
        );
        let origin: Vec3 = random_vector(&mut rng, 4.0);
        // Aim near the triangle so that about half the rays hit.
        let target = tri.centroid() + random_vector::<Vec3>(&mut rng, 1.5);
        let Ok(ray) = Ray3::new(origin, target - origin) else {
            continue;
        };
        let Some((t_ref, min_bary)) = reference_triangle_hit(&tri, &ray) else {
            continue;
        };
        if min_bary.abs() < 1e-4 || t_ref.abs() < 1e-4 {
            continue; // on an edge or at the origin: rounding may decide either way
        }
        checked += 1;
        let expected = (min_bary > 0.0 && t_ref > 0.0).then_some(t_ref);
        match (tri.ray_hit(&ray), expected) {
            (Some(t), Some(t_ref)) => {
                hits += 1;
                assert!(
                    (f64::from(t) - t_ref).abs() <= 1e-5 * t_ref.max(1.0),
                    "t {t} vs {t_ref}"
                );
            }
            (None, None) => {}
            (got, want) => panic!("{tri:?} {ray:?}: got {got:?}, reference {want:?}"),
        }
    }
    assert!(
        checked > 15_000 && hits > 2_000,
        "too few cases exercised: {checked} checked, {hits} hits"
    );
}

#[test]
fn triangle_closest_point_is_never_beaten_by_a_dense_sample() {
    let mut rng = rng(2);
    for _ in 0..300 {
        let tri = Triangle3::new(
            random_vector(&mut rng, 2.0),
            random_vector(&mut rng, 2.0),
            random_vector(&mut rng, 2.0),
        );
        let p: Vec3 = random_vector(&mut rng, 4.0);
        let q = tri.project_point(p);
        let reported = (q - p).length();
        // q lies on the triangle: in its plane and inside its edges.
        if let Some((_, min_bary)) = Ray3::new(q + tri.normal(), -tri.normal())
            .ok()
            .and_then(|r| reference_triangle_hit(&tri, &r))
        {
            assert!(min_bary > -1e-4, "closest point {q} is off the triangle");
        }
        let n = 150;
        let mut best = f32::INFINITY;
        for i in 0..=n {
            for j in 0..=n - i {
                let (u, v) = (i as f32 / n as f32, j as f32 / n as f32);
                let s = tri.a + (tri.b - tri.a) * u + (tri.c - tri.a) * v;
                best = best.min((s - p).length());
            }
        }
        let spacing = ((tri.b - tri.a).length() + (tri.c - tri.a).length()) / n as f32;
        assert!(
            reported <= best + 1e-5,
            "sample at {best} beats reported {reported}"
        );
        assert!(
            reported >= best - spacing,
            "reported {reported} far below the sampled {best}"
        );
    }
}

#[test]
fn segment_ray_hits_agree_with_line_intersection_in_f64() {
    let mut rng = rng(3);
    let mut hits = 0;
    for _ in 0..20_000 {
        let seg = Segment2::new(random_vector(&mut rng, 2.0), random_vector(&mut rng, 2.0));
        let origin: Vec2 = random_vector(&mut rng, 4.0);
        let target = seg.centroid() + random_vector::<Vec2>(&mut rng, 1.5);
        let Ok(ray) = Ray2::new(origin, target - origin) else {
            continue;
        };
        let (a, b, o, d) = (
            seg.a.as_dvec2(),
            seg.b.as_dvec2(),
            origin.as_dvec2(),
            ray.dir().as_dvec2(),
        );
        let e = b - a;
        let denom = d.perp_dot(e);
        if denom.abs() < 1e-9 * d.length() * e.length() {
            continue;
        }
        // o + t d = a + s e  =>  t = (a - o) x e / (d x e),  s = (a - o) x d / (d x e)
        let t = (a - o).perp_dot(e) / denom;
        let s = (a - o).perp_dot(d) / denom;
        if s.abs() < 1e-5 || (s - 1.0).abs() < 1e-5 || t.abs() < 1e-5 {
            continue;
        }
        let expected = ((0.0..=1.0).contains(&s) && t >= 0.0).then_some(t);
        match (seg.ray_hit(&ray), expected) {
            (Some(got), Some(t)) => {
                hits += 1;
                assert!((f64::from(got) - t).abs() <= 1e-5 * t.max(1.0));
            }
            (None, None) => {}
            (got, want) => panic!("{seg:?} {ray:?}: got {got:?}, reference {want:?}"),
        }
    }
    assert!(hits > 2_000);
}

#[test]
fn segment_closest_point_is_never_beaten_by_a_dense_sample() {
    let mut rng = rng(4);
    for _ in 0..1000 {
        let seg = Segment2::new(random_vector(&mut rng, 2.0), random_vector(&mut rng, 2.0));
        let p: Vec2 = random_vector(&mut rng, 4.0);
        let reported = seg.distance(p);
        let best = (0..=2000)
            .map(|k| (seg.a + (seg.b - seg.a) * (k as f32 / 2000.0) - p).length())
            .fold(f32::INFINITY, f32::min);
        assert!(reported <= best + 1e-5 && reported >= best - seg.length() / 2000.0);
    }
}

/// Woop, Benthin and Wald's property: a ray through a shared edge or vertex of a closed mesh
/// hits at least one of the triangles there. Rays are aimed at the exact `f32` vertices and at
/// points on edges, from outside the mesh, and one triangle must report the aimed point (t = 1).
/// Rays are kept off tangency (they cross the surface at more than ~10 degrees): an edge
/// point rounded to `f32` may lie a hair outside the convex mesh, and a grazing ray through it
/// then truly misses.
#[test]
fn rays_through_shared_edges_and_vertices_of_a_closed_mesh_never_slip_through() {
    let mesh = closed_sphere_mesh(1.0, 24, 48);
    let mut rng = rng(5);
    let mut targets: Vec<Vec3> = Vec::new();
    for tri in &mesh {
        targets.extend([tri.a, tri.b, tri.c]);
        for (p, q) in [(tri.a, tri.b), (tri.b, tri.c), (tri.c, tri.a)] {
            targets.push((p + q) * 0.5);
            targets.push(p + (q - p) * rng.random_range(0.0f32..1.0));
        }
    }
    let mut aimed = 0;
    for target in targets.iter().step_by(3) {
        let origin = random_vector::<Vec3>(&mut rng, 1.0).normalize_or(Vec3::X) * 3.0;
        if (*target - origin).normalize().dot(target.normalize()).abs() < 0.2 {
            continue;
        }
        let ray = Ray3::new(origin, *target - origin).expect("origin is off the mesh");
        let hit_at_target = mesh
            .iter()
            .filter_map(|t| t.ray_hit(&ray))
            .any(|t| (t - 1.0).abs() < 1e-4);
        assert!(
            hit_at_target,
            "ray {ray:?} aimed at {target} slipped through the mesh"
        );
        aimed += 1;
    }
    assert!(aimed > 2000, "only {aimed} rays aimed");
}

/// The 2D analogue: a closed polygon, rays aimed at its exact vertices, off tangency.
#[test]
fn rays_through_shared_end_points_of_a_closed_polygon_never_slip_through() {
    let n = 97;
    let vertex = |i: usize| {
        let a = std::f32::consts::TAU * (i % n) as f32 / n as f32;
        Vec2::new(a.cos(), a.sin()) * 1.7
    };
    let polygon: Vec<Segment2> = (0..n)
        .map(|i| Segment2::new(vertex(i), vertex(i + 1)))
        .collect();
    let mut rng = rng(6);
    for i in 0..n {
        for _ in 0..20 {
            let origin = random_vector::<Vec2>(&mut rng, 1.0).normalize_or(Vec2::X) * 5.0;
            // Off tangency: a tangent ray's rounded direction may pass a hair beside the
            // vertex, and then it truly misses (as in the 3D test).
            if (vertex(i) - origin)
                .normalize()
                .dot(vertex(i).normalize())
                .abs()
                < 0.2
            {
                continue;
            }
            let ray = Ray2::new(origin, vertex(i) - origin).expect("origin off the polygon");
            let hit = polygon
                .iter()
                .filter_map(|s| s.ray_hit(&ray))
                .any(|t| (t - 1.0).abs() < 1e-4);
            assert!(hit, "ray aimed at vertex {i} slipped through");
        }
    }
}

/// Regression: at 1e-20 scale the f32 edge products underflowed and a triangle behind the ray's
/// origin was reported hit at t = -0 (found by the grid's conformance tests).
#[test]
fn tiny_triangles_behind_the_origin_are_not_hit_and_tiny_hits_keep_their_t() {
    for s in [1.0f32, 1e-12, 1e-20, 1e-30, 1e20, 1e30] {
        let tri = Triangle3::new(
            Vec3::new(0.0, -1.0, -1.0) * s,
            Vec3::new(0.0, 1.0, -1.0) * s,
            Vec3::new(0.0, 0.0, 1.0) * s,
        );
        let away = Ray3::new(Vec3::new(5.0, 0.0, 0.0) * s, Vec3::X).expect("ray");
        assert_eq!(tri.ray_hit(&away), None, "scale {s}");
        let toward = Ray3::new(Vec3::new(5.0, 0.0, 0.0) * s, -Vec3::X * s).expect("ray");
        assert_eq!(tri.ray_hit(&toward), Some(5.0), "scale {s}");
        let p = Vec3::new(3.0, 0.0, 0.0) * s;
        assert_eq!(tri.project_point(p), Vec3::ZERO, "scale {s}");
    }
}
