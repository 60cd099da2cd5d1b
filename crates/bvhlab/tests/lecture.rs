//! The slides' own BVH queries (`Bvh::lecture_*`): the same answers as brute force and as the
//! real traversals, the costs the slides' omissions imply, and event streams that follow the
//! recursion exactly as the lab's pseudocode view reads them.
//!
//! The event streams are checked twice: against the protocol, re-derived here from the tree's
//! public layout and the primitives' own tests ([`expect_intersect`], [`expect_min_distance`]),
//! and against properties that need no re-derivation (costs count the events, a queued child
//! is the next node entered, a left subtree is finished before its right sibling is entered).

use crate::bvh_common;

use std::path::PathBuf;

use bvh_common::scenes::{degenerate, random};
use bvh_common::{TestPrim, assert_counts, plausible_hit, points_for, rays_for, rng, scene_box};
use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
use bvhlab::structure::bvh::{Bvh, BvhOptions, NodeVolume, PreparedRay, SLACK, SplitMethod, TINY};
use bvhlab::structure::{
    BruteForce, Event, Hit, NodeId, PrimitiveResult, PruneAt, PruneReason, QueryCost, Recorder,
};
use bvhlab::{Aabb, Mesh, Obb, Ray, Sphere};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

// ---- the event stream, re-derived from the protocol ----

/// Reads events one at a time, naming the position of any surprise.
struct Cursor<'e, V: Vector> {
    events: &'e [Event<V>],
    at: usize,
}

impl<'e, V: Vector> Cursor<'e, V> {
    fn new(events: &'e [Event<V>]) -> Self {
        Self { events, at: 0 }
    }

    fn peek(&self) -> Option<&Event<V>> {
        self.events.get(self.at)
    }

    /// Takes the next event, which must be `want` (compared by their `Debug` forms, so that
    /// a NaN distance, of a primitive whose coordinates overflow, equals itself).
    fn expect(&mut self, want: Event<V>) {
        let got = self.events.get(self.at);
        assert_eq!(
            format!("{got:?}"),
            format!("{:?}", Some(&want)),
            "event {}",
            self.at
        );
        self.at += 1;
    }

    fn finish(&self) {
        assert_eq!(self.at, self.events.len(), "events left over");
    }
}

/// The nearest hit so far, by the rule the brief gives (smaller `t`, then lower index).
fn improves(best: Option<(f32, u32)>, t: f32, prim: u32) -> bool {
    t >= 0.0 && best.is_none_or(|(bt, bp)| t < bt || (t == bt && prim < bp))
}

/// What `intersect(node)` must report, recursively: `EnterNode`, `RayBoundTest` (the volume's
/// own `ray_entry`), `Prune(RayMissed)` on a miss, else each primitive's test and `NewBest`
/// when the query's best improves, or `ChildQueued` and the call, left then right.
fn expect_intersect<B, P>(
    bvh: &Bvh<B, P>,
    ray: &PreparedRay<P::Point>,
    t_max: f32,
    events: &mut Cursor<'_, P::Point>,
    (node, depth): (NodeId, u32),
    best: &mut Option<(f32, u32)>,
) where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    events.expect(Event::EnterNode { node, depth });
    let interval = bvh.node(node).volume.ray_entry(ray);
    events.expect(Event::RayBoundTest { node, interval });
    if interval.is_none() {
        events.expect(Event::Prune {
            node,
            reason: PruneReason::RayMissed,
            at: PruneAt::Test,
        });
        return;
    }
    if let Some((left, right)) = bvh.children(node) {
        for (rank, child) in [left, right].into_iter().enumerate() {
            events.expect(Event::ChildQueued {
                parent: node,
                child,
                key: 0.0,
                rank: rank as u32,
            });
            expect_intersect(bvh, ray, t_max, events, (child, depth + 1), best);
        }
        return;
    }
    for &prim in bvh.leaf_primitives(node) {
        let t = bvh.primitives()[prim as usize]
            .ray_hit(&ray.ray)
            .filter(|&t| t <= t_max);
        events.expect(Event::PrimitiveTest {
            prim,
            result: t.map_or(PrimitiveResult::Miss, PrimitiveResult::Hit),
        });
        if let Some(t) = t
            && improves(*best, t, prim)
        {
            events.expect(Event::NewBest { prim, value: t });
            *best = Some((t, prim));
        }
    }
}

