//! The 3D mesh that moves (the twisting torus): each frame moves it, the structure follows (a
//! refit, or a rebuild), the live answer stays brute force's on the moved triangles, and the
//! heat map is traced again for the moved mesh. The model is driven with actions, the heat map
//! in the headless harness (no GPU there: the CPU traces it).

use crate::common;

use bvhlab::RayCast;
use bvhlab::glam::Vec3;
use bvhlab::{BruteForce, Ray3, SpatialIndex, Triangle3};
use bvhlab_app::LabApp;
use bvhlab_app::model::heat::HeatSettings;
use bvhlab_app::model::lab3d::Lab3d;
use bvhlab_app::model::mesh::MeshSource;
use bvhlab_app::model::refit::{EditKind, UpdateMode};
use bvhlab_app::model::{Action, Action3d, Dimension, HalfAction, Lab};
use bvhlab_meshio::builtin::{self, TWISTING_TORUS};
use egui_kittest::Harness;

/// A frame of 1/60 s with time to finish any build.
const FRAME: Action = Action::Tick {
    seconds: 1.0 / 60.0,
    build_ms: 1_000.0,
};

fn open_torus() -> Action {
    Action3d::OpenMesh(MeshSource::Builtin(TWISTING_TORUS.to_owned())).into()
}

/// A lab showing the twisting torus, loaded and built, with a ray straight down onto the
/// tube.
fn torus_lab() -> Lab {
    let mut lab = Lab::default();
    lab.apply(open_torus()).expect("a built-in mesh");
    lab.apply(FRAME).expect("a frame");
    let ray = Ray3::new(Vec3::new(1.02, 3.0, 0.05), Vec3::NEG_Y).expect("a ray");
    lab.apply(Action3d::SetRay(Some(ray)).into())
        .expect("a ray");
    assert_eq!(lab.dimension(), Dimension::Three);
    assert!(
        lab.three()
            .half
            .lane
            .current(lab.three().revision())
            .is_some()
    );
    lab
}

fn triangles(lab: &Lab3d) -> Vec<Triangle3> {
    lab.triangles().to_vec()
}

#[test]
fn the_torus_opens_moving_and_each_frame_moves_it_as_the_time_says() {
    let mut lab = torus_lab();
    assert!(lab.three().motion.on, "it moves as it opens");
    assert!(lab.animating());
    let start = triangles(lab.three());
    let mut revisions = vec![lab.three().revision()];
    for _ in 0..10 {
        lab.apply(FRAME).expect("a frame");
        revisions.push(lab.three().revision());
    }
    let three = lab.three();
    assert!((three.motion.seconds - 10.0 / 60.0).abs() < 1e-9);
    assert_eq!(three.motion.frames, 10);
    assert!(revisions.windows(2).all(|w| w[0] < w[1]), "{revisions:?}");
    assert_ne!(triangles(three), start, "the triangles moved");
    // The triangles are the generator's at the motion's time.
    let expected = builtin::make_at(TWISTING_TORUS, three.motion.seconds).expect("it moves");
    assert_eq!(three.triangles(), expected.triangles());
    // Stopped, it stays; a frame of another half does not move it either.
    lab.apply(Action3d::Animate(false).into())
        .expect("a switch");
    assert!(!lab.animating());
    let stopped = (three_revision(&lab), triangles(lab.three()));
    lab.apply(FRAME).expect("a frame");
    assert_eq!((three_revision(&lab), triangles(lab.three())), stopped);
    lab.apply(Action3d::Animate(true).into()).expect("a switch");
    lab.apply(Action::Show(Dimension::Two)).expect("2D");
    lab.apply(FRAME).expect("a frame");
    assert_eq!(three_revision(&lab), stopped.0, "only the half shown moves");
    // A long pause is one short step, not a jump.
    lab.apply(Action::Show(Dimension::Three)).expect("3D");
    let before = lab.three().motion.seconds;
    lab.apply(Action::Tick {
        seconds: 30.0,
        build_ms: 1_000.0,
    })
    .expect("a frame");
    assert!(lab.three().motion.seconds - before <= 0.1 + 1e-9);
}

fn three_revision(lab: &Lab) -> u64 {
    lab.three().revision()
}

/// The 3D half's main lane.
fn lane(lab: &Lab) -> &bvhlab_app::model::lane::Lane<Triangle3> {
    &lab.three().half.lane
}

