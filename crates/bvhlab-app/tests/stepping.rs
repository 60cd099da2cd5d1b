//! Headless UI tests of playback (issue 5): a student steps through a traversal with the
//! panel's buttons, and at each step the panel's sentence, highlighted pseudocode line,
//! current node and counters are checked against the core's own event stream, counted here
//! independently; at the end the counters equal the core's cost and brute force's.

use bvhlab::{Event, NodeId};
use bvhlab_app::LabApp;
use bvhlab_app::model::structures::StructureKind;
use bvhlab_app::pseudocode::describe;
use bvhlab_app::pseudocode::{Task, Variant};
use egui_kittest::Harness;

use crate::common;
use common::*;

/// The "Step through" panel's counters: (name, this step, so far, total, brute force).
fn step_counters(h: &Harness<'_, LabApp>) -> Vec<(String, String, String, String, String)> {
    let all = labels(h);
    let start = all
        .iter()
        .position(|l| l == "Step through")
        .expect("the panel is shown");
    let all = &all[start..];
    let mut rows = Vec::new();
    for (i, l) in all.iter().enumerate() {
        if COUNTER_NAMES.contains(&l.as_str()) {
            let at = |j: usize| all.get(i + j).cloned().unwrap_or_default();
            rows.push((l.clone(), at(1), at(2), at(3), at(4)));
        }
    }
    rows
}

/// The node an event names, as the canvas and the tree diagram highlight it.
fn node_named(e: &Event<bvhlab::glam::Vec2>) -> Option<NodeId> {
    match *e {
        Event::EnterNode { node, .. }
        | Event::RayBoundTest { node, .. }
        | Event::DistanceBoundTest { node, .. }
        | Event::Prune { node, .. }
        | Event::PlaneCrossed { node, .. }
        | Event::BuildNode { node, .. }
        | Event::BuildSplit { node, .. }
        | Event::BuildLeaf { node, .. } => Some(node),
        Event::CellEnter { cell, .. } => Some(cell),
        _ => None,
    }
}

/// Checks the panel against the recording at the current step.
fn check_step(h: &Harness<'_, LabApp>, step: usize) {
    let app = h.state();
    let rec = app.lab().two().half.lane.recorded().expect("recorded");
    let events = &rec.events[..step];
    let kind = app.lab().two().half.lane.settings.kind;
    let q = rec.question;
    // The sentence names the step's event.
    match events.last() {
        Some(e) => {
            let said = describe(e, kind, q.task, q.variant);
            label_containing(h, &format!("step {step}: {said}"));
        }
        None => {
            label_containing(h, "step 0 of ");
        }
    }
    // The highlighted line is the one the event happens at.
    let code = bvhlab_app::pseudocode::pseudocode(kind, q.task, q.variant).expect("pseudocode");
    assert!(!code.lines.is_empty(), "{kind:?} has pseudocode");
    let marked: Vec<String> = labels(h)
        .into_iter()
        .filter(|l| {
            l.len() > 3 && l.as_bytes()[2] == b'>' && l[..2].trim().parse::<usize>().is_ok()
        })
        .collect();
    match step.checked_sub(1) {
        Some(i) => {
            let line = bvhlab_app::pseudocode::line_of(kind, q.task, q.variant, &rec.events, i)
                .expect("every event has a line");
            let want = format!("{:>2}> {}", line + 1, code.lines[line]);
            assert_eq!(marked, vec![want], "{kind:?} step {step}");
        }
        None => assert!(marked.is_empty(), "no line before the first step"),
    }
    // The current node is the last one an event named.
    let current = events.iter().rev().find_map(node_named);
    let snap = app
        .lab()
        .two()
        .half
        .lane
        .snapshot
        .as_ref()
        .expect("a snapshot");
    assert_eq!(snap.current, current, "{kind:?} step {step}");
    // The counters so far are the events counted here.
    let [nodes, bvs, prims] = count(events);
    let rows = step_counters(h);
    assert_eq!(rows.len(), 3, "{rows:?}");
    assert_eq!(rows[0].2, nodes.to_string(), "{kind:?} step {step}: nodes");
    assert_eq!(rows[1].2, bvs.to_string(), "{kind:?} step {step}: BV tests");
    assert_eq!(
        rows[2].2,
        prims.to_string(),
        "{kind:?} step {step}: primitive tests"
    );
    let this = count(&events[step.saturating_sub(1)..step]);
    assert_eq!(rows[0].1, this[0].to_string());
    assert_eq!(rows[2].1, this[2].to_string());
}