/// The query point, and whether the pruned variant is being checked.
#[derive(Clone, Copy)]
struct Probe<V> {
    point: V,
    pruned: bool,
}

/// What `minDistance(node)` must report, recursively. The pruned variant starts each call
/// with `DistanceBoundTest` (the volume's own `distance_bound`) and, when the stream prunes,
/// the prune must be sound (farther than the best so far) and reported with that best; a node
/// not pruned must lie within the best so far plus the documented slack.
fn expect_min_distance<B, P>(
    bvh: &Bvh<B, P>,
    probe: Probe<P::Point>,
    events: &mut Cursor<'_, P::Point>,
    (node, depth): (NodeId, u32),
    best: &mut Option<(f32, u32)>,
) where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    let point = probe.point;
    if probe.pruned {
        let distance = bvh.node(node).volume.distance_bound(point);
        events.expect(Event::DistanceBoundTest { node, distance });
        let bound = best.map_or(f32::INFINITY, |b| b.0);
        if let Some(Event::Prune { .. }) = events.peek() {
            assert!(
                distance > bound,
                "{node:?} pruned at {distance}, best {bound}"
            );
            events.expect(Event::Prune {
                node,
                reason: PruneReason::NoNearer {
                    distance,
                    best: bound,
                },
                at: PruneAt::Test,
            });
            return;
        }
        let slack = SLACK * point.abs().max_element() + TINY;
        assert!(
            distance <= bound * (1.0 + SLACK) + slack,
            "{node:?} at {distance} entered, best {bound}"
        );
    }
    events.expect(Event::EnterNode { node, depth });
    if let Some((left, right)) = bvh.children(node) {
        for (rank, child) in [left, right].into_iter().enumerate() {
            events.expect(Event::ChildQueued {
                parent: node,
                child,
                key: 0.0,
                rank: rank as u32,
            });
            expect_min_distance(bvh, probe, events, (child, depth + 1), best);
        }
        return;
    }
    for &prim in bvh.leaf_primitives(node) {
        let q = bvh.primitives()[prim as usize].project_point(point);
        let d = (q - point).length();
        events.expect(Event::PrimitiveTest {
            prim,
            result: PrimitiveResult::Distance(d),
        });
        if best.is_none_or(|b| (d, prim) < b) {
            events.expect(Event::NewBest { prim, value: d });
            *best = Some((d, prim));
        }
    }
}

// ---- properties of an event stream that need no re-derivation ----

/// Every node of the subtree under `node`, found through `children` alone.
fn subtree<B, P: Primitive>(bvh: &Bvh<B, P>, node: NodeId, into: &mut Vec<NodeId>) {
    into.push(node);
    if let Some((a, b)) = bvh.children(node) {
        subtree(bvh, a, into);
        subtree(bvh, b, into);
    }
}

/// A queued child is the next node the stream turns to (entered at once, or for the pruned
/// distance query bound-tested at once and then entered or pruned), and every node entered
/// after the root was queued by its parent just before.
fn check_children_entered_next<V: Vector>(events: &[Event<V>], pruned: bool) {
    for (i, event) in events.iter().enumerate() {
        if let Event::ChildQueued { child, .. } = *event {
            let next = events.get(i + 1);
            if pruned {
                assert!(
                    matches!(next, Some(Event::DistanceBoundTest { node, .. }) if *node == child),
                    "event {i}: {child:?} queued, then {next:?}"
                );
                let after = events.get(i + 2);
                assert!(
                    matches!(after, Some(Event::EnterNode { node, .. } | Event::Prune { node, .. }) if *node == child),
                    "event {}: {child:?} tested, then {after:?}",
                    i + 1
                );
            } else {
                assert!(
                    matches!(next, Some(Event::EnterNode { node, .. }) if *node == child),
                    "event {i}: {child:?} queued, then {next:?}"
                );
            }
        }
        if let Event::EnterNode { node, .. } = *event
            && node != NodeId(0)
        {
            let queued = events[..i].iter().rev().find_map(|e| match e {
                Event::ChildQueued { child, .. } => Some(*child),
                _ => None,
            });
            assert_eq!(
                queued,
                Some(node),
                "event {i}: entered without being queued"
            );
        }
    }
}

