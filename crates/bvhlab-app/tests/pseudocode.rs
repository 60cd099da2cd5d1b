//! The pseudocode panel's event → line mapping, on the events real queries and builds emit.
//!
//! Every structure answers every task on seeded random scenes and the lecture presets, with
//! several build options; every event of every stream must map to a line, and the lines the
//! lab promises (the pop, the skipped child the ray misses, the primitive test, the mailbox,
//! the split...) must be the ones highlighted, checked by a keyword of their text so that
//! rewording other lines does not matter. The slides' recursions are not in the core on this
//! branch: a small recursive simulator over a real BVH's outline emits their events.

use bvhlab::PointQuery;
use std::collections::HashSet;

use bvhlab::glam::Vec2;
use bvhlab::structure::kdtree::{AxisRule, KdTreeOptions};
use bvhlab::structure::{
    BspOptions, BvhOptions, GridOptions, NodeOutline, OrthtreeOptions, PrimitiveResult, PruneAt,
    PruneReason, RangeShape, SplitMethod,
};
use bvhlab::{
    Aabb, AabbTree2, BoundingVolume, Bsp2, Event, Grid2, KdTree2, NodeId, NodeShape, ObbTree2,
    Quadtree2, Ray2, Recorder, Segment2, SpatialIndex, Sphere, SphereTree2,
};
use bvhlab_app::model::presets::{Preset, random_points, random_segments};
use bvhlab_app::model::structures::{BuildSettings, Built, KdSplit, StructureKind};
use bvhlab_app::pseudocode::{Task, Variant, line_of, pseudocode};

/// A small deterministic generator (`SplitMix64`), so that the scenes and queries repeat.
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 40) as f32 / (1u64 << 24) as f32
    }

    fn point(&mut self, lo: f32, hi: f32) -> Vec2 {
        Vec2::new(lo + (hi - lo) * self.unit(), lo + (hi - lo) * self.unit())
    }
}

/// The scenes: seeded random segments and points, and the lecture presets (all but the
/// 10,000 segments, whose streams would only make the test slow).
fn scenes() -> Vec<(String, Vec<Segment2>)> {
    let mut out: Vec<(String, Vec<Segment2>)> = Preset::ALL
        .into_iter()
        .filter(|&p| p != Preset::TenThousand)
        .map(|p| (format!("{p:?}"), p.build().0.primitives().segments))
        .collect();
    for seed in 1..=3 {
        let scene = random_segments(80, 20.0, 4.0, seed);
        out.push((format!("segments {seed}"), scene.primitives().segments));
    }
    out.push((
        "points".into(),
        random_points(60, 20.0, 7).primitives().segments,
    ));
    out
}

/// The build options tried for `kind`: the default and the ones that change the tree.
fn settings(kind: StructureKind) -> Vec<BuildSettings> {
    let base = BuildSettings {
        kind,
        ..BuildSettings::default()
    };
    let mut out = vec![base];
    match kind {
        StructureKind::SphereTree | StructureKind::AabbTree | StructureKind::ObbTree => {
            for bvh_split in [SplitMethod::BinnedSah, SplitMethod::ObjectMedian] {
                out.push(BuildSettings {
                    bvh_split,
                    leaf_size: 4,
                    ..base
                });
            }
        }
        StructureKind::KdTree => {
            for kd_split in [KdSplit::MedianLongest, KdSplit::Sah] {
                out.push(BuildSettings { kd_split, ..base });
            }
        }
        StructureKind::Grid => out.push(BuildSettings {
            grid_cells: 4,
            ..base
        }),
        StructureKind::Bsp | StructureKind::Quadtree => out.push(BuildSettings {
            leaf_size: 1,
            ..base
        }),
        StructureKind::BruteForce => {}
    }
    out
}

/// One query of a task.
enum Query {
    Ray(Task, Ray2, f32),
    Nearest(Vec2, usize),
    Range(RangeShape<Vec2>),
}

