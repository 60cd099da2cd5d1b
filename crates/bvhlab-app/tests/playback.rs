//! Playback folds the core's events into counters, a stack or queue and a best answer; these
//! tests check the fold against the core's own count, answer and structure, for every
//! structure and task, on seeded random scenes.

use bvhlab::glam::Vec2;
use bvhlab::{Event, Ray2};
use bvhlab::{NodeOutline, Segment2};
use bvhlab_app::model::build_job::{BuildJob, Structure};
use bvhlab_app::model::presets::{random_points, random_segments};
use bvhlab_app::model::recording::{Answer, Question, Recording};
use bvhlab_app::model::scene::Scene;
use bvhlab_app::model::snapshot::{Frontier, Snapshot};
use bvhlab_app::model::structures::{BuildSettings, StructureKind};
use bvhlab_app::pseudocode::{Task, Variant};

/// A structure built on a scene as the lab builds it, with the scene's segments.
struct Built2d {
    segments: Vec<Segment2>,
    structure: Structure<Segment2>,
}

impl Built2d {
    fn new(scene: &Scene, settings: BuildSettings) -> Self {
        let segments = scene.primitives().segments;
        let structure = BuildJob::start(&segments, scene.revision(), settings)
            .expect("every structure is offered in 2D")
            .run(&segments, f64::INFINITY)
            .expect("a 2D scene builds at once");
        Self {
            segments,
            structure,
        }
    }

    fn record(&self, question: Question) -> Result<Recording, String> {
        Recording::record_on(self.structure.subject(&self.segments), question)
    }

    fn outline(&self) -> &[NodeOutline<Vec2>] {
        self.structure
            .outline
            .as_deref()
            .expect("2D structures are listed")
    }
}

fn question(task: Task, ray: Ray2, point: Vec2) -> Question {
    Question {
        task,
        variant: Variant::Full,
        ray: Some(ray),
        point: Some(point),
        k: 3,
        radius: 4.0,
    }
}

fn rays() -> Vec<(Ray2, Vec2)> {
    let mut out = Vec::new();
    for i in 0..12 {
        let a = i as f32 * 0.55;
        let origin = Vec2::new(25.0, 25.0) + Vec2::new(a.cos(), a.sin()) * (5.0 + i as f32 * 3.0);
        let target = Vec2::new(25.0 + i as f32, 20.0 - i as f32 * 0.7);
        let Ok(ray) = Ray2::through(origin, target) else {
            continue;
        };
        out.push((ray, origin + Vec2::new(0.3, -0.2)));
    }
    out
}

fn scenes() -> Vec<Scene> {
    vec![
        random_segments(300, 50.0, 3.0, 11),
        random_segments(60, 50.0, 8.0, 12),
        random_points(200, 50.0, 13),
    ]
}

#[test]
fn the_last_step_counts_what_the_core_counted_and_holds_its_answer() {
    for scene in scenes() {
        for kind in StructureKind::ALL {
            let settings = BuildSettings {
                kind,
                ..BuildSettings::default()
            };
            let built = Built2d::new(&scene, settings);
            for (ray, point) in rays() {
                for task in [
                    Task::FirstHit,
                    Task::AnyHit,
                    Task::AllHits,
                    Task::Nearest,
                    Task::Range,
                ] {
                    let rec = built
                        .record(question(task, ray, point))
                        .unwrap_or_else(|e| panic!("{kind:?} {task:?}: {e}"));
                    assert!(rec.agrees(), "{kind:?} {task:?} answers like brute force");
                    let end = Snapshot::at(&rec, kind, rec.events.len(), built.outline().len());
                    let what = format!("{kind:?} {task:?} {ray:?}");
                    assert_eq!(end.so_far.nodes, rec.cost.nodes_visited, "nodes: {what}");
                    // Range queries report no event per volume test (only the refusals), so
                    // the panel shows their total only.
                    // A uniform grid's ray walk first clips the ray to the grid's box: one
                    // test the core counts but reports no event for (there is no node for
                    // the whole grid).
                    let unreported = u64::from(
                        kind == StructureKind::Grid
                            && matches!(task, Task::FirstHit | Task::AnyHit | Task::AllHits),
                    );
                    if task != Task::Range {
                        assert_eq!(
                            end.so_far.bound_tests + unreported,
                            rec.cost.bound_tests,
                            "BV: {what}"
                        );
                    }
                    assert_eq!(end.so_far.prim_tests, rec.cost.prim_tests, "prims: {what}");
                    let best: Vec<u32> = end.best.iter().map(|b| b.0).collect();
                    match &rec.answer {
                        Answer::Hit(hit) => {
                            assert_eq!(
                                best.first().map(|&p| p as usize),
                                hit.map(|h| h.prim),
                                "{what}"
                            );
                        }
                        Answer::Hits(hits) => {
                            let mut want: Vec<u32> = hits.iter().map(|h| h.prim as u32).collect();
                            let mut got = best.clone();
                            want.sort_unstable();
                            got.sort_unstable();
                            assert_eq!(got, want, "{what}");
                        }
                        Answer::Nearest(near) => {
                            let want: Vec<u32> = near.iter().map(|n| n.prim as u32).collect();
                            assert_eq!(best, want, "{what}");
                        }
                        Answer::Indices(inside) => {
                            let mut got = best.clone();
                            got.sort_unstable();
                            let want: Vec<u32> = inside.iter().map(|&i| i as u32).collect();
                            assert_eq!(got, want, "{what}");
                        }
                        Answer::Nodes(_) => unreachable!("not a build"),
                    }
                    // The start shows nothing done.
                    let start = Snapshot::at(&rec, kind, 0, built.outline().len());
                    assert_eq!(start.so_far.nodes + start.so_far.prim_tests, 0);
                    assert!(start.best.is_empty() && start.event.is_none());
                }
            }
        }
    }
}

