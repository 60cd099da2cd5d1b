//! The 3D half of the lab, driven headless as a student drives it (no GPU here: the view's
//! drawing is tested on lavapipe in `render3d.rs`; this checks what the view does).

use crate::common;

use bvhlab::RayCast;
use bvhlab::Triangle3;
use bvhlab::glam::Vec2;
use bvhlab::{BruteForce, SpatialIndex};
use bvhlab_app::LabApp;
use bvhlab_app::lab3d::input::{Handle, handles};
use bvhlab_app::model::Dimension;
use bvhlab_app::model::build_job::Structure;
use bvhlab_app::model::lab3d::Lab3d;
use bvhlab_app::model::mesh::{Mesh3d, MeshSource};
use bvhlab_app::model::structures::StructureKind;
use bvhlab_app::model::{Action3d, HalfAction};
use bvhlab_app::pseudocode::{Task, line_of};
use bvhlab_app::report::HeatReport;
use common::{act, click, click_at, count, lab, painted, press, settle};
use egui::Key;
use egui_kittest::Harness;

/// The 3D half of the lab in the harness.
pub(crate) fn three<'a>(h: &'a Harness<'_, LabApp>) -> &'a Lab3d {
    h.state().lab().three()
}

/// The main lane's structure, when it is built on the mesh shown with the lane's settings.
fn built<'a>(h: &'a Harness<'_, LabApp>) -> Option<&'a Structure<Triangle3>> {
    let lab = three(h);
    lab.half.lane.current(lab.revision())
}

/// Frames run until the 3D view has built its structure (or a limit, which fails).
fn until_built(h: &mut Harness<'_, LabApp>) -> usize {
    for frame in 0..2_000 {
        if built(h).is_some() && !three(h).busy() {
            settle(h);
            return frame;
        }
        h.step();
    }
    panic!("the structure was not built in 2,000 frames");
}

/// The lab switched to 3D, its default mesh loaded and built.
pub(crate) fn lab_3d() -> Harness<'static, LabApp> {
    let mut h = lab();
    click(&mut h, "3D: meshes");
    assert_eq!(h.state().lab().dimension(), Dimension::Three);
    until_built(&mut h);
    h
}

/// The 3D view's area on screen.
pub(crate) fn view_rect(h: &Harness<'_, LabApp>) -> egui::Rect {
    h.state().ui.view3d.rect
}

/// The heat map's report, when it is shown.
fn heat_report(h: &Harness<'_, LabApp>) -> Option<HeatReport> {
    h.state()
        .report
        .three
        .as_ref()
        .and_then(|t| t.heat_map.clone())
}

/// Clicks the middle of the 3D view; returns the pixel's position in the view.
fn click_view_middle(h: &mut Harness<'_, LabApp>) -> (Vec2, Vec2) {
    let rect = view_rect(h);
    assert!(rect.is_positive(), "the view has an area: {rect:?}");
    let at = rect.center() + egui::vec2(3.0, -7.0);
    click_at(h, at);
    (
        Vec2::new(at.x - rect.min.x, at.y - rect.min.y),
        Vec2::new(rect.width(), rect.height()),
    )
}

/// Asks the half shown for another structure, with the other build settings kept.
fn set_kind(h: &mut Harness<'_, LabApp>, kind: StructureKind) {
    let mut settings = three(h).half.lane.settings;
    settings.kind = kind;
    act(h, HalfAction::SetStructure(settings));
}

#[test]
fn a_click_on_the_bunny_casts_the_camera_ray_and_the_hit_is_brute_forces() {
    let mut h = lab_3d();
    let (pixel, size) = click_view_middle(&mut h);
    let lab = three(&h);
    let expected = lab
        .camera
        .ray_through(pixel, size)
        .expect("a finite camera");
    let ray = lab.ray.expect("the click cast a ray");
    assert_eq!(ray.origin(), expected.origin(), "from the eye");
    let cos = ray.dir().normalize().dot(expected.dir().normalize());
    assert!(cos > 1.0 - 1e-6, "through the clicked pixel");
    let mesh = &lab.mesh.as_ref().expect("the bunny").mesh;
    let brute = BruteForce::build(mesh.triangles()).ray_first_hit(&ray, f32::INFINITY);
    let report = &h.state().report;
    let three = report.three.as_ref().expect("the 3D report");
    let hit = three
        .hit
        .as_ref()
        .expect("the middle of the view is on the bunny");
    let brute = brute.expect("brute force hits too");
    assert_eq!(hit.triangle, brute.prim);
    assert_eq!(hit.t, brute.t);
    assert_eq!(three.agrees, Some(true));
    assert!(
        three
            .cost
            .is_some_and(|c| c[2] < three.brute_force_tests.unwrap_or(0))
    );
}