impl Query {
    fn task(&self) -> Task {
        match self {
            Query::Ray(task, ..) => *task,
            Query::Nearest(..) => Task::Nearest,
            Query::Range(..) => Task::Range,
        }
    }
}

/// Rays from outside and inside the scene, some along the axes, with and without `tMax`;
/// points inside and outside; boxes and balls.
fn queries(seed: u64) -> Vec<Query> {
    let mut rng = Rng(seed);
    let mut out = Vec::new();
    for i in 0..8 {
        let from = if i % 2 == 0 {
            rng.point(-6.0, 26.0)
        } else {
            rng.point(2.0, 18.0)
        };
        let to = match i % 4 {
            1 => from + Vec2::X,
            3 => from - Vec2::Y,
            _ => rng.point(0.0, 20.0),
        };
        let Ok(ray) = Ray2::through(from, to) else {
            continue;
        };
        for task in [Task::FirstHit, Task::AnyHit, Task::AllHits] {
            out.push(Query::Ray(task, ray, f32::INFINITY));
        }
        out.push(Query::Ray(Task::AnyHit, ray, 6.0));
        out.push(Query::Ray(Task::AllHits, ray, 8.0));
        out.push(Query::Ray(Task::FirstHit, ray, 8.0));
    }
    for i in 0..6 {
        out.push(Query::Nearest(rng.point(-8.0, 28.0), 1 + 2 * (i % 3)));
    }
    for _ in 0..3 {
        let c = rng.point(-2.0, 22.0);
        let r = 1.0 + 4.0 * rng.unit();
        out.push(Query::Range(RangeShape::Box(Aabb::new(
            c - Vec2::splat(r),
            c + Vec2::new(r, 0.5 * r),
        ))));
        out.push(Query::Range(RangeShape::Ball(Sphere::new(c, r))));
    }
    out
}

/// Runs `query` on `s`, recording its events.
fn run<S: SpatialIndex<Prim = Segment2>>(s: &S, query: &Query) -> Vec<Event<Vec2>> {
    let mut rec = Recorder::default();
    match query {
        Query::Ray(Task::AnyHit, ray, t_max) => {
            s.ray_any_hit_observed(ray, *t_max, &mut rec);
        }
        Query::Ray(Task::AllHits, ray, t_max) => {
            s.ray_all_hits_observed(ray, *t_max, &mut rec);
        }
        Query::Ray(_, ray, t_max) => {
            s.ray_first_hit_observed(ray, *t_max, &mut rec);
        }
        Query::Nearest(point, k) => {
            s.k_nearest_observed(*point, *k, &mut rec);
        }
        Query::Range(shape) => {
            s.range_observed(shape, &mut rec);
        }
    }
    rec.events
}

/// Runs `query` on whichever structure `built` holds.
fn events_of(built: &Built, query: &Query) -> Vec<Event<Vec2>> {
    match built {
        Built::BruteForce(s) => run(s, query),
        Built::SphereTree(s) => run(s, query),
        Built::AabbTree(s) => run(s, query),
        Built::ObbTree(s) => run(s, query),
        Built::Grid(s) => run(s, query),
        Built::Bsp(s) => run(s, query),
        Built::Quadtree(s) => run(s, query),
        Built::KdTree(s) => run(s, query),
    }
}