fn step_through_a_ray(kind: StructureKind) {
    let mut h = lab();
    choose(&mut h, "Structure", kind.label());
    drag_test_ray(&mut h);
    assert_eq!(h.state().lab().two().half.task, Task::FirstHit);
    let len = h.state().lab().two().half.lane.steps();
    assert!(len > 3, "{kind:?}: a real traversal has steps ({len})");
    click(&mut h, "first step");
    check_step(&h, 0);
    for step in 1..=len.min(25) {
        click(&mut h, "next step");
        assert_eq!(h.state().lab().two().half.playback.step, step);
        check_step(&h, step);
    }
    // One step back undoes the last step.
    if len > 2 {
        let at = h.state().lab().two().half.playback.step;
        click(&mut h, "previous step");
        check_step(&h, at - 1);
    }
    // The end: the counters are the core's cost, and brute force tested every primitive.
    click(&mut h, "last step");
    check_step(&h, len);
    let app = h.state();
    let rec = app.lab().two().half.lane.recorded().expect("recorded");
    let rows = step_counters(&h);
    let prims = app.lab().two().scene.primitives().segments.len();
    assert_eq!(rows[0].3, rec.cost.nodes_visited.to_string());
    assert_eq!(rows[2].3, rec.cost.prim_tests.to_string());
    assert_eq!(
        rows[2].4,
        prims.to_string(),
        "brute force tests every primitive"
    );
    assert!(rec.agrees());
    assert!(shows(&h, "answer agrees with brute force"));
}

#[test]
fn stepping_a_sphere_tree_traversal() {
    step_through_a_ray(StructureKind::SphereTree);
}

#[test]
fn stepping_an_aabb_tree_traversal() {
    step_through_a_ray(StructureKind::AabbTree);
}

#[test]
fn stepping_a_k_d_tree_traversal() {
    step_through_a_ray(StructureKind::KdTree);
}

#[test]
fn stepping_a_grid_traversal() {
    step_through_a_ray(StructureKind::Grid);
}

#[test]
fn the_slides_version_and_the_full_one_are_both_counted() {
    let mut h = lab();
    choose(&mut h, "Structure", StructureKind::SphereTree.label());
    drag_test_ray(&mut h);
    click(&mut h, "the slides' version");
    assert_eq!(h.state().lab().two().half.variant, Variant::Lecture);
    let len = h.state().lab().two().half.lane.steps();
    click(&mut h, "first step");
    for step in 1..=len.min(12) {
        click(&mut h, "next step");
        check_step(&h, step);
    }
    let rec = h
        .state()
        .lab()
        .two()
        .half
        .lane
        .recorded()
        .expect("recorded");
    let (full, slides) = (rec.variant_costs[0].1, rec.variant_costs[1].1);
    assert!(slides.bound_tests > full.bound_tests);
    assert!(shows(
        &h,
        &format!("full (near first, pruning): {} nodes", full.nodes_visited)
    ));
    assert!(shows(
        &h,
        &format!("the slides' version: {} nodes", slides.nodes_visited)
    ));
}

#[test]
fn the_tree_and_the_canvas_find_each_others_nodes() {
    use bvhlab::BoundingVolume;
    let mut h = lab();
    choose(&mut h, "Structure", StructureKind::AabbTree.label());
    let outline = h
        .state()
        .lab()
        .two()
        .half
        .lane
        .structure
        .as_ref()
        .and_then(|s| s.outline.clone())
        .expect("built");
    // Tree -> canvas: hovering a leaf's dot in the diagram makes it the canvas's hovered node.
    let leaf = outline
        .iter()
        .rev()
        .find(|n| n.is_leaf())
        .expect("a leaf")
        .id;
    let at = h.state().ui.trees.two[0].node_screen_pos(leaf);
    let at = at.expect("the leaf is drawn in the diagram");
    h.hover_at(at);
    settle(&mut h);
    assert_eq!(h.state().ui.hovered, Some((0, leaf)));
    // Canvas -> tree: hovering a point on the canvas links the deepest node whose box holds
    // it (found here by scanning every node).
    let node = &outline[leaf.index()];
    let target = node.shape.aabb().center();
    let expected = outline
        .iter()
        .filter(|n| n.shape.aabb().contains(target))
        .max_by(|a, b| {
            let area = |n: &bvhlab::NodeOutline<bvhlab::glam::Vec2>| {
                let d = n.shape.aabb().max - n.shape.aabb().min;
                d.x * d.y
            };
            a.depth.cmp(&b.depth).then(area(b).total_cmp(&area(a)))
        })
        .map(|n| n.id);
    h.hover_at(screen(&h, target));
    settle(&mut h);
    assert_eq!(h.state().ui.hovered.map(|(_, n)| n), expected);
    assert_eq!(
        h.state().ui.linked.map(|(_, n)| n),
        expected,
        "the tree shows it"
    );
}

