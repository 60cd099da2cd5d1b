//! k-d trees (both builders) checked against brute force on random, degenerate and real
//! scenes in 2D and 3D, with rays that start on and run inside split planes.

use crate::kdtree_bsp_common;

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::kdtree::{AxisRule, KdNodeView, KdTree, KdTreeOptions};
use bvhlab::structure::{Event, NodeId, PrimitiveResult, RangeShape, Recorder};
use bvhlab::{Ray, Vector};
use kdtree_bsp_common::check::{check_collide, check_events, check_queries, queries};
use kdtree_bsp_common::{Sample, height_field, load_mesh, polygon, random_vector, rng, scenes};
use proptest::prelude::*;
use rand::RngExt;

fn all_options() -> [(&'static str, KdTreeOptions); 3] {
    [
        ("sah", KdTreeOptions::sah()),
        ("median", KdTreeOptions::median(AxisRule::LongestAxis)),
        ("round robin", KdTreeOptions::median(AxisRule::RoundRobin)),
    ]
}

/// Rays that start exactly on an inner node's split plane, inside its cell: crossing it both
/// ways, and running inside it.
fn split_plane_rays<P: Primitive>(
    tree: &KdTree<P>,
    seed: u64,
    n: usize,
) -> Vec<(Ray<P::Point>, f32)> {
    let mut r = rng(seed);
    let cells = tree.cells();
    let inner: Vec<usize> = (0..tree.nodes().len())
        .filter(|&i| !tree.nodes()[i].is_leaf())
        .collect();
    if inner.is_empty() {
        return Vec::new();
    }
    (0..n)
        .filter_map(|i| {
            let node = inner[r.random_range(0..inner.len())];
            let KdNodeView::Inner { axis, split, .. } = tree.node(NodeId(node as u32)) else {
                unreachable!("an inner node")
            };
            let cell = cells[node];
            let mut origin = cell.min;
            for a in 0..P::Point::DIM {
                let t: f32 = r.random_range(0.0..=1.0);
                origin.set_coord(a, cell.min.coord(a) * (1.0 - t) + cell.max.coord(a) * t);
            }
            origin.set_coord(axis, split);
            let mut dir: P::Point = random_vector(&mut r, 1.0);
            match i % 3 {
                0 => dir.set_coord(axis, 0.0),
                1 => dir.set_coord(axis, 1.0),
                _ => dir.set_coord(axis, -1.0),
            }
            Ray::new(origin, dir).ok().map(|ray| (ray, f32::INFINITY))
        })
        .collect()
}

fn check_scene<P: Sample>(label: &str, prims: &[P], seed: u64) {
    for (name, options) in all_options() {
        let label = format!("{label}, {name}");
        let tree = KdTree::build_with(prims, &options);
        tree.validate().unwrap_or_else(|e| panic!("{label}: {e}"));
        let mut q = queries(&mut rng(seed), prims, 60);
        q.rays.extend(split_plane_rays(&tree, seed, 30));
        check_queries(&label, &tree, &q);
        check_events(&label, &tree, &q);
        // Against a shifted copy of itself.
        let shift: P::Point = random_vector(&mut rng(seed), 0.5);
        let moved: Vec<P> = prims.iter().map(|p| p.map(|v| v + shift)).collect();
        check_collide(&label, &tree, &KdTree::build_with(&moved, &options));
        let stats = tree.stats();
        assert!(stats.references >= prims.iter().filter(|p| p.bounds().min.is_finite()).count());
        assert_eq!(stats.nodes, tree.nodes().len(), "{label}");
    }
}

fn check_scenes<P: Sample>(seed: u64) {
    for (name, prims) in scenes::<P>(seed) {
        check_scene(name, &prims, seed);
    }
}

#[test]
fn segments_match_brute_force() {
    check_scenes::<Segment2>(1);
    check_scene("polygon", &polygon(100, 5.0), 2);
}

#[test]
fn points_2d_match_brute_force() {
    check_scenes::<Vec2>(3);
}

#[test]
fn triangles_match_brute_force() {
    check_scenes::<Triangle3>(4);
    check_scene("height field", &height_field(12, &mut rng(5)), 5);
}

#[test]
fn points_3d_match_brute_force() {
    check_scenes::<Vec3>(6);
}

#[test]
fn real_meshes_match_brute_force() {
    // (mesh, rays; the bunny is large: fewer queries against brute force, and no collision).
    let meshes = [
        ("spot.obj", 40),
        ("teapot.obj", 40),
        ("fandisk.obj", 40),
        ("stanford-bunny.obj", 8),
    ];
    for (i, (name, n)) in meshes.into_iter().enumerate() {
        let Some(mesh) = load_mesh(name) else {
            continue;
        };
        for (builder, options) in &all_options()[..2] {
            let label = format!("{name}, {builder}");
            let tree = KdTree::build_with(&mesh, options);
            tree.validate().unwrap_or_else(|e| panic!("{label}: {e}"));
            let mut q = queries(&mut rng(i as u64), &mesh, n);
            q.rays.extend(split_plane_rays(&tree, i as u64, n / 2));
            check_queries(&label, &tree, &q);
        }
        if mesh.len() > 20_000 {
            continue;
        }
        let part: Vec<Triangle3> = mesh
            .iter()
            .step_by(mesh.len() / 100 + 1)
            .map(|t| t.map(|v| v * 1.01))
            .collect();
        let tree = KdTree::build(&mesh);
        let other = KdTree::build(&part);
        let brute = bvhlab::BruteForce::build(&mesh);
        assert_eq!(
            tree.collide(&other),
            brute.collide(&bvhlab::BruteForce::build(&part)),
            "{name}"
        );
    }
}

#[test]
fn empty_and_non_finite_input() {
    let empty = KdTree::<Triangle3>::build(&[]);
    empty.validate().expect("an empty tree is valid");
    let ray = Ray::new(Vec3::ZERO, Vec3::X).expect("a valid ray");
    assert_eq!(empty.ray_first_hit(&ray, f32::INFINITY), None);
    assert!(empty.k_nearest(Vec3::ZERO, 3).is_empty());
    assert_eq!(empty.stats().nodes, 0);

    let mut prims = vec![
        Segment2::new(Vec2::new(0.0, -1.0), Vec2::new(0.0, 1.0)),
        Segment2::new(Vec2::new(f32::NAN, 0.0), Vec2::new(2.0, 0.0)),
        Segment2::new(Vec2::new(3.0, -1.0), Vec2::new(3.0, f32::INFINITY)),
    ];
    prims.extend(polygon(20, 2.0));
    for (name, options) in all_options() {
        let tree = KdTree::build_with(&prims, &options);
        tree.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
        let ray = Ray::new(Vec2::new(-5.0, 0.0), Vec2::X).expect("a valid ray");
        let hits = tree.ray_all_hits(&ray, f32::INFINITY);
        assert!(
            hits.iter().all(|h| h.prim != 1 && h.prim != 2),
            "{name}: {hits:?}"
        );
        assert_eq!(
            tree.ray_first_hit(&ray, f32::INFINITY).map(|h| h.t),
            Some(3.0),
            "{name}"
        );
        assert!(tree.k_nearest(Vec2::new(f32::NAN, 0.0), 1).is_empty());
    }
}

#[test]
fn identical_primitives_make_one_leaf() {
    let tri = Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::Y);
    for (name, options) in all_options() {
        let tree = KdTree::build_with(&[tri; 100], &options);
        tree.validate().expect("valid");
        let stats = tree.stats();
        assert_eq!((stats.nodes, stats.references), (1, 100), "{name}");
    }
}