#[test]
fn a_clicked_ray_is_a_dot_in_the_view_and_a_line_in_the_side_view() {
    let mut h = lab_3d();
    act(&mut h, Action3d::SetRay(None));
    assert!(h.state().ui.view3d.side.is_none(), "no ray, no inset");
    // The hint under "A click:" is readable.
    let hint = painted(&h)
        .into_iter()
        .find(|t| t.text.starts_with("Drag to orbit"))
        .expect("the 3D view's hint");
    assert!(hint.size >= 11.0, "the hint is {} points", hint.size);
    click_view_middle(&mut h);
    let lab = three(&h);
    let ray = lab.ray.expect("the click cast a ray");
    let rect = view_rect(&h);
    let size = Vec2::new(rect.width(), rect.height());
    let t = h
        .state()
        .report
        .three
        .as_ref()
        .and_then(|r| r.hit.as_ref())
        .expect("a hit on the bunny")
        .t;
    // In the view the ray runs straight into the screen: halfway and its hit are one pixel.
    let seen = |t: f32| lab.camera.project(ray.at(t), size).expect("in front");
    assert!(seen(0.5 * t).distance(seen(t)) < 1.0);
    let side = h.state().ui.view3d.side.expect("the side view is drawn");
    assert!(rect.contains_rect(side.rect), "{:?} in {rect:?}", side.rect);
    for end in [side.origin, side.end] {
        assert!(side.rect.contains(end), "{end:?} in {:?}", side.rect);
    }
    let long = side.origin.distance(side.end);
    assert!(long >= 60.0, "the ray is {long} points long in the inset");
    if let Some(hit) = side.hit {
        assert!(hit.distance(side.end) < 0.5, "the ray ends at its hit");
    }
    // Casting the point (no ray question) takes the inset away.
    act(&mut h, HalfAction::SetTask(Task::Nearest));
    assert!(h.state().ui.view3d.side.is_none());
}

#[test]
fn stepping_in_3d_marks_the_lines_and_counts_as_in_2d() {
    let mut h = lab_3d();
    click_view_middle(&mut h);
    press(&mut h, Key::Home);
    let rec = three(&h).half.lane.recorded().expect("recorded").clone();
    assert!(rec.events.len() > 3);
    let kind = three(&h).half.lane.settings.kind;
    for step in 0..=rec.events.len() {
        let report = h.state().report.playback.first().expect("one lane").clone();
        assert_eq!(report.step, step);
        assert_eq!(report.steps, rec.events.len());
        let line = step
            .checked_sub(1)
            .and_then(|i| line_of(kind, Task::FirstHit, rec.question.variant, &rec.events, i));
        assert_eq!(report.line, line.map(|l| l + 1), "step {step}");
        assert_eq!(report.so_far, count(&rec.events[..step]), "step {step}");
        if step < rec.events.len() {
            press(&mut h, Key::Period);
        }
    }
    let report = &h.state().report.playback[0];
    assert_eq!(
        report.total,
        [
            rec.cost.nodes_visited,
            rec.cost.bound_tests,
            rec.cost.prim_tests
        ]
    );
    assert_eq!(report.so_far, report.total);
    // The panel shows the listing with one line marked.
    let marked = common::labels(&h)
        .into_iter()
        .filter(|l| l.get(2..3) == Some(">"))
        .count();
    assert_eq!(marked, 1);
}

