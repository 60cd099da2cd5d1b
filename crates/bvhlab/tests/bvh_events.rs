//! The events each query reports, replayed against the tree: nodes are entered in the order
//! the stack dictates, children are queued nearer first, pruned nodes say why, primitive
//! tests come from the leaf just entered, and the costs count the events.

use crate::bvh_common;

use bvh_common::scenes::random;
use bvh_common::{TestPrim, assert_counts, rng};
use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::bvh::{Bvh, NodeVolume};
use bvhlab::structure::{Event, NodeId, PruneAt, PruneReason, RangeShape, Recorder};
use bvhlab::{Aabb, Obb, Sphere};
use rand::RngExt;

/// Depth of every node.
fn depths<B, P: Primitive>(bvh: &Bvh<B, P>) -> Vec<u32> {
    let mut d = vec![0; bvh.nodes().len()];
    for i in 0..d.len() {
        if let Some((a, b)) = bvh.children(NodeId(i as u32)) {
            d[a.index()] = d[i] + 1;
            d[b.index()] = d[i] + 1;
        }
    }
    d
}

/// Replays a traversal's events: a simulated stack must agree with every `EnterNode` and
/// every prune at a pop or a stop; bound tests and `ChildQueued` must concern the children of
/// the node just entered (or the root, first), in visiting order; primitive tests must be of
/// the leaf just entered. Returns the nodes entered.
fn replay<B, P: Primitive>(bvh: &Bvh<B, P>, events: &[Event<P::Point>]) -> Vec<NodeId> {
    let depth = depths(bvh);
    let mut stack: Vec<NodeId> = Vec::new();
    let mut entered = Vec::new();
    let mut current: Option<NodeId> = None;
    let mut queued: Vec<(NodeId, f32, u32)> = Vec::new();
    let flush = |stack: &mut Vec<NodeId>, queued: &mut Vec<(NodeId, f32, u32)>| {
        for w in queued.windows(2) {
            assert!(
                w[0].1 <= w[1].1 && w[0].2 + 1 == w[1].2,
                "visiting order {queued:?}"
            );
        }
        stack.extend(queued.drain(..).rev().map(|q| q.0));
    };
    for (i, event) in events.iter().enumerate() {
        match *event {
            Event::RayBoundTest { node, .. } | Event::DistanceBoundTest { node, .. } => {
                let expected: Vec<NodeId> = match current {
                    None => vec![NodeId(0)],
                    Some(c) => bvh.children(c).map(|(a, b)| vec![a, b]).unwrap_or_default(),
                };
                assert!(
                    expected.contains(&node),
                    "event {i}: test of {node:?} under {current:?}"
                );
            }
            Event::ChildQueued {
                parent,
                child,
                key,
                rank,
            } => {
                assert_eq!(Some(parent), current, "event {i}");
                assert!(
                    bvh.children(parent)
                        .is_some_and(|(a, b)| child == a || child == b)
                );
                queued.push((child, key, rank));
            }
            Event::Prune { node, reason, at } => {
                if at == PruneAt::Test {
                    // Refused at its own test: the root, or a child of the node just entered,
                    // right after its bound test (a range query tests volumes silently).
                    let expected: Vec<NodeId> = match current {
                        None => vec![NodeId(0)],
                        Some(c) => bvh.children(c).map(|(a, b)| vec![a, b]).unwrap_or_default(),
                    };
                    assert!(
                        expected.contains(&node),
                        "event {i}: prune of {node:?} under {current:?}"
                    );
                    let just_tested = i > 0
                        && matches!(
                            events[i - 1],
                            Event::RayBoundTest { node: n, .. } | Event::DistanceBoundTest { node: n, .. }
                                if n == node
                        );
                    assert!(
                        just_tested || reason == PruneReason::NoOverlap,
                        "event {i}: {node:?} pruned at its test, but not right after it"
                    );
                } else {
                    // Taken from the stack (at a pop, or when the query stops).
                    flush(&mut stack, &mut queued);
                    assert_eq!(
                        stack.pop(),
                        Some(node),
                        "event {i}: pruned {node:?} is not on top"
                    );
                }
            }
            Event::EnterNode { node, depth: d } => {
                flush(&mut stack, &mut queued);
                if current.is_none() && entered.is_empty() {
                    assert_eq!(node, NodeId(0));
                } else {
                    assert_eq!(stack.pop(), Some(node), "event {i}: entered out of order");
                }
                assert_eq!(d, depth[node.index()]);
                entered.push(node);
                current = Some(node);
            }
            Event::PrimitiveTest { prim, .. } => {
                let leaf = current.expect("a primitive test inside a node");
                assert!(bvh.leaf_primitives(leaf).contains(&prim), "event {i}");
            }
            Event::NewBest { .. } => {}
            ref other => panic!("event {i}: unexpected {other:?}"),
        }
    }
    flush(&mut stack, &mut queued);
    assert!(
        stack.is_empty(),
        "nodes queued but never entered or pruned: {stack:?}"
    );
    entered
}

