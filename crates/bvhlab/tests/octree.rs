//! The quadtree (2D) and octree (3D), one generic `Orthtree`, against brute force on random,
//! degenerate and scaled scenes, with rays that start on, run along and cross split planes;
//! and the tree's own promises: termination on inseparable input, front-to-back order, the
//! hit-inside-the-leaf rule, exact leaf lists.

use crate::grid_support;

use bvhlab::RayCast;
use bvhlab::SpatialQuery;
use bvhlab::glam::{Vec2, Vec3};
use bvhlab::structure::quadtree::{Orthtree, OrthtreeOptions};
use bvhlab::structure::{NodeId, PrimitiveResult, Recorder};
use bvhlab::{Event, Primitive, Ray, Segment2, SpatialIndex, Triangle3, Vector};
use grid_support::{Map, check_queries, load_mesh, points_for, rays_for, rng, scenes};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// Corners of random cells: they lie on split planes, where cells meet.
fn corners<P: Primitive>(tree: &Orthtree<P>, rng: &mut ChaCha8Rng, count: usize) -> Vec<P::Point> {
    let cells = tree.cells();
    if cells.is_empty() {
        return Vec::new();
    }
    (0..count)
        .map(|_| {
            let cell = cells[rng.random_range(0..cells.len())].bounds;
            if rng.random_bool(0.5) {
                cell.min
            } else {
                cell.center()
            }
        })
        .collect()
}

fn options() -> [(&'static str, OrthtreeOptions); 3] {
    let deep = OrthtreeOptions {
        leaf_size: 1,
        max_depth: 12,
    };
    let shallow = OrthtreeOptions {
        leaf_size: 3,
        max_depth: 2,
    };
    [
        ("default", OrthtreeOptions::default()),
        ("deep", deep),
        ("shallow", shallow),
    ]
}

fn conformance<P: Map>(seed: u64) {
    let mut rng = rng(seed);
    let scenes = scenes::<P>(&mut rng);
    let other = Orthtree::build(&scenes[3].1);
    for (name, prims) in &scenes {
        for (label, options) in options() {
            let tree = Orthtree::build_with(prims, &options);
            let corners = corners(&tree, &mut rng, 10);
            let rays = rays_for(&mut rng, prims, &corners, 40);
            let points = points_for(&mut rng, prims, &corners, 10);
            let name = format!("{name} ({label}, {} nodes)", tree.node_count());
            check_queries(&name, &tree, Some(&other), &rays, &points, &mut rng);
        }
    }
}

#[test]
fn quadtree_of_segments_agrees_with_brute_force() {
    conformance::<Segment2>(21);
}

#[test]
fn octree_of_triangles_agrees_with_brute_force() {
    conformance::<Triangle3>(22);
}

#[test]
fn quadtree_of_points_agrees_with_brute_force() {
    conformance::<Vec2>(23);
}

#[test]
fn octree_of_points_agrees_with_brute_force() {
    conformance::<Vec3>(24);
}

#[test]
fn cells_have_two_to_the_dimension_children_inside_a_square_root() {
    let mut rng = rng(25);
    let quad = Orthtree::build(&Segment2::random(&mut rng, 200, 1.0));
    let oct = Orthtree::build(&Triangle3::random(&mut rng, 200, 1.0));
    assert_eq!(quad.children(NodeId(0)).map(|c| c.len()), Some(4));
    assert_eq!(oct.children(NodeId(0)).map(|c| c.len()), Some(8));
    let root = quad.root_box().size();
    assert!(
        (root.x - root.y).abs() <= 1e-5 * root.x,
        "square root cell {root:?}"
    );
    let root = oct.root_box().size();
    assert!((root.x - root.z).abs() <= 1e-5 * root.x && (root.y - root.z).abs() <= 1e-5 * root.x);
    for tree_stats in [quad.stats(), oct.stats()] {
        assert!(
            tree_stats.sah_cost.is_some_and(|c| c > 0.0),
            "{tree_stats:?}"
        );
        assert!(tree_stats.max_depth >= 2);
        assert_eq!(
            tree_stats.leaf_sizes.iter().sum::<usize>(),
            tree_stats.leaves
        );
    }
}

#[test]
fn inseparable_primitives_stop_the_splitting() {
    // Identical triangles, and a fan of triangles around one vertex: no split separates them.
    let same = vec![Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::Y); 100];
    let tree = Orthtree::build(&same);
    tree.validate().expect("valid");
    assert!(tree.node_count() <= 1 + 8 * 16, "{}", tree.node_count());
    let fan: Vec<Triangle3> = (0..40)
        .map(|k| {
            let a = k as f32 * std::f32::consts::TAU / 40.0;
            let b = a + std::f32::consts::TAU / 40.0;
            Triangle3::new(
                Vec3::ZERO,
                Vec3::new(a.cos(), a.sin(), 0.0),
                Vec3::new(b.cos(), b.sin(), 0.3),
            )
        })
        .collect();
    let tree = Orthtree::build(&fan);
    tree.validate().expect("valid");
    assert!(tree.stats().max_depth < 16, "{:?}", tree.stats());
    let points = vec![Vec2::new(3.0, 4.0); 1000];
    let tree = Orthtree::build(&points);
    assert_eq!(tree.node_count(), 1);
    assert_eq!(
        tree.k_nearest(Vec2::ZERO, 3)
            .iter()
            .map(|n| n.prim)
            .collect::<Vec<_>>(),
        [0, 1, 2]
    );
}