/// The nodes entered, in order, are a depth-first, left-first order: each node comes before
/// everything entered below it, and everything entered in its left subtree comes before
/// everything entered in its right subtree.
fn check_recursion_order<B, P: Primitive>(bvh: &Bvh<B, P>, events: &[Event<P::Point>]) {
    let entered: Vec<NodeId> = events
        .iter()
        .filter_map(|e| match e {
            Event::EnterNode { node, .. } => Some(*node),
            _ => None,
        })
        .collect();
    let position = |n: NodeId| entered.iter().position(|&m| m == n);
    for (at, &node) in entered.iter().enumerate() {
        let Some((left, right)) = bvh.children(node) else {
            continue;
        };
        let (mut below_left, mut below_right) = (Vec::new(), Vec::new());
        subtree(bvh, left, &mut below_left);
        subtree(bvh, right, &mut below_right);
        let lefts: Vec<usize> = below_left.into_iter().filter_map(position).collect();
        let rights: Vec<usize> = below_right.into_iter().filter_map(position).collect();
        assert!(lefts.iter().chain(&rights).all(|&p| p > at), "{node:?}");
        if let (Some(last_left), Some(first_right)) = (lefts.iter().max(), rights.iter().min()) {
            assert!(
                last_left < first_right,
                "{node:?}: right subtree entered early"
            );
        }
    }
}

/// `NewBest` values never grow, and the last one is the answer.
fn check_new_bests<V: Vector>(events: &[Event<V>], answer: Option<(usize, f32)>) {
    let bests: Vec<(usize, f32)> = events
        .iter()
        .filter_map(|e| match e {
            Event::NewBest { prim, value } => Some((*prim as usize, *value)),
            _ => None,
        })
        .collect();
    assert!(bests.windows(2).all(|w| w[1].1 <= w[0].1), "{bests:?}");
    assert_eq!(bests.last().copied(), answer);
}

// ---- one query of each kind, checked against everything ----

/// What one scene's queries cost, summed.
#[derive(Default, Debug)]
struct Tally {
    lecture: QueryCost,
    real: QueryCost,
    rays: usize,
    /// Rays on which the slides' intersect entered strictly more nodes than the real one.
    rays_costlier: usize,
    unpruned: QueryCost,
    pruned: QueryCost,
    real_nearest: QueryCost,
    points: usize,
}

/// The slides' intersect on one ray: brute force's and the real traversal's answer, at least
/// the real traversal's cost, and the protocol's events.
fn check_intersect<B, P>(
    name: &str,
    (bvh, brute): (&Bvh<B, P>, &BruteForce<P>),
    ray: &Ray<P::Point>,
    t_max: f32,
    tally: &mut Tally,
) where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    let mut recorder = Recorder::default();
    let lecture = bvh.lecture_intersect_observed(ray, t_max, &mut recorder);
    let real = bvh.ray_first_hit_observed(ray, t_max, &mut ());
    let want = brute.ray_first_hit(ray, t_max);
    let name = format!("{name}: {ray:?}, t_max {t_max}");
    assert_eq!(lecture.answer, real.answer, "{name}: real traversal");
    let plausible = |h: &Hit| plausible_hit(&brute.primitives()[h.prim], ray, h.t);
    if want.as_ref().is_none_or(plausible) {
        assert_eq!(lecture.answer, want, "{name}: brute force");
    }
    assert_eq!(bvh.lecture_intersect(ray, t_max), lecture.answer, "{name}");

    assert!(
        lecture.cost.nodes_visited >= real.cost.nodes_visited,
        "{name}"
    );
    assert!(lecture.cost.prim_tests >= real.cost.prim_tests, "{name}");
    tally.lecture += lecture.cost;
    tally.real += real.cost;
    tally.rays += 1;
    tally.rays_costlier += usize::from(lecture.cost.nodes_visited > real.cost.nodes_visited);

    let events = &recorder.events;
    assert_counts(&name, &recorder, lecture.cost);
    if let Some(root) = bvh.root() {
        let mut cursor = Cursor::new(events);
        let mut best = None;
        let prepared = PreparedRay::new(ray);
        expect_intersect(bvh, &prepared, t_max, &mut cursor, (root, 0), &mut best);
        cursor.finish();
    }
    check_children_entered_next(events, false);
    check_recursion_order(bvh, events);
    check_new_bests(events, lecture.answer.map(|h| (h.prim, h.t)));
}

