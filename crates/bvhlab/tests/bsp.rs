//! BSP trees (random autopartition) checked against brute force on random, degenerate and real
//! scenes in 2D and 3D, with rays that start on and run inside splitting planes.

use crate::kdtree_bsp_common;

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::bsp::{BspNodeView, BspOptions, BspTree};
use bvhlab::structure::{Event, NodeId, Recorder};
use bvhlab::{Ray, Vector};
use kdtree_bsp_common::check::{check_collide, check_events, check_queries, queries};
use kdtree_bsp_common::{Sample, height_field, load_mesh, polygon, random_vector, rng, scenes};
use proptest::prelude::*;
use rand::RngExt;

fn all_options() -> [(&'static str, BspOptions); 3] {
    [
        ("default", BspOptions::default()),
        (
            "one candidate",
            BspOptions {
                candidates: 1,
                leaf_size: 1,
                ..BspOptions::default()
            },
        ),
        (
            "shallow",
            BspOptions {
                max_depth: Some(3),
                seed: 7,
                ..BspOptions::default()
            },
        ),
    ]
}

/// Rays that start on an inner node's plane (as nearly as `f32` allows), crossing it or
/// running inside it.
fn plane_rays<P: Primitive>(tree: &BspTree<P>, seed: u64, n: usize) -> Vec<(Ray<P::Point>, f32)> {
    let mut r = rng(seed);
    let inner: Vec<(P::Point, f32, bvhlab::Aabb<P::Point>)> = (0..tree.nodes().len())
        .filter_map(|i| match tree.node(NodeId(i as u32)) {
            BspNodeView::Inner {
                normal,
                offset,
                bounds,
                ..
            } => Some((normal, offset, bounds)),
            BspNodeView::Leaf { .. } => None,
        })
        .collect();
    if inner.is_empty() {
        return Vec::new();
    }
    (0..n)
        .filter_map(|i| {
            let (normal, offset, bounds) = inner[r.random_range(0..inner.len())];
            let mut p = bounds.min;
            for a in 0..P::Point::DIM {
                let t: f32 = r.random_range(0.0..=1.0);
                p.set_coord(a, bounds.min.coord(a) * (1.0 - t) + bounds.max.coord(a) * t);
            }
            let origin = p - normal * (normal.dot(p) - offset);
            let d: P::Point = random_vector(&mut r, 1.0);
            let dir = match i % 3 {
                0 => d - normal * normal.dot(d),
                1 => normal + d * 0.3,
                _ => -normal + d * 0.3,
            };
            Ray::new(origin, dir).ok().map(|ray| (ray, f32::INFINITY))
        })
        .collect()
}

fn check_scene<P: Sample>(label: &str, prims: &[P], seed: u64) {
    for (name, options) in all_options() {
        let label = format!("{label}, {name}");
        let tree = BspTree::build_with(prims, &options);
        tree.validate().unwrap_or_else(|e| panic!("{label}: {e}"));
        let mut q = queries(&mut rng(seed), prims, 60);
        q.rays.extend(plane_rays(&tree, seed, 30));
        check_queries(&label, &tree, &q);
        check_events(&label, &tree, &q);
        let shift: P::Point = random_vector(&mut rng(seed), 0.5);
        let moved: Vec<P> = prims.iter().map(|p| p.map(|v| v + shift)).collect();
        check_collide(&label, &tree, &BspTree::build_with(&moved, &options));
        assert_eq!(tree.stats().nodes, tree.nodes().len(), "{label}");
    }
}

fn check_scenes<P: Sample>(seed: u64) {
    for (name, prims) in scenes::<P>(seed) {
        check_scene(name, &prims, seed);
    }
}

#[test]
fn segments_match_brute_force() {
    check_scenes::<Segment2>(11);
    check_scene("polygon", &polygon(100, 5.0), 12);
}

#[test]
fn points_2d_match_brute_force() {
    check_scenes::<Vec2>(13);
}

#[test]
fn triangles_match_brute_force() {
    check_scenes::<Triangle3>(14);
    check_scene("height field", &height_field(12, &mut rng(15)), 15);
}

#[test]
fn points_3d_match_brute_force() {
    check_scenes::<Vec3>(16);
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
        let tree = BspTree::build(&mesh);
        tree.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut q = queries(&mut rng(20 + i as u64), &mesh, n);
        q.rays.extend(plane_rays(&tree, i as u64, n / 2));
        check_queries(name, &tree, &q);
        if mesh.len() > 20_000 {
            continue;
        }
        let part: Vec<Triangle3> = mesh
            .iter()
            .step_by(mesh.len() / 100 + 1)
            .map(|t| t.map(|v| v * 1.01))
            .collect();
        let brute = bvhlab::BruteForce::build(&mesh);
        let expected = brute.collide(&bvhlab::BruteForce::build(&part));
        assert_eq!(tree.collide(&BspTree::build(&part)), expected, "{name}");
    }
}