/// The build's events, with the options `Built::build` derives from `settings`.
fn build_events(prims: &[Segment2], settings: &BuildSettings) -> Vec<Event<Vec2>> {
    let mut rec = Recorder::default();
    let leaf_size = settings.leaf_size.max(1);
    let bvh = BvhOptions {
        method: settings.bvh_split,
        leaf_size,
        sphere_fit: settings.sphere_fit,
        ..BvhOptions::default()
    };
    match settings.kind {
        StructureKind::BruteForce => {}
        StructureKind::SphereTree => {
            SphereTree2::build_observed(prims, &bvh, &mut rec);
        }
        StructureKind::AabbTree => {
            AabbTree2::build_observed(prims, &bvh, &mut rec);
        }
        StructureKind::ObbTree => {
            ObbTree2::build_observed(prims, &bvh, &mut rec);
        }
        StructureKind::Grid => {
            let n = settings.grid_cells;
            let options = GridOptions {
                resolution: (n > 0).then_some([n, n, 1]),
                ..GridOptions::default()
            };
            Grid2::build_observed(prims, &options, &mut rec);
        }
        StructureKind::Bsp => {
            let options = BspOptions {
                leaf_size,
                ..BspOptions::default()
            };
            Bsp2::build_observed(prims, &options, &mut rec);
        }
        StructureKind::Quadtree => {
            let options = OrthtreeOptions {
                leaf_size,
                max_depth: settings.quadtree_depth,
            };
            Quadtree2::build_observed(prims, &options, &mut rec);
        }
        StructureKind::KdTree => {
            let options = match settings.kd_split {
                KdSplit::MedianRoundRobin => KdTreeOptions {
                    leaf_size,
                    ..KdTreeOptions::median(AxisRule::RoundRobin)
                },
                KdSplit::MedianLongest => KdTreeOptions {
                    leaf_size,
                    ..KdTreeOptions::median(AxisRule::LongestAxis)
                },
                KdSplit::Sah => KdTreeOptions::sah(),
            };
            KdTree2::build_observed(prims, &options, &mut rec);
        }
    }
    rec.events
}

/// The highlighted line of every step: each event must have one.
fn lines(
    kind: StructureKind,
    task: Task,
    variant: Variant,
    events: &[Event<Vec2>],
    what: &str,
) -> Vec<&'static str> {
    let code = pseudocode(kind, task, variant).expect("the variant exists");
    (0..events.len())
        .map(|step| {
            let line = line_of(kind, task, variant, events, step);
            let line = line
                .unwrap_or_else(|| panic!("{what}: no line for step {step}, {:?}", events[step]));
            assert!(line < code.lines.len(), "{what}: line {line} out of range");
            code.lines[line]
        })
        .collect()
}

/// The keyword the line of `event` must contain in every full query listing, where the
/// event alone decides it.
fn query_keyword(kind: StructureKind, task: Task, event: &Event<Vec2>) -> Option<&'static str> {
    Some(match event {
        Event::PrimitiveTest {
            result: PrimitiveResult::AlreadyTested,
            ..
        } => "already",
        Event::PrimitiveTest { .. } => match task {
            Task::Nearest => "p.distance(point)",
            Task::Range => "overlaps region",
            _ => "p.intersect(ray, tp)",
        },
        Event::NewBest { .. } if task == Task::Nearest => "add p to best",
        Event::NewBest { .. } => "t = tp",
        Event::ChildQueued { .. } => "push",
        Event::PlaneCrossed { .. } => "crosses",
        Event::HitBeyondRegion { .. } => "tExit",
        Event::CellEnter { .. } => "cells along the ray",
        Event::EnterNode { .. } if kind == StructureKind::Grid => "c.primitives",
        Event::EnterNode { .. } => "pop",
        _ => return None,
    })
}