#[test]
fn the_next_node_entered_is_the_one_the_stack_or_queue_shows_first() {
    let mut checked = 0;
    for scene in scenes() {
        for kind in StructureKind::ALL {
            let settings = BuildSettings {
                kind,
                ..BuildSettings::default()
            };
            let built = Built2d::new(&scene, settings);
            for (ray, point) in rays() {
                for task in [Task::FirstHit, Task::AllHits, Task::Nearest] {
                    let rec = built.record(question(task, ray, point)).expect("recorded");
                    for (i, event) in rec.events.iter().enumerate() {
                        let Event::EnterNode { node, .. } = *event else {
                            continue;
                        };
                        let before = Snapshot::at(&rec, kind, i, built.outline().len());
                        if before.frontier.is_empty() {
                            continue; // the root
                        }
                        let next = before.frontier[0].node;
                        if before.frontier_kind == Some(Frontier::Queue) {
                            // Ties in a priority queue may pop in either order.
                            let key = before.frontier[0].key;
                            assert!(
                                before
                                    .frontier
                                    .iter()
                                    .any(|p| p.node == node && p.key == key),
                                "{kind:?} {task:?}: entered {node:?}, queue head {next:?}"
                            );
                        } else {
                            assert_eq!(node, next, "{kind:?} {task:?} step {i}");
                        }
                        checked += 1;
                    }
                }
            }
        }
    }
    assert!(checked > 1000, "only {checked} pops were checked");
}

#[test]
fn builds_make_every_node_of_the_outline_with_its_parent() {
    for scene in scenes() {
        for kind in StructureKind::ALL {
            let settings = BuildSettings {
                kind,
                ..BuildSettings::default()
            };
            let built = Built2d::new(&scene, settings);
            let rec = built
                .record(question(
                    Task::Build,
                    Ray2::through(Vec2::ZERO, Vec2::X).expect("ray"),
                    Vec2::ZERO,
                ))
                .expect("recorded");
            let end = Snapshot::at(&rec, kind, rec.events.len(), built.outline().len());
            if kind == StructureKind::BruteForce {
                assert!(rec.events.is_empty() && built.outline().is_empty());
                continue;
            }
            for (node, made) in built.outline().iter().zip(&end.existing) {
                // A grid reports only the cells it puts primitives in.
                let reported = kind != StructureKind::Grid || !node.primitives.is_empty();
                assert!(*made || !reported, "{kind:?}: node {:?} is made", node.id);
            }
            for event in &rec.events {
                if let Event::BuildNode {
                    node,
                    parent,
                    depth,
                    ..
                } = *event
                {
                    let o = &built.outline()[node.index()];
                    assert_eq!(o.parent, parent, "{kind:?} node {node:?}'s parent");
                    assert_eq!(o.depth, depth, "{kind:?} node {node:?}'s depth");
                }
            }
            let half = Snapshot::at(&rec, kind, rec.events.len() / 2, built.outline().len());
            let made = half.existing.iter().filter(|&&e| e).count();
            assert!(
                made < built.outline().len() || built.outline().len() <= 1,
                "{kind:?}: half a build is not all of it"
            );
        }
    }
}