/// Both slides' distance queries at one point: brute force's and the real traversal's
/// nearest, every node and primitive for the unpruned one, no more primitives for the pruned
/// one, and the protocol's events.
fn check_min_distance<B, P>(
    name: &str,
    (bvh, brute): (&Bvh<B, P>, &BruteForce<P>),
    point: P::Point,
    tally: &mut Tally,
) where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    let name = format!("{name}: nearest to {point:?}");
    let want = brute.closest_point(point);
    let real = bvh.k_nearest_observed(point, 1, &mut ());
    assert_eq!(real.answer.first().copied(), want, "{name}: real vs brute");
    let indexed = bvh.primitives().len() - bvh.skipped();
    let mut costs = [QueryCost::default(); 2];
    for (pruned, cost) in [false, true].into_iter().zip(&mut costs) {
        let mut recorder = Recorder::default();
        let traced = if pruned {
            assert_eq!(bvh.lecture_min_distance_pruned(point), want, "{name}");
            bvh.lecture_min_distance_pruned_observed(point, &mut recorder)
        } else {
            assert_eq!(bvh.lecture_min_distance(point), want, "{name}");
            bvh.lecture_min_distance_observed(point, &mut recorder)
        };
        assert_eq!(traced.answer, want, "{name}: pruned {pruned}");
        *cost = traced.cost;
        let events = &recorder.events;
        assert_counts(&name, &recorder, traced.cost);
        if let Some(root) = bvh.root() {
            let mut cursor = Cursor::new(events);
            let probe = Probe { point, pruned };
            expect_min_distance(bvh, probe, &mut cursor, (root, 0), &mut None);
            cursor.finish();
        }
        check_children_entered_next(events, pruned);
        check_recursion_order(bvh, events);
        check_new_bests(events, traced.answer.map(|n| (n.prim, n.distance)));
    }
    let [unpruned, pruned] = costs;
    let all = QueryCost {
        nodes_visited: bvh.nodes().len() as u64,
        bound_tests: 0,
        prim_tests: indexed as u64,
    };
    assert_eq!(
        unpruned, all,
        "{name}: the slide's minDistance visits everything"
    );
    assert!(pruned.prim_tests <= unpruned.prim_tests, "{name}");
    assert!(pruned.nodes_visited <= unpruned.nodes_visited, "{name}");
    tally.unpruned += unpruned;
    tally.pruned += pruned;
    tally.real_nearest += real.cost;
    tally.points += 1;
}

// ---- scenes ----

/// Rays the generic generator may not give every scene: from the scene's centre (inside)
/// along each axis both ways, along each axis from outside, and rays that start outside and
/// point away from everything.
fn extra_rays<P: Primitive>(prims: &[P]) -> Vec<Ray<P::Point>> {
    let (bounds, size) = scene_box(prims);
    let centre = bounds.center();
    let mut rays = Vec::new();
    for axis in 0..P::Point::DIM {
        for sign in [1.0, -1.0] {
            let dir = P::Point::unit_axis(axis) * sign;
            let outside = centre - dir * (2.0 * size);
            let away = bounds.max + P::Point::splat(size) * sign;
            rays.extend(Ray::new(centre, dir).ok());
            rays.extend(Ray::new(outside, dir).ok());
            rays.extend(Ray::new(away, P::Point::splat(sign)).ok());
            rays.extend(Ray::new(bounds.min - P::Point::splat(size), -dir.abs()).ok());
        }
    }
    rays
}