const ALREADY: PrimitiveResult = PrimitiveResult::AlreadyTested;

#[test]
fn straddlers_are_listed_on_both_sides_and_counted() {
    // A long diagonal segment crosses every split of a grid of short ones.
    let mut prims: Vec<Segment2> = (0..64)
        .map(|i| {
            let at = Vec2::new((i % 8) as f32, (i / 8) as f32) + 0.25;
            Segment2::new(at, at + 0.5)
        })
        .collect();
    prims.push(Segment2::new(Vec2::ZERO, Vec2::splat(8.0)));
    for (name, options) in all_options() {
        let tree = KdTree::build_with(&prims, &options);
        tree.validate().expect("valid");
        let stats = tree.stats();
        assert!(stats.duplicated_references() > 0, "{name}: {stats:?}");
        // The mailbox tests the diagonal once although many leaves list it.
        let ray = Ray::new(Vec2::new(-1.0, -1.0), Vec2::ONE).expect("a valid ray");
        let mut recorder = Recorder::default();
        let all = tree.ray_all_hits_observed(&ray, f32::INFINITY, &mut recorder);
        let tests_of_diagonal = recorder
            .events
            .iter()
            .filter(
                |e| matches!(e, Event::PrimitiveTest { prim: 64, result } if *result != ALREADY),
            )
            .count();
        assert_eq!(tests_of_diagonal, 1, "{name}");
        assert!(all.answer.iter().any(|h| h.prim == 64), "{name}");
    }
}

#[test]
fn build_events_describe_the_tree() {
    let mut r = rng(9);
    let prims: Vec<Triangle3> = (0..200)
        .map(|_| {
            let at = random_vector(&mut r, 5.0);
            Triangle3::near(&mut r, at, 0.5)
        })
        .collect();
    for (name, options) in all_options() {
        let mut recorder = Recorder::default();
        let tree = KdTree::build_observed(&prims, &options, &mut recorder);
        let stats = tree.stats();
        let count = |f: fn(&Event<Vec3>) -> bool| recorder.events.iter().filter(|e| f(e)).count();
        assert_eq!(
            count(|e| matches!(e, Event::BuildNode { .. })),
            stats.nodes,
            "{name}"
        );
        assert_eq!(
            count(|e| matches!(e, Event::BuildLeaf { .. })),
            stats.leaves,
            "{name}"
        );
        assert_eq!(
            count(|e| matches!(e, Event::BuildSplit { .. })),
            stats.nodes - stats.leaves,
            "{name}"
        );
        assert!(stats.sah_cost.is_some_and(|c| c > 0.0), "{name}");
        assert_eq!(
            tree,
            KdTree::build_with(&prims, &options),
            "{name}: deterministic"
        );
    }
}

