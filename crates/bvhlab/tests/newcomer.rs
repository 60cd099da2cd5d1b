//! Regression tests for what a newcomer ran into (issue 20, "What a newcomer ran into"), one
//! test named for each.

use bvhlab::glam::{DVec3, Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::bvh::{BvhBuild, SphereTree};
use bvhlab::structure::{BruteForce, Hit};
use bvhlab::{Aabb, BspTree, Bvh, Grid, KdTree, Mesh, Orthtree, Sphere};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

pub(crate) fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

pub(crate) fn random_vec3(rng: &mut ChaCha8Rng, extent: f32) -> Vec3 {
    Vec3::new(
        rng.random_range(-extent..extent),
        rng.random_range(-extent..extent),
        rng.random_range(-extent..extent),
    )
}

fn random_triangles(seed: u64, n: usize) -> Vec<Triangle3> {
    let mut rng = rng(seed);
    (0..n)
        .map(|_| {
            let a = random_vec3(&mut rng, 10.0);
            Triangle3::new(
                a,
                a + random_vec3(&mut rng, 1.5),
                a + random_vec3(&mut rng, 1.5),
            )
        })
        .collect()
}

/// Rays from outside the scene aimed at random points inside it.
pub(crate) fn random_rays(seed: u64, n: usize) -> Vec<Ray3> {
    let mut rng = rng(seed);
    (0..n)
        .map(|_| {
            let from = random_vec3(&mut rng, 14.0);
            let to = random_vec3(&mut rng, 8.0);
            Ray3::through(from, to).expect("distinct points")
        })
        .collect()
}

// `use bvhlab::Bvh4` did not compile: the fast tree was in neither the crate root nor the
// prelude. Both paths must name the same type.
#[test]
fn use_bvhlab_bvh4_compiles_from_the_crate_root_and_the_prelude() {
    use bvhlab::Bvh4 as FromRoot;
    let tris = random_triangles(1, 200);
    let from_root: FromRoot<Triangle3> = FromRoot::build(&tris);
    // `Bvh4` here is the prelude's (glob import above).
    let from_prelude: Bvh4<Triangle3> = from_root.clone();
    let tree = AabbTree3::build(&tris);
    let mut hits = 0;
    for ray in random_rays(2, 100) {
        let want = tree.ray_first_hit(&ray, f32::INFINITY);
        hits += usize::from(want.is_some());
        assert_eq!(from_prelude.ray_first_hit(&ray, f32::INFINITY), want);
    }
    assert!(hits > 10, "the rays must hit something ({hits})");
}

/// A ball as a custom primitive; `honest` picks whether its vertices enclose it (the corners
/// of its box) or not (its centre alone: the mistake the newcomer made).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ball {
    pub(crate) center: Vec3,
    pub(crate) radius: f32,
    pub(crate) honest: bool,
}

impl Primitive for Ball {
    type Point = Vec3;

    fn bounds(&self) -> Aabb<Vec3> {
        Aabb::new(self.center - self.radius, self.center + self.radius)
    }
    fn centroid(&self) -> Vec3 {
        self.center
    }
    fn ray_hit(&self, ray: &Ray3) -> Option<f32> {
        let (e, d) = (
            ray.origin().as_dvec3() - self.center.as_dvec3(),
            ray.dir().as_dvec3(),
        );
        let r = f64::from(self.radius);
        let (a, half_b, c) = (d.dot(d), e.dot(d), e.dot(e) - r * r);
        let disc = half_b * half_b - a * c;
        if disc < 0.0 {
            return None;
        }
        let root = disc.sqrt();
        let (t0, t1) = ((-half_b - root) / a, (-half_b + root) / a);
        if t1 < 0.0 {
            return None;
        }
        Some(t0.max(0.0) as f32)
    }
    fn project_point(&self, point: Vec3) -> Vec3 {
        let offset = point.as_dvec3() - self.center.as_dvec3();
        let length = offset.length();
        if length <= f64::from(self.radius) {
            point
        } else {
            (self.center.as_dvec3() + offset * (f64::from(self.radius) / length)).as_vec3()
        }
    }
    fn measure(&self) -> f32 {
        Sphere::new(self.center, self.radius).measure()
    }
    fn normal(&self) -> Vec3 {
        Vec3::ZERO
    }
    fn vertices(&self) -> impl Iterator<Item = Vec3> {
        let corners: Vec<Vec3> = if self.honest {
            self.bounds().corners().collect()
        } else {
            vec![self.center]
        };
        corners.into_iter()
    }
    fn intersects_aabb(&self, aabb: &Aabb<Vec3>) -> bool {
        aabb.distance(self.center) <= self.radius
    }
    fn intersects(&self, other: &Self) -> bool {
        self.center.distance(other.center) <= self.radius + other.radius
    }
}

