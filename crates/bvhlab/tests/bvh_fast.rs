//! The unobserved ray first hit and closest point of the AABB tree take their own, faster
//! walks, and so do those of its 4-wide copy ([`Bvh4`]): they must answer exactly what the
//! observed walks (and brute force) answer, bit for bit, on random scenes at tiny and huge
//! scales, on rays parallel to the axes, and on the real meshes. The unlogged build (which costs only the planes that can win) must make the
//! logged build's tree.

use crate::bvh_common;

use bvh_common::{TestPrim, rays_for, rng, shared_mesh};
use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::structure::BruteForce;
use bvhlab::structure::bvh::{Bvh4, BvhOptions, SplitMethod, WIDTH};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// Compares the fast, wide and observed first hits on `rays` (and brute force on the first
/// `brute_rays` of them); returns how many hit.
fn check_rays(name: &str, tree: &AabbTree3, rays: &[Ray3], brute_rays: usize) -> usize {
    let brute = BruteForce::build(tree.primitives());
    let wide = Bvh4::from_bvh(tree);
    let mut hits = 0;
    for (i, ray) in rays.iter().enumerate() {
        for t_max in [f32::INFINITY, 0.5] {
            let fast = tree.ray_first_hit(ray, t_max);
            let observed = tree.ray_first_hit_observed(ray, t_max, &mut ()).answer;
            assert_eq!(fast, observed, "{name}: ray {i} {ray:?}, t_max {t_max}");
            assert_eq!(
                wide.ray_first_hit(ray, t_max),
                observed,
                "{name}: wide, ray {i} {ray:?}, t_max {t_max}"
            );
            if i < brute_rays {
                assert_eq!(
                    fast,
                    brute.ray_first_hit(ray, t_max),
                    "{name}: brute force, ray {i} {ray:?}, t_max {t_max}"
                );
            }
            hits += usize::from(fast.is_some());
        }
    }
    hits
}

/// Compares the fast, wide and observed closest points on `points` (and brute force on the
/// first `brute_points` of them).
fn check_points(name: &str, tree: &AabbTree3, points: &[Vec3], brute_points: usize) {
    let brute = BruteForce::build(tree.primitives());
    let wide = Bvh4::from_bvh(tree);
    for (i, &point) in points.iter().enumerate() {
        let fast = tree.closest_point(point);
        let observed = tree.k_nearest_observed(point, 1, &mut ()).answer;
        assert_eq!(
            fast,
            observed.first().copied(),
            "{name}: point {i} {point:?}"
        );
        assert_eq!(
            wide.closest_point(point),
            fast,
            "{name}: wide, point {i} {point:?}"
        );
        assert!(fast.is_some(), "{name}: no nearest to {point:?}");
        if i < brute_points {
            assert_eq!(
                fast,
                brute.closest_point(point),
                "{name}: brute force, point {i} {point:?}"
            );
        }
    }
}

/// Points in the scene's box grown by half its size, and the triangles' own vertices.
fn box_points(rng: &mut ChaCha8Rng, tris: &[Triangle3], n: usize) -> Vec<Vec3> {
    let bounds = tris
        .iter()
        .map(Primitive::bounds)
        .reduce(|a, b| a.merge(&b))
        .expect("a scene");
    let size = bounds.max - bounds.min;
    let mut points: Vec<Vec3> = (0..n)
        .map(|_| {
            bounds.min - size * 0.5
                + size
                    * 2.0
                    * Vec3::new(
                        rng.random::<f32>(),
                        rng.random::<f32>(),
                        rng.random::<f32>(),
                    )
        })
        .collect();
    points.extend(tris.iter().take(n / 4).map(|t| t.b));
    points
}

/// Rays from random points of the scene's box toward random points of it, and the same
/// rays turned parallel to each axis.
fn box_rays(rng: &mut ChaCha8Rng, tris: &[Triangle3], n: usize) -> Vec<Ray3> {
    let bounds = tris
        .iter()
        .map(Primitive::bounds)
        .reduce(|a, b| a.merge(&b))
        .expect("a scene");
    let point = |rng: &mut ChaCha8Rng| {
        bounds.min
            + (bounds.max - bounds.min)
                * Vec3::new(
                    rng.random::<f32>(),
                    rng.random::<f32>(),
                    rng.random::<f32>(),
                )
    };
    let mut rays = Vec::new();
    for i in 0..n {
        let origin = point(rng);
        let dir = match i % 4 {
            3 => Vec3::AXES[rng.random_range(0..3)] * if rng.random_bool(0.5) { 1.0 } else { -1.0 },
            _ => point(rng) - origin,
        };
        rays.extend(Ray3::new(origin, dir));
    }
    rays
}