/// The lines the brief names for particular structures, read with the event before; the
/// keywords checked go into `seen`, so that the test knows every case came up.
fn check_named_lines(
    kind: StructureKind,
    task: Task,
    events: &[Event<Vec2>],
    texts: &[&str],
    what: &str,
    seen: &mut HashSet<&'static str>,
) {
    for (step, (event, text)) in events.iter().zip(texts).enumerate() {
        if let Some(keyword) = query_keyword(kind, task, event) {
            assert!(text.contains(keyword), "{what}: {event:?} at {text:?}");
            seen.insert(keyword);
        }
        let previous = step.checked_sub(1).map(|s| &events[s]);
        match (event, previous) {
            // A BVH child the ray misses, right after its test.
            (
                Event::Prune {
                    node,
                    reason: PruneReason::RayMissed,
                    ..
                },
                Some(Event::RayBoundTest { node: tested, .. }),
            ) if kind.is_bvh() && node == tested && node.0 != 0 => {
                assert!(text.contains("the ray misses c"), "{what}: {text:?}");
                seen.insert("the ray misses c");
            }
            // Any query's first bound test is the root's.
            (Event::RayBoundTest { .. } | Event::DistanceBoundTest { .. }, None)
                if kind != StructureKind::Grid =>
            {
                assert!(text.contains("root"), "{what}: {text:?}");
                seen.insert("root");
            }
            // The grid's walk ends at the first cell beyond the best hit.
            (Event::Prune { .. }, _) if kind == StructureKind::Grid && task == Task::FirstHit => {
                assert!(text.contains("return hit"), "{what}: {text:?}");
                seen.insert("return hit");
            }
            // A k-d or BSP first hit ends right after a leaf, skipping all that is left.
            (Event::Prune { .. }, _)
                if matches!(kind, StructureKind::KdTree | StructureKind::Bsp)
                    && task == Task::FirstHit
                    && text.contains("return hit") =>
            {
                let later = &events[step..];
                assert!(
                    later.iter().all(|e| matches!(e, Event::Prune { .. })),
                    "{what}: the search went on after {text:?}"
                );
                seen.insert("plane tree: return hit");
            }
            // The quadtree's best-first search ends at a popped cell no nearer than the best.
            (
                Event::Prune { node, .. },
                Some(Event::NewBest { .. } | Event::PrimitiveTest { .. }),
            ) if kind == StructureKind::Quadtree && task == Task::Nearest => {
                assert!(
                    node.0 == 0 || text.contains("return best"),
                    "{what}: {text:?}"
                );
                seen.insert("return best");
            }
            _ => {}
        }
    }
}

#[test]
fn every_event_of_every_real_query_has_its_line() {
    let mut streams = 0;
    let mut events_checked = 0;
    let mut seen = HashSet::new();
    for (name, prims) in scenes() {
        for kind in StructureKind::ALL {
            for settings in settings(kind) {
                let built = Built::build(&prims, &settings);
                for (i, query) in queries(name.len() as u64 + 17).iter().enumerate() {
                    let task = query.task();
                    let events = events_of(&built, query);
                    let what = format!("{name}, {settings:?}, query {i} ({task:?})");
                    let texts = lines(kind, task, Variant::Full, &events, &what);
                    check_named_lines(kind, task, &events, &texts, &what, &mut seen);
                    streams += 1;
                    events_checked += events.len();
                }
            }
        }
    }
    assert!(
        streams > 1000 && events_checked > 100_000,
        "{streams} {events_checked}"
    );
    let named = [
        "already",
        "p.distance(point)",
        "overlaps region",
        "p.intersect(ray, tp)",
        "add p to best",
        "t = tp",
        "push",
        "crosses",
        "tExit",
        "cells along the ray",
        "c.primitives",
        "pop",
        "the ray misses c",
        "root",
        "return hit",
        "plane tree: return hit",
        "return best",
    ];
    for keyword in named {
        assert!(seen.contains(keyword), "no event highlighted {keyword:?}");
    }
}

#[test]
fn every_build_event_has_its_line_and_splits_and_leaves_are_named() {
    let mut splits = 0;
    for (name, prims) in scenes() {
        for kind in StructureKind::ALL {
            for settings in settings(kind) {
                let events = build_events(&prims, &settings);
                let what = format!("{name}, {settings:?}");
                let texts = lines(kind, Task::Build, Variant::Full, &events, &what);
                for (event, text) in events.iter().zip(&texts) {
                    match event {
                        Event::BuildSplit { .. } => {
                            splits += 1;
                            assert!(text.contains("split"), "{what}: {text:?}");
                        }
                        Event::BuildLeaf { .. } if kind == StructureKind::Grid => {
                            assert!(text.contains("list is done"), "{what}: {text:?}");
                        }
                        Event::BuildLeaf { .. } => {
                            assert!(text.contains("is a leaf"), "{what}: {text:?}");
                        }
                        Event::BuildNode { .. } => {
                            assert!(text.contains("new") || text.contains("fit"), "{what}");
                        }
                        _ => panic!("{what}: a build reported {event:?}"),
                    }
                }
            }
        }
    }
    assert!(splits > 100, "{splits} splits");
}

