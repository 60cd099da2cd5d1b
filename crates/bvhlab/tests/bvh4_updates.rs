//! `Bvh4::insert` and `Bvh4::remove` (issue 33, the last newcomer item): after every step of
//! seeded random sequences of inserts and removes (now and then a primitive with a NaN
//! vertex), the tree validates, gives back what a plain `Vec` gives back with the same
//! swap-remove, and answers first hits, any hits, all hits, closest points, k nearest and
//! ranges as brute force over that `Vec`; then a mesh loses and regains half its triangles,
//! and a tree emptied and refilled still answers. A saved tree round-trips.

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::structure::{BruteForce, Removed, UpdateError};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::batch_queries::{random_vec3, triangles_and_rays};
use crate::newcomer_spatial_query::answers;

/// The tree's answers beside brute force's over `held` (the `Vec` it must mirror).
fn check_answers(tree: &Bvh4<Triangle3>, held: &[Triangle3], rng: &mut ChaCha8Rng, what: &str) {
    tree.validate().unwrap_or_else(|e| panic!("{what}: {e}"));
    let finite = held.iter().filter(|t| t.has_finite_coordinates()).count();
    assert_eq!(tree.len(), finite, "{what}: primitives indexed");
    let (_, rays) = triangles_and_rays(rng, 0, 12);
    let points: Vec<Vec3> = (0..6).map(|_| random_vec3(rng, 12.0)).collect();
    let want = answers(&BruteForce::build(held), &rays, &points);
    let got = answers(tree, &rays, &points);
    for (i, (a, b)) in got.iter().zip(&want).enumerate() {
        assert_eq!(a, b, "{what}: answer {i}");
    }
}

/// A random triangle, one time in 25 with a NaN vertex.
fn random_triangle(rng: &mut ChaCha8Rng) -> Triangle3 {
    let a = random_vec3(rng, 10.0);
    let t = Triangle3::new(a, a + random_vec3(rng, 1.5), a + random_vec3(rng, 1.5));
    if rng.random_range(0..25) == 0 {
        Triangle3::new(t.a, t.b * f32::NAN, t.c)
    } else {
        t
    }
}

#[test]
fn inserts_and_removes_keep_every_answer_brute_forces() {
    for seed in [3, 33] {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut held: Vec<Triangle3> = (0..150).map(|_| random_triangle(&mut rng)).collect();
        let mut tree = Bvh4::build(&held);
        let mut hits = 0;
        for step in 0..400 {
            let what = format!("seed {seed}, step {step}");
            if held.is_empty() || rng.random_range(0..5) < 3 {
                let t = random_triangle(&mut rng);
                assert_eq!(tree.insert(t), held.len(), "{what}: insert's index");
                held.push(t);
            } else {
                let index = rng.random_range(0..held.len());
                let last = held.len() - 1;
                let removed = tree.remove(index).expect("in range");
                let want = Removed {
                    prim: held.swap_remove(index),
                    moved_from: (index != last).then_some(last),
                };
                // Compared as text: a NaN triangle is not equal to itself.
                assert_eq!(format!("{removed:?}"), format!("{want:?}"), "{what}");
            }
            if step % 8 == 0 {
                check_answers(&tree, &held, &mut rng, &what);
                hits += 1;
            } else {
                tree.validate().unwrap_or_else(|e| panic!("{what}: {e}"));
            }
        }
        assert!(held.len() > 150, "the sequence grew the tree");
        assert!(hits >= 50);
        // Out of range: refused, nothing changes.
        let before = format!("{tree:?}");
        assert_eq!(
            tree.remove(held.len()),
            Err(UpdateError::NoSuchPrimitive {
                index: held.len(),
                len: held.len()
            })
        );
        assert_eq!(format!("{tree:?}"), before);
    }
}

#[test]
fn a_tree_emptied_and_refilled_answers_and_sorted_input_stays_within_the_depth() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let (tris, _) = triangles_and_rays(&mut rng, 300, 0);
    let mut tree = Bvh4::build(&tris);
    let mut held = tris.clone();
    while !held.is_empty() {
        let index = held.len() / 2;
        tree.remove(index).expect("in range");
        held.swap_remove(index);
    }
    assert!(tree.is_empty() && tree.nodes().is_empty());
    tree.validate().expect("an empty tree is valid");
    check_answers(&tree, &held, &mut rng, "emptied");
    // Refilled in sorted order along x: the worst case for a tree grown by inserts.
    let mut sorted = tris;
    sorted.sort_by(|a, b| a.a.x.total_cmp(&b.a.x));
    for t in &sorted {
        tree.insert(*t);
        held.push(*t);
    }
    check_answers(&tree, &held, &mut rng, "refilled in order");
    assert!(tree.depth() <= bvhlab::structure::bvh::MAX_DEPTH);
}

#[test]
fn a_mesh_loses_and_regains_half_its_triangles() {
    let Some(mesh) = crate::bvh_common::shared_mesh("spot.obj") else {
        return;
    };
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    // Scaled to the random rays' and points' scene (the cow is about 2 units across).
    let mesh: Vec<Triangle3> = mesh
        .iter()
        .map(|t| Triangle3::new(t.a * 6.0, t.b * 6.0, t.c * 6.0))
        .collect();
    let mut tree = Bvh4::build(&mesh);
    let mut held = mesh.clone();
    let mut taken = Vec::new();
    for _ in 0..mesh.len() / 2 {
        let index = rng.random_range(0..held.len());
        taken.push(tree.remove(index).expect("in range").prim);
        held.swap_remove(index);
    }
    check_answers(&tree, &held, &mut rng, "spot without half");
    for t in taken {
        tree.insert(t);
        held.push(t);
    }
    check_answers(&tree, &held, &mut rng, "spot whole again");
    let report = tree.refit_report();
    assert!(report.sah_cost.is_some());
}

#[cfg(feature = "serde")]
#[test]
fn an_updated_tree_round_trips_through_a_saved_file() {
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    let mut held: Vec<Triangle3> = (0..80).map(|_| random_triangle(&mut rng)).collect();
    let mut tree = Bvh4::build(&held);
    held.push(Triangle3::new(Vec3::NAN, Vec3::ONE, Vec3::X));
    tree.insert(held[80]);
    tree.remove(3).expect("in range");
    held.swap_remove(3);
    let bytes = bvhlab::saved::save(&tree).expect("saved");
    let mut back: Bvh4<Triangle3> = bvhlab::saved::load(&bytes).expect("loaded");
    assert_eq!(format!("{back:?}"), format!("{tree:?}"));
    // The left-out triangle comes back from the loaded tree too.
    let nan = held
        .iter()
        .position(|t| !t.has_finite_coordinates())
        .expect("one");
    let removed = back.remove(nan).expect("in range");
    assert!(!removed.prim.has_finite_coordinates());
}