/// Builds `Bvh<B, P>` over `prims` and checks every lecture query on `rays` rays and
/// `points` points (plus [`extra_rays`] and the scene's vertices), adding the costs to
/// `tally`.
fn check_tree<B, P>(
    name: &str,
    prims: &[P],
    options: &BvhOptions,
    rng: &mut ChaCha8Rng,
    (rays, points): (usize, usize),
) -> Tally
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    let name = format!("{name} ({} tree, {:?})", B::NAME, options.method);
    let mut split_log = Recorder::default();
    let bvh = Bvh::<B, P>::build_observed(prims, options, &mut split_log);
    let log = split_log.splits;
    let brute = BruteForce::build(prims);
    let mut tally = Tally::default();
    let mut all_rays = rays_for(rng, prims, &log, rays);
    all_rays.extend(extra_rays(prims));
    for (i, ray) in all_rays.iter().enumerate() {
        let t_max = [f32::INFINITY, rng.random_range(0.0f32..1.5), 0.0][i % 3];
        check_intersect(&name, (&bvh, &brute), ray, t_max, &mut tally);
    }
    for point in points_for(rng, prims, &log, points) {
        check_min_distance(&name, (&bvh, &brute), point, &mut tally);
    }
    tally
}

/// The build methods the lab offers: the lecture's median splits and the SAH.
fn builds() -> [BvhOptions; 3] {
    [
        BvhOptions::with_method(SplitMethod::SpatialMedian),
        BvhOptions {
            leaf_size: 2,
            ..BvhOptions::with_method(SplitMethod::ObjectMedian)
        },
        BvhOptions::default(),
    ]
}

/// Every node volume and build over `prims`.
fn check_all<P: Primitive>(name: &str, prims: &[P], seed: u64, budget: (usize, usize))
where
    Aabb<P::Point>: NodeVolume<Point = P::Point>,
    Sphere<P::Point>: NodeVolume<Point = P::Point>,
    Obb<P::Point>: NodeVolume<Point = P::Point>,
{
    let mut rng = rng(seed);
    for options in builds() {
        check_tree::<Aabb<P::Point>, P>(name, prims, &options, &mut rng, budget);
        check_tree::<Sphere<P::Point>, P>(name, prims, &options, &mut rng, budget);
        check_tree::<Obb<P::Point>, P>(name, prims, &options, &mut rng, budget);
    }
}

#[test]
fn random_segments_2d() {
    let prims: Vec<Segment2> = random(&mut rng(81), 300);
    check_all("random segments", &prims, 82, (45, 15));
}

#[test]
fn random_triangles_3d() {
    let prims: Vec<Triangle3> = random(&mut rng(83), 300);
    check_all("random triangles", &prims, 84, (45, 15));
}

#[test]
fn degenerate_scenes() {
    fn run<P: TestPrim>(seed: u64)
    where
        Aabb<P::Point>: NodeVolume<Point = P::Point>,
        Sphere<P::Point>: NodeVolume<Point = P::Point>,
        Obb<P::Point>: NodeVolume<Point = P::Point>,
    {
        for (name, prims) in degenerate::<P>(&mut rng(seed)) {
            check_all(name, &prims, seed + 1, (12, 4));
        }
    }
    run::<Segment2>(85);
    run::<Triangle3>(87);
}

#[test]
fn empty_tree_answers_none_silently() {
    fn run<B: NodeVolume<Point = P::Point>, P: Primitive>(point: P::Point, ray: &Ray<P::Point>) {
        let bvh = Bvh::<B, P>::build(&[]);
        let mut recorder = Recorder::default();
        let hit = bvh.lecture_intersect_observed(ray, f32::INFINITY, &mut recorder);
        let near = bvh.lecture_min_distance_observed(point, &mut recorder);
        let pruned = bvh.lecture_min_distance_pruned_observed(point, &mut recorder);
        assert_eq!((hit.answer, near.answer, pruned.answer), (None, None, None));
        assert_eq!(hit.cost, QueryCost::default());
        assert_eq!(near.cost, QueryCost::default());
        assert_eq!(pruned.cost, QueryCost::default());
        assert!(recorder.events.is_empty(), "{:?}", recorder.events);
    }
    let ray2 = Ray::new(Vec2::ZERO, Vec2::X).expect("a valid ray");
    let ray3 = Ray::new(Vec3::ZERO, Vec3::X).expect("a valid ray");
    run::<Aabb<Vec2>, Segment2>(Vec2::ONE, &ray2);
    run::<Sphere<Vec3>, Triangle3>(Vec3::ONE, &ray3);
    run::<Obb<Vec3>, Triangle3>(Vec3::ONE, &ray3);
}