/// Issue 21: the lecture's construction question (median against SAH) compares two build
/// options of one structure. Both lanes are named by what differs, build different trees, and
/// step the build side by side, the SAH lane with its cost curve.
#[test]
fn median_against_sah_compares_two_builds_of_one_structure() {
    use bvhlab::structure::bvh::SplitMethod;
    use bvhlab_app::model::HalfAction;
    use bvhlab_app::model::structures::BuildSettings;

    let mut h = lab();
    let sah = BuildSettings {
        kind: StructureKind::AabbTree,
        bvh_split: SplitMethod::BinnedSah,
        ..BuildSettings::default()
    };
    act(&mut h, HalfAction::SetStructure(sah));
    act(
        &mut h,
        HalfAction::SetCompare(Some(BuildSettings {
            bvh_split: SplitMethod::SpatialMedian,
            ..sah
        })),
    );
    act(&mut h, HalfAction::SetTask(Task::Build));
    settle(&mut h);
    assert!(shows(&h, "AABB tree, SAH split"), "{:?}", labels(&h));
    assert!(shows(
        &h,
        "AABB tree, split at the middle of the longest axis"
    ));
    let half = &h.state().lab().two().half;
    let [a, b] = [half.lane_at(0), half.lane_at(1)].map(|l| {
        l.current(h.state().lab().two().scene.revision())
            .expect("built")
            .stats
            .clone()
    });
    assert_eq!(a.primitives, b.primitives);
    assert_ne!(
        (a.nodes, a.max_depth, &a.leaf_sizes),
        (b.nodes, b.max_depth, &b.leaf_sizes),
        "median and SAH build different trees on 200 random segments"
    );
    // Step into the build: the root's split is logged in both lanes.
    click(&mut h, "first step");
    for _ in 0..3 {
        click(&mut h, "next step");
    }
    assert!(
        shows(&h, "SAH cost of each candidate plane"),
        "the SAH lane's cost curve: {:?}",
        labels(&h)
    );
    assert!(
        shows(&h, "median splits have none"),
        "the median lane says why it has no curve"
    );
}

#[test]
fn two_structures_step_together() {
    let mut h = lab();
    choose(&mut h, "Structure", StructureKind::SphereTree.label());
    click(&mut h, "compare with");
    assert!(h.state().lab().two().half.compare.is_some());
    drag_test_ray(&mut h);
    let kinds: Vec<StructureKind> = h
        .state()
        .lab()
        .two()
        .half
        .lanes()
        .map(|l| l.settings.kind)
        .collect();
    assert_eq!(
        kinds,
        vec![StructureKind::SphereTree, StructureKind::AabbTree]
    );
    click(&mut h, "first step");
    for step in 1..=6 {
        click(&mut h, "next step");
        for lane in h.state().lab().two().half.lanes() {
            let rec = lane.recorded().expect("both lanes recorded the same ray");
            let snap = lane.snapshot.as_ref().expect("a snapshot");
            assert_eq!(snap.step, step.min(rec.events.len()));
            assert_eq!(
                rec.question.ray,
                h.state().lab().two().ray.and_then(|r| r.ray().ok())
            );
        }
    }
    click(&mut h, "last step");
    for lane in h.state().lab().two().half.lanes() {
        let rec = lane.recorded().expect("recorded");
        assert!(rec.agrees(), "{:?}", lane.settings.kind);
        assert_eq!(
            lane.snapshot.as_ref().map(|s| s.step),
            Some(rec.events.len())
        );
    }
}