fn balls(seed: u64, n: usize, honest: bool) -> Vec<Ball> {
    let mut rng = rng(seed);
    (0..n)
        .map(|_| Ball {
            center: random_vec3(&mut rng, 10.0),
            radius: rng.random_range(0.2..1.5),
            honest,
        })
        .collect()
}

// A custom primitive whose `vertices()` do not enclose it made the sphere tree disagree with
// brute force, and `validate()` said Ok. Now `validate()` names the broken contract, and a
// ball that keeps it gets brute force's answers.
#[test]
fn a_ball_whose_vertices_do_not_enclose_it_fails_validate() {
    let dishonest = balls(3, 300, false);
    let tree = SphereTree::<Ball>::build(&dishonest);
    let err = tree
        .validate()
        .expect_err("a ball whose vertex is its centre breaks the contract");
    assert!(
        err.message.contains("Primitive contract") && err.message.contains("vertices"),
        "{err}"
    );
    // The same holds for every BVH (they share the check).
    assert!(AabbTree3::build(&[Triangle3::default()]).validate().is_ok());
    assert!(
        Bvh::<Aabb<Vec3>, Ball>::build(&dishonest)
            .validate()
            .is_err()
    );

    let honest = balls(3, 300, true);
    let tree = SphereTree::<Ball>::build(&honest);
    tree.validate()
        .expect("a ball with its box's corners keeps the contract");
    let brute = BruteForce::build(&honest);
    let mut rng = rng(4);
    for ray in random_rays(5, 200) {
        assert_eq!(
            tree.ray_first_hit(&ray, f32::INFINITY),
            brute.ray_first_hit(&ray, f32::INFINITY)
        );
        assert_eq!(
            tree.ray_all_hits(&ray, f32::INFINITY),
            brute.ray_all_hits(&ray, f32::INFINITY)
        );
    }
    for _ in 0..100 {
        let p = random_vec3(&mut rng, 12.0);
        assert_eq!(tree.k_nearest(p, 3), brute.k_nearest(p, 3));
    }
}

/// Möller and Trumbore's barycentric coordinates of the ray's crossing, in f64, as a
/// reference independent of the core's watertight test.
fn moller_trumbore(tri: &Triangle3, ray: &Ray3) -> (f64, f64) {
    let (a, b, c) = (tri.a.as_dvec3(), tri.b.as_dvec3(), tri.c.as_dvec3());
    let (o, d) = (ray.origin().as_dvec3(), ray.dir().as_dvec3());
    let (e1, e2) = (b - a, c - a);
    let p = d.cross(e2);
    let det = e1.dot(p);
    let s = o - a;
    let q = s.cross(e1);
    (s.dot(p) / det, d.dot(q) / det)
}

fn barycentric_point(tri: &Triangle3, hit: &Hit) -> DVec3 {
    let (u, v) = (f64::from(hit.u), f64::from(hit.v));
    tri.a.as_dvec3() * (1.0 - u - v) + tri.b.as_dvec3() * u + tri.c.as_dvec3() * v
}