#[test]
fn random_scenes_at_every_scale() {
    for (seed, scale) in [
        (1, 1.0e-3f32),
        (2, 1.0),
        (3, 1.0e4),
        (4, 1.0e-20),
        (5, 1.0e15),
    ] {
        let mut rng = rng(seed);
        let tris: Vec<Triangle3> = (0..2000)
            .map(|_| Triangle3::random(&mut rng, 10.0).map(|v| v * scale))
            .collect();
        for method in [SplitMethod::BinnedSah, SplitMethod::SpatialMedian] {
            let name = format!("scale {scale}, {method:?}");
            let options = BvhOptions::with_method(method);
            let tree = AabbTree3::build_with(&tris, &options);
            let mut split_log = bvhlab::Recorder::default();
            let observed = AabbTree3::build_observed(&tris, &options, &mut split_log);
            let log = split_log.splits;
            assert_eq!(tree, observed, "{name}: the unlogged build differs");
            let mut rays = box_rays(&mut rng, &tris, 600);
            rays.extend(rays_for(&mut rng, &tris, &log, 600));
            let hits = check_rays(&name, &tree, &rays, 300);
            assert!(hits > rays.len() / 4, "{name}: only {hits} hits");
            let points = box_points(&mut rng, &tris, 600);
            check_points(&name, &tree, &points, 300);
        }
    }
}

#[test]
fn real_meshes() {
    for (seed, name) in [(7, "stanford-bunny.obj"), (8, "fandisk.obj")] {
        let Some(tris) = shared_mesh(name) else {
            continue;
        };
        let mut rng = rng(seed);
        let tree = AabbTree3::build(&tris);
        let mut split_log = bvhlab::Recorder::default();
        let observed = AabbTree3::build_observed(&tris, &BvhOptions::default(), &mut split_log);
        let log = split_log.splits;
        assert_eq!(tree, observed, "{name}: the unlogged build differs");
        let mut rays = box_rays(&mut rng, &tris, 4000);
        rays.extend(rays_for(&mut rng, &tris, &log, 2000));
        let hits = check_rays(name, &tree, &rays, 100);
        assert!(hits > rays.len() / 2, "{name}: only {hits} hits");
        let points = box_points(&mut rng, &tris, 3000);
        check_points(name, &tree, &points, 100);
    }
}

/// The wide tree of a tree with one leaf (the root), or none, answers as brute force; and a
/// collapse fills its nodes.
#[test]
fn wide_tree_edge_cases() {
    let mut rng = rng(9);
    let empty = Bvh4::from_bvh(&AabbTree3::build(&[]));
    let ray = Ray3::new(Vec3::ZERO, Vec3::X).expect("a ray");
    assert_eq!(empty.ray_first_hit(&ray, f32::INFINITY), None);
    assert_eq!(empty.closest_point(Vec3::ZERO), None);
    for n in [1, 3, 2000] {
        let tris: Vec<Triangle3> = (0..n).map(|_| Triangle3::random(&mut rng, 10.0)).collect();
        let tree = AabbTree3::build(&tris);
        let wide = Bvh4::from_bvh(&tree);
        assert_eq!(wide.len(), n);
        let rays = box_rays(&mut rng, &tris, 400);
        let hits = check_rays(&format!("{n} triangles"), &tree, &rays, 400);
        assert!(hits > 0, "{n} triangles: no hit");
        check_points(
            &format!("{n} triangles"),
            &tree,
            &box_points(&mut rng, &tris, 100),
            100,
        );
        // The collapse opens inner lanes until four are used: a node with fewer holds
        // leaves only.
        for (i, node) in wide.nodes().iter().enumerate() {
            let used = (0..WIDTH).filter(|&lane| node.is_used(lane)).count();
            let all_leaves = (0..used).all(|lane| node.count[lane] > 0);
            assert!(
                used == WIDTH || all_leaves || n < 4,
                "{n}: node {i} {node:?}"
            );
        }
        let inner = tree.nodes().iter().filter(|n| !n.is_leaf()).count();
        // Each wide node stands for a distinct inner node, the opened ones for none.
        assert!(
            wide.nodes().len() <= inner.max(1),
            "{n}: {} wide nodes",
            wide.nodes().len()
        );
    }
}