#[test]
fn sah_beats_median_on_a_clustered_scene() {
    let mut r = rng(10);
    let mut prims: Vec<Triangle3> = (0..400)
        .map(|_| {
            let at = random_vector(&mut r, 1.0);
            Triangle3::near(&mut r, at, 0.05)
        })
        .collect();
    prims.push(Triangle3::new(
        Vec3::splat(100.0),
        Vec3::splat(100.0) + Vec3::X,
        Vec3::splat(100.0) + Vec3::Y,
    ));
    let sah = KdTree::build(&prims).stats().sah_cost.expect("a cost");
    let median = KdTree::build_with(&prims, &KdTreeOptions::median(AxisRule::LongestAxis))
        .stats()
        .sah_cost
        .expect("a cost");
    assert!(sah < median, "SAH {sah} vs median {median}");
}

fn extreme() -> impl Strategy<Value = f32> {
    prop_oneof![
        -1.0e30f32..1.0e30,
        -1.0e-30f32..1.0e-30,
        Just(0.0f32),
        -10.0f32..10.0,
        Just(f32::MAX / 4.0),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn extreme_values_do_not_panic(
        coords in prop::collection::vec(extreme(), 0..60),
        query in prop::collection::vec(extreme(), 6),
        median in any::<bool>(),
    ) {
        let v = |c: &[f32]| Vec3::new(c[0], c[1], c[2]);
        let tris: Vec<Triangle3> = coords
            .chunks_exact(9)
            .map(|c| Triangle3::new(v(&c[0..3]), v(&c[3..6]), v(&c[6..9])))
            .collect();
        let options = if median {
            KdTreeOptions::median(AxisRule::RoundRobin)
        } else {
            KdTreeOptions::sah()
        };
        let tree = KdTree::build_with(&tris, &options);
        prop_assert!(tree.validate().is_ok());
        let (o, d) = (v(&query[0..3]), v(&query[3..6]));
        if let Ok(ray) = Ray::new(o, d) {
            let _ = tree.ray_first_hit(&ray, f32::INFINITY);
            let _ = tree.ray_all_hits(&ray, 1.0);
        }
        let _ = tree.k_nearest(o, 2);
        let _ = tree.range(&RangeShape::Ball(bvhlab::Sphere::new(o, d.x.abs())));
        let _ = tree.collide(&tree);
        let segs: Vec<Segment2> = coords
            .chunks_exact(4)
            .map(|c| Segment2::new(Vec2::new(c[0], c[1]), Vec2::new(c[2], c[3])))
            .collect();
        let tree = KdTree::build_with(&segs, &options);
        prop_assert!(tree.validate().is_ok());
        let _ = tree.k_nearest(o.truncate(), 3);
    }
}

/// Regression (found by `tests/extreme_values.rs`): segment 1 runs from (-5.8e14, 65.5) to
/// (0, 9e-6), and its `f32` ray test reports a hit at `t = 0` for a ray starting at (1e-7, 0),
/// just past its end: its hits are only as exact as its 5.8e14 coordinates. The SAH tree's
/// plane crossings allowed only for the rounding of the plane and the ray origin (both tiny
/// there), so the tree skipped the cell where that hit lies and answered segment 0 instead.
#[test]
fn a_hit_as_inexact_as_a_huge_primitive_is_found_across_a_plane() {
    let segments = [
        Segment2::new(
            Vec2::new(2.282_646_2e-7, 0.0),
            Vec2::new(-579_430_300_000_000.0, 65.524_72),
        ),
        Segment2::new(
            Vec2::new(-579_430_300_000_000.0, 65.524_72),
            Vec2::new(0.0, 8.970_413e-6),
        ),
    ];
    let ray = Ray::new(Vec2::new(1e-7, 0.0), Vec2::new(-1e-7, 1e-6)).expect("ray");
    let brute = bvhlab::BruteForce::build(&segments);
    let want = brute.ray_first_hit(&ray, f32::INFINITY);
    assert_eq!(want.map(|h| h.prim), Some(1), "{want:?}");
    for options in [
        KdTreeOptions::sah(),
        KdTreeOptions::median(AxisRule::RoundRobin),
        KdTreeOptions::median(AxisRule::LongestAxis),
    ] {
        let tree = KdTree::build_with(&segments, &options);
        assert_eq!(tree.ray_first_hit(&ray, f32::INFINITY), want, "{options:?}");
        assert_eq!(
            tree.ray_all_hits(&ray, f32::INFINITY),
            brute.ray_all_hits(&ray, f32::INFINITY),
            "{options:?}"
        );
    }
}
