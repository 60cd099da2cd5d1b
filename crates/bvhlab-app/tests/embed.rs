//! Embedding: the address's parameters, where the lab starts from, the 3D half kept across
//! reloads, and the scripting API driven command by command through real frames. What the
//! tests change themselves, they change with actions, as the panels do.

use crate::common;

use bvhlab::glam::{Vec2, Vec3};
use bvhlab_app::LabApp;
use bvhlab_app::embed::{PARAMETERS, Scripting, StartParams, start};
use bvhlab_app::model::lab2d::RayHandles;
use bvhlab_app::model::orbit_camera::OrbitCamera;
use bvhlab_app::model::presets::Preset;
use bvhlab_app::model::structures::{BuildSettings, StructureKind};
use bvhlab_app::model::{Action, Action2d, Action3d, Dimension, HalfAction};
use bvhlab_app::persist::{STORAGE_KEY, SavedState, StructureName, TaskName, to_file};
use egui_kittest::Harness;

/// A harness over `app`, run until it settles.
fn harness(app: LabApp) -> Harness<'static, LabApp> {
    let mut h = Harness::builder()
        .with_size(common::WINDOW)
        .build_ui_state(|ui, app: &mut LabApp| app.show(ui), app);
    h.run();
    h
}

/// The lab opened on `preset`.
fn with_preset(preset: Preset) -> LabApp {
    LabApp::with([Action2d::LoadPreset(preset).into()])
}

/// Frames until the 3D half is idle (loaded and built), or a failure.
fn until_idle(h: &mut Harness<'_, LabApp>) {
    for _ in 0..2_000 {
        let three = h.state().lab().three();
        if !three.busy() && three.half.lane.current(three.revision()).is_some() {
            h.run();
            return;
        }
        h.step();
    }
    panic!("the 3D half did not finish loading and building in 2,000 frames");
}

#[test]
fn every_documented_parameter_is_read_and_a_typo_is_named() {
    let p = StartParams::parse(
        "?preset=quadtree&structure=kd-tree&compare=grid&task=nearest&ray=1,2,3,4&point=5,6\
         &step=7&lab=left&origin=https%3A%2F%2Fcourse.example.edu&fresh=1&panels=stepper",
    );
    assert_eq!(p.problems, Vec::<String>::new());
    assert_eq!(p.preset, Some(Preset::QuadtreeHandful));
    assert_eq!(p.structure, Some(StructureName::KdTree));
    assert_eq!(p.compare, Some(StructureName::Grid));
    assert_eq!(p.task, Some(TaskName::Nearest));
    assert_eq!(p.ray, Some(vec![1.0, 2.0, 3.0, 4.0]));
    assert_eq!(p.point, Some(vec![5.0, 6.0]));
    assert_eq!(p.step, Some(7));
    assert_eq!(p.lab.as_deref(), Some("left"));
    assert_eq!(p.origins, vec!["https://course.example.edu".to_owned()]);
    assert!(p.fresh);
    let panels = p.panels.expect("panels");
    assert!(panels.stepper && !panels.controls && !panels.tree);
    // The documented list is what the parser knows (debug is for the browser test only).
    let names: Vec<&str> = PARAMETERS.iter().map(|(n, _)| *n).collect();
    for name in [
        "preset",
        "mesh",
        "structure",
        "compare",
        "task",
        "ray",
        "point",
        "step",
        "lab",
        "origin",
        "fresh",
        "panels",
    ] {
        assert!(names.contains(&name), "{name} is documented");
    }

    let bad = StartParams::parse(
        "structur=kd-tree&structure=octopus&ray=1,2,nan,4&point=1e39,0&step=-1&origin=*\
         &origin=https://a.example/path&mesh=teapot&preset=&panels=sidebar",
    );
    let text = bad.problems.join("\n");
    for part in [
        "\"structur\" is not one the lab reads",
        "octopus",
        "has NaN",
        "within ±1e15",
        "step \"-1\" is not a whole number",
        "\"*\" is not an origin",
        "\"https://a.example/path\" is not an origin",
        "no mesh named \"teapot\"",
        "no preset named \"\"",
        "no panel named \"sidebar\"",
    ] {
        assert!(
            text.contains(part),
            "a problem names {part:?}; problems:\n{text}"
        );
    }
    assert_eq!(bad.problems.len(), 10, "{text}");
    assert_eq!(bad.structure, None, "a bad value is not used");
}

