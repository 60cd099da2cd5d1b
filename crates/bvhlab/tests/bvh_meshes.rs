//! The real meshes of the shared data folder: every tree kind builds, validates, and answers
//! rays (random, aimed at vertices, axis-parallel along vertex coordinates) and nearest and
//! range queries exactly as brute force. Skipped, with a message, when the folder is absent.

use crate::bvh_common;

use std::path::PathBuf;

use bvh_common::{Budget, check_collide, check_scene, rng};
use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::structure::bvh::{BvhOptions, NodeVolume, SplitMethod};
use bvhlab::{Aabb, Mesh, Obb, Sphere};

fn mesh_dir() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/meshes");
    dir.is_dir().then_some(dir)
}

/// The triangles of a mesh of the shared data folder, or `None` (with a message) when the
/// folder is absent.
fn load(name: &str) -> Option<Vec<Triangle3>> {
    let Some(dir) = mesh_dir() else {
        eprintln!("skipping {name}: the shared mesh folder is absent");
        return None;
    };
    let bytes = std::fs::read(dir.join(name)).expect("a readable mesh");
    let mesh = Mesh::from_obj(&bytes).expect("a valid OBJ file");
    Some(mesh.triangles().to_vec())
}

fn run<B: NodeVolume<Point = Vec3>>(name: &str, seed: u64, budget: Budget) {
    let Some(prims) = load(name) else { return };
    let mut rng = rng(seed);
    let checked =
        check_scene::<B, Triangle3>(name, &prims, &BvhOptions::default(), &mut rng, budget);
    assert!(
        checked.rays_hit * 3 >= budget.rays,
        "{name}: only {} rays hit",
        checked.rays_hit
    );
}

#[test]
fn spot_teapot_fandisk() {
    let budget = Budget {
        rays: 90,
        points: 16,
    };
    for (i, name) in ["spot.obj", "teapot.obj", "fandisk.obj"]
        .into_iter()
        .enumerate()
    {
        run::<Aabb<Vec3>>(name, 60 + i as u64, budget);
        run::<Sphere<Vec3>>(name, 63 + i as u64, budget);
        run::<Obb<Vec3>>(name, 66 + i as u64, budget);
    }
}

#[test]
fn bunny() {
    let budget = Budget {
        rays: 24,
        points: 6,
    };
    run::<Aabb<Vec3>>("stanford-bunny.obj", 70, budget);
    run::<Sphere<Vec3>>("stanford-bunny.obj", 71, budget);
    run::<Obb<Vec3>>("stanford-bunny.obj", 72, budget);
}

/// Fandisk's flat, axis-aligned faces with the lecture's median splits.
#[test]
fn fandisk_with_median_splits() {
    let Some(prims) = load("fandisk.obj") else {
        return;
    };
    let mut rng = rng(73);
    for method in [SplitMethod::SpatialMedian, SplitMethod::ObjectMedian] {
        let options = BvhOptions::with_method(method);
        check_scene::<Aabb<Vec3>, Triangle3>(
            "fandisk",
            &prims,
            &options,
            &mut rng,
            Budget {
                rays: 60,
                points: 8,
            },
        );
    }
}

/// A mesh against a moved copy of itself: many touching and crossing triangles.
#[test]
fn spot_collides_with_a_moved_copy() {
    let Some(prims) = load("spot.obj") else {
        return;
    };
    let part = &prims[..1500];
    let moved: Vec<Triangle3> = part
        .iter()
        .map(|t| {
            Triangle3::new(
                t.a + Vec3::new(0.02, 0.01, 0.0),
                t.b + Vec3::new(0.02, 0.01, 0.0),
                t.c + Vec3::new(0.02, 0.01, 0.0),
            )
        })
        .collect();
    let options = BvhOptions::default();
    check_collide::<Aabb<Vec3>, Triangle3>("spot", part, &moved, &options);
    check_collide::<Sphere<Vec3>, Triangle3>("spot", part, &moved, &options);
    check_collide::<Obb<Vec3>, Triangle3>("spot", part, &moved, &options);
    check_collide::<Obb<Vec3>, Triangle3>("spot itself", part, part, &options);
}