#[test]
fn splitters_are_the_primitives_own_lines() {
    // Autopartition: the splitting lines of a segment scene are the segments' own lines.
    let mut r = rng(30);
    let prims: Vec<Segment2> = (0..200)
        .map(|_| {
            let at = random_vector(&mut r, 10.0);
            Segment2::near(&mut r, at, 1.0)
        })
        .collect();
    let tree = BspTree::build(&prims);
    tree.validate().expect("valid");
    let (mut planes, mut own) = (0, 0);
    for i in 0..tree.nodes().len() {
        if let BspNodeView::Inner { normal, offset, .. } = tree.node(NodeId(i as u32)) {
            planes += 1;
            let on_line = |p: Vec2| (normal.dot(p) - offset).abs() <= 1e-4 * (1.0 + p.length());
            own += usize::from(prims.iter().any(|s| on_line(s.a) && on_line(s.b)));
        }
    }
    // The rest are the median-line fallback of nodes whose candidates separate nothing.
    assert!(
        planes > 10 && own * 10 >= planes * 8,
        "{own} of {planes} planes"
    );
}

#[test]
fn points_split_at_the_median_across_the_principal_axis() {
    // A long thin cloud along (1, 1): the root's plane is across that direction.
    let mut r = rng(31);
    let points: Vec<Vec2> = (0..500)
        .map(|_| {
            let t: f32 = r.random_range(-10.0..10.0);
            Vec2::splat(t) + random_vector::<Vec2>(&mut r, 0.1)
        })
        .collect();
    let tree = BspTree::build(&points);
    tree.validate().expect("valid");
    let BspNodeView::Inner {
        normal, children, ..
    } = tree.node(NodeId(0))
    else {
        panic!("the root is split")
    };
    assert!(normal.dot(Vec2::ONE.normalize()).abs() > 0.99, "{normal:?}");
    let count = |c: NodeId| -> usize {
        let mut recorder = Recorder::default();
        let _ = BspTree::build_observed(&points, &BspOptions::default(), &mut recorder);
        recorder
            .events
            .iter()
            .find_map(|e| match e {
                Event::BuildNode { node, prims, .. } if *node == c => Some(*prims as usize),
                _ => None,
            })
            .expect("the child was built")
    };
    let (below, above) = (count(children[0]), count(children[1]));
    assert!(below.abs_diff(above) <= 2, "{below} vs {above}");
}

#[test]
fn empty_identical_and_non_finite_input() {
    let empty = BspTree::<Triangle3>::build(&[]);
    empty.validate().expect("an empty tree is valid");
    let ray = Ray::new(Vec3::ZERO, Vec3::X).expect("a valid ray");
    assert_eq!(empty.ray_first_hit(&ray, f32::INFINITY), None);
    assert!(
        empty
            .range(&bvhlab::structure::RangeShape::Ball(bvhlab::Sphere::new(
                Vec3::ZERO,
                1.0
            )))
            .is_empty()
    );

    let tri = Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::Y);
    let same = BspTree::build(&[tri; 50]);
    same.validate().expect("valid");
    assert_eq!((same.stats().nodes, same.stats().references), (1, 50));

    let mut prims = polygon(20, 2.0);
    prims.push(Segment2::new(Vec2::new(f32::NAN, 0.0), Vec2::new(2.0, 0.0)));
    let tree = BspTree::build(&prims);
    tree.validate().expect("valid");
    let ray = Ray::new(Vec2::new(-5.0, 0.0), Vec2::X).expect("a valid ray");
    assert!(
        tree.ray_all_hits(&ray, f32::INFINITY)
            .iter()
            .all(|h| h.prim != 20)
    );
}

#[test]
fn builds_are_deterministic_and_reported() {
    let mut r = rng(32);
    let prims: Vec<Triangle3> = (0..300)
        .map(|_| {
            let at = random_vector(&mut r, 5.0);
            Triangle3::near(&mut r, at, 0.7)
        })
        .collect();
    let mut recorder = Recorder::default();
    let tree = BspTree::build_observed(&prims, &BspOptions::default(), &mut recorder);
    assert_eq!(tree, BspTree::build(&prims));
    let stats = tree.stats();
    let count = |f: fn(&Event<Vec3>) -> bool| recorder.events.iter().filter(|e| f(e)).count();
    assert_eq!(count(|e| matches!(e, Event::BuildNode { .. })), stats.nodes);
    assert_eq!(
        count(|e| matches!(e, Event::BuildLeaf { .. })),
        stats.leaves
    );
    assert_eq!(
        count(|e| matches!(e, Event::BuildSplit { .. })),
        stats.nodes - stats.leaves
    );
    assert!(stats.references >= prims.len() && stats.sah_cost.is_some());
    let other = BspTree::build_with(
        &prims,
        &BspOptions {
            seed: 99,
            ..BspOptions::default()
        },
    );
    other.validate().expect("valid");
    assert_ne!(other, tree, "the seed matters");
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
    ) {
        let v = |c: &[f32]| Vec3::new(c[0], c[1], c[2]);
        let tris: Vec<Triangle3> = coords
            .chunks_exact(9)
            .map(|c| Triangle3::new(v(&c[0..3]), v(&c[3..6]), v(&c[6..9])))
            .collect();
        let tree = BspTree::build(&tris);
        prop_assert!(tree.validate().is_ok());
        let (o, d) = (v(&query[0..3]), v(&query[3..6]));
        if let Ok(ray) = Ray::new(o, d) {
            let _ = tree.ray_first_hit(&ray, f32::INFINITY);
            let _ = tree.ray_any_hit(&ray, 1.0);
        }
        let _ = tree.k_nearest(o, 2);
        let _ = tree.collide(&tree);
        let points: Vec<Vec2> = coords.chunks_exact(2).map(|c| Vec2::new(c[0], c[1])).collect();
        let tree = BspTree::build(&points);
        prop_assert!(tree.validate().is_ok());
        let _ = tree.k_nearest(o.truncate(), 3);
    }
}