#[test]
fn in_refit_mode_the_tree_keeps_its_nodes_and_in_rebuild_mode_it_is_built_anew() {
    let mut lab = torus_lab();
    assert_eq!(
        lane(&lab).update,
        UpdateMode::Refit,
        "the moving mesh opens in refit mode"
    );
    let nodes = |lab: &Lab| {
        let three = lab.three();
        let built = three
            .half
            .lane
            .current(three.revision())
            .expect("follows the mesh");
        (built.node_count, built.refits, built.stats.sah_cost)
    };
    let (count, _, built_cost) = nodes(&lab);
    for _ in 0..30 {
        lab.apply(FRAME).expect("a frame");
    }
    let (after, refits, cost) = nodes(&lab);
    assert_eq!(after, count, "a refit keeps the tree's nodes");
    assert_eq!(refits, 30, "one refit a frame");
    assert_eq!(lane(&lab).log.last().map(|e| e.how), Some(EditKind::Refit));
    assert_ne!(cost, built_cost, "the SAH cost follows the moved boxes");
    // Rebuild now: one build, then refits again.
    lab.apply(HalfAction::RebuildNow.into()).expect("applies");
    lab.apply(FRAME).expect("a frame");
    assert_eq!(
        lane(&lab).log.last().map(|e| e.how),
        Some(EditKind::Rebuild)
    );
    lab.apply(FRAME).expect("a frame");
    assert_eq!(lane(&lab).log.last().map(|e| e.how), Some(EditKind::Refit));
    // Rebuild mode: every frame builds.
    lab.apply(
        HalfAction::SetUpdateMode {
            lane: 0,
            mode: UpdateMode::Rebuild,
        }
        .into(),
    )
    .expect("applies");
    let before = lane(&lab).log.count(EditKind::Rebuild);
    for _ in 0..5 {
        lab.apply(FRAME).expect("a frame");
    }
    assert_eq!(lane(&lab).log.count(EditKind::Rebuild), before + 5);
    assert_eq!(nodes(&lab).1, 0, "a fresh build has no refits");
}

#[test]
fn other_meshes_do_not_move() {
    let mut lab = Lab::default();
    lab.apply(Action3d::OpenMesh(MeshSource::Builtin("torus".to_owned())).into())
        .expect("a built-in mesh");
    lab.apply(FRAME).expect("a frame");
    let revision = three_revision(&lab);
    assert!(!lab.animating(), "the plain torus does not move");
    for _ in 0..3 {
        lab.apply(FRAME).expect("a frame");
    }
    assert_eq!(three_revision(&lab), revision);
}

#[test]
fn after_many_frames_the_live_ray_answer_is_brute_forces_on_the_moved_triangles() {
    let mut lab = torus_lab();
    let mut hits = 0;
    for frame in 0..90 {
        lab.apply(FRAME).expect("a frame");
        let three = lab.three();
        let lane = &three.half.lane;
        let built = lane
            .current(three.revision())
            .unwrap_or_else(|| panic!("frame {frame}: the structure follows the mesh"));
        assert_eq!(built.revision, three.revision());
        let outcome = lane.ray_outcome.as_ref().expect("the live answer");
        let ray = three.ray.expect("the ray");
        let brute = BruteForce::build(three.triangles()).ray_first_hit(&ray, f32::INFINITY);
        assert_eq!(
            outcome.hit.map(|h| (h.prim, h.t)),
            brute.map(|h| (h.prim, h.t)),
            "frame {frame}"
        );
        assert!(outcome.agrees(), "frame {frame}");
        hits += usize::from(brute.is_some());
    }
    assert!(hits > 10, "the ray hits the tube in some frames: {hits}");
}

// ---------- the heat map, in the harness ----------

/// The lab in the harness, showing the twisting torus with the heat map on.
fn torus_with_heat() -> Harness<'static, LabApp> {
    let mut h = common::lab();
    for action in [
        open_torus(),
        Action3d::SetHeat(HeatSettings {
            on: true,
            ..HeatSettings::default()
        })
        .into(),
    ] {
        h.state_mut().apply(action).expect("applies");
    }
    for _ in 0..3 {
        h.step();
    }
    h
}

/// Frames until the heat map shows a finished image of a tree other than `after`'s
/// revision; its revision and counts.
fn next_image(h: &mut Harness<'_, LabApp>, after: Option<u64>) -> (u64, Vec<u32>) {
    for _ in 0..400 {
        h.step();
        let heat = &h.state().ui.view3d.heat;
        if let Some((revision, counts)) = heat.moving_image()
            && Some(revision) != after
        {
            return (revision, counts.to_vec());
        }
    }
    panic!("no new heat map image in 400 frames");
}

#[test]
fn the_heat_map_is_traced_again_for_the_moved_mesh() {
    let mut h = torus_with_heat();
    let (first, image) = next_image(&mut h, None);
    let (second, moved) = next_image(&mut h, Some(first));
    assert!(second > first, "a later tree: {first} then {second}");
    assert!(image.iter().any(|&c| c > 0), "rays visited nodes");
    assert_eq!(image.len(), moved.len(), "the same view");
    assert_ne!(image, moved, "the map follows the moved mesh");
    let heat = &h.state().ui.view3d.heat;
    let every = heat.moving_every().expect("it says how often");
    assert!(every >= 1, "{every}");
    // Stopped, the map is traced again in full resolution, once.
    h.state_mut()
        .apply(Action3d::Animate(false))
        .expect("a switch");
    for _ in 0..400 {
        h.step();
        if h.state()
            .report
            .three
            .as_ref()
            .and_then(|t| t.heat_map.as_ref())
            .is_some_and(|m| m.progress >= 1.0)
        {
            break;
        }
    }
    let heat = &h.state().ui.view3d.heat;
    assert!(heat.moving_every().is_none());
    assert!(
        heat.moving_image().is_none(),
        "a full image, not a moving one"
    );
}