/// Where a half's playback stands, and what it shows: (step shown, steps, live, playing).
fn standing<P: bvhlab_app::model::dimension::LabPrimitive>(
    half: &bvhlab_app::model::half::Half<P>,
) -> (usize, usize, bool, bool) {
    let p = &half.playback;
    let len = half.steps();
    (p.shown(len), len, p.at_end, p.playing)
}

/// The answer the live query found, in 2D or 3D: the first primitive hit for a first-hit
/// task, the nearest primitive otherwise.
fn live_answer<P: bvhlab_app::model::dimension::LabPrimitive>(
    half: &bvhlab_app::model::half::Half<P>,
) -> Option<u32> {
    let lane = &half.lane;
    match half.task {
        Task::FirstHit => lane
            .ray_outcome
            .as_ref()
            .and_then(|o| o.hit)
            .map(|hit| hit.prim as u32),
        _ => lane
            .point_outcome
            .as_ref()
            .and_then(|o| o.nearest.first())
            .map(|n| n.prim as u32),
    }
}

/// Asserts that playback stands at the end of a real recording, live and still, and that the
/// snapshot shown holds the answer the lab gives (`answer`: the first primitive hit or
/// nearest, as the live query found it).
fn assert_answer_shown<P: bvhlab_app::model::dimension::LabPrimitive>(
    half: &bvhlab_app::model::half::Half<P>,
    answer: Option<u32>,
    what: &str,
) {
    let (shown, len, live, playing) = standing(half);
    assert!(len > 0, "{what}: a recording");
    assert_eq!((shown, live, playing), (len, true, false), "{what}");
    let snap = half.lane.snapshot.as_ref().expect("a snapshot");
    assert_eq!(snap.step, len, "{what}: the snapshot is at the end");
    assert_eq!(
        snap.best.first().map(|b| b.0),
        answer,
        "{what}: the answer is drawn"
    );
}

/// Issue 21: after a new question playback stood sometimes at the end with the answer
/// drawn, sometimes at step 0 with none ("step 0 of 24: nothing done yet" after placing a
/// point on the quadtree preset). The rule (model/playback.rs): a new question (a ray, a
/// point, a task, a structure) puts playback at the end, live, with the answer drawn, and
/// stops it playing, whatever the student did with the step before. 2D in the UI, 3D in the
/// model, for every structure and for the first hit and the nearest point.
#[test]
fn a_new_question_shows_its_answer_at_the_end_for_every_structure_and_task() {
    new_questions_in_2d();
    new_questions_in_3d();
}

/// The 2D half of the test above, in the UI.
fn new_questions_in_2d() {
    use bvhlab::glam::Vec2;
    use bvhlab_app::model::lab2d::RayHandles;
    use bvhlab_app::model::presets::Preset;
    use bvhlab_app::model::{Action2d, HalfAction, PlaybackAction};

    let mut h = lab();
    act(&mut h, Action2d::LoadPreset(Preset::QuadtreeHandful));
    let (lo, hi) = h.state().lab().two().scene.bounds().expect("shapes");
    let mid = (lo + hi) * 0.5;
    let rays = [
        RayHandles {
            origin: Vec2::new(lo.x - 2.0, mid.y + 0.1),
            target: mid,
        },
        RayHandles {
            origin: Vec2::new(mid.x - 0.3, hi.y + 2.0),
            target: Vec2::new(mid.x + 0.2, mid.y),
        },
    ];
    let points = [mid + Vec2::new(0.4, 0.3), lo + (hi - lo) * 0.3];
    // A recording to step away from.
    act(&mut h, Action2d::SetRay(Some(rays[1])));
    for kind in StructureKind::ALL {
        let mut settings = h.state().lab().two().half.lane.settings;
        settings.kind = kind;
        // Away from the end (step 0, as Home puts it), then a new structure.
        act(&mut h, PlaybackAction::GoTo(0));
        act(&mut h, HalfAction::SetStructure(settings));
        let what = format!("2D {kind:?}, a new structure");
        assert_answer_shown(
            &h.state().lab().two().half,
            live_answer(&h.state().lab().two().half),
            &what,
        );
        for (i, (ray, point)) in rays.iter().zip(points).enumerate() {
            // A ray placed while playback stands at step 0.
            press(&mut h, egui::Key::Home);
            act(&mut h, Action2d::SetRay(Some(*ray)));
            let what = format!("2D {kind:?}, ray {i}");
            assert_answer_shown(
                &h.state().lab().two().half,
                live_answer(&h.state().lab().two().half),
                &what,
            );
            assert!(!shows(&h, "nothing done yet"), "{what}");
            // A point placed while playing.
            act(&mut h, PlaybackAction::GoTo(1));
            // Playing (a frame, not settled: it repaints until the end).
            h.state_mut()
                .apply(PlaybackAction::Play(true))
                .expect("plays");
            h.step();
            assert!(h.state().lab().playing(), "2D {kind:?}: playing");
            h.state_mut()
                .apply(Action2d::SetPoint(Some(point)))
                .expect("a point");
            h.step();
            let what = format!("2D {kind:?}, point {i}");
            assert_eq!(h.state().lab().two().half.task, Task::Nearest, "{what}");
            assert_answer_shown(
                &h.state().lab().two().half,
                live_answer(&h.state().lab().two().half),
                &what,
            );
            assert!(!shows(&h, "nothing done yet"), "{what}");
            settle(&mut h);
            // Back to the ray's task from a step in the middle.
            act(&mut h, PlaybackAction::GoTo(2));
            act(&mut h, HalfAction::SetTask(Task::FirstHit));
            let what = format!("2D {kind:?}, task back to the ray {i}");
            assert_answer_shown(
                &h.state().lab().two().half,
                live_answer(&h.state().lab().two().half),
                &what,
            );
        }
    }
}