fn check_triangle_hit(tris: &[Triangle3], ray: &Ray3, hit: &Hit, what: &str) {
    let tri = &tris[hit.prim];
    assert!(
        hit.u >= 0.0 && hit.v >= 0.0 && hit.u + hit.v <= 1.0 + 1e-6,
        "{what}: {hit:?} outside the triangle"
    );
    let (u, v) = moller_trumbore(tri, ray);
    assert!(
        (u - f64::from(hit.u)).abs() < 1e-4 && (v - f64::from(hit.v)).abs() < 1e-4,
        "{what}: {hit:?}, Möller-Trumbore ({u}, {v})"
    );
    let on_ray = ray.origin().as_dvec3() + ray.dir().as_dvec3() * f64::from(hit.t);
    let gap = barycentric_point(tri, hit).distance(on_ray);
    assert!(gap < 1e-4, "{what}: {hit:?} is {gap} from the ray's point");
}

// `Hit` had no barycentric coordinates, so shading normals and UVs could not be
// interpolated. Every structure now reports Möller-Trumbore's (u, v), the same as brute
// force's.
#[test]
fn hits_carry_barycentric_coordinates_that_rebuild_the_hit_point() {
    let tris = random_triangles(6, 400);
    let brute = BruteForce::build(&tris);
    let (aabb, sphere, obb) = (
        AabbTree3::build(&tris),
        SphereTree3::build(&tris),
        ObbTree3::build(&tris),
    );
    let (wide, kd, bsp, grid, octree) = (
        Bvh4::build(&tris),
        KdTree3::build(&tris),
        Bsp3::build(&tris),
        Grid3::build(&tris),
        Octree3::build(&tris),
    );
    let mut hits = 0;
    for ray in random_rays(7, 300) {
        let Some(want) = brute.ray_first_hit(&ray, f32::INFINITY) else {
            continue;
        };
        hits += 1;
        check_triangle_hit(&tris, &ray, &want, "brute force");
        let got = [
            aabb.ray_first_hit(&ray, f32::INFINITY),
            aabb.ray_first_hit_observed(&ray, f32::INFINITY, &mut ())
                .answer,
            aabb.lecture_intersect(&ray, f32::INFINITY),
            sphere.ray_first_hit(&ray, f32::INFINITY),
            obb.ray_first_hit(&ray, f32::INFINITY),
            wide.ray_first_hit(&ray, f32::INFINITY),
            kd.ray_first_hit(&ray, f32::INFINITY),
            bsp.ray_first_hit(&ray, f32::INFINITY),
            grid.ray_first_hit(&ray, f32::INFINITY),
            octree.ray_first_hit(&ray, f32::INFINITY),
        ];
        for (i, g) in got.iter().enumerate() {
            assert_eq!(*g, Some(want), "structure {i}, {ray:?}");
        }
        for all in [
            brute.ray_all_hits(&ray, f32::INFINITY),
            aabb.ray_all_hits(&ray, f32::INFINITY),
            grid.ray_all_hits(&ray, f32::INFINITY),
        ] {
            for h in &all {
                check_triangle_hit(&tris, &ray, h, "all hits");
            }
        }
        for any in [
            aabb.ray_any_hit(&ray, f32::INFINITY),
            kd.ray_any_hit(&ray, f32::INFINITY),
        ] {
            check_triangle_hit(&tris, &ray, &any.expect("a hit exists"), "any hit");
        }
    }
    assert!(hits > 50, "the rays must hit ({hits})");
    // Corners: a ray straight down onto each corner of a triangle gets its weights.
    let tri = Triangle3::new(
        Vec3::ZERO,
        Vec3::new(4.0, 0.0, 0.0),
        Vec3::new(0.0, 4.0, 0.0),
    );
    let brute = BruteForce::build(&[tri]);
    for (x, y, u, v) in [
        (0.0, 0.0, 0.0, 0.0),
        (4.0, 0.0, 1.0, 0.0),
        (0.0, 4.0, 0.0, 1.0),
        (1.0, 2.0, 0.25, 0.5),
    ] {
        let ray = Ray3::new(Vec3::new(x, y, 5.0), -Vec3::Z).expect("ray");
        let hit = brute.ray_first_hit(&ray, f32::INFINITY).expect("a hit");
        assert_eq!((hit.t, hit.u, hit.v), (5.0, u, v), "at ({x}, {y})");
    }
}

