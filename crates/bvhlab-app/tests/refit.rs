//! Refit against rebuild in the lab: a lane in refit mode follows moved shapes with the same
//! tree (its boxes grow, its SAH cost rises), "Rebuild now" brings the cost down, the answers
//! stay exact, and the structures that partition space say why they rebuild instead.

use bvhlab::RayCast;
use bvhlab::SpatialQuery;
use bvhlab::glam::Vec2;
use bvhlab::{BruteForce, Ray2, Segment2, SpatialIndex};
use bvhlab_app::model::build_job::Structure;
use bvhlab_app::model::presets::Preset;
use bvhlab_app::model::refit::{EditKind, UpdateMode};
use bvhlab_app::model::structures::{BuildSettings, StructureKind};
use bvhlab_app::model::{Action, Action2d, HalfAction, Lab};

fn apply(lab: &mut Lab, action: impl Into<Action>) -> Result<(), String> {
    lab.apply(action.into())
}

fn refit_lab() -> Lab {
    let mut lab = Lab::with_preset(Preset::RandomSegments);
    apply(
        &mut lab,
        HalfAction::SetUpdateMode {
            lane: 0,
            mode: UpdateMode::Refit,
        },
    )
    .expect("refit mode");
    lab
}

fn structure(lab: &Lab) -> &Structure<Segment2> {
    lab.two()
        .half
        .lane
        .current(lab.two().scene.revision())
        .expect("a current structure")
}

/// Each node's children and primitives: the tree's shape without its volumes.
fn topology(s: &Structure<Segment2>) -> Vec<(Vec<u32>, Vec<u32>)> {
    s.outline
        .as_ref()
        .expect("2D structures are listed")
        .iter()
        .map(|n| {
            (
                n.children.iter().map(|c| c.0).collect(),
                n.primitives.clone(),
            )
        })
        .collect()
}

/// Moves shapes `shapes` by `delta`, as a drag does.
fn move_shapes(lab: &mut Lab, shapes: Vec<usize>, delta: Vec2) {
    apply(lab, Action2d::Select(shapes)).expect("select");
    apply(lab, Action2d::MoveSelection(delta)).expect("move");
}

/// Checks that the lab's structure answers rays and nearest-point queries as brute force
/// over the scene's segments does.
fn answers_like_brute_force(lab: &Lab) {
    let segments = lab.two().scene.primitives().segments;
    let brute = BruteForce::build(&segments);
    let s = structure(lab);
    for i in 0..40 {
        let t = i as f32 * 0.37;
        let origin = Vec2::new(-3.0 + (t * 1.7).sin(), 10.0 + 12.0 * t.cos());
        let target = Vec2::new(25.0, 20.0 * (t * 0.9).sin().abs());
        let ray = Ray2::through(origin, target).expect("a ray");
        let hit = s.built.ray_first_hit(&ray, &mut ()).answer;
        let expected = brute.ray_first_hit(&ray, f32::INFINITY);
        assert_eq!(
            hit.map(|h| h.t),
            expected.map(|h| h.t),
            "ray {i} after a refit"
        );
        let point = Vec2::new(20.0 * (t * 0.3).fract(), 20.0 * (t * 0.7).fract());
        let near = s.built.k_nearest(point, 3, &mut ()).answer;
        let want = brute.k_nearest(point, 3);
        let d: Vec<f32> = near.iter().map(|n| n.distance).collect();
        let w: Vec<f32> = want.iter().map(|n| n.distance).collect();
        assert_eq!(d, w, "nearest to point {i} after a refit");
    }
}

#[test]
fn refit_keeps_the_tree_and_grows_its_boxes() {
    let mut lab = refit_lab();
    let before = structure(&lab);
    let (nodes, shape) = (before.node_count, topology(before));
    let root = before.outline.as_ref().expect("listed")[0].shape.aabb();
    let built_ms = before.build_ms;
    assert!(built_ms >= 0.0);
    // Shape 3 leaves the scene's square far to the right: its leaf and every box above it
    // stretch to follow.
    move_shapes(&mut lab, vec![3], Vec2::new(30.0, 0.0));
    let after = structure(&lab);
    assert_eq!(after.node_count, nodes, "a refit keeps the node count");
    assert_eq!(
        topology(after),
        shape,
        "a refit keeps every node's children"
    );
    assert_eq!(after.refits, 1);
    let grown = after.outline.as_ref().expect("listed")[0].shape.aabb();
    assert!(
        grown.max.x > root.max.x + 15.0,
        "the root box grew: {root:?} to {grown:?}"
    );
    let log = &lab.two().half.lane.log;
    assert_eq!(log.last().map(|e| e.how), Some(EditKind::Refit));
    assert!(log.last().is_some_and(|e| e.millis >= 0.0));
    answers_like_brute_force(&lab);
}