/// The wide tree over segments in 2D answers as brute force (its third axis is unused).
#[test]
fn wide_tree_in_2d() {
    use bvhlab::glam::Vec2;
    let mut rng = rng(10);
    let point = |rng: &mut ChaCha8Rng| {
        Vec2::new(rng.random_range(-10.0..10.0), rng.random_range(-10.0..10.0))
    };
    let segs: Vec<Segment2> = (0..1000)
        .map(|_| {
            let a = point(&mut rng);
            Segment2::new(a, a + (point(&mut rng) * 0.05))
        })
        .collect();
    let tree = AabbTree2::build(&segs);
    let wide = Bvh4::from_bvh(&tree);
    let brute = BruteForce::build(&segs);
    let mut hits = 0;
    for i in 0..2000 {
        let (origin, target) = (point(&mut rng), point(&mut rng));
        let Ok(ray) = Ray2::new(origin, target - origin) else {
            continue;
        };
        let answer = wide.ray_first_hit(&ray, f32::INFINITY);
        assert_eq!(
            answer,
            brute.ray_first_hit(&ray, f32::INFINITY),
            "ray {i} {ray:?}"
        );
        assert_eq!(
            answer,
            tree.ray_first_hit(&ray, f32::INFINITY),
            "ray {i} {ray:?}"
        );
        hits += usize::from(answer.is_some());
        assert_eq!(
            wide.closest_point(origin),
            brute.closest_point(origin),
            "point {i}"
        );
    }
    assert!(hits > 500, "only {hits} hits");
}

/// The wide walks size their stacks by the tree's depth (up to 16 wide levels, up to 24,
/// deeper): chains of triangles whose sizes halve one after another, split by the spatial
/// median one triangle per level, make trees of every size class, and each answers as the
/// binary and observed walks and brute force do, toward every triangle of the chain.
#[test]
fn wide_stacks_of_every_depth() {
    let mut rng = rng(11);
    let options = BvhOptions {
        leaf_size: 1,
        ..BvhOptions::with_method(SplitMethod::SpatialMedian)
    };
    let mut depths = Vec::new();
    for n in [24i32, 70, 90] {
        let tris: Vec<Triangle3> = (0..n)
            .map(|i| {
                let s = 2.0f32.powi(-i);
                Triangle3::new(
                    Vec3::new(s, 0.0, 0.0),
                    Vec3::new(s * 1.5, s, 0.0),
                    Vec3::new(s * 1.5, 0.0, s),
                )
            })
            .collect();
        let tree = AabbTree3::build_with(&tris, &options);
        let wide = Bvh4::from_bvh(&tree);
        depths.push(wide.depth());
        // Down onto each triangle, from above and from the side, and through the box.
        let mut rays = box_rays(&mut rng, &tris, 200);
        for t in &tris {
            let centre = t.centroid();
            rays.extend(Ray3::new(
                centre + Vec3::new(0.1, 0.2, 3.0),
                -Vec3::new(0.1, 0.2, 3.0),
            ));
            rays.extend(Ray3::new(centre - Vec3::X, Vec3::X));
        }
        let name = format!("chain of {n} ({} wide levels)", wide.depth());
        let hits = check_rays(&name, &tree, &rays, rays.len());
        assert!(hits > tris.len(), "{name}: {hits} hits");
        let mut points = box_points(&mut rng, &tris, 100);
        points.extend(tris.iter().map(|t| t.centroid() * 0.999));
        check_points(&name, &tree, &points, points.len());
    }
    let classes = [
        depths.iter().any(|&d| d <= 16),
        depths.iter().any(|&d| (17..=24).contains(&d)),
        depths.iter().any(|&d| d > 24),
    ];
    assert_eq!(classes, [true; 3], "wide depths {depths:?}");
}
