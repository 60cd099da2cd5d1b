//! The parallel build (`Bvh::build_with_parallel`, `Bvh4::build_with_parallel`, the
//! `parallel` feature) against the serial one (`build_with`): the same tree, bit for bit:
//! every node's box (as bits), children and leaf range, the leaf order, the primitives and the
//! recorded SAH cost. Run with `cargo test -p bvhlab --features parallel --test
//! bvh_parallel_build`.
//!
//! The parallel build changes its path at sizes (`build/parallel.rs`: nodes of 4096
//! primitives and more build their children at once, nodes of 32768 and more are binned on
//! every core), so the random scenes take sizes on both sides of each; the degenerate ones
//! are large enough to reach the parallel paths with coincident centres (the object-median
//! fallback), one flat axis, signed zeros, and leaves forced by the depth limit.
#![cfg(feature = "parallel")]

use crate::bvh_common;

use bvh_common::scenes::{degenerate, random};
use bvh_common::{TestPrim, TreeBits, rng, shared_mesh, tree_bits};
use bvhlab::Segment2;
use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::bvh::{AabbTree, Bvh4, BvhOptions, SplitMethod};
use rand::RngExt;

/// Everything of a box tree, as bits (`tree_bits`), and its recorded SAH cost.
fn tree_and_cost_bits<P: Primitive>(tree: &AabbTree<P>) -> (TreeBits, Option<u32>) {
    (tree_bits(tree), tree.build_sah_cost().map(f32::to_bits))
}

/// Everything of a wide tree, as bits.
fn wide_bits<P: Primitive>(tree: &Bvh4<P>) -> Vec<u32> {
    tree.nodes()
        .iter()
        .flat_map(|node| {
            node.planes
                .iter()
                .flatten()
                .flatten()
                .map(|c| c.to_bits())
                .chain(node.child)
                .chain(node.count)
                .collect::<Vec<_>>()
        })
        .collect()
}

/// Builds `prims` with `options` serially and in parallel, binary and wide, and asserts
/// one tree each.
fn assert_same_tree<P: Primitive>(name: &str, prims: &[P], options: &BvhOptions) {
    let serial = AabbTree::<P>::build_with(prims, options);
    let parallel = AabbTree::<P>::build_with_parallel(prims, options);
    assert_eq!(
        tree_and_cost_bits(&serial),
        tree_and_cost_bits(&parallel),
        "{name} ({} primitives): serial and parallel, {options:?}",
        prims.len()
    );
    // The rest (input copy, leaf primitives, options) by value.
    assert!(serial == parallel, "{name}: the whole tree, {options:?}");
    parallel
        .validate()
        .unwrap_or_else(|e| panic!("{name}: the tree is valid: {e}"));
    let wide_serial = Bvh4::build_with(prims, options);
    let wide_parallel = Bvh4::build_with_parallel(prims, options);
    assert_eq!(
        wide_bits(&wide_serial),
        wide_bits(&wide_parallel),
        "{name}: wide nodes, {options:?}"
    );
    assert!(
        wide_serial == wide_parallel,
        "{name}: the wide tree, {options:?}"
    );
}

/// The option sets the tests run: the default and each knob at its edges, among them
/// leaves forced at a shallow depth and a leaf size above the subtree threshold (large
/// nodes that the SAH may keep as leaves).
fn option_sets() -> Vec<BvhOptions> {
    let default = BvhOptions::default();
    vec![
        default,
        BvhOptions { bins: 2, ..default },
        BvhOptions {
            bins: 64,
            ..default
        },
        BvhOptions {
            leaf_size: 1,
            ..default
        },
        BvhOptions {
            leaf_size: 5000,
            ..default
        },
        BvhOptions {
            max_depth: 0,
            ..default
        },
        BvhOptions {
            max_depth: 3,
            ..default
        },
        BvhOptions::for_triangle_blocks(),
    ]
}