#[test]
fn scrambling_raises_the_sah_cost_and_rebuild_now_brings_it_down() {
    let mut lab = refit_lab();
    let built = structure(&lab).build_sah_cost.expect("a cost");
    // Swap the scene's corners: shapes far apart in the tree trade places.
    for (i, shape) in (0..200).step_by(7).enumerate() {
        let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
        move_shapes(&mut lab, vec![shape], Vec2::new(12.0 * sign, -9.0 * sign));
    }
    let s = structure(&lab);
    let now = s.stats.sah_cost.expect("a cost");
    assert!(s.refits >= 20, "every move was a refit: {}", s.refits);
    assert!(
        now > 1.3 * built,
        "the SAH cost rose: {built} at the build, {now} now"
    );
    answers_like_brute_force(&lab);

    apply(&mut lab, HalfAction::RebuildNow).expect("rebuild now");
    let s = structure(&lab);
    let rebuilt = s.stats.sah_cost.expect("a cost");
    assert_eq!(s.refits, 0, "a fresh tree");
    assert!(
        rebuilt < now,
        "rebuilding lowers the cost: {now} to {rebuilt}"
    );
    assert_eq!(s.build_sah_cost, Some(rebuilt));
    let log = &lab.two().half.lane.log;
    assert_eq!(log.last().map(|e| e.how), Some(EditKind::Rebuild));
    assert!(log.count(EditKind::Refit) >= 20);
    // Refit mode stays on: the next move refits the new tree.
    move_shapes(&mut lab, vec![1], Vec2::new(0.5, 0.5));
    assert_eq!(structure(&lab).refits, 1);
}

#[test]
fn rebuild_mode_rebuilds_every_move() {
    let mut lab = Lab::with_preset(Preset::RandomSegments);
    move_shapes(&mut lab, vec![3], Vec2::new(30.0, 0.0));
    let s = structure(&lab);
    assert_eq!(s.refits, 0);
    let log = &lab.two().half.lane.log;
    assert_eq!(log.last().map(|e| e.how), Some(EditKind::Rebuild));
    assert_eq!(log.count(EditKind::Refit), 0);
    assert_eq!(lab.two().half.lane.refit_note, None);
}

#[test]
fn a_grid_in_refit_mode_rebuilds_and_says_why() {
    let mut lab = refit_lab();
    apply(
        &mut lab,
        HalfAction::SetStructure(BuildSettings {
            kind: StructureKind::Grid,
            ..BuildSettings::default()
        }),
    )
    .expect("a grid");
    move_shapes(&mut lab, vec![3], Vec2::new(5.0, 0.0));
    let lane = &lab.two().half.lane;
    assert_eq!(lane.log.last().map(|e| e.how), Some(EditKind::Rebuild));
    let note = lane.refit_note.as_deref().expect("why it rebuilt");
    assert!(note.contains("grid updates by rebuilding"), "{note}");
    answers_like_brute_force(&lab);
}

#[test]
fn a_changed_count_rebuilds_and_says_why() {
    let mut lab = refit_lab();
    apply(&mut lab, Action2d::Select(vec![0, 1])).expect("select");
    apply(&mut lab, Action2d::DeleteSelection).expect("delete");
    let lane = &lab.two().half.lane;
    assert_eq!(lane.log.last().map(|e| e.how), Some(EditKind::Rebuild));
    let note = lane.refit_note.as_deref().expect("why it rebuilt");
    assert!(note.contains("rebuild"), "{note}");
    answers_like_brute_force(&lab);
}

#[test]
fn the_comparison_lane_has_its_own_mode() {
    let mut lab = Lab::with_preset(Preset::RandomSegments);
    let settings = lab.two().half.lane.settings;
    assert!(
        apply(
            &mut lab,
            HalfAction::SetUpdateMode {
                lane: 1,
                mode: UpdateMode::Refit
            }
        )
        .is_err(),
        "no comparison yet"
    );
    lab.apply_all([
        Action::Half(HalfAction::SetCompare(Some(settings))),
        Action::Half(HalfAction::SetUpdateMode {
            lane: 1,
            mode: UpdateMode::Refit,
        }),
    ])
    .expect("a refitting comparison");
    move_shapes(&mut lab, vec![3], Vec2::new(3.0, 0.0));
    let half = &lab.two().half;
    assert_eq!(half.lane.log.last().map(|e| e.how), Some(EditKind::Rebuild));
    let other = half.compare.as_ref().expect("compared");
    assert_eq!(other.log.last().map(|e| e.how), Some(EditKind::Refit));
}