// For a 2D segment `u` is the parameter along it (`a + u (b - a)`), and `v` is 0.
#[test]
fn segment_hits_carry_the_parameter_along_the_segment() {
    let mut rng = rng(8);
    let segs: Vec<Segment2> = (0..300)
        .map(|_| {
            let a = Vec2::new(rng.random_range(-10.0..10.0), rng.random_range(-10.0..10.0));
            Segment2::new(
                a,
                a + Vec2::new(rng.random_range(-2.0..2.0), rng.random_range(-2.0..2.0)),
            )
        })
        .collect();
    let brute = BruteForce::build(&segs);
    let tree = AabbTree2::build(&segs);
    let mut hits = 0;
    for _ in 0..300 {
        let from = Vec2::new(rng.random_range(-14.0..14.0), rng.random_range(-14.0..14.0));
        let to = Vec2::new(rng.random_range(-8.0..8.0), rng.random_range(-8.0..8.0));
        let ray = Ray2::through(from, to).expect("distinct");
        for h in brute.ray_all_hits(&ray, f32::INFINITY) {
            hits += 1;
            let s = &segs[h.prim];
            assert!((0.0..=1.0).contains(&h.u) && h.v == 0.0, "{h:?}");
            let on_segment = s.a + (s.b - s.a) * h.u;
            assert!(
                on_segment.distance(ray.at(h.t)) < 1e-4,
                "{h:?} {s:?} {ray:?}"
            );
        }
        assert_eq!(
            tree.ray_all_hits(&ray, f32::INFINITY),
            brute.ray_all_hits(&ray, f32::INFINITY)
        );
    }
    assert!(hits > 50, "the rays must hit ({hits})");
    // Along the segment: the ray enters at `a`.
    let s = Segment2::new(Vec2::new(2.0, 0.0), Vec2::new(6.0, 0.0));
    let along = Ray2::new(Vec2::ZERO, Vec2::X).expect("ray");
    let hit = BruteForce::build(&[s])
        .ray_first_hit(&along, 10.0)
        .expect("hit");
    assert_eq!((hit.t, hit.u, hit.v), (2.0, 0.0, 0.0));
    let inside = Ray2::new(Vec2::new(3.0, 0.0), -Vec2::X).expect("ray");
    let hit = BruteForce::build(&[s])
        .ray_first_hit(&inside, 10.0)
        .expect("hit");
    assert_eq!((hit.t, hit.u), (0.0, 0.25));
}

// A ray with a subnormal direction (1e-40) was accepted and never hit anything. The checked
// constructor now refuses it, with a message that says why and what to do.
#[test]
fn a_ray_with_a_subnormal_direction_is_refused() {
    let origin = Vec3::new(0.0, 0.0, 5.0);
    for dir in [
        Vec3::splat(1e-40),
        Vec3::new(0.0, 0.0, -1e-40),
        Vec3::new(f32::MIN_POSITIVE / 2.0, -1e-45, 0.0),
    ] {
        let err = Ray3::new(origin, dir).expect_err("subnormal direction");
        assert!(
            matches!(err, GeometryError::TinyDirection { .. }),
            "{dir:?}: {err:?}"
        );
        assert!(err.to_string().contains("too small"), "{err}");
    }
    let err = Ray2::through(Vec2::ZERO, Vec2::new(1e-39, 0.0)).expect_err("subnormal");
    assert!(
        matches!(err, GeometryError::TinyDirection { .. }),
        "{err:?}"
    );
    // Zero stays its own error; one subnormal component beside a normal one is fine.
    assert_eq!(
        Ray3::new(origin, Vec3::ZERO),
        Err(GeometryError::ZeroDirection)
    );
    let tri = Triangle3::new(
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(3.0, -1.0, 0.0),
        Vec3::new(-1.0, 3.0, 0.0),
    );
    let brute = BruteForce::build(&[tri]);
    let slanted = Ray3::new(origin, Vec3::new(1e-40, 0.0, -1.0)).expect("a normal component");
    assert_eq!(
        brute.ray_first_hit(&slanted, f32::INFINITY).map(|h| h.t),
        Some(5.0)
    );
    // The smallest normal direction is accepted and still hits what lies within
    // `f32::MAX` of its units (t = 2 / 1.2e-38 = 1.7e38).
    let near = Vec3::new(0.0, 0.0, 2.0);
    let smallest = Ray3::new(near, Vec3::new(0.0, 0.0, -f32::MIN_POSITIVE)).expect("normal");
    let hit = brute.ray_first_hit(&smallest, f32::INFINITY).expect("hit");
    assert!(hit.t.is_finite() && hit.t > 1e38, "{hit:?}");
}