/// The slides' recursions over a BVH's outline, emitting the events the core's lecture
/// traversals report (the protocol in the brief and in the core's `bvh/lecture.rs`).
struct Slides<'a> {
    nodes: &'a [NodeOutline<Vec2>],
    prims: &'a [Segment2],
    events: Vec<Event<Vec2>>,
    /// The query's best so far (`t` or distance).
    best: f32,
}

fn ray_interval(shape: &NodeShape<Vec2>, ray: &Ray2) -> Option<(f32, f32)> {
    match shape {
        NodeShape::Aabb(b) => b.ray_interval(ray),
        NodeShape::Sphere(s) => s.ray_interval(ray),
        NodeShape::Obb(o) => o.ray_interval(ray),
    }
}

fn distance(shape: &NodeShape<Vec2>, point: Vec2) -> f32 {
    match shape {
        NodeShape::Aabb(b) => b.distance(point),
        NodeShape::Sphere(s) => s.distance(point),
        NodeShape::Obb(o) => o.distance(point),
    }
}

impl Slides<'_> {
    fn queue(&mut self, parent: NodeId, child: NodeId, rank: u32) {
        self.events.push(Event::ChildQueued {
            parent,
            child,
            key: 0.0,
            rank,
        });
    }

    fn intersect(&mut self, node: NodeId, depth: u32, ray: &Ray2) {
        let outline = &self.nodes[node.index()];
        self.events.push(Event::EnterNode { node, depth });
        let interval = ray_interval(&outline.shape, ray);
        self.events.push(Event::RayBoundTest { node, interval });
        if interval.is_none() {
            self.events.push(Event::Prune {
                node,
                reason: PruneReason::RayMissed,
                at: PruneAt::Test,
            });
            return;
        }
        for &prim in &outline.primitives {
            let t = self.prims[prim as usize].ray_hit(ray);
            self.events.push(Event::PrimitiveTest {
                prim,
                result: t.map_or(PrimitiveResult::Miss, PrimitiveResult::Hit),
            });
            if let Some(t) = t.filter(|&t| t < self.best) {
                self.best = t;
                self.events.push(Event::NewBest { prim, value: t });
            }
        }
        for (rank, &child) in outline.children.iter().enumerate() {
            self.queue(node, child, rank as u32);
            self.intersect(child, depth + 1, ray);
        }
    }

    fn min_distance(&mut self, node: NodeId, depth: u32, point: Vec2, prune: bool) {
        let outline = &self.nodes[node.index()];
        if prune {
            let d = distance(&outline.shape, point);
            self.events
                .push(Event::DistanceBoundTest { node, distance: d });
            if d > self.best {
                self.events.push(Event::Prune {
                    node,
                    reason: PruneReason::NoNearer {
                        distance: d,
                        best: self.best,
                    },
                    at: PruneAt::Test,
                });
                return;
            }
        }
        self.events.push(Event::EnterNode { node, depth });
        for &prim in &outline.primitives {
            let d = (self.prims[prim as usize].project_point(point) - point).length();
            self.events.push(Event::PrimitiveTest {
                prim,
                result: PrimitiveResult::Distance(d),
            });
            if d < self.best {
                self.best = d;
                self.events.push(Event::NewBest { prim, value: d });
            }
        }
        for (rank, &child) in outline.children.iter().enumerate() {
            self.queue(node, child, rank as u32);
            self.min_distance(child, depth + 1, point, prune);
        }
    }
}