/// Issue 21: a wrong name in the address was "unknown variant `kdtree`"; every parameter
/// whose value is one of a list of names now says which name it does not know and lists the
/// names it does, the nearest spelling first.
#[test]
fn a_wrong_name_in_the_address_is_answered_with_the_names_the_lab_knows() {
    let meshes: Vec<&str> = bvhlab_meshio::builtin::list()
        .iter()
        .map(|b| b.slug)
        .collect();
    let presets: Vec<&str> = Preset::ALL.iter().map(|p| p.slug()).collect();
    let cases: [(&str, &str, &[&str]); 6] = [
        (
            "structure=kdtree",
            "the address's structure: no structure named \"kdtree\"; try kd-tree, ",
            StructureName::NAMES,
        ),
        (
            "compare=aabbtree",
            "the address's compare: no structure named \"aabbtree\"; try aabb-tree, ",
            StructureName::NAMES,
        ),
        (
            "task=nearst",
            "the address's task: no task named \"nearst\"; try nearest, ",
            TaskName::NAMES,
        ),
        (
            "preset=quadtre",
            "the address's preset: no preset named \"quadtre\"; try quadtree, ",
            &presets,
        ),
        (
            "mesh=buny",
            "the address's mesh: no mesh named \"buny\"; try bunny, ",
            &meshes,
        ),
        (
            "panels=stepper,tre",
            "the address's panels: no panel named \"tre\"; try tree, ",
            &["controls", "stepper", "tree"],
        ),
    ];
    for (query, start, names) in cases {
        let p = StartParams::parse(query);
        assert_eq!(p.problems.len(), 1, "{query}: {:?}", p.problems);
        let said = &p.problems[0];
        assert!(said.starts_with(start), "{query}: {said}");
        assert!(!said.contains("variant"), "{query}: {said}");
        for name in names {
            assert!(said.contains(name), "{query} lists {name}: {said}");
        }
    }
    assert_eq!(StructureName::NAMES.len(), 8);
    assert_eq!(TaskName::NAMES.len(), 6);
}

#[test]
fn percent_escapes_are_decoded_as_browsers_do() {
    use bvhlab_app::address::decode;
    assert_eq!(decode("a%20b+c"), "a b c");
    assert_eq!(decode("%E2%9C%93"), "✓");
    assert_eq!(decode("100%"), "100%", "a cut escape stays");
    assert_eq!(decode("%zz%4"), "%zz%4");
    assert_eq!(decode("%FF"), "\u{fffd}", "not UTF-8");
}

#[test]
fn two_labs_with_different_scenes_keep_their_state_apart() {
    let plain = StartParams::parse("");
    let a = StartParams::parse("preset=kd-tree&structure=kd-tree");
    let b = StartParams::parse("preset=kd-tree&structure=aabb-tree");
    let named = StartParams::parse("lab=left&preset=kd-tree");
    assert_eq!(plain.storage_key(), STORAGE_KEY);
    assert_ne!(a.storage_key(), b.storage_key());
    assert_ne!(a.storage_key(), plain.storage_key());
    assert_eq!(named.storage_key(), format!("{STORAGE_KEY}?lab=left"));
    // Who may script the lab, and `fresh`, do not change whose state it is.
    let same =
        StartParams::parse("preset=kd-tree&structure=kd-tree&origin=https://x.example&fresh=1");
    assert_eq!(same.storage_key(), a.storage_key());
}