fn assert_send_sync<T: Send + Sync>() {}

/// Every structure for every primitive the crate indexes.
fn assert_every_structure_send_sync<P: Primitive>() {
    assert_send_sync::<BruteForce<P>>();
    assert_send_sync::<Bvh<Aabb<P::Point>, P>>();
    assert_send_sync::<Bvh<Sphere<P::Point>, P>>();
    assert_send_sync::<Bvh<bvhlab::Obb<P::Point>, P>>();
    assert_send_sync::<Bvh4<P>>();
    assert_send_sync::<BvhBuild<Aabb<P::Point>, P>>();
    assert_send_sync::<KdTree<P>>();
    assert_send_sync::<BspTree<P>>();
    assert_send_sync::<Grid<P>>();
    assert_send_sync::<Orthtree<P>>();
}

// Every structure is `Send + Sync`, so one tree can be queried from several threads. The
// assertions are checked when this file compiles; the threads below show it in use.
#[test]
fn every_structure_is_send_and_sync() {
    assert_every_structure_send_sync::<Segment2>();
    assert_every_structure_send_sync::<Triangle3>();
    assert_every_structure_send_sync::<Vec2>();
    assert_every_structure_send_sync::<Vec3>();
    assert_send_sync::<Mesh>();
    let tris = random_triangles(9, 500);
    let tree = AabbTree3::build(&tris);
    let rays = random_rays(10, 200);
    let want: Vec<Option<Hit>> = rays
        .iter()
        .map(|r| tree.ray_first_hit(r, f32::INFINITY))
        .collect();
    std::thread::scope(|scope| {
        let handles: Vec<_> = rays
            .chunks(50)
            .map(|chunk| {
                let tree = &tree;
                scope.spawn(move || {
                    chunk
                        .iter()
                        .map(|r| tree.ray_first_hit(r, f32::INFINITY))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        let got: Vec<Option<Hit>> = handles
            .into_iter()
            .flat_map(|h| h.join().expect("no panic"))
            .collect();
        assert_eq!(got, want);
    });
}

// Any hit on `AabbTree3` took the observed walk (slower than first hit on the same shadow
// rays). The plain `ray_any_hit` now takes the fast walk, stopping at the first hit; it must
// stop at the same primitive as the observed walk.
#[test]
fn aabb_tree_any_hit_takes_the_fast_walk_and_answers_as_the_observed_one() {
    let tris = random_triangles(11, 2000);
    let tree = AabbTree3::build(&tris);
    let brute = BruteForce::build(&tris);
    let mut hits = 0;
    for (i, ray) in random_rays(12, 400).iter().enumerate() {
        let t_max = [f32::INFINITY, 1.0, 0.5, f32::NAN][i % 4];
        let fast = tree.ray_any_hit(ray, t_max);
        assert_eq!(fast, tree.ray_any_hit_observed(ray, t_max, &mut ()).answer);
        assert_eq!(
            fast.is_some(),
            brute.ray_first_hit(ray, t_max).is_some(),
            "{ray:?}"
        );
        if let Some(h) = fast {
            hits += 1;
            assert!(h.t <= t_max && tris[h.prim].ray_hit(ray) == Some(h.t));
        }
    }
    assert!(hits > 50, "the rays must hit ({hits})");
}