#[test]
fn the_slides_versions_answer_alike_and_cost_more() {
    let scene = random_segments(400, 50.0, 3.0, 21);
    for kind in [
        StructureKind::SphereTree,
        StructureKind::AabbTree,
        StructureKind::ObbTree,
    ] {
        let settings = BuildSettings {
            kind,
            ..BuildSettings::default()
        };
        let built = Built2d::new(&scene, settings);
        let (mut full_bv, mut lecture_bv, mut pruned_prims, mut unpruned_prims) = (0, 0, 0, 0);
        for (ray, point) in rays() {
            for (task, variant) in [
                (Task::FirstHit, Variant::Lecture),
                (Task::Nearest, Variant::Lecture),
                (Task::Nearest, Variant::LecturePruned),
            ] {
                let mut q = question(task, ray, point);
                q.variant = variant;
                q.k = 1;
                let rec = built.record(q).expect("a BVH offers the slides' version");
                assert!(rec.agrees(), "{kind:?} {task:?} {variant:?}");
                let end = Snapshot::at(&rec, kind, rec.events.len(), built.outline().len());
                assert_eq!(end.so_far.nodes, rec.cost.nodes_visited);
                assert_eq!(end.so_far.prim_tests, rec.cost.prim_tests);
                assert_eq!(end.frontier_kind, Some(Frontier::Calls));
                // The core's own recursion maps onto the slide's lines, step by step.
                for step in 0..rec.events.len() {
                    let line =
                        bvhlab_app::pseudocode::line_of(kind, task, variant, &rec.events, step);
                    assert!(line.is_some(), "{kind:?} {task:?} {variant:?} step {step}");
                }
                let full = rec
                    .variant_costs
                    .iter()
                    .find(|(v, _)| *v == Variant::Full)
                    .expect("the full version's cost is there too")
                    .1;
                match (task, variant) {
                    (Task::FirstHit, _) => {
                        full_bv += full.bound_tests;
                        lecture_bv += rec.cost.bound_tests;
                    }
                    (_, Variant::Lecture) => {
                        // The slide's minDistance tests every primitive.
                        assert_eq!(rec.cost.prim_tests as usize, built.segments.len());
                        unpruned_prims += rec.cost.prim_tests;
                    }
                    _ => pruned_prims += rec.cost.prim_tests,
                }
            }
        }
        assert!(lecture_bv > full_bv, "{kind:?}: {lecture_bv} vs {full_bv}");
        assert!(pruned_prims < unpruned_prims, "{kind:?}");
    }
    // Other structures have no slides' version, and say so.
    let built = Built2d::new(
        &scene,
        BuildSettings {
            kind: StructureKind::KdTree,
            ..BuildSettings::default()
        },
    );
    let (ray, point) = rays()[0];
    let mut q = question(Task::FirstHit, ray, point);
    q.variant = Variant::Lecture;
    let err = built
        .record(q)
        .expect_err("no slides' version for k-d trees");
    assert!(err.contains("only for BVHs"), "{err}");
}

#[test]
fn the_live_answers_read_from_a_recording_are_the_ones_a_query_gives() {
    use bvhlab_app::model::outcome::{PointOutcome, RayOutcome};
    let scene = random_segments(300, 50.0, 3.0, 31);
    for kind in StructureKind::ALL {
        let built = Built2d::new(
            &scene,
            BuildSettings {
                kind,
                ..BuildSettings::default()
            },
        );
        for (ray, point) in rays() {
            let rec = built
                .record(question(Task::FirstHit, ray, point))
                .expect("ray");
            let read = rec
                .ray_outcome()
                .expect("a full first hit gives the live answer");
            let run = RayOutcome::run(&built.structure.built, &built.structure.brute, ray);
            assert_eq!(
                (
                    read.hit,
                    read.cost,
                    read.brute_hit,
                    read.brute_cost,
                    &read.events
                ),
                (
                    run.hit,
                    run.cost,
                    run.brute_hit,
                    run.brute_cost,
                    &run.events
                ),
                "{kind:?}"
            );
            let rec = built
                .record(question(Task::Nearest, ray, point))
                .expect("point");
            let read = rec
                .point_outcome()
                .expect("a full k nearest gives the live answer");
            let run = PointOutcome::run(&built.structure.built, &built.structure.brute, point, 3);
            assert_eq!(
                (
                    &read.nearest,
                    read.cost,
                    &read.brute_nearest,
                    read.brute_cost,
                    &read.events
                ),
                (
                    &run.nearest,
                    run.cost,
                    &run.brute_nearest,
                    run.brute_cost,
                    &run.events
                ),
                "{kind:?}"
            );
            assert!(
                rec.ray_outcome().is_none(),
                "a point question has no ray answer"
            );
        }
    }
}