#[test]
fn children_are_visited_front_to_back() {
    let mut rng = rng(26);
    let prims = Triangle3::random(&mut rng, 500, 1.0);
    let tree = Orthtree::build(&prims);
    for _ in 0..40 {
        let origin: Vec3 = grid_support::random_vector(&mut rng, 15.0);
        let ray = Ray::new(origin, grid_support::random_vector(&mut rng, 1.0)).expect("ray");
        let mut recorder = Recorder::default();
        tree.ray_all_hits_observed(&ray, f32::INFINITY, &mut recorder);
        let mut last = (NodeId(u32::MAX), f32::NEG_INFINITY, 0);
        for event in &recorder.events {
            if let Event::ChildQueued {
                parent, key, rank, ..
            } = *event
            {
                if parent == last.0 {
                    assert!(
                        key >= last.1 && rank == last.2 + 1,
                        "{event:?} after {last:?}"
                    );
                } else {
                    assert_eq!(rank, 0);
                }
                last = (parent, key, rank);
            }
        }
        // Leaves are entered in order of where the ray enters them.
        let entered: Vec<u32> = recorder
            .events
            .iter()
            .filter_map(|e| match e {
                Event::EnterNode { node, .. } if tree.children(*node).is_none() => Some(node.0),
                _ => None,
            })
            .collect();
        let mut seen = entered.clone();
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(seen.len(), entered.len(), "a leaf entered twice");
    }
}

#[test]
fn a_hit_beyond_the_leaf_does_not_end_the_search() {
    // A long slanted segment crosses many leaves; the ray meets it late, a short wall first.
    let mut segments = vec![
        Segment2::new(Vec2::new(0.5, 5.2), Vec2::new(9.5, 5.8)),
        Segment2::new(Vec2::new(3.0, 5.1), Vec2::new(3.0, 5.9)),
    ];
    segments.extend(
        (0..40).map(|k| Segment2::new(Vec2::splat(k as f32 * 0.25), Vec2::splat(k as f32 * 0.25))),
    );
    let tree = Orthtree::build_with(
        &segments,
        &OrthtreeOptions {
            leaf_size: 2,
            max_depth: 6,
        },
    );
    let ray = Ray::new(Vec2::new(0.0, 5.5), Vec2::X).expect("ray");
    let mut recorder = Recorder::default();
    let hit = tree
        .ray_first_hit_observed(&ray, f32::INFINITY, &mut recorder)
        .answer;
    assert_eq!(hit.map(|h| h.prim), Some(1));
    assert!(
        recorder
            .events
            .iter()
            .any(|e| matches!(e, Event::HitBeyondRegion { prim: 0, .. }))
    );
    let mut recorder = Recorder::default();
    let all = tree.ray_all_hits_observed(&ray, f32::INFINITY, &mut recorder);
    // The wall, the slanted segment and the point (5.5, 5.5).
    assert_eq!(all.answer.len(), 3);
    let repeats = recorder
        .events
        .iter()
        .filter(|e| {
            matches!(
                e,
                Event::PrimitiveTest {
                    prim: 0,
                    result: PrimitiveResult::AlreadyTested
                }
            )
        })
        .count();
    assert!(
        repeats >= 1,
        "the slanted segment is listed in several leaves on the ray"
    );
}

#[test]
fn non_finite_primitives_are_left_out_and_never_answered() {
    let mut rng = rng(27);
    let mut prims = Segment2::random(&mut rng, 100, 1.5);
    prims[0].a.y = f32::NAN;
    prims[99].b = Vec2::splat(f32::NEG_INFINITY);
    let tree = Orthtree::build(&prims);
    let listed: Vec<u32> = tree
        .cells()
        .iter()
        .filter_map(|cell| cell.prims)
        .flatten()
        .copied()
        .collect();
    assert!(!listed.contains(&0) && !listed.contains(&99), "{listed:?}");
    // Aimed at the left-out segments' finite ends too: no answer names them.
    let rays = rays_for(&mut rng, &prims, &[], 60);
    let points = points_for(&mut rng, &prims, &[], 10);
    check_queries("non-finite", &tree, Some(&tree), &rays, &points, &mut rng);
    for point in &points {
        for near in tree.k_nearest(*point, 5) {
            assert!(near.prim != 0 && near.prim != 99, "{near:?}");
        }
    }
}

#[test]
fn coordinates_near_the_float_limit() {
    let mut rng = rng(28);
    let prims: Vec<Triangle3> = Triangle3::random(&mut rng, 60, 3.0)
        .iter()
        .map(|t| t.map(|v| v * 3e37))
        .collect();
    let tree = Orthtree::build(&prims);
    let rays = rays_for(&mut rng, &prims, &[], 60);
    let points = points_for(&mut rng, &prims, &[], 10);
    check_queries(
        "near f32::MAX",
        &tree,
        Some(&tree),
        &rays,
        &points,
        &mut rng,
    );
    let empty = Orthtree::<Triangle3>::build(&[]);
    assert_eq!(empty.node_count(), 0);
    assert!(empty.ray_first_hit(&rays[0], f32::INFINITY).is_none());
    empty.validate().expect("empty tree is valid");
}

#[test]
fn real_meshes() {
    let mut rng = rng(29);
    for (name, rays) in [
        ("spot.obj", 150),
        ("teapot.obj", 150),
        ("fandisk.obj", 150),
        ("stanford-bunny.obj", 40),
    ] {
        let Some(mesh) = load_mesh(name) else { return };
        let tree = Orthtree::build(&mesh);
        let corners = corners(&tree, &mut rng, 5);
        let rays: Vec<Ray<Vec3>> = rays_for(&mut rng, &mesh, &corners, rays);
        let points = points_for(&mut rng, &mesh, &[], 6);
        let other = Orthtree::build(&mesh[..20]);
        let other = (mesh.len() < 20_000).then_some(&other);
        check_queries(name, &tree, other, &rays, &points, &mut rng);
        assert!(<Vec3 as Vector>::DIM == 3 && tree.stats().references >= mesh.len());
    }
}
