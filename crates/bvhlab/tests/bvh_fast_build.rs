//! The one-go box-tree build (`build/fast.rs`, what [`Bvh::build_with`] runs for a
//! binned-SAH AABB tree) against the resumable builder the lab steps through ([`BvhBuild`]
//! and [`Bvh::build_observed`]): the same tree, bit for bit (every node's box, children and
//! leaf range, and the leaf order), on every shared mesh and on seeded scenes built to hit
//! each of its paths: nodes of two (its shortcut), coincident centres (the object-median
//! fallback), flat and line-like scenes (axes that cannot be binned), every bin count, leaf
//! size and depth limit.

use crate::bvh_common;

use bvh_common::scenes::{degenerate, random};
use bvh_common::{rng, shared_mesh, tree_bits};
use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::bvh::{AabbTree, Bvh, Bvh4, BvhBuild, BvhOptions, SplitMethod};
use bvhlab::{Aabb, Segment2};

/// Builds `prims` with `options` three ways (one go, in slices, observed) and asserts one
/// tree.
fn assert_same_tree<P: Primitive>(name: &str, prims: &[P], options: &BvhOptions) {
    let fast = Bvh::<Aabb<P::Point>, P>::build_with(prims, options);
    let mut build = BvhBuild::<Aabb<P::Point>, P>::new(prims.to_vec(), *options);
    while !build.is_done() {
        build.step(997);
    }
    let stepped = build.finish();
    let observed = Bvh::<Aabb<P::Point>, P>::build_observed(prims, options, &mut ());
    let bits = tree_bits(&fast);
    assert_eq!(
        bits,
        tree_bits(&stepped),
        "{name}: one go and in slices, {options:?}"
    );
    assert_eq!(
        bits,
        tree_bits(&observed),
        "{name}: one go and observed, {options:?}"
    );
    fast.validate()
        .unwrap_or_else(|e| panic!("{name}: the tree is valid: {e}"));
}

/// The option sets the tests run: the default, and each knob at its edges.
fn option_sets() -> Vec<BvhOptions> {
    let default = BvhOptions::default();
    let mut sets = vec![default];
    for bins in [2, 3, 7, 32, 64, 1000] {
        sets.push(BvhOptions { bins, ..default });
    }
    for leaf_size in [1, 2, 8, 64] {
        sets.push(BvhOptions {
            leaf_size,
            ..default
        });
    }
    for max_depth in [0, 1, 5] {
        sets.push(BvhOptions {
            max_depth,
            ..default
        });
    }
    let blocks = BvhOptions::for_triangle_blocks();
    sets.extend([
        blocks,
        BvhOptions {
            leaf_block: 2,
            ..blocks
        },
        // Blocks larger than the leaf size: the one-go build skips the binning of nodes
        // of at most both (they are leaves whatever the SAH says), so this is the case
        // where only the leaf size stops the skip.
        BvhOptions {
            leaf_block: 8,
            leaf_size: 3,
            ..default
        },
        BvhOptions {
            leaf_block: 16,
            ..blocks
        },
    ]);
    sets
}

#[test]
fn every_shared_mesh_gives_the_same_tree() {
    for name in [
        "stanford-bunny.obj",
        "dragon.obj",
        "ogre.obj",
        "spot.obj",
        "teapot.obj",
        "fandisk.obj",
        "suzanne.obj",
    ] {
        if let Some(tris) = shared_mesh(name) {
            assert_same_tree(name, &tris, &BvhOptions::default());
        }
    }
}

#[test]
fn a_mesh_with_every_option_set_gives_the_same_tree() {
    let Some(tris) = shared_mesh("spot.obj") else {
        return;
    };
    for options in option_sets() {
        assert_same_tree("spot", &tris, &options);
    }
}

#[test]
fn degenerate_scenes_give_the_same_tree_in_2d_and_3d() {
    let mut r = rng(71);
    for options in option_sets() {
        for (name, prims) in degenerate::<Triangle3>(&mut r) {
            assert_same_tree(name, &prims, &options);
        }
        for (name, prims) in degenerate::<Segment2>(&mut r) {
            assert_same_tree(name, &prims, &options);
        }
        for (name, prims) in degenerate::<Vec3>(&mut r) {
            assert_same_tree(name, &prims, &options);
        }
        for (name, prims) in degenerate::<Vec2>(&mut r) {
            assert_same_tree(name, &prims, &options);
        }
    }
}

#[test]
fn pairs_and_coincident_centres_give_the_same_tree() {
    let mut r = rng(72);
    // Many nodes of two: a leaf size of 1 splits every pair the SAH allows.
    let options = BvhOptions {
        leaf_size: 1,
        ..BvhOptions::default()
    };
    for n in [2, 3, 4, 5, 17, 64] {
        let tris: Vec<Triangle3> = random(&mut r, n);
        assert_same_tree("random", &tris, &options);
        // Each triangle twice: pairs with one centre, which the SAH cannot bin and the
        // object median splits.
        let twins: Vec<Triangle3> = tris.iter().flat_map(|t| [*t, *t]).collect();
        assert_same_tree("twins", &twins, &options);
        assert_same_tree("twins", &twins, &BvhOptions::default());
    }
    // Centres a few subnormals apart: the bins' scale overflows to infinity and the
    // least centre's bin position is `0 * inf`, a NaN, which the bins take as bin 0.
    let tiny: Vec<Vec3> = (0..40)
        .map(|i| Vec3::new(f32::from_bits(i % 7), f32::from_bits(3 * (i % 5)), 1.0))
        .collect();
    assert_same_tree("subnormal", &tiny, &options);
    assert_same_tree("subnormal", &tiny, &BvhOptions::default());
    // Non-finite primitives are left out the same way.
    let mut tris: Vec<Triangle3> = random(&mut r, 50);
    tris[7].a.x = f32::NAN;
    tris[20].b.y = f32::INFINITY;
    assert_same_tree("with NaN", &tris, &BvhOptions::default());
}

/// `Bvh4::build_with` (built without keeping the binary tree) is the collapse of the
/// binary tree built with the same options, for every option set and split method.
#[test]
fn a_wide_tree_built_directly_is_the_collapsed_binary_tree() {
    let mut r = rng(73);
    let mut scenes = degenerate::<Triangle3>(&mut r);
    scenes.extend(shared_mesh("spot.obj").map(|spot| ("spot", spot)));
    let mut sets = option_sets();
    for method in [SplitMethod::SpatialMedian, SplitMethod::ObjectMedian] {
        sets.push(BvhOptions::with_method(method));
    }
    for (name, tris) in &scenes {
        for options in &sets {
            let direct = Bvh4::build_with(tris, options);
            let collapsed = Bvh4::from_bvh(&AabbTree::build_with(tris, options));
            assert!(direct == collapsed, "{name}, {options:?}");
        }
        // Over triangles `build` costs leaves by blocks of four.
        let options = BvhOptions::for_triangle_blocks();
        assert!(
            Bvh4::build(tris) == Bvh4::from_bvh(&AabbTree::build_with(tris, &options)),
            "{name}"
        );
    }
}
