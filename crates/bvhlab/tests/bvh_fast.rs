//! The unobserved ray first hit and closest point of the AABB tree take their own, faster
//! walks: they must answer exactly what the observed walks (and brute force) answer, bit for
//! bit, on random scenes at tiny and huge scales, on rays parallel to the axes, and on the
//! real meshes. The unlogged build (which costs only the planes that can win) must make the
//! logged build's tree.

mod bvh_common;

use std::path::PathBuf;

use bvh_common::{TestPrim, rays_for, rng};
use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::structure::BruteForce;
use bvhlab::structure::bvh::{BvhOptions, SplitMethod};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// Compares the fast and observed first hits on `rays` (and brute force on the first
/// `brute_rays` of them); returns how many hit.
fn check_rays(name: &str, tree: &AabbTree3, rays: &[Ray3], brute_rays: usize) -> usize {
    let brute = BruteForce::build(tree.primitives());
    let mut hits = 0;
    for (i, ray) in rays.iter().enumerate() {
        for t_max in [f32::INFINITY, 0.5] {
            let fast = tree.ray_first_hit(ray, t_max);
            let observed = tree.ray_first_hit_observed(ray, t_max, &mut ()).answer;
            assert_eq!(fast, observed, "{name}: ray {i} {ray:?}, t_max {t_max}");
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

/// Compares the fast and observed closest points on `points` (and brute force on the first
/// `brute_points` of them).
fn check_points(name: &str, tree: &AabbTree3, points: &[Vec3], brute_points: usize) {
    let brute = BruteForce::build(tree.primitives());
    for (i, &point) in points.iter().enumerate() {
        let fast = tree.closest_point(point);
        let observed = tree.k_nearest_observed(point, 1, &mut ()).answer;
        assert_eq!(
            fast,
            observed.first().copied(),
            "{name}: point {i} {point:?}"
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
            let tree = AabbTree3::with_options(&tris, &options);
            let (observed, log) = AabbTree3::build_observed(&tris, &options, &mut ());
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

/// The shared meshes' folder beside the repository, if present.
fn mesh(name: &str) -> Option<Vec<Triangle3>> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data/meshes")
        .join(name);
    let Ok(bytes) = std::fs::read(&path) else {
        eprintln!("skipping {name}: {} is absent", path.display());
        return None;
    };
    Some(
        Mesh::from_obj(&bytes)
            .expect("a valid OBJ file")
            .triangles()
            .to_vec(),
    )
}

#[test]
fn real_meshes() {
    for (seed, name) in [(7, "stanford-bunny.obj"), (8, "fandisk.obj")] {
        let Some(tris) = mesh(name) else { continue };
        let mut rng = rng(seed);
        let tree = AabbTree3::build(&tris);
        let (observed, log) = AabbTree3::build_observed(&tris, &BvhOptions::default(), &mut ());
        assert_eq!(tree, observed, "{name}: the unlogged build differs");
        let mut rays = box_rays(&mut rng, &tris, 4000);
        rays.extend(rays_for(&mut rng, &tris, &log, 2000));
        let hits = check_rays(name, &tree, &rays, 100);
        assert!(hits > rays.len() / 2, "{name}: only {hits} hits");
        let points = box_points(&mut rng, &tris, 3000);
        check_points(name, &tree, &points, 100);
    }
}