#[test]
fn every_structure_answers_the_click_and_the_point_like_brute_force() {
    let mut h = lab_3d();
    click_view_middle(&mut h);
    for kind in StructureKind::ALL {
        set_kind(&mut h, kind);
        until_built(&mut h);
        assert_eq!(built(&h).map(|s| s.settings.kind), Some(kind));
        for task in [Task::FirstHit, Task::Nearest, Task::Range, Task::AllHits] {
            act(&mut h, HalfAction::SetTask(task));
            let lane = &three(&h).half.lane;
            let rec = lane
                .recorded()
                .unwrap_or_else(|| panic!("{kind:?} {task:?}: {:?}", lane.recording));
            assert_eq!(rec.question.task, task, "{kind:?}");
            assert!(rec.agrees(), "{kind:?} {task:?}");
        }
        act(&mut h, HalfAction::SetTask(Task::FirstHit));
    }
}

#[test]
fn stepping_through_a_build_of_the_bunny_makes_every_node() {
    let mut h = lab_3d();
    act(&mut h, HalfAction::SetTask(Task::Build));
    // The task is the 3D half's own: the 2D half still asks about its ray.
    assert_eq!(three(&h).half.task, Task::Build);
    assert_eq!(h.state().lab().two().half.task, Task::FirstHit);
    press(&mut h, Key::End);
    let lane = &three(&h).half.lane;
    let snap = lane.snapshot.as_ref().expect("a snapshot");
    let built = built(&h).expect("built");
    assert_eq!(snap.existing.len(), built.node_count);
    assert!(
        snap.existing.iter().all(|&e| e),
        "every node made by the end"
    );
    press(&mut h, Key::Home);
    let snap = three(&h).half.lane.snapshot.as_ref().expect("a snapshot");
    assert!(snap.existing.iter().all(|&e| !e), "none at step 0");
}

#[test]
fn a_million_triangles_build_over_many_frames_with_rising_progress() {
    let mut h = lab_3d();
    // Applied without settling: the harness's `run` refuses a UI that keeps repainting for
    // more than a few frames, as a build under way does.
    h.state_mut()
        .apply(Action3d::OpenMesh(MeshSource::Builtin(
            "lumpy-sphere".to_owned(),
        )))
        .expect("a built-in mesh");
    let mut progress = Vec::new();
    for _ in 0..4_000 {
        h.step();
        let lab = three(&h);
        if let Some(fraction) = lab.half.lane.building() {
            progress.push(fraction);
        }
        if built(&h).is_some() && !lab.busy() {
            break;
        }
    }
    let lab = three(&h);
    assert_eq!(
        lab.mesh.as_ref().map(Mesh3d::triangle_count),
        Some(1_000_000)
    );
    let built = built(&h).expect("built");
    assert!(built.frames > 2, "sliced over frames: {}", built.frames);
    assert!(progress.len() > 2, "progress was shown: {progress:?}");
    assert!(progress.windows(2).all(|w| w[0] <= w[1]), "{progress:?}");
    assert!(built.stats.nodes > 100_000);
    // A structure that is not offered at this size says so, and keeps the mesh.
    set_kind(&mut h, StructureKind::Bsp);
    let lab = three(&h);
    let message = lab.message.clone().unwrap_or_default();
    assert!(message.contains("offered up to"), "{message}");
    assert_eq!(
        lab.mesh.as_ref().map(Mesh3d::triangle_count),
        Some(1_000_000)
    );
}