/// The keyword of the slide line each lecture event must highlight.
fn lecture_keyword(task: Task, variant: Variant, event: &Event<Vec2>) -> &'static str {
    match (event, task, variant) {
        (Event::EnterNode { .. }, Task::FirstHit, _) => "intersect(bvNode, ray, t)",
        (Event::EnterNode { .. }, _, Variant::LecturePruned) => "isLeaf",
        (Event::EnterNode { .. }, ..) => "minDistance(bvNode, point, currentMin)",
        (Event::RayBoundTest { .. }, ..) => "!bvNode.intersect(ray, t)",
        (Event::Prune { .. }, Task::FirstHit, _) => "return false;",
        (Event::DistanceBoundTest { .. }, ..) => "bvNode.distance(point) > currentMin",
        (Event::Prune { .. }, ..) => "return currentMin;",
        (Event::PrimitiveTest { .. }, Task::FirstHit, _) => "p.intersect(ray, tp)",
        (Event::PrimitiveTest { .. }, ..) => "p.distance(point) < d",
        (Event::NewBest { .. }, Task::FirstHit, _) => "t = tp",
        (Event::NewBest { .. }, ..) => "d = p.distance(point)",
        (Event::ChildQueued { rank: 0, .. }, Task::FirstHit, _) => "intersect(bvNode.left",
        (Event::ChildQueued { .. }, Task::FirstHit, _) => "intersect(bvNode.right",
        (Event::ChildQueued { rank: 0, .. }, ..) => "minDistance(bvNode.left",
        (Event::ChildQueued { .. }, ..) => "minDistance(bvNode.right",
        _ => panic!("the slides emit no {event:?}"),
    }
}

#[test]
fn the_slides_recursions_highlight_the_slides_lines() {
    let mut pruned_fewer = false;
    for (name, prims) in scenes() {
        for kind in [
            StructureKind::SphereTree,
            StructureKind::AabbTree,
            StructureKind::ObbTree,
        ] {
            let built = Built::build(
                &prims,
                &BuildSettings {
                    kind,
                    ..BuildSettings::default()
                },
            );
            let nodes = built.outline();
            if nodes.is_empty() {
                continue;
            }
            let slides = |run: &dyn Fn(&mut Slides<'_>)| {
                let mut s = Slides {
                    nodes: &nodes,
                    prims: &prims,
                    events: Vec::new(),
                    best: f32::INFINITY,
                };
                run(&mut s);
                s.events
            };
            for (i, query) in queries(name.len() as u64).iter().enumerate() {
                let streams = match query {
                    Query::Ray(Task::FirstHit, ray, _) => {
                        vec![(
                            Task::FirstHit,
                            Variant::Lecture,
                            slides(&|s| s.intersect(NodeId(0), 0, ray)),
                        )]
                    }
                    Query::Nearest(point, _) => {
                        let plain = slides(&|s| s.min_distance(NodeId(0), 0, *point, false));
                        let pruned = slides(&|s| s.min_distance(NodeId(0), 0, *point, true));
                        let entered = |e: &[Event<Vec2>]| {
                            e.iter()
                                .filter(|e| matches!(e, Event::EnterNode { .. }))
                                .count()
                        };
                        assert_eq!(entered(&plain), nodes.len(), "the slide visits every node");
                        pruned_fewer |= entered(&pruned) < nodes.len();
                        vec![
                            (Task::Nearest, Variant::Lecture, plain),
                            (Task::Nearest, Variant::LecturePruned, pruned),
                        ]
                    }
                    _ => continue,
                };
                for (task, variant, events) in streams {
                    let what = format!("{name}, {kind:?}, query {i}, {variant:?}");
                    let texts = lines(kind, task, variant, &events, &what);
                    for (event, text) in events.iter().zip(&texts) {
                        let keyword = lecture_keyword(task, variant, event);
                        assert!(text.contains(keyword), "{what}: {event:?} at {text:?}");
                    }
                }
            }
        }
    }
    assert!(pruned_fewer, "the pruning skipped something somewhere");
}
