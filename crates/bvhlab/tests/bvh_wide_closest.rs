//! The 4-wide tree's closest point tests a node's leaf lanes where it meets the node and
//! prunes the node's inner lanes against the best they leave, so a leaf lane is tested
//! before a nearer inner lane's subtree: the answer must still be brute force's, bit for bit
//! (the least `(distance, index)`), on the peer workload's points (the mesh's box grown 1.5
//! times), on the real meshes at their own scale (the bunny is 0.15 units across), shrunk,
//! grown and moved far from the origin, on duplicated triangles (ties go to the lower
//! index), and on seeded random scenes at every scale.

use crate::bvh_common;

use bvh_common::{TestPrim, rng, shared_mesh};
use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::structure::BruteForce;
use bvhlab::structure::bvh::Bvh4;
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// Points uniform in the scene's box grown to 1.5 times its size about its centre (the peer
/// comparison's closest-point workload), and a few of its vertices (distance 0, shared by
/// several triangles: ties).
fn workload_points(rng: &mut ChaCha8Rng, tris: &[Triangle3], n: usize) -> Vec<Vec3> {
    let bounds = tris
        .iter()
        .map(Primitive::bounds)
        .reduce(|a, b| a.merge(&b))
        .expect("a scene");
    let (center, size) = ((bounds.min + bounds.max) * 0.5, bounds.max - bounds.min);
    let mut points: Vec<Vec3> = (0..n)
        .map(|_| {
            let unit = Vec3::new(
                rng.random::<f32>(),
                rng.random::<f32>(),
                rng.random::<f32>(),
            );
            center + size * 1.5 * (unit - 0.5)
        })
        .collect();
    for _ in 0..n / 8 {
        points.push(tris[rng.random_range(0..tris.len())].c);
    }
    points
}

/// Checks the wide tree's closest point against brute force's, and the binary tree's fast
/// walk against both, on `points`.
fn check(name: &str, tris: &[Triangle3], points: &[Vec3]) {
    let tree = AabbTree3::build(tris);
    let wide = Bvh4::from_bvh(&tree);
    let brute = BruteForce::build(tris);
    for (i, &point) in points.iter().enumerate() {
        let expected = brute.closest_point(point);
        assert!(expected.is_some(), "{name}: no nearest to {point:?}");
        assert_eq!(
            wide.closest_point(point),
            expected,
            "{name}: wide, point {i} {point:?}"
        );
        assert_eq!(
            tree.closest_point(point),
            expected,
            "{name}: binary, point {i} {point:?}"
        );
    }
}

#[test]
fn real_meshes_on_the_peer_workload() {
    for (seed, name, n) in [
        (21, "stanford-bunny.obj", 150),
        (22, "ogre.obj", 100),
        (23, "fandisk.obj", 400),
        (24, "spot.obj", 400),
        (25, "teapot.obj", 400),
        (26, "suzanne.obj", 400),
    ] {
        let Some(tris) = shared_mesh(name) else {
            continue;
        };
        let mut rng = rng(seed);
        let points = workload_points(&mut rng, &tris, n);
        check(name, &tris, &points);
    }
}

/// The bunny (0.15 units across) shrunk a thousand times, grown a million times and moved
/// 1e4 and 1e6 of its sizes from the origin, where `f32` coordinates are coarse relative to
/// its triangles.
#[test]
fn bunny_scaled_and_moved() {
    let Some(tris) = shared_mesh("stanford-bunny.obj") else {
        return;
    };
    let transforms: [(&str, f32, Vec3); 5] = [
        ("shrunk", 1e-3, Vec3::ZERO),
        ("grown", 1e6, Vec3::ZERO),
        ("moved 1e3", 1.0, Vec3::new(1e3, -2e3, 5e2)),
        ("moved 1e5", 1.0, Vec3::new(-1e5, 3e4, 1e5)),
        ("tiny and moved", 1e-3, Vec3::new(2.0, 1.0, -3.0)),
    ];
    for (k, (label, scale, offset)) in transforms.into_iter().enumerate() {
        let moved: Vec<Triangle3> = tris.iter().map(|t| t.map(|v| v * scale + offset)).collect();
        let mut rng = rng(30 + k as u64);
        let points = workload_points(&mut rng, &moved, 120);
        check(&format!("bunny {label}"), &moved, &points);
    }
}

/// Every triangle twice (the copy after all originals): every distance is tied, and the
/// answer must be the original, the lower index, wherever the leaves put the two.
#[test]
fn duplicated_triangles_answer_the_lower_index() {
    for name in ["suzanne.obj", "spot.obj"] {
        let Some(tris) = shared_mesh(name) else {
            continue;
        };
        let doubled: Vec<Triangle3> = tris.iter().chain(&tris).copied().collect();
        let mut rng = rng(40);
        let points = workload_points(&mut rng, &doubled, 400);
        check(&format!("{name} doubled"), &doubled, &points);
        let wide = Bvh4::from_bvh(&AabbTree3::build(&doubled));
        for &point in &points {
            let nearest = wide.closest_point(point).expect("a nearest");
            assert!(
                nearest.prim < tris.len(),
                "{name}: the copy {} won a tie at {point:?}",
                nearest.prim
            );
        }
    }
}

/// Seeded triangle soups (2000 small random triangles) at scales from 1e-20 to 1e15.
#[test]
fn random_scenes_at_every_scale() {
    for (seed, scale) in [
        (51, 1.0e-20f32),
        (52, 1.0e-3),
        (53, 1.0),
        (54, 1.0e4),
        (55, 1.0e15),
    ] {
        let mut rng = rng(seed);
        let tris: Vec<Triangle3> = (0..2000)
            .map(|_| Triangle3::random(&mut rng, 10.0).map(|v| v * scale))
            .collect();
        let points = workload_points(&mut rng, &tris, 500);
        check(&format!("scale {scale}"), &tris, &points);
    }
}