#[test]
fn saved_state_round_trips_the_update_modes() {
    use bvhlab_app::persist::{SavedState, from_file, to_file};
    let mut lab = refit_lab();
    let settings = lab.two().half.lane.settings;
    apply(&mut lab, HalfAction::SetCompare(Some(settings))).expect("a comparison, rebuilding");
    let file = to_file(&lab);
    let text = String::from_utf8(file.clone()).expect("UTF-8");
    assert!(text.contains("\"update\": \"refit\""), "{text}");
    let mut back = Lab::with_preset(Preset::KdHandful);
    apply(
        &mut back,
        from_file(&file).expect("reads").apply().expect("applies"),
    )
    .expect("restores");
    assert_eq!(back.two().half.lane.update, UpdateMode::Refit);
    let other = back.two().half.compare.as_ref().expect("compared");
    assert_eq!(other.update, UpdateMode::Rebuild);

    // A file from before refitting (no "update") loads, rebuilding.
    let old = text
        .replace(",\n    \"update\": \"refit\"", "")
        .replace("\"update\": \"refit\"", "");
    assert!(!old.contains("update"), "{old}");
    let state = from_file(old.as_bytes()).expect("an old file reads");
    let mut back = Lab::with_preset(Preset::KdHandful);
    apply(&mut back, state.apply().expect("applies")).expect("restores");
    assert_eq!(back.two().half.lane.update, UpdateMode::Rebuild);
    // The default is left out of files, so that they read as before.
    let plain = SavedState::capture(&Lab::with_preset(Preset::RandomSegments));
    let json = serde_json::to_string(&plain).expect("serializes");
    assert!(!json.contains("update"), "{json}");
}

#[test]
fn the_drifting_preset_refits_beside_a_rebuild_every_frame() {
    let mut lab = Lab::with_preset(Preset::Drifting);
    assert!(lab.animating(), "the preset starts moving");
    let start = lab.two().scene.shapes().to_vec();
    let tick = Action::Tick {
        seconds: 1.0 / 30.0,
        build_ms: 8.0,
    };
    for _ in 0..60 {
        apply(&mut lab, tick.clone()).expect("a frame");
    }
    let two = lab.two();
    assert_ne!(two.scene.shapes(), start.as_slice(), "the shapes moved");
    let time = two.animation.expect("animated").time;
    assert!((time - 2.0).abs() < 1e-9, "two seconds of motion: {time}");
    let refitted = &two.half.lane;
    let rebuilt = two.half.compare.as_ref().expect("the rebuilt comparison");
    assert_eq!(refitted.update, UpdateMode::Refit);
    assert_eq!(rebuilt.update, UpdateMode::Rebuild);
    assert_eq!(
        refitted.log.count(EditKind::Refit),
        60,
        "a refit every frame"
    );
    assert_eq!(
        rebuilt.log.count(EditKind::Rebuild),
        61,
        "the first build and every frame"
    );
    assert!(refitted.log.mean_millis(EditKind::Refit).is_some());
    assert_eq!(two.half.lane_name(0), "AABB tree, refitted");
    assert_eq!(two.half.lane_name(1), "AABB tree, rebuilt");
    // The refitted tree has drifted from the rebuilt one's quality.
    let cost = |l: &bvhlab_app::model::lane::Lane<Segment2>| {
        l.current(two.scene.revision())
            .and_then(|s| s.stats.sah_cost)
            .expect("a cost")
    };
    assert!(
        cost(refitted) > cost(rebuilt),
        "refitted {} against rebuilt {}",
        cost(refitted),
        cost(rebuilt)
    );
    answers_like_brute_force(&lab);

    // The same time gives the same shapes.
    let again = bvhlab_app::model::presets::drifting_shapes(2.0);
    assert_eq!(lab.two().scene.shapes(), again.as_slice());

    // Editing stops the motion; "Animate" starts it again.
    move_shapes(&mut lab, vec![0], Vec2::new(1.0, 0.0));
    assert!(!lab.animating());
    apply(&mut lab, tick.clone()).expect("a frame");
    assert!((lab.two().animation.expect("kept").time - 2.0).abs() < 1e-9);
    apply(&mut lab, Action2d::SetAnimate(true)).expect("animate");
    apply(&mut lab, tick).expect("a frame");
    assert!(lab.animating());

    // Another preset ends the comparison and the motion.
    apply(&mut lab, Action2d::LoadPreset(Preset::RandomSegments)).expect("another preset");
    assert!(!lab.animating());
    assert!(lab.two().half.compare.is_none());
    assert_eq!(lab.two().half.lane.update, UpdateMode::Rebuild);
    assert!(apply(&mut lab, Action2d::SetAnimate(true)).is_err());
}