#[test]
fn parameters_set_the_scene_structure_ray_and_step_and_the_answer_is_brute_forces() {
    let params = StartParams::parse("preset=kd-tree&structure=aabb-tree&ray=0,4.5,1,0&step=3");
    let started = start(None, &params, None);
    assert_eq!(started.message, None);
    let mut h = harness(started.app);
    let app = h.state();
    let two = app.lab().two();
    assert_eq!(two.preset, Preset::KdHandful);
    assert_eq!(two.half.lane.settings.kind, StructureKind::AabbTree);
    let ray = two.ray.expect("the ray").ray().expect("a valid ray");
    assert_eq!(ray.origin(), Vec2::new(0.0, 4.5));
    assert_eq!(ray.dir(), Vec2::new(1.0, 0.0));
    assert_eq!(two.half.playback.step, 3);
    let query = app.report.query.clone().expect("the ray's report");
    // Brute force, by hand: every segment's hit, the nearest.
    let brute = two
        .scene
        .primitives()
        .segments
        .iter()
        .enumerate()
        .filter_map(|(i, s)| s.ray_hit(&ray).map(|t| (i, t)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .expect("the ray hits the scene");
    let hit = query.hit.expect("a hit");
    assert_eq!((hit.primitive, hit.t), brute);
    assert!(query.agrees);
    h.step();
    assert_eq!(h.state().report.playback[0].step, 3);
}

#[test]
fn a_comparison_from_the_address_answers_beside_the_first_structure() {
    let params = StartParams::parse("preset=kd-tree&structure=kd-tree&compare=grid&ray=0,4.5,1,0");
    let started = start(None, &params, None);
    assert_eq!(started.message, None);
    let h = harness(started.app);
    let half = &h.state().lab().two().half;
    assert_eq!(half.lane.settings.kind, StructureKind::KdTree);
    let other = half.compare.as_ref().expect("a comparison lane");
    assert_eq!(other.settings.kind, StructureKind::Grid);
    // Both lanes answer the one ray, each as brute force does.
    let playback = &h.state().report.playback;
    assert_eq!(playback.len(), 2, "{playback:?}");
    assert!(
        playback.iter().all(|p| p.agrees && p.error.is_none()),
        "{playback:?}"
    );
    assert_eq!(playback[1].structure, StructureKind::Grid.label());
}

#[test]
fn a_saved_state_wins_over_the_parameters_unless_fresh_and_a_broken_one_is_kept() {
    let params = StartParams::parse("preset=kd-tree&structure=grid");
    let settings = BuildSettings {
        kind: StructureKind::Bsp,
        ..Preset::QuadtreeHandful.build().1
    };
    let edited = LabApp::with([
        Action2d::LoadPreset(Preset::QuadtreeHandful).into(),
        HalfAction::SetStructure(settings).into(),
    ]);
    let saved = serde_json::to_string(&SavedState::capture(edited.lab())).expect("json");

    let restored = start(None, &params, Some(&saved));
    let two = restored.app.lab().two();
    assert_eq!(two.preset, Preset::QuadtreeHandful);
    assert_eq!(two.half.lane.settings.kind, StructureKind::Bsp);
    assert!(!restored.saved_failed);

    let fresh = start(
        None,
        &StartParams::parse("preset=kd-tree&structure=grid&fresh=1"),
        Some(&saved),
    );
    let two = fresh.app.lab().two();
    assert_eq!(two.preset, Preset::KdHandful);
    assert_eq!(two.half.lane.settings.kind, StructureKind::Grid);

    let broken = start(None, &params, Some("{\"version\": 1, \"k\": \"many\""));
    assert!(
        broken.saved_failed,
        "kept until the student changes something"
    );
    assert_eq!(
        broken.app.lab().two().half.lane.settings.kind,
        StructureKind::Grid,
        "the parameters apply"
    );
    let message = broken.message.expect("a message");
    assert!(message.contains("could not be restored"), "{message}");
}

#[test]
fn the_3d_half_comes_back_after_a_reload_with_its_mesh_camera_ray_and_point() {
    let params =
        StartParams::parse("mesh=torus&structure=kd-tree&ray=0,0,5,0.1,0.05,-1&point=0.5,0.5,0.5");
    let started = start(None, &params, None);
    assert_eq!(started.message, None);
    let mut h = harness(started.app);
    until_idle(&mut h);
    let camera = {
        let lab = h.state().lab().three();
        assert_eq!(h.state().lab().dimension(), Dimension::Three);
        assert_eq!(
            lab.mesh.as_ref().and_then(|m| m.slug.as_deref()),
            Some("torus")
        );
        assert_eq!(lab.half.lane.settings.kind, StructureKind::KdTree);
        let ray = lab.ray.expect("the address's ray, not the default one");
        assert_eq!(ray.origin(), Vec3::new(0.0, 0.0, 5.0));
        assert_eq!(lab.point, Some(Vec3::splat(0.5)));
        lab.camera
    };
    // The student turns the camera and moves the point; the lab saves; the page reloads.
    common::act(
        &mut h,
        Action3d::SetCamera(OrbitCamera {
            yaw: camera.yaw + 0.7,
            ..camera
        }),
    );
    common::act(
        &mut h,
        Action3d::SetPoint(Some(Vec3::new(-0.25, 0.5, 0.75))),
    );
    until_idle(&mut h);
    let before = SavedState::capture(h.state().lab());
    let saved = serde_json::to_string(&before).expect("json");
    let again = start(None, &params, Some(&saved));
    let mut h2 = harness(again.app);
    until_idle(&mut h2);
    let (a, b) = (h.state().lab().three(), h2.state().lab().three());
    assert_eq!(h2.state().lab().dimension(), Dimension::Three);
    assert_eq!(
        b.mesh.as_ref().and_then(|m| m.slug.as_deref()),
        Some("torus")
    );
    assert_eq!(b.half.lane.settings, a.half.lane.settings);
    assert_eq!(b.camera, a.camera, "the turned camera, not a fresh framing");
    assert_eq!(b.ray, a.ray);
    assert_eq!(b.point, a.point);
    assert_eq!(b.half.radius, a.half.radius);
    assert_eq!(b.half.task, a.half.task);
    assert_eq!(SavedState::capture(h2.state().lab()), before);
    // The answers are the same too.
    assert_eq!(
        h2.state()
            .report
            .three
            .as_ref()
            .map(|t| (t.hit.clone(), t.cost)),
        h.state()
            .report
            .three
            .as_ref()
            .map(|t| (t.hit.clone(), t.cost))
    );
}

#[test]
fn a_file_mesh_comes_back_as_its_name_with_a_message_and_everything_else() {
    let mut h = harness(LabApp::with([Action::Show(Dimension::Three)]));
    until_idle(&mut h);
    let mut state = SavedState::capture(h.state().lab());
    let three = state.three.as_mut().expect("the 3D half");
    three.mesh = bvhlab_app::persist::MeshState::File("my-part.stl".to_owned());
    three.structure.kind = StructureName::Bsp;
    let json = serde_json::to_string(&state).expect("json");
    let started = start(None, &StartParams::default(), Some(&json));
    let mut h2 = harness(started.app);
    until_idle(&mut h2);
    let lab = h2.state().lab();
    assert_eq!(lab.three().half.lane.settings.kind, StructureKind::Bsp);
    let message = lab.message().unwrap_or_default();
    assert!(
        message.contains("my-part.stl") && message.contains("drop it"),
        "{message}"
    );
}

#[test]
fn export_then_import_gives_the_same_state_in_both_halves() {
    let mut h = harness(with_preset(Preset::RandomSegments));
    common::act(
        &mut h,
        Action2d::SetRay(Some(RayHandles {
            origin: Vec2::new(-1.0, 3.0),
            target: Vec2::new(4.0, 5.0),
        })),
    );
    common::act(&mut h, Action::Show(Dimension::Three));
    until_idle(&mut h);
    // The structure of the half shown: the 3D half's.
    let settings = BuildSettings {
        leaf_size: 2,
        ..h.state().lab().three().half.lane.settings
    };
    common::act(&mut h, HalfAction::SetStructure(settings));
    until_idle(&mut h);
    assert_eq!(h.state().lab().three().half.lane.settings.leaf_size, 2);
    let file = to_file(h.state().lab());
    let mut other = LabApp::default();
    other
        .apply(bvhlab_app::persist::open_file(&file).expect("the exported file opens"))
        .expect("applies");
    assert_eq!(
        SavedState::capture_full(other.lab()),
        SavedState::capture_full(h.state().lab())
    );
}

/// A test's stand-in for the window a reply goes to.
type Sent = Vec<(u32, serde_json::Value)>;

fn replies(scripting: &mut Scripting<u32>, h: &mut Harness<'_, LabApp>, sent: &mut Sent) {
    for frame in 0..2_000 {
        let now = f64::from(frame) * 0.016;
        scripting.before_frame(h.state_mut(), now);
        h.step();
        for (to, json) in scripting.after_frame(h.state(), now) {
            sent.push((to, serde_json::from_str(&json).expect("a reply is JSON")));
        }
        if !scripting.pending() {
            return;
        }
    }
    panic!("replies still owed after 2,000 frames");
}

#[test]
fn commands_are_applied_in_order_and_answered_with_the_report() {
    let mut h = harness(with_preset(Preset::KdHandful));
    let mut scripting = Scripting::new(false);
    let mut sent = Sent::new();
    let id = |n: u32| n.to_string();
    scripting.receive(
        1,
        &id(1),
        r#"{"type": "set-structure", "structure": "kd-tree"}"#,
    );
    scripting.receive(
        1,
        &id(2),
        r#"{"type": "set-ray", "origin": [0, 4.5], "direction": [1, 0]}"#,
    );
    scripting.receive(1, &id(3), r#"{"type": "go-to-step", "step": 0}"#);
    scripting.receive(1, &id(4), r#"{"type": "step", "by": 2}"#);
    scripting.receive(
        2,
        &id(5),
        r#"{"type": "set-structure", "structure": "octopus"}"#,
    );
    scripting.receive(
        2,
        &id(6),
        r#"{"type": "set-ray", "origin": [0, 0], "direction": [0, 0]}"#,
    );
    scripting.receive(2, &id(7), r#"{"type": "panic-for-test"}"#);
    scripting.receive(2, &id(8), "not json");
    replies(&mut scripting, &mut h, &mut sent);
    assert_eq!(sent.len(), 8, "{sent:#?}");
    let by_id = |n: u64| {
        sent.iter()
            .find(|(_, r)| r["id"] == n)
            .expect("reply")
            .clone()
    };
    for n in 1..=4 {
        let (to, reply) = by_id(n);
        assert_eq!(to, 1);
        assert_eq!(reply["bvhlab"], "reply");
        assert_eq!(reply["ok"], true, "{reply}");
    }
    let (_, stepped) = by_id(4);
    let lane = &stepped["report"]["playback"][0];
    assert_eq!(lane["structure"], "k-d tree");
    assert_eq!(lane["step"], 2);
    assert_eq!(stepped["report"]["query"]["agrees"], true);
    assert_eq!(
        stepped["report"]["query"]["ray"],
        serde_json::json!([0.0, 4.5, 1.0, 0.0])
    );
    for (n, part) in [
        (5, "octopus"),
        (6, "zero"),
        (7, "debug=panic"),
        (8, "not a command"),
    ] {
        let (to, reply) = by_id(n);
        assert_eq!(to, 2);
        assert_eq!(reply["ok"], false);
        let error = reply["error"].as_str().unwrap_or_default();
        assert!(error.to_lowercase().contains(part), "reply {n}: {error}");
    }
    // The refused commands changed nothing.
    let two = h.state().lab().two();
    assert_eq!(two.half.lane.settings.kind, StructureKind::KdTree);
    assert_eq!(two.ray.map(|r| r.origin), Some(Vec2::new(0.0, 4.5)));
}

#[test]
fn a_reply_waits_for_a_3d_build_and_export_scene_gives_a_scene_that_loads() {
    let mut h = harness(LabApp::default());
    let mut scripting = Scripting::new(false);
    let mut sent = Sent::new();
    scripting.receive(0, r#""a""#, r#"{"type": "load-mesh", "mesh": "sphere"}"#);
    scripting.receive(
        0,
        r#""b""#,
        r#"{"type": "set-ray", "origin": [0, 0, 5], "direction": [0, 0, -1]}"#,
    );
    scripting.receive(0, r#""c0""#, r#"{"type": "go-to-step", "step": 0}"#);
    scripting.receive(0, r#""c""#, r#"{"type": "step", "by": 4}"#);
    scripting.receive(0, r#""d""#, r#"{"type": "export-scene"}"#);
    replies(&mut scripting, &mut h, &mut sent);
    assert_eq!(sent.len(), 5);
    for (_, reply) in &sent {
        assert_eq!(reply["ok"], true, "{reply}");
        // Every reply came after the build: the report has the answer.
        assert!(reply["report"]["three"]["hit"].is_object(), "{reply}");
        assert_eq!(reply["report"]["three"]["mesh"], "UV sphere");
    }
    assert_eq!(sent[3].1["report"]["playback"][0]["step"], 4);
    let scene = sent[4].1["scene"].clone();
    let mut other = harness(LabApp::default());
    let mut scripting = Scripting::new(false);
    let mut sent = Sent::new();
    let command = serde_json::json!({"type": "load-scene", "scene": scene}).to_string();
    scripting.receive(0, "1", &command);
    replies(&mut scripting, &mut other, &mut sent);
    assert_eq!(sent[0].1["ok"], true, "{}", sent[0].1);
    until_idle(&mut other);
    assert_eq!(other.state().lab().three().ray, h.state().lab().three().ray);
    assert_eq!(other.state().lab().dimension(), Dimension::Three);
}

#[test]
fn ids_come_back_exactly_as_the_page_wrote_them() {
    let mut h = harness(LabApp::default());
    let mut scripting = Scripting::new(false);
    // A Math.random() id (its digits need not survive a trip through an f64 and back, so it
    // must be echoed verbatim), an object, and an id that is not JSON (echoed as null).
    let ids = ["0.40478935219183896", r#"{"page": [1, "a"]}"#, "not json"];
    for (n, id) in (0u32..).zip(ids) {
        scripting.receive(n, id, r#"{"type": "report"}"#);
    }
    scripting.before_frame(h.state_mut(), 0.0);
    h.step();
    let out = scripting.after_frame(h.state(), 0.0);
    assert_eq!(out.len(), 3);
    for ((_, json), expected) in out.iter().zip([
        r#""id":0.40478935219183896,"#,
        r#""id":{"page": [1, "a"]},"#,
        r#""id":null,"#,
    ]) {
        assert!(json.contains(expected), "{expected} in {json}");
        serde_json::from_str::<serde_json::Value>(json).expect("the reply is JSON");
    }
}