#[test]
fn a_broken_mesh_file_is_refused_and_the_open_mesh_stays() {
    let mut h = lab_3d();
    let before = three(&h)
        .mesh
        .as_ref()
        .map(|m| (m.name.clone(), m.revision));
    let dir = std::env::temp_dir().join(format!("bvhlab-view3d-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let bad = dir.join("broken.stl");
    // A binary STL header that promises 1,200 triangles and holds none.
    let mut bytes = vec![0u8; 80];
    bytes.extend_from_slice(&1200u32.to_le_bytes());
    std::fs::write(&bad, &bytes).expect("write");
    common::drop_file(&mut h, &bad);
    h.run();
    settle(&mut h);
    let lab = three(&h);
    let message = lab.message.clone().unwrap_or_default();
    assert!(message.starts_with("broken.stl"), "{message}");
    assert!(message.contains("stays open"), "{message}");
    assert_eq!(
        lab.mesh.as_ref().map(|m| (m.name.clone(), m.revision)),
        before
    );
    // A good file in another format opens.
    let good = dir.join("tri.obj");
    std::fs::write(&good, b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").expect("write");
    common::drop_file(&mut h, &good);
    h.run();
    until_built(&mut h);
    let lab = three(&h);
    assert_eq!(lab.mesh.as_ref().map(|m| m.name.as_str()), Some("tri.obj"));
    assert_eq!(built(&h).map(|b| b.stats.primitives), Some(1));
    std::fs::remove_dir_all(&dir).ok();
}

/// A primary-button drag in the 3D view from `from` to `to`, in eight moves.
fn drag_3d(h: &mut Harness<'_, LabApp>, from: egui::Pos2, to: egui::Pos2) {
    h.hover_at(from);
    h.step();
    h.drag_at(from);
    h.step();
    for i in 1..=8 {
        h.hover_at(from.lerp(to, i as f32 / 8.0));
        h.step();
    }
    h.drop_at(to);
    settle(h);
}

/// Where a handle is on screen.
pub(crate) fn handle_on_screen(h: &Harness<'_, LabApp>, which: Handle) -> egui::Pos2 {
    let lab = three(h);
    let rect = view_rect(h);
    let (_, at) = handles(lab, rect)
        .into_iter()
        .find(|(handle, _)| {
            std::mem::discriminant(handle) == std::mem::discriminant(&which)
                && match (handle, which) {
                    (Handle::Axis(a, _), Handle::Axis(b, _)) => *a == b,
                    _ => true,
                }
        })
        .expect("the handle is shown");
    let p = lab
        .camera
        .project(at, Vec2::new(rect.width(), rect.height()))
        .expect("in front of the camera");
    rect.min + egui::vec2(p.x, p.y)
}

#[test]
fn the_gizmo_moves_the_point_along_an_axis_and_in_the_view_plane() {
    let mut h = lab_3d();
    click(&mut h, "places the point");
    assert_eq!(three(&h).half.task, Task::Nearest);
    let before = three(&h).point.expect("a point is placed on load");
    // The x arrow: dragging along its screen direction moves the point along x only.
    let base = handle_on_screen(&h, Handle::Point);
    let tip = handle_on_screen(&h, Handle::Axis(0, before));
    let along = (tip - base).normalized() * 40.0;
    let rect = view_rect(&h);
    assert!(
        rect.contains(base) && rect.contains(tip),
        "the gizmo is in view: {base:?} {tip:?} in {rect:?}"
    );
    let camera = three(&h).camera;
    drag_3d(&mut h, tip, tip + along);
    assert_eq!(three(&h).camera, camera, "a handle drag does not orbit");
    let after = three(&h).point.expect("still placed");
    assert!(after.x > before.x + 1e-3, "{before} -> {after}");
    assert_eq!((after.y, after.z), (before.y, before.z));
    // The centre dot: the point moves in the plane facing the camera.
    let depth = |p: bvhlab::glam::Vec3| (p - camera.eye()).dot(camera.basis().forward);
    let centre = handle_on_screen(&h, Handle::Point);
    drag_3d(&mut h, centre, centre + egui::vec2(-30.0, 25.0));
    let moved = three(&h).point.expect("still placed");
    assert!((moved - after).length() > 1e-3);
    assert!((depth(moved) - depth(after)).abs() < 1e-3 * depth(after).abs().max(1.0));
    // The answer follows the point, and agrees with brute force.
    let rec = three(&h).half.lane.recorded().expect("recorded");
    assert_eq!(rec.question.point, Some(moved));
    assert!(rec.agrees());
}

#[test]
fn the_heat_map_fills_in_on_the_cpu_without_a_gpu() {
    let mut h = lab_3d();
    // Frame by frame: the map keeps the lab repainting until it is done.
    h.key_press(Key::H);
    h.step();
    assert!(three(&h).heat.on, "H shows the heat map");
    let mut progress = Vec::new();
    for _ in 0..500 {
        h.step();
        let heat = heat_report(&h).expect("shown");
        assert_eq!(heat.device, "cpu", "no GPU in this harness");
        progress.push(heat.progress);
        if heat.progress >= 1.0 {
            break;
        }
    }
    assert_eq!(progress.last(), Some(&1.0), "{progress:?}");
    assert!(progress.windows(2).all(|w| w[0] <= w[1]));
    let heat = heat_report(&h).expect("shown");
    assert!(heat.max > 0, "some ray visited a node");
    h.key_press(Key::H);
    h.step();
    assert!(heat_report(&h).is_none(), "H hides it again");
}