fn run<B, P>(seed: u64)
where
    B: NodeVolume<Point = P::Point>,
    P: TestPrim,
{
    let mut rng = rng(seed);
    let prims: Vec<P> = random(&mut rng, 400);
    let bvh = Bvh::<B, P>::build(&prims);
    let rays = bvh_common::rays_for(&mut rng, &prims, &[], 40);
    for ray in &rays {
        let mut recorder = Recorder::default();
        let first = bvh.ray_first_hit_observed(ray, f32::INFINITY, &mut recorder);
        replay(&bvh, &recorder.events);
        assert_counts("first hit", &recorder, first.cost);
        // NewBest values only decrease, and the last is the answer.
        let bests: Vec<(u32, f32)> = recorder
            .events
            .iter()
            .filter_map(|e| match e {
                Event::NewBest { prim, value } => Some((*prim, *value)),
                _ => None,
            })
            .collect();
        assert!(bests.windows(2).all(|w| w[1].1 <= w[0].1));
        assert_eq!(
            bests.last().map(|b| (b.0 as usize, b.1)),
            first.answer.map(|h| (h.prim, h.t))
        );

        let mut recorder = Recorder::default();
        let any = bvh.ray_any_hit_observed(ray, f32::INFINITY, &mut recorder);
        replay(&bvh, &recorder.events);
        assert_counts("any hit", &recorder, any.cost);
        assert!(
            any.cost.prim_tests
                <= bvh
                    .ray_all_hits_observed(ray, f32::INFINITY, &mut ())
                    .cost
                    .prim_tests
        );
    }
    for _ in 0..20 {
        let point: P::Point = bvh_common::random_vector(&mut rng, 12.0);
        let mut recorder = Recorder::default();
        let nearest = bvh.k_nearest_observed(point, 4, &mut recorder);
        replay(&bvh, &recorder.events);
        assert_counts("k nearest", &recorder, nearest.cost);
        // Branch and bound visits few leaves of a 400-primitive tree.
        assert!(nearest.cost.prim_tests < 200, "{:?}", nearest.cost);

        let shape = RangeShape::Ball(Sphere::new(point, rng.random_range(0.5..3.0)));
        let mut recorder = Recorder::default();
        let range = bvh.range_observed(&shape, &mut recorder);
        replay(&bvh, &recorder.events);
        assert_eq!(
            range.cost.prim_tests,
            recorder
                .events
                .iter()
                .filter(|e| matches!(e, Event::PrimitiveTest { .. }))
                .count() as u64
        );
    }
}

#[test]
fn aabb_events_replay() {
    run::<Aabb<Vec3>, Triangle3>(51);
    run::<Aabb<Vec2>, Segment2>(52);
}

#[test]
fn sphere_events_replay() {
    run::<Sphere<Vec3>, Triangle3>(53);
    run::<Sphere<Vec2>, Vec2>(54);
}

#[test]
fn obb_events_replay() {
    run::<Obb<Vec3>, Vec3>(55);
    run::<Obb<Vec2>, Segment2>(56);
}

/// A first-hit query prunes by the best hit: on a wall of triangles behind a near one, it
/// tests far fewer primitives than the all-hits query, and reports `BeyondBestHit` prunes.
#[test]
fn first_hit_prunes_beyond_the_best_hit() {
    let prims: Vec<Triangle3> = (0..200)
        .map(|i| {
            let z = i as f32;
            Triangle3::new(
                Vec3::new(-1.0, -1.0, z),
                Vec3::new(3.0, -1.0, z),
                Vec3::new(-1.0, 3.0, z),
            )
        })
        .collect();
    let bvh = Bvh::<Aabb3, Triangle3>::build(&prims);
    let ray = Ray3::new(Vec3::new(0.0, 0.0, -5.0), Vec3::Z).expect("valid");
    let mut recorder = Recorder::default();
    let first = bvh.ray_first_hit_observed(&ray, f32::INFINITY, &mut recorder);
    assert_eq!(first.answer.map(|h| h.prim), Some(0));
    let all = bvh.ray_all_hits_observed(&ray, f32::INFINITY, &mut ());
    assert_eq!(all.answer.len(), 200);
    assert!(
        first.cost.prim_tests * 10 < all.cost.prim_tests,
        "{:?}",
        first.cost
    );
    assert!(recorder.events.iter().any(|e| matches!(
        e,
        Event::Prune {
            reason: PruneReason::BeyondBestHit { .. },
            ..
        }
    )));
}

/// The collision query starts with the roots, tests node pairs before their children, and
/// tests primitive pairs only of overlapping leaves.
#[test]
fn collision_events_descend_from_the_roots() {
    let mut rng = rng(57);
    let a: Vec<Triangle3> = random(&mut rng, 200);
    let b: Vec<Triangle3> = random(&mut rng, 150);
    let (ta, tb) = (
        Bvh::<Obb3, Triangle3>::build(&a),
        Bvh::<Obb3, Triangle3>::build(&b),
    );
    let mut recorder = Recorder::default();
    let traced = ta.collide_observed(&tb, &mut recorder);
    assert_eq!(
        recorder.events.first(),
        Some(&Event::NodePairTest {
            a: NodeId(0),
            b: NodeId(0),
            overlap: true
        })
    );
    let mut last_pair = None;
    for event in &recorder.events {
        match *event {
            Event::NodePairTest { a, b, overlap } => last_pair = Some((a, b, overlap)),
            Event::PairTest { a: pa, b: pb, .. } => {
                let (na, nb, overlap) = last_pair.expect("a node pair first");
                assert!(overlap);
                assert!(
                    ta.leaf_primitives(na).contains(&pa) && tb.leaf_primitives(nb).contains(&pb)
                );
            }
            ref other => panic!("unexpected {other:?}"),
        }
    }
    assert!(!traced.answer.is_empty());
    assert!(
        traced.cost.prim_tests < (a.len() * b.len() / 10) as u64,
        "{:?}",
        traced.cost
    );
}