/// The 3D half of the test above, in the model: a small mesh, built as the frames build it.
fn new_questions_in_3d() {
    use bvhlab::glam::Vec3;
    use bvhlab_app::model::mesh::MeshSource;
    use bvhlab_app::model::{Action, Action3d, HalfAction, Lab, PlaybackAction};

    let mut lab = Lab::default();
    let tick = |lab: &mut Lab| {
        for _ in 0..2_000 {
            lab.apply(Action::Tick {
                seconds: 0.0,
                build_ms: 1e6,
            })
            .expect("a frame");
            let three = lab.three();
            if !three.busy()
                && three
                    .half
                    .lanes()
                    .all(|l| l.current(three.revision()).is_some())
            {
                return;
            }
        }
        panic!("the 3D half did not finish loading and building");
    };
    lab.apply(Action3d::OpenMesh(MeshSource::Builtin("tetrahedra".to_owned())).into())
        .expect("opens");
    tick(&mut lab);
    let tris = lab.three().triangles();
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for t in tris {
        for v in [t.a, t.b, t.c] {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    let size = (hi - lo).length();
    // Aimed at a triangle's centroid, so that the ray hits something.
    let t = tris[tris.len() / 2];
    let mid = (t.a + t.b + t.c) / 3.0;
    let ray = bvhlab::Ray3::new(
        mid - 2.0 * size * Vec3::new(1.0, 0.13, 0.07),
        Vec3::new(1.0, 0.13, 0.07),
    )
    .expect("a ray");
    // A recording to step away from.
    lab.apply(Action3d::SetRay(Some(ray)).into())
        .expect("a ray");
    for kind in StructureKind::ALL {
        let mut settings = lab.three().half.lane.settings;
        settings.kind = kind;
        lab.apply(PlaybackAction::GoTo(0).into()).expect("goes");
        lab.apply(HalfAction::SetStructure(settings).into())
            .expect("a structure");
        tick(&mut lab);
        assert_answer_shown(
            &lab.three().half,
            live_answer(&lab.three().half),
            &format!("3D {kind:?}, a new structure"),
        );
        lab.apply(PlaybackAction::GoTo(0).into()).expect("goes");
        lab.apply(Action3d::SetRay(Some(ray)).into())
            .expect("a ray");
        assert!(
            live_answer(&lab.three().half).is_some(),
            "3D {kind:?}: the ray hits"
        );
        assert_answer_shown(
            &lab.three().half,
            live_answer(&lab.three().half),
            &format!("3D {kind:?}, ray"),
        );
        lab.apply(PlaybackAction::GoTo(1).into()).expect("goes");
        lab.apply(PlaybackAction::Play(true).into()).expect("plays");
        assert!(lab.playing(), "3D {kind:?}: playing");
        lab.apply(Action3d::SetPoint(Some(mid + Vec3::splat(0.1 * size))).into())
            .expect("a point");
        assert_answer_shown(
            &lab.three().half,
            live_answer(&lab.three().half),
            &format!("3D {kind:?}, point"),
        );
    }
}