/// Sizes on both sides of the parallel build's thresholds, and the smallest.
const SIZES: [usize; 12] = [
    0, 1, 2, 3, 100, 4095, 4096, 4097, 9000, 32767, 32768, 50_000,
];

#[test]
fn random_triangles_of_every_size_give_the_same_tree() {
    let mut r = rng(81);
    for n in SIZES {
        let tris: Vec<Triangle3> = random(&mut r, n);
        assert_same_tree("random triangles", &tris, &BvhOptions::default());
    }
}

#[test]
fn every_option_set_gives_the_same_tree() {
    let mut r = rng(82);
    let tris: Vec<Triangle3> = random(&mut r, 40_000);
    for options in option_sets() {
        assert_same_tree("random triangles", &tris, &options);
    }
    // The median methods are the serial build's on one thread: still the same tree.
    for method in [SplitMethod::SpatialMedian, SplitMethod::ObjectMedian] {
        assert_same_tree("random triangles", &tris, &BvhOptions::with_method(method));
    }
}

#[test]
fn points_and_segments_in_2d_and_3d_give_the_same_tree() {
    let mut r = rng(83);
    for n in [5000, 40_000] {
        let segments: Vec<Segment2> = random(&mut r, n);
        assert_same_tree("segments", &segments, &BvhOptions::default());
        let points: Vec<Vec2> = random(&mut r, n);
        assert_same_tree("2D points", &points, &BvhOptions::default());
        let points: Vec<Vec3> = random(&mut r, n);
        assert_same_tree("3D points", &points, &BvhOptions::default());
    }
}

/// The small degenerate scenes every builder is tested on (empty, one primitive,
/// duplicates, flat, on a line, far away, tiny, huge...), and each scaled up past the
/// parallel thresholds by repeating it with small shifts.
#[test]
fn degenerate_scenes_give_the_same_tree() {
    let mut r = rng(84);
    for (name, tris) in degenerate::<Triangle3>(&mut r) {
        for options in option_sets() {
            assert_same_tree(name, &tris, &options);
        }
        if tris.is_empty() {
            continue;
        }
        let copies = 40_000 / tris.len() + 1;
        let big: Vec<Triangle3> = (0..copies)
            .flat_map(|k| {
                let shift = Vec3::splat((k % 3) as f32);
                tris.iter().map(move |t| t.map(|v| v + shift))
            })
            .collect();
        assert_same_tree(name, &big, &BvhOptions::default());
    }
}

/// Large nodes whose centres coincide (the object-median fallback above the thresholds),
/// and points whose coordinates are `0.0` and `-0.0` (the one case where the order of the
/// box merges shows, in the sign of a zero).
#[test]
fn coincident_centres_and_signed_zeros_give_the_same_tree() {
    let mut r = rng(85);
    let one: Vec<Triangle3> = random(&mut r, 1);
    let identical = vec![one[0]; 40_000];
    assert_same_tree("identical", &identical, &BvhOptions::default());
    let few: Vec<Triangle3> = random(&mut r, 3);
    let twins: Vec<Triangle3> = (0..45_000).map(|i| few[i % 3]).collect();
    assert_same_tree(
        "three triangles over and over",
        &twins,
        &BvhOptions::default(),
    );
    let zeros: Vec<Vec3> = (0..40_000)
        .map(|_| {
            let mut coord = || match r.random_range(0..4) {
                0 => 0.0,
                1 => -0.0,
                2 => 1.0,
                _ => -1.0,
            };
            Vec3::new(coord(), coord(), coord())
        })
        .collect();
    for options in option_sets() {
        assert_same_tree("signed zeros", &zeros, &options);
    }
}

#[test]
fn shared_meshes_give_the_same_tree() {
    for name in ["stanford-bunny.obj", "dragon.obj", "spot.obj"] {
        if let Some(tris) = shared_mesh(name) {
            assert_same_tree(name, &tris, &BvhOptions::default());
        }
    }
}
