//! `Outline` lists every structure's nodes so that the lab can draw them: ids match the
//! events' node ids, children lie where their parents say, and every stored primitive is in
//! some leaf.

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::structure::BruteForce;
use bvhlab::structure::bvh::{AabbTree, ObbTree, SphereTree};
use bvhlab::{
    BoundingVolume, BspTree, Event, Grid, KdTree, NodeShape, Orthtree, Outline, Primitive,
    Recorder, Segment2, SpatialIndex, Triangle3, Vector,
};
use bvhlab_tests::scenes::{random_segments, random_triangles};
use bvhlab_tests::{random_ray, random_vector, rng};

/// Checks the outline of `S` built over `prims` against the structure's own answers.
fn check<S>(prims: &[S::Prim], cells_nest: bool)
where
    S: Outline,
{
    let structure = S::build(prims);
    let outline = structure.outline();
    assert!(!outline.is_empty(), "a non-empty scene has nodes");
    let mut in_leaf = vec![false; prims.len()];
    for (i, node) in outline.iter().enumerate() {
        assert_eq!(node.id.index(), i, "outline is indexed by node id");
        for &child in &node.children {
            let c = &outline[child.index()];
            assert_eq!(c.parent, Some(node.id), "child {child:?} names its parent");
            assert_eq!(c.depth, node.depth + 1);
            if cells_nest {
                let (inner, outer) = (c.shape.aabb(), node.shape.aabb());
                assert!(
                    outer.contains(inner.min) && outer.contains(inner.max),
                    "cell {child:?} lies inside its parent's cell"
                );
            }
        }
        if node.is_leaf() {
            assert!(node.splits.is_empty(), "leaves have no split planes");
        } else {
            assert!(node.primitives.is_empty(), "inner nodes list no primitives");
        }
        for &p in &node.primitives {
            in_leaf[p as usize] = true;
            // Every listed primitive touches its node's region.
            let region = node.shape.aabb();
            let bounds = prims[p as usize].bounds();
            assert!(
                region.overlaps(&bounds) || matches!(node.shape, NodeShape::Sphere(_)),
                "primitive {p} listed in node {i} lies outside it"
            );
        }
    }
    assert!(
        in_leaf.iter().all(|&x| x),
        "every primitive is in some leaf"
    );

    // The node ids that queries report all name outline entries.
    let mut rng = rng(9);
    for _ in 0..50 {
        let ray = random_ray::<<S::Prim as Primitive>::Point>(&mut rng, 12.0);
        let mut recorder = Recorder::default();
        structure.ray_first_hit_observed(&ray, f32::INFINITY, &mut recorder);
        let point = random_vector(&mut rng, 12.0);
        structure.k_nearest_observed(point, 2, &mut recorder);
        for event in recorder.events {
            let (Event::EnterNode { node, .. }
            | Event::RayBoundTest { node, .. }
            | Event::DistanceBoundTest { node, .. }
            | Event::Prune { node, .. }
            | Event::PlaneCrossed { node, .. }
            | Event::CellEnter { cell: node, .. }) = event
            else {
                continue;
            };
            assert!(
                node.index() < outline.len(),
                "event {event:?} names a node the outline lacks"
            );
        }
    }
}

fn all_structures<P: Primitive>(prims: &[P])
where
    P::Point: Vector,
{
    check::<AabbTree<P>>(prims, true);
    check::<SphereTree<P>>(prims, false);
    check::<ObbTree<P>>(prims, false);
    check::<KdTree<P>>(prims, true);
    check::<BspTree<P>>(prims, false);
    check::<Grid<P>>(prims, true);
    check::<Orthtree<P>>(prims, true);
}

#[test]
fn outlines_in_2d() {
    let prims: Vec<Segment2> = random_segments(&mut rng(1), 300);
    all_structures(&prims);
}

#[test]
fn outlines_in_3d() {
    let prims: Vec<Triangle3> = random_triangles(&mut rng(2), 300);
    all_structures(&prims);
}

#[test]
fn points_are_primitives_too() {
    let mut rng = rng(3);
    let points: Vec<Vec2> = (0..200).map(|_| random_vector(&mut rng, 5.0)).collect();
    all_structures(&points);
    let points: Vec<Vec3> = (0..200).map(|_| random_vector(&mut rng, 5.0)).collect();
    all_structures(&points);
}

#[test]
fn brute_force_and_empty_structures_have_no_nodes() {
    assert!(
        BruteForce::<Segment2>::build(&random_segments(&mut rng(4), 10))
            .outline()
            .is_empty()
    );
    assert!(AabbTree::<Segment2>::build(&[]).outline().is_empty());
    assert!(KdTree::<Segment2>::build(&[]).outline().is_empty());
    assert!(Orthtree::<Segment2>::build(&[]).outline().is_empty());
}