/// A non-finite query point or a NaN `t_max` has no answer, as for the real traversals.
#[test]
fn non_finite_queries_answer_none() {
    let prims: Vec<Triangle3> = random(&mut rng(89), 50);
    let bvh = Bvh::<Aabb<Vec3>, Triangle3>::build(&prims);
    let ray = Ray::through(Vec3::splat(-20.0), prims[0].centroid()).expect("a valid ray");
    assert!(bvh.ray_first_hit(&ray, f32::INFINITY).is_some());
    assert!(bvh.lecture_intersect(&ray, f32::INFINITY).is_some());
    assert_eq!(bvh.lecture_intersect(&ray, f32::NAN), None);
    for point in [
        Vec3::NAN,
        Vec3::INFINITY,
        Vec3::new(0.0, f32::NEG_INFINITY, 0.0),
    ] {
        assert_eq!(bvh.lecture_min_distance(point), None);
        assert_eq!(bvh.lecture_min_distance_pruned(point), None);
        assert_eq!(bvh.closest_point(point), None);
    }
}

// ---- cost on big scenes ----

/// The slides' intersect never enters fewer nodes than the real traversal (checked per ray
/// above) and, on a big scene, strictly more in aggregate and on many rays; the pruned
/// distance query tests far fewer primitives than the unpruned one.
fn assert_slides_costlier(name: &str, tally: &Tally) {
    eprintln!("{name}: {tally:?}");
    assert!(
        tally.lecture.nodes_visited > tally.real.nodes_visited,
        "{name}: {tally:?}"
    );
    assert!(
        tally.rays_costlier * 4 >= tally.rays,
        "{name}: only {} of {} rays cost more",
        tally.rays_costlier,
        tally.rays
    );
    assert!(
        tally.pruned.prim_tests * 4 < tally.unpruned.prim_tests,
        "{name}: {tally:?}"
    );
}

#[test]
fn slides_cost_more_on_a_big_random_scene() {
    let prims: Vec<Triangle3> = random(&mut rng(91), 3000);
    let mut rng = rng(92);
    let options = BvhOptions::default();
    let tally =
        check_tree::<Aabb<Vec3>, Triangle3>("3000 triangles", &prims, &options, &mut rng, (60, 8));
    assert_slides_costlier("3000 triangles, AABB SAH", &tally);
    let prims: Vec<Segment2> = random(&mut rng, 3000);
    let options = BvhOptions::with_method(SplitMethod::SpatialMedian);
    let tally =
        check_tree::<Sphere<Vec2>, Segment2>("3000 segments", &prims, &options, &mut rng, (60, 8));
    assert_slides_costlier("3000 segments, sphere median", &tally);
}

/// The triangles of a mesh of the shared data folder, or `None` (with a message) when the
/// folder is absent.
fn load(name: &str) -> Option<Vec<Triangle3>> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/meshes");
    if !dir.is_dir() {
        eprintln!("skipping {name}: the shared mesh folder is absent");
        return None;
    }
    let bytes = std::fs::read(dir.join(name)).expect("a readable mesh");
    Some(
        Mesh::from_obj(&bytes)
            .expect("a valid OBJ file")
            .triangles()
            .to_vec(),
    )
}

#[test]
fn suzanne_mesh() {
    let Some(prims) = load("suzanne.obj") else {
        return;
    };
    check_all("suzanne", &prims, 93, (30, 8));
    let options = BvhOptions::default();
    let tally =
        check_tree::<Obb<Vec3>, Triangle3>("suzanne", &prims, &options, &mut rng(94), (80, 10));
    assert_slides_costlier("suzanne, OBB SAH", &tally);
}
