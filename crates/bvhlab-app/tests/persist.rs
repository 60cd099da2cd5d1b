//! Saving and restoring the lab: every preset, with and without a comparison lane, goes
//! through JSON, scene files and share links and comes back bit for bit, answering the same
//! queries; hostile files and links (truncated, wrong types, huge numbers and counts,
//! garbage, deflate bombs, a few hundred seeded mutations) give a message and leave the lab
//! as it was; the start-up order and the autosave are checked on plain data; a scene file
//! and a share link written before each half kept its own question and playback still open
//! as they did.
//!
//! The labs here are set up, and files and links opened, with actions
//! ([`LabApp::apply`]), as the panels and the page do.

use crate::common;

use base64::Engine as _;
use base64::engine::general_purpose::URL_SAFE_NO_PAD;
use bvhlab::Ray3;
use bvhlab::glam::{Vec2, Vec3};
use bvhlab::structure::SplitMethod;
use bvhlab::structure::bvh::SphereFit;
use bvhlab_app::LabApp;
use bvhlab_app::model::camera2d::Camera2d;
use bvhlab_app::model::lab2d::{Display, RayHandles};
use bvhlab_app::model::mesh::MeshSource;
use bvhlab_app::model::orbit_camera::OrbitCamera;
use bvhlab_app::model::presets::Preset;
use bvhlab_app::model::scene::{Scene, Shape, ShapeKind};
use bvhlab_app::model::structures::{BuildSettings, KdSplit, StructureKind};
use bvhlab_app::model::volumes::VolumeToggles;
use bvhlab_app::model::{Action, Action2d, Dimension, HalfAction, Lab, PlaybackAction};
use bvhlab_app::persist::{
    self, Autosave, AutosaveStep, MAX_FILE_BYTES, MAX_LINK_CHARS, MAX_POINTS, MAX_SHAPES,
    SavedState, TaskName, from_file, from_fragment, link_fragment, open_file, open_fragment,
    to_file,
};
use bvhlab_app::pseudocode::{Task, Variant};

/// `SplitMix64` (Steele, Lea and Flood, OOPSLA 2014): seeded, so failures replay.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// Applies `action` to `app`, failing the test when it is refused.
fn set(app: &mut LabApp, action: impl Into<Action>) {
    let action = action.into();
    if let Err(e) = app.apply(action.clone()) {
        panic!("{action:?} was refused: {e}");
    }
}

/// The lab opened on `preset`.
fn with_preset(preset: Preset) -> LabApp {
    LabApp::with([Action2d::LoadPreset(preset).into()])
}

/// Opens a scene file in `app` as a dropped file opens: the action it makes, applied.
fn open(app: &mut LabApp, bytes: &[u8]) -> Result<(), String> {
    app.apply(open_file(bytes)?)
}

/// Opens a share link's fragment in `app`: the action it makes, applied.
fn open_link(app: &mut LabApp, fragment: &str) -> Result<(), String> {
    app.apply(open_fragment(fragment)?)
}

/// A lab whose scene is `shapes` (the default lab's state otherwise), put in with one
/// action, as a big scene file opens: adding 100,000 shapes one action at a time would
/// rebuild the structure 100,000 times.
fn showing(shapes: Vec<Shape>) -> LabApp {
    let mut app = LabApp::default();
    let Ok(Action::Restore(mut state)) = SavedState::capture(app.lab()).restore() else {
        panic!("the default lab's state restores");
    };
    state.two.scene = Scene::from_shapes(shapes);
    state.two.selection.clear();
    set(&mut app, Action::Restore(state));
    app
}

/// A lab on `preset` with everything set away from its defaults: a structure and task that
/// depend on `variety`, a comparison lane if asked, ray, point, switches, view, and playback
/// paused half way through the recording.
fn dressed(preset: Preset, variety: usize, compare: bool) -> LabApp {
    let mut app = with_preset(preset);
    let two = app.lab().two();
    let (lo, hi) = two.scene.bounds().expect("presets are not empty");
    let mid = (lo + hi) * 0.5;
    let kind = StructureKind::ALL[variety % StructureKind::ALL.len()];
    let task = [Task::FirstHit, Task::Nearest, Task::AllHits, Task::Range][variety % 4];
    let variant = if kind.is_bvh() && task == Task::FirstHit {
        Variant::Lecture
    } else if kind.is_bvh() && task == Task::Nearest {
        Variant::LecturePruned
    } else {
        Variant::Full
    };
    let display = Display {
        leaf_colours: true,
        max_depth: 5,
        slab_test: true,
        ..two.display
    };
    let volumes = VolumeToggles {
        ritter: false,
        hull: false,
        ..two.volumes
    };
    let mut actions: Vec<Action> = vec![
        HalfAction::SetStructure(BuildSettings {
            kind,
            bvh_split: [
                SplitMethod::SpatialMedian,
                SplitMethod::ObjectMedian,
                SplitMethod::BinnedSah,
            ][variety % 3],
            sphere_fit: SphereFit::Welzl,
            leaf_size: 1 + variety % 4,
            kd_split: [
                KdSplit::MedianRoundRobin,
                KdSplit::MedianLongest,
                KdSplit::Sah,
            ][variety % 3],
            grid_cells: (variety % 2) as u32 * 7,
            quadtree_depth: 5 + variety,
        })
        .into(),
    ];
    if compare {
        actions.push(
            HalfAction::SetCompare(Some(BuildSettings {
                kind: StructureKind::ALL[(variety + 3) % StructureKind::ALL.len()],
                ..BuildSettings::default()
            }))
            .into(),
        );
    }
    actions.extend([
        // The ray and the point first: placing each makes the task one about it.
        Action2d::SetRay(Some(RayHandles {
            origin: lo - Vec2::new(1.3, 0.7),
            target: mid + Vec2::new(0.13, -0.071),
        }))
        .into(),
        Action2d::SetPoint(Some(mid + Vec2::new(0.317, 0.173))).into(),
        HalfAction::SetTask(task).into(),
        HalfAction::SetVariant(variant).into(),
        HalfAction::SetK(3).into(),
        HalfAction::SetRadius(2.5).into(),
        Action2d::Select(vec![0]).into(),
        Action2d::SetDisplay(display).into(),
        Action2d::SetVolumes(volumes).into(),
        // Framed as the canvas frames a new preset, then panned and zoomed away from that.
        Action2d::FrameScene(Vec2::new(800.0, 600.0)).into(),
        Action2d::SetCamera(Camera2d {
            center: mid + Vec2::new(0.1, -0.2),
            scale: 17.25,
        })
        .into(),
    ]);
    for action in actions {
        set(&mut app, action);
    }
    assert!(!app.lab().two().fit_pending);
    let len = app.lab().steps();
    set(&mut app, PlaybackAction::GoTo(len / 2));
    app
}

/// Bits of a point, for exact comparison (`-0.0 != 0.0` here, `NaN == NaN`).
fn bits(p: Vec2) -> [u32; 2] {
    [p.x.to_bits(), p.y.to_bits()]
}

/// Asserts that `b` holds the same state as `a`, bit for bit, and answers the same.
fn assert_same(a: &Lab, b: &Lab, what: &str) {
    let (ta, tb) = (a.two(), b.two());
    let (ha, hb) = (&ta.half, &tb.half);
    assert_eq!(a.dimension(), b.dimension(), "{what}: half shown");
    assert_eq!(ta.preset, tb.preset, "{what}: preset");
    let (sa, sb) = (ta.scene.shapes(), tb.scene.shapes());
    assert_eq!(sa.len(), sb.len(), "{what}: shape count");
    for (i, (x, y)) in sa.iter().zip(sb).enumerate() {
        assert_eq!(x.kind, y.kind, "{what}: shape {i} kind");
        let px: Vec<[u32; 2]> = x.points.iter().copied().map(bits).collect();
        let py: Vec<[u32; 2]> = y.points.iter().copied().map(bits).collect();
        assert_eq!(px, py, "{what}: shape {i} points");
    }
    assert_eq!(ta.selection, tb.selection, "{what}: selection");
    assert_eq!(ha.lane.settings, hb.lane.settings, "{what}: settings");
    assert_eq!(
        ha.compare.as_ref().map(|l| l.settings),
        hb.compare.as_ref().map(|l| l.settings),
        "{what}: comparison settings"
    );
    assert_eq!(ta.display, tb.display, "{what}: display");
    assert_eq!(ta.volumes, tb.volumes, "{what}: volumes");
    assert_eq!(
        ta.ray.map(|r| (bits(r.origin), bits(r.target))),
        tb.ray.map(|r| (bits(r.origin), bits(r.target))),
        "{what}: ray"
    );
    assert_eq!(ta.point.map(bits), tb.point.map(bits), "{what}: point");
    assert_eq!(ha.k, hb.k, "{what}: k");
    assert_eq!(ha.radius.to_bits(), hb.radius.to_bits(), "{what}: radius");
    assert_eq!(ha.task, hb.task, "{what}: task");
    assert_eq!(ha.variant, hb.variant, "{what}: variant");
    assert_eq!(ha.playback.step, hb.playback.step, "{what}: step");
    assert_eq!(ha.playback.at_end, hb.playback.at_end, "{what}: live");
    assert_eq!(
        bits(ta.camera.center),
        bits(tb.camera.center),
        "{what}: view centre"
    );
    assert_eq!(
        ta.camera.scale.to_bits(),
        tb.camera.scale.to_bits(),
        "{what}: view scale"
    );
    // The 3D half's saved part (its mesh, structure, camera, and its own question and
    // playback) comes back too.
    assert_eq!(
        SavedState::capture(a).three,
        SavedState::capture(b).three,
        "{what}: the 3D half"
    );
    // The restored lab answers as the original does (every action brings the answers up
    // to date).
    assert_eq!(ha.steps(), hb.steps(), "{what}: recording length");
    assert_eq!(
        ha.lane.ray_outcome.as_ref().map(|o| o.hit),
        hb.lane.ray_outcome.as_ref().map(|o| o.hit),
        "{what}: ray answer"
    );
    assert_eq!(
        ha.lane.point_outcome.as_ref().map(|o| o.nearest.clone()),
        hb.lane.point_outcome.as_ref().map(|o| o.nearest.clone()),
        "{what}: nearest answer"
    );
}

/// A fresh lab (on another preset, so that nothing matches by accident) with `state`
/// applied.
fn restored(state: &SavedState) -> LabApp {
    let mut app = with_preset(Preset::KdHandful);
    set(&mut app, state.apply().expect("a captured state applies"));
    assert!(
        !app.lab().two().fit_pending,
        "the saved view is kept, not refitted"
    );
    app
}

#[test]
fn every_preset_round_trips_through_json_files_and_links() {
    for (variety, preset) in Preset::ALL.into_iter().enumerate() {
        for compare in [false, true] {
            let app = dressed(preset, variety, compare);
            let lab = app.lab();
            let what = format!("{preset:?}, compare {compare}");
            let state = SavedState::capture(lab);
            assert_eq!(
                state.scene,
                persist::SceneState::Preset(persist::PresetSlug(preset)),
                "{what}: an unmodified preset is stored by name"
            );

            let json = serde_json::to_string(&state).expect("serializes");
            let back: SavedState = serde_json::from_str(&json).expect("parses");
            assert_eq!(back, state, "{what}: JSON");
            assert_same(lab, restored(&back).lab(), &format!("{what} via JSON"));

            let file = to_file(lab);
            let from = from_file(&file).expect("a written file reads back");
            assert!(
                matches!(from.scene, persist::SceneState::Shapes(_)),
                "{what}: files hold every shape"
            );
            assert_same(lab, restored(&from).lab(), &format!("{what} via file"));

            let link = link_fragment(&state).expect("presets fit in a link");
            assert!(link.starts_with("#s=") && link.len() <= MAX_LINK_CHARS);
            let from = from_fragment(&link).expect("a link made reads back");
            assert_same(lab, restored(&from).lab(), &format!("{what} via link"));
        }
    }
}

#[test]
fn an_edited_scene_round_trips_with_its_shapes() {
    let mut app = dressed(Preset::KdHandful, 2, true);
    set(
        &mut app,
        Action2d::AddShape {
            kind: ShapeKind::Polyline,
            points: vec![
                Vec2::new(-0.0, 1e-30),
                Vec2::new(0.1, 0.2),
                Vec2::new(-3.5, 1e7),
            ],
        },
    );
    // Shape 0 is selected (dressed selects it): move it.
    assert_eq!(app.lab().two().selection, [0]);
    set(&mut app, Action2d::MoveSelection(Vec2::new(0.3, -0.1)));
    set(&mut app, PlaybackAction::GoTo(2));
    let state = SavedState::capture(app.lab());
    assert!(matches!(state.scene, persist::SceneState::Shapes(_)));
    let link = link_fragment(&state).expect("a small scene fits in a link");
    assert_same(
        app.lab(),
        restored(&from_fragment(&link).expect("reads")).lab(),
        "link",
    );
    assert_same(
        app.lab(),
        restored(&from_file(&to_file(app.lab())).expect("reads")).lab(),
        "file",
    );
}

#[test]
fn coordinates_come_back_bit_for_bit() {
    // Finite f32 of every magnitude within the limit, from random bit patterns: the file
    // writes each as its shortest decimal and reads it through f64.
    let mut rng = Rng(7);
    let mut points = Vec::new();
    while points.len() < 20_000 {
        let x = f32::from_bits(rng.next() as u32);
        let y = f32::from_bits(rng.next() as u32);
        if x.is_finite() && y.is_finite() && x.abs() <= 1e15 && y.abs() <= 1e15 {
            points.push(Vec2::new(x, y));
        }
    }
    points.extend([
        Vec2::new(-0.0, 0.0),
        Vec2::new(f32::MIN_POSITIVE, -f32::MIN_POSITIVE / 3.0),
        Vec2::new(1e15, -1e15),
        Vec2::new(0.1, 16_777_217.0),
    ]);
    let app = showing(vec![Shape::new(ShapeKind::Points, points).expect("ok")]);
    let back = restored(&from_file(&to_file(app.lab())).expect("reads"));
    let want: Vec<[u32; 2]> = app.lab().two().scene.shapes()[0]
        .points
        .iter()
        .copied()
        .map(bits)
        .collect();
    let got: Vec<[u32; 2]> = back.lab().two().scene.shapes()[0]
        .points
        .iter()
        .copied()
        .map(bits)
        .collect();
    assert_eq!(want, got);
}

#[test]
fn scene_files_are_readable_json_with_a_shape_per_line() {
    let app = with_preset(Preset::KdHandful);
    let text = String::from_utf8(to_file(app.lab())).expect("UTF-8");
    assert!(text.contains("\"version\": 1"), "{text}");
    assert!(text.contains("\"kind\": \"polygon\""), "{text}");
    assert!(
        text.contains(
            "\n      {\"kind\": \"polygon\", \"points\": [[1.0, 1.0], [3.0, 1.2], [2.0, 2.6]]},\n"
        ),
        "a shape per line: {text}"
    );
    assert!(text.contains("\"center\": ["), "{text}");
    assert!(text.contains("\"kind\": \"kd-tree\""), "{text}");
    // The same text parses as plain JSON, and a hand-written minimal file opens.
    let _: serde_json::Value = serde_json::from_str(&text).expect("plain JSON");
    let minimal =
        br#"{"version": 1, "scene": {"shapes": [{"kind": "segment", "points": [[0, 0], [2, 1]]}]},
        "structure": {"kind": "bsp"}}"#;
    let mut lab = LabApp::default();
    open(&mut lab, minimal).expect("a minimal hand-written file opens");
    let two = lab.lab().two();
    assert_eq!(two.scene.shapes().len(), 1);
    assert_eq!(two.half.lane.settings.kind, StructureKind::Bsp);
    assert_eq!(
        two.half.lane.settings.leaf_size,
        BuildSettings::default().leaf_size
    );
}

#[test]
fn the_10k_preset_fits_in_a_link_but_a_drawn_10k_scene_does_not() {
    let app = with_preset(Preset::TenThousand);
    let link = link_fragment(&SavedState::capture(app.lab())).expect("stored by name");
    assert!(link.len() < 1_000, "{} characters", link.len());
    let back = restored(&from_fragment(&link).expect("reads"));
    assert_eq!(
        back.lab().two().scene.shapes(),
        app.lab().two().scene.shapes()
    );

    // The same segments, drawn by hand (moved by a hair, so no longer the preset).
    let mut drawn = with_preset(Preset::TenThousand);
    set(&mut drawn, Action2d::Select(vec![0]));
    set(&mut drawn, Action2d::MoveSelection(Vec2::new(1e-3, 0.0)));
    set(&mut drawn, Action2d::Select(Vec::new()));
    let err = link_fragment(&SavedState::capture(drawn.lab())).expect_err("too long");
    assert!(err.contains("export the scene as a file instead"), "{err}");
    // ...which works.
    let file = to_file(drawn.lab());
    let back = restored(&from_file(&file).expect("the file reads"));
    assert_eq!(
        back.lab().two().scene.shapes(),
        drawn.lab().two().scene.shapes()
    );
}

#[test]
fn scenes_at_the_limits_export_and_import() {
    // Worst-case coordinates: the longest decimals f32 has, negative.
    let mut rng = Rng(11);
    let mut long = || -1.234_567_9e-7 * (1.0 + rng.unit());
    let shapes: Vec<Shape> = (0..MAX_SHAPES)
        .map(|_| {
            Shape::new(
                ShapeKind::Segment,
                vec![Vec2::new(long(), long()), Vec2::new(long(), long())],
            )
            .expect("ok")
        })
        .collect();
    let app = showing(shapes);
    let file = to_file(app.lab());
    assert!(file.len() <= MAX_FILE_BYTES, "{} bytes", file.len());
    let state = from_file(&file).expect("a scene at the shape limit reads back");
    assert!(matches!(&state.scene, persist::SceneState::Shapes(s) if s.len() == MAX_SHAPES));

    let cloud: Vec<Vec2> = (0..MAX_POINTS).map(|_| Vec2::new(long(), long())).collect();
    let app = showing(vec![Shape::new(ShapeKind::Points, cloud).expect("ok")]);
    let file = to_file(app.lab());
    assert!(file.len() <= MAX_FILE_BYTES, "{} bytes", file.len());
    from_file(&file).expect("a scene at the point limit reads back");
}

/// A small valid file with every field, to break.
fn valid_file() -> Vec<u8> {
    to_file(dressed(Preset::KdHandful, 1, true).lab())
}

/// `valid_file` with the first `from` replaced by `to`.
fn edited(from: &str, to: &str) -> Vec<u8> {
    let text = String::from_utf8(valid_file()).expect("UTF-8");
    assert!(text.contains(from), "{from:?} is in the file");
    text.replacen(from, to, 1).into_bytes()
}

/// Asserts that `bytes` is refused, by `from_file` and by `open_file` on a lab that then
/// still has its scene; returns the message.
fn refused(bytes: &[u8], what: &str) -> String {
    let err = from_file(bytes).expect_err(what);
    assert!(!err.is_empty() && err.len() < 600, "{what}: {err}");
    let mut app = with_preset(Preset::DuplicateTriangle);
    let changes = app.lab().changes();
    let two = app.lab().two();
    let (revision, shapes) = (two.scene.revision(), two.scene.shapes().to_vec());
    let message = open(&mut app, bytes).expect_err(what);
    assert!(
        message.ends_with("The current scene was kept."),
        "{what}: {message}"
    );
    let two = app.lab().two();
    assert_eq!(app.lab().changes(), changes, "{what}: nothing applied");
    assert_eq!(two.scene.revision(), revision, "{what}: scene untouched");
    assert_eq!(two.scene.shapes(), &shapes[..], "{what}: shapes untouched");
    assert_eq!(
        two.half.lane.settings.kind,
        StructureKind::Grid,
        "{what}: settings untouched"
    );
    err
}

/// Edits of [`valid_file`] (first occurrence of the first string replaced by the second)
/// that break it, and what the message must say.
const BROKEN: &[(&str, &str, &str)] = &[
    ("\"version\": 1", "\"version\": 2", "version 2"),
    ("\"version\": 1", "\"version\": 0", "version 0"),
    ("\"version\": 1", "\"version\": \"1\"", "invalid type"),
    ("\"k\": 3", "\"k\": \"3\"", "invalid type"),
    ("\"k\": 3", "\"k\": 100000000000000000000", "invalid type"),
    ("\"k\": 3", "\"k\": 65", "k is 65"),
    ("\"k\": 3", "\"k\": 0", "k is 0"),
    ("\"k\": 3", "\"k\": -1", "invalid value"),
    ("\"radius\": 2.5", "\"radius\": -1.0", "radius is -1"),
    ("\"radius\": 2.5", "\"radius\": \"NaN\"", "invalid type"),
    ("\"radius\": 2.5", "\"radius\": NaN", "not a bvh-lab scene"),
    (
        "\"radius\": 2.5",
        "\"radius\": Infinity",
        "not a bvh-lab scene",
    ),
    ("\"radius\": 2.5", "\"radius\": 1e300", "too large"),
    ("\"radius\": 2.5", "\"radius\": 1e400", "out of range"),
    ("[1.0, 1.0]", "[1e300, 1.0]", "too large"),
    ("[1.0, 1.0]", "[1.0, -1e16]", "too large"),
    ("[1.0, 1.0]", "[1.0, null]", "invalid type"),
    ("[1.0, 1.0]", "[1.0]", "invalid length"),
    ("[1.0, 1.0]", "[1.0, 1.0, 1.0]", "not a bvh-lab scene"),
    ("\"sphere-tree\"", "\"r-tree\"", "unknown variant"),
    ("\"polygon\"", "\"circle\"", "unknown variant"),
    ("\"nearest\"", "\"near_est\"", "unknown variant"),
    ("\"kd-tree\"", "\"nope\"", "unknown preset"),
    ("\"leaf_size\": 2", "\"leaf_sise\": 2", "unknown field"),
    ("\"leaf_size\": 2", "\"leaf_size\": 1000000000", "leaf size"),
    ("\"grid_cells\": 7", "\"grid_cells\": 1000000", "grid"),
    (
        "\"quadtree_depth\": 6",
        "\"quadtree_depth\": 0",
        "quadtree depth",
    ),
    ("\"selection\": [", "\"selection\": [99, ", "shape 99"),
    ("\"scale\": 17.25", "\"scale\": 0.0", "scale"),
    (
        "\"scene\": {",
        "\"scene\": {\"preset\": \"10k\", ",
        "not a bvh-lab",
    ),
    ("\"points\": [[", "\"points\": [[[", "not a bvh-lab scene"),
];

#[test]
fn hostile_files_are_refused_with_a_message() {
    let valid = valid_file();
    assert!(from_file(&valid).is_ok());
    for cut in [1, 2, 10, valid.len() / 3, valid.len() / 2, valid.len() - 2] {
        refused(&valid[..cut], &format!("truncated at {cut}"));
    }
    let whole: [(&[u8], &str); 5] = [
        (b"", "empty"),
        (b"  \n\t ", "empty"),
        (b"null", "not a bvh-lab scene"),
        (b"[1, 2]", "not a bvh-lab scene"),
        (b"{}", "no \"version\""),
    ];
    for (bytes, expected) in whole {
        let err = refused(bytes, expected);
        assert!(err.contains(expected), "{err}");
    }
    for &(from, to, expected) in BROKEN {
        let err = refused(&edited(from, to), to);
        assert!(err.contains(expected), "{to}: {err}");
    }
    // A polygon of two points (Shape::new's rule).
    let err = refused(
        br#"{"version": 1, "scene": {"shapes": [{"kind": "polygon", "points": [[0, 0], [1, 0]]}]}}"#,
        "a two-point polygon",
    );
    assert!(err.contains("at least 3"), "{err}");
}

#[test]
fn too_many_shapes_or_points_are_refused() {
    let many = format!(
        r#"{{"version": 1, "scene": {{"shapes": [{}]}}}}"#,
        vec![r#"{"kind":"points","points":[[0,0]]}"#; MAX_SHAPES + 1].join(",")
    );
    let err = refused(many.as_bytes(), "too many shapes");
    assert!(err.contains(&format!("{}", MAX_SHAPES + 1)), "{err}");
    let cloud = format!(
        r#"{{"version": 1, "scene": {{"shapes": [{{"kind":"points","points":[{}]}}]}}}}"#,
        vec!["[0,0]"; MAX_POINTS + 1].join(",")
    );
    let err = refused(cloud.as_bytes(), "too many points");
    assert!(err.contains(&format!("{}", MAX_POINTS + 1)), "{err}");
}

#[test]
fn garbage_deep_nesting_and_oversized_files_are_refused() {
    // Deep nesting: the typed schema stops at the first list where it expects something
    // else, and serde_json skips an ignored value without recursing; neither overflows.
    refused(&vec![b'['; 200_000], "deep nesting");
    let nest = format!("{}{}", "[".repeat(200_000), "]".repeat(200_000));
    for deep in [
        format!("{{\"version\": 1, \"extra\": {nest}}}"),
        format!("{{\"extra\": {nest}, \"version\": 1}}"),
        format!("{{\"version\": 1, \"scene\": {{\"shapes\": {nest}}}}}"),
        format!("{{\"version\": 1, \"selection\": {nest}}}"),
    ] {
        refused(deep.as_bytes(), "deep nesting");
    }
    // An oversized file is not parsed.
    let mut huge = valid_file();
    huge.resize(MAX_FILE_BYTES + 1, b' ');
    let err = refused(&huge, "oversized");
    assert!(err.contains("MiB"), "{err}");
    // Binary garbage, and an unknown string the message must not repeat in full.
    let mut rng = Rng(3);
    for _ in 0..20 {
        let garbage: Vec<u8> = (0..rng.below(4000)).map(|_| rng.next() as u8).collect();
        refused(&garbage, "garbage");
    }
    let long = edited("\"kd-tree\"", &format!("\"{}\"", "x".repeat(1_000_000)));
    refused(&long, "a megabyte of preset name");
}

#[test]
fn a_state_made_in_code_is_checked_before_anything_changes() {
    let mut app = with_preset(Preset::QuadtreeHandful);
    let revision = app.lab().two().scene.revision();
    let mut state = SavedState::capture_full(dressed(Preset::KdHandful, 0, false).lab());
    if let persist::SceneState::Shapes(shapes) = &mut state.scene {
        shapes[2].points[1][0] = persist::Coord(f32::NAN);
    }
    let err = state
        .apply()
        .and_then(|action| app.apply(action))
        .expect_err("NaN");
    assert!(
        err.starts_with("Point 1 of shape 2 is [NaN")
            && err.ends_with("The current scene was kept."),
        "{err}"
    );
    assert_eq!(app.lab().two().scene.revision(), revision);
    state.scene = persist::SceneState::Preset(persist::PresetSlug(Preset::RandomPoints));
    state.ray = Some(persist::RayState {
        origin: [persist::Coord(0.0), persist::Coord(f32::INFINITY)],
        target: [persist::Coord(1.0), persist::Coord(1.0)],
    });
    let err = state
        .apply()
        .and_then(|action| app.apply(action))
        .expect_err("infinite ray");
    assert!(err.contains("ray's origin"), "{err}");
    assert_eq!(app.lab().two().scene.revision(), revision);
    assert_eq!(app.lab().two().preset, Preset::QuadtreeHandful);
}

/// Asserts that `fragment` is refused, and that `open_fragment` leaves the lab's scene.
fn refused_link(fragment: &str, what: &str) -> String {
    let err = from_fragment(fragment).expect_err(what);
    let mut app = LabApp::default();
    let revision = app.lab().two().scene.revision();
    let message = open_link(&mut app, fragment).expect_err(what);
    assert!(
        message.ends_with("The current scene was kept."),
        "{what}: {message}"
    );
    assert_eq!(app.lab().two().scene.revision(), revision, "{what}");
    err
}

#[test]
fn hostile_links_are_refused_with_a_message() {
    let good = link_fragment(&SavedState::capture(
        dressed(Preset::KdHandful, 1, false).lab(),
    ))
    .expect("fits");
    assert!(from_fragment(&good).is_ok());
    assert!(from_fragment(&good[1..]).is_ok(), "the '#' is optional");
    let pack = |bytes: &[u8]| {
        format!(
            "#s={}",
            URL_SAFE_NO_PAD.encode(miniz_oxide::deflate::compress_to_vec_zlib(bytes, 10))
        )
    };
    let cases = [
        ("#view=3".to_owned(), "not a share link", "no #s="),
        ("#s=".to_owned(), "empty", "does not inflate"),
        ("#s=!!!not*base64".to_owned(), "bad base64", "not base64url"),
        (
            format!("#s={}", URL_SAFE_NO_PAD.encode(b"hello, world")),
            "bad deflate",
            "does not inflate",
        ),
        (good[..good.len() / 2].to_owned(), "truncated", "damaged"),
        (pack(b"{\"version\": 1, \"k\": 0}"), "bad state", "k is 0"),
        (
            pack(b"\x00\x01garbage"),
            "garbage JSON",
            "not a bvh-lab scene",
        ),
        (
            format!("#s={}", "A".repeat(MAX_LINK_CHARS)),
            "too long",
            "more than any link",
        ),
    ];
    for (fragment, what, expected) in cases {
        let err = refused_link(&fragment, what);
        assert!(err.contains(expected), "{what}: {err}");
    }
    // A flipped character in the middle: the checksum (or the JSON) catches it.
    let mut chars: Vec<char> = good.chars().collect();
    let mid = chars.len() / 2;
    chars[mid] = if chars[mid] == 'A' { 'B' } else { 'A' };
    refused_link(
        &chars.into_iter().collect::<String>(),
        "a flipped character",
    );
}

#[test]
fn deflate_bombs_stop_at_the_limit() {
    // 100 MB of zeros packs into a link far over the length limit: refused unread.
    let zeros = vec![b' '; 100 << 20];
    let bomb = format!(
        "#s={}",
        URL_SAFE_NO_PAD.encode(miniz_oxide::deflate::compress_to_vec_zlib(&zeros, 10))
    );
    assert!(bomb.len() > MAX_LINK_CHARS);
    let err = refused_link(&bomb, "100 MB bomb");
    assert!(err.contains("more than any link"), "{err}");
    // 16 MiB of spaces (valid JSON whitespace) fits within the length limit: inflation must
    // stop at the limit, not inflate it all.
    let small_bomb = format!(
        "#s={}",
        URL_SAFE_NO_PAD.encode(miniz_oxide::deflate::compress_to_vec_zlib(
            &zeros[..16 << 20],
            10
        ))
    );
    assert!(small_bomb.len() <= MAX_LINK_CHARS, "{}", small_bomb.len());
    let start = std::time::Instant::now();
    let err = refused_link(&small_bomb, "16 MiB bomb");
    assert!(err.contains("inflates past"), "{err}");
    assert!(start.elapsed().as_secs_f64() < 5.0);
}

#[test]
fn hundreds_of_mutated_files_and_links_never_panic() {
    let file = valid_file();
    let link = link_fragment(&SavedState::capture(
        dressed(Preset::KdHandful, 1, true).lab(),
    ))
    .expect("fits");
    let mut rng = Rng(2024);
    let (mut opened, mut refused_count) = (0, 0);
    for round in 0..400 {
        let mut bytes = file.clone();
        match round % 4 {
            0 => {
                for _ in 0..=rng.below(8) {
                    let i = rng.below(bytes.len());
                    bytes[i] ^= 1 << rng.below(8);
                }
            }
            1 => {
                // Swap in a digit, a sign or a bracket where it can change a value's meaning.
                let i = rng.below(bytes.len());
                bytes[i] = b"0123456789-e.[]{}\",:"[rng.below(20)];
            }
            2 => bytes.truncate(rng.below(bytes.len())),
            _ => {
                let i = rng.below(bytes.len());
                let j = rng.below(bytes.len());
                let chunk = bytes[i.min(j)..i.max(j)].to_vec();
                let at = rng.below(bytes.len());
                bytes.splice(at..at, chunk);
            }
        }
        let mut app = with_preset(Preset::DuplicateTriangle);
        let revision = app.lab().two().scene.revision();
        // Whatever passed the checks must be a lab that works: applying the action brings
        // the structures, recordings and answers up to date.
        match open(&mut app, &bytes) {
            Ok(()) => {
                opened += 1;
                for s in app.lab().two().scene.shapes() {
                    Shape::new(s.kind, s.points.clone()).expect("opened shapes are valid");
                }
            }
            Err(e) => {
                refused_count += 1;
                assert!(e.ends_with("The current scene was kept."), "{e}");
                assert_eq!(app.lab().two().scene.revision(), revision);
            }
        }
        // And the link, one character changed.
        let mut chars: Vec<char> = link.chars().collect();
        let i = 3 + rng.below(chars.len() - 3);
        chars[i] = ['A', 'z', '_', '-', '0', '#', '%'][rng.below(7)];
        let mutated: String = chars.into_iter().collect();
        let mut app = LabApp::default();
        let _ = open_link(&mut app, &mutated);
    }
    assert!(
        refused_count > 100,
        "most mutations break the file ({refused_count})"
    );
    assert!(opened > 0, "some mutations leave a valid file ({opened})");
}

#[test]
fn startup_prefers_the_link_then_the_preset_then_the_saved_state() {
    let linked = dressed(Preset::KdHandful, 2, false);
    let link = link_fragment(&SavedState::capture(linked.lab())).expect("fits");
    let saved_app = dressed(Preset::RandomPoints, 5, true);
    let saved = serde_json::to_string(&SavedState::capture(saved_app.lab())).expect("json");

    let (lab, message) = persist::startup(Some(&link), Some("quadtree"), Some(&saved));
    assert_eq!(message, None);
    assert_same(linked.lab(), &lab, "the link wins");

    let (lab, message) = persist::startup(Some("#section-2"), Some("quadtree"), Some(&saved));
    assert_eq!(message, None);
    assert_eq!(
        lab.two().preset,
        Preset::QuadtreeHandful,
        "other fragments are not links"
    );
    assert_eq!(
        lab.two().scene.shapes(),
        Preset::QuadtreeHandful.build().0.shapes()
    );

    let (lab, message) = persist::startup(None, None, Some(&saved));
    assert_eq!(message, None);
    assert_same(saved_app.lab(), &lab, "the saved state");

    let (lab, message) = persist::startup(None, None, None);
    assert_eq!(message, None);
    assert_eq!(lab.two().preset, Preset::default());

    let default_shapes = Lab::default().two().scene.shapes().to_vec();
    for (fragment, preset, saved, expected) in [
        (
            Some("#s=garbage"),
            Some("quadtree"),
            Some(saved.as_str()),
            "share link",
        ),
        (None, Some("octree"), Some(saved.as_str()), "\"octree\""),
        (
            None,
            None,
            Some("{\"version\": 1, \"k\": 99}"),
            "saved in this browser",
        ),
        (None, None, Some("not json"), "saved in this browser"),
    ] {
        let (lab, message) = persist::startup(fragment, preset, saved);
        let message = message.expect("a failure is said");
        assert!(message.contains(expected), "{message}");
        assert!(
            message.ends_with("The default scene is shown."),
            "{message}"
        );
        assert_eq!(lab.message(), Some(message.as_str()));
        assert_eq!(lab.two().scene.shapes(), &default_shapes[..]);
        assert_eq!(lab.two().preset, Preset::default());
    }
}

#[test]
fn autosave_writes_changes_at_most_every_half_second() {
    let mut app = dressed(Preset::RandomSegments, 1, false);
    let mut autosave = Autosave::default();
    let AutosaveStep::Save(first) = autosave.poll(app.lab(), 0.0) else {
        panic!("the first poll saves");
    };
    assert_eq!(autosave.poll(app.lab(), 0.01), AutosaveStep::Idle);
    // A write at 5.0 (the preset's view moved), then nothing for a while.
    let camera = Camera2d {
        scale: 20.0,
        ..app.lab().two().camera
    };
    set(&mut app, Action2d::SetCamera(camera));
    assert!(matches!(
        autosave.poll(app.lab(), 5.0),
        AutosaveStep::Save(_)
    ));
    assert_eq!(
        autosave.poll(app.lab(), 5.1),
        AutosaveStep::Idle,
        "nothing changed"
    );

    set(&mut app, Action2d::SetPoint(Some(Vec2::new(1.0, 2.0))));
    let AutosaveStep::Wait(wait) = autosave.poll(app.lab(), 5.2) else {
        panic!("a change waits for the interval since the last write");
    };
    assert!((wait - (5.5 - 5.2)).abs() < 1e-9, "{wait}");
    let AutosaveStep::Save(second) = autosave.poll(app.lab(), 5.5) else {
        panic!("then it is written");
    };
    assert_ne!(first, second);
    let mut back = LabApp::default();
    open(&mut back, second.as_bytes()).expect("the saved JSON opens");
    assert_same(app.lab(), back.lab(), "autosaved");

    // A change undone before the write: the JSON is the same, nothing is written.
    set(&mut app, HalfAction::SetK(5));
    assert!(matches!(
        autosave.poll(app.lab(), 5.6),
        AutosaveStep::Wait(_)
    ));
    set(&mut app, HalfAction::SetK(3));
    assert_eq!(autosave.poll(app.lab(), 6.2), AutosaveStep::Idle);

    // After a failed start, the default scene does not overwrite the saved state until the
    // student changes something.
    let (mut fallen_back, message) = persist::startup(Some("#s=broken"), None, Some(&second));
    assert!(message.is_some());
    let mut held = Autosave::new(Some(second.clone()));
    held.keep_current(&fallen_back);
    assert_eq!(held.poll(&fallen_back, 0.0), AutosaveStep::Idle);
    fallen_back
        .apply(HalfAction::SetK(2).into())
        .expect("k 2 applies");
    assert!(matches!(
        held.poll(&fallen_back, 0.1),
        AutosaveStep::Save(_)
    ));

    // A lab started from the stored state does not write it again.
    let mut fresh = Autosave::new(Some(second.clone()));
    assert_eq!(fresh.poll(app.lab(), 0.0), AutosaveStep::Idle);
    fresh.write_failed();
    set(&mut app, HalfAction::SetK(4));
    assert!(matches!(fresh.poll(app.lab(), 1.0), AutosaveStep::Save(_)));
}

#[test]
fn a_file_dropped_on_the_window_opens_and_a_bad_one_is_refused() {
    use egui_kittest::Harness;
    use egui_kittest::kittest::Queryable as _;

    let dir = std::env::temp_dir().join(format!("bvhlab-persist-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let good = dir.join("scene.json");
    let source = dressed(Preset::KdHandful, 3, false);
    std::fs::write(&good, to_file(source.lab())).expect("write");
    let bad = dir.join("bad.json");
    std::fs::write(&bad, b"{\"version\": 1, \"k\": \"many\"}").expect("write");

    let mut h = Harness::builder()
        .with_size(egui::vec2(1800.0, 1800.0))
        .build_ui_state(|ui, app: &mut LabApp| app.show(ui), LabApp::default());
    h.run();
    common::drop_file(&mut h, &good);
    h.run();
    let lab = h.state().lab();
    assert_eq!(lab.two().scene.shapes(), source.lab().two().scene.shapes());
    assert_eq!(
        lab.two().half.lane.settings,
        source.lab().two().half.lane.settings
    );
    assert!(
        lab.message().is_some_and(|m| m.starts_with("Opened")),
        "{:?}",
        lab.message()
    );

    let revision = h.state().lab().two().scene.revision();
    common::drop_file(&mut h, &bad);
    h.run();
    let message = h.state().lab().message().unwrap_or_default().to_owned();
    assert!(
        message.contains("invalid type") && message.ends_with("kept."),
        "{message}"
    );
    assert_eq!(h.state().lab().two().scene.revision(), revision);

    // The share link appears in a field natively (the controls are taller than the window
    // with this lab's ray and slab test: scroll to the button first, as a student would).
    h.get_by_label("Copy share link").scroll_to_me();
    h.run();
    h.get_by_label("Copy share link").click();
    h.run();
    let shown = persist::share_link_text(&h.ctx).expect("a link is shown");
    assert!(from_fragment(&shown).is_ok());
    std::fs::remove_dir_all(&dir).ok();
}

/// A scene file written by the lab as it was before each half kept its own question and
/// playback (commit c1eefd9; `tests/fixtures/README.md` says how): version 1, every field,
/// and a `three` part without the task, variant, k, comparison and playback that 3D states
/// now save. The 2D half is shown.
const OLD_FILE: &str = include_str!("fixtures/v1-before-halves.json");
/// The same lab's share link, made with the 3D half shown.
const OLD_LINK: &str = include_str!("fixtures/v1-before-halves.link");

/// The old lab's scene, made again: the k-d tree preset with shape 1 moved and a polyline
/// added.
fn old_scene() -> Lab {
    let mut lab = Lab::default();
    lab.apply_all([
        Action2d::LoadPreset(Preset::KdHandful).into(),
        Action2d::Select(vec![1]).into(),
        Action2d::MoveSelection(Vec2::new(0.5, -0.25)).into(),
        Action2d::AddShape {
            kind: ShapeKind::Polyline,
            points: vec![
                Vec2::new(0.25, 6.5),
                Vec2::new(2.75, 7.125),
                Vec2::new(4.5, 6.0),
            ],
        }
        .into(),
    ])
    .expect("the old scene, made again");
    lab
}

/// Asserts that `lab` holds what the old lab held after opening [`OLD_FILE`] or
/// [`OLD_LINK`] (as it printed then): the scene, the structures, the ray and point, the
/// question, the playback step, the view, and the answers.
fn assert_old_2d(lab: &Lab, what: &str) {
    let two = lab.two();
    assert_eq!(two.preset, Preset::KdHandful, "{what}: preset");
    assert_eq!(
        two.scene.shapes(),
        old_scene().two().scene.shapes(),
        "{what}: scene"
    );
    assert_eq!(two.selection, [2], "{what}: selection");
    assert_eq!(
        two.half.lane.settings,
        BuildSettings {
            kind: StructureKind::AabbTree,
            bvh_split: SplitMethod::BinnedSah,
            sphere_fit: SphereFit::Ritter,
            leaf_size: 2,
            kd_split: KdSplit::MedianRoundRobin,
            grid_cells: 0,
            quadtree_depth: 8,
        },
        "{what}: structure"
    );
    assert_eq!(
        two.half.compare.as_ref().map(|l| l.settings),
        Some(BuildSettings {
            kind: StructureKind::Grid,
            bvh_split: SplitMethod::SpatialMedian,
            sphere_fit: SphereFit::Ritter,
            leaf_size: 2,
            kd_split: KdSplit::MedianRoundRobin,
            grid_cells: 6,
            quadtree_depth: 8,
        }),
        "{what}: comparison"
    );
    assert_eq!(
        two.display,
        Display {
            structure: true,
            max_depth: 6,
            leaf_colours: true,
            query_marks: true,
            volumes: false,
            slab_test: false,
        },
        "{what}: display"
    );
    assert_eq!(
        two.volumes,
        VolumeToggles {
            centroid: true,
            ritter: false,
            welzl: true,
            aabb: true,
            obb: true,
            hull: true,
        },
        "{what}: volumes"
    );
    assert_eq!(
        two.ray,
        Some(RayHandles {
            origin: Vec2::new(-0.5, 1.75),
            target: Vec2::new(4.75, 4.6),
        }),
        "{what}: ray"
    );
    assert_eq!(two.point, Some(Vec2::new(3.125, 3.5)), "{what}: point");
    let half = &two.half;
    assert_eq!(half.task, Task::Nearest, "{what}: task");
    assert_eq!(half.variant, Variant::LecturePruned, "{what}: variant");
    assert_eq!(half.k, 3, "{what}: k");
    assert_eq!(half.radius, 1.5, "{what}: radius");
    assert_eq!(
        (half.playback.step, half.playback.at_end, half.steps()),
        (20, false, 41),
        "{what}: playback step, live, recording length"
    );
    assert_eq!(
        two.camera,
        Camera2d {
            center: Vec2::new(3.0, 3.5),
            scale: 42.5,
        },
        "{what}: view"
    );
    // The answers the old lab gave.
    let hit = half.lane.ray_outcome.as_ref().and_then(|o| o.hit);
    assert_eq!(hit.map(|h| (h.prim, h.t)), Some((7, 1.0)), "{what}: hit");
    let nearest: Vec<(usize, f32)> = half
        .lane
        .point_outcome
        .as_ref()
        .map(|o| o.nearest.iter().map(|n| (n.prim, n.distance)).collect())
        .unwrap_or_default();
    assert_eq!(
        nearest,
        [(7, 1.007_782_2), (13, 1.437_228_1), (1, 1.440_703)],
        "{what}: nearest"
    );
}

/// Asserts that `lab`'s 3D half holds what the old lab's did once its mesh had loaded, and
/// the question and playback of the 2D half, which the old lab shared between the halves.
fn assert_old_3d(lab: &mut Lab, what: &str) {
    let half = &lab.three().half;
    assert_eq!(half.task, Task::Nearest, "{what}: 3D task (the 2D half's)");
    // The 2D half's version does not exist for the 3D half's k-d tree: the full one runs,
    // and is the one selected (issue 21: neither was shown selected).
    assert_eq!(half.variant, Variant::Full, "{what}: 3D variant");
    assert_eq!(half.k, 3, "{what}: 3D k");
    assert!(half.compare.is_none(), "{what}: no 3D comparison");
    assert_eq!(
        (half.playback.step, half.playback.at_end),
        (20, false),
        "{what}: 3D playback (the 2D half's)"
    );
    assert_eq!(
        lab.three().pending,
        Some(MeshSource::Builtin("torus".to_owned())),
        "{what}: the mesh to load"
    );
    // Load and build it, as the frames do.
    let shown = lab.dimension();
    lab.apply(Action::Show(Dimension::Three)).expect("shows 3D");
    for _ in 0..1_000 {
        if !lab.busy() {
            break;
        }
        lab.apply(Action::Tick {
            seconds: 0.0,
            build_ms: 1_000.0,
        })
        .expect("a frame");
    }
    assert!(!lab.busy(), "{what}: the torus loads and builds");
    let three = lab.three();
    assert_eq!(
        three.mesh.as_ref().and_then(|m| m.slug.as_deref()),
        Some("torus"),
        "{what}: mesh"
    );
    assert_eq!(
        three.half.lane.settings,
        BuildSettings {
            kind: StructureKind::KdTree,
            bvh_split: SplitMethod::SpatialMedian,
            sphere_fit: SphereFit::Ritter,
            leaf_size: 4,
            kd_split: KdSplit::MedianRoundRobin,
            grid_cells: 0,
            quadtree_depth: 8,
        },
        "{what}: 3D structure"
    );
    assert_eq!(
        three.camera,
        OrbitCamera {
            target: Vec3::new(0.125, -0.25, 0.5),
            distance: 6.5,
            yaw: 0.75,
            pitch: 0.375,
            ..OrbitCamera::default()
        },
        "{what}: camera"
    );
    assert_eq!(
        three.ray,
        Some(Ray3::new(Vec3::new(-4.0, 0.5, 0.25), Vec3::new(1.0, -0.125, 0.0)).expect("ray")),
        "{what}: 3D ray"
    );
    assert_eq!(
        three.point,
        Some(Vec3::new(0.5, 1.25, -0.75)),
        "{what}: 3D point"
    );
    assert_eq!(three.half.radius, 0.625, "{what}: 3D radius");
    assert_eq!(
        (three.half.playback.step, three.half.steps()),
        (20, 206),
        "{what}: 3D playback step and recording length"
    );
    // Saved again, the 3D half keeps its own question and playback.
    let again = SavedState::capture(lab).three.expect("the 3D part");
    assert_eq!(again.task, Some(TaskName::Nearest), "{what}: saved 3D task");
    assert_eq!(
        again.playback.map(|p| (p.step, p.live)),
        Some((20, false)),
        "{what}: saved 3D playback"
    );
    lab.apply(Action::Show(shown))
        .expect("shows the half again");
}

#[test]
fn a_file_and_a_link_from_before_the_halves_kept_their_own_question_still_open() {
    // The fixtures are what the old code wrote: the 3D part has none of the new fields.
    let old: serde_json::Value = serde_json::from_str(OLD_FILE).expect("JSON");
    assert_eq!(old["version"], 1);
    for field in ["task", "variant", "k", "compare", "playback"] {
        assert!(
            old["three"].get(field).is_none(),
            "no 3D {field} in the file"
        );
    }
    let link = OLD_LINK.trim();

    // The scene file, opened on a lab elsewhere (as a dropped file or "Import scene…").
    let mut lab = Lab::default();
    lab.apply(Action2d::LoadPreset(Preset::RandomPoints).into())
        .expect("a preset");
    lab.apply(open_file(OLD_FILE.as_bytes()).expect("the old file opens"))
        .expect("applies");
    assert_eq!(
        lab.dimension(),
        Dimension::Two,
        "file: the 2D half is shown"
    );
    assert_old_2d(&lab, "file");
    assert_old_3d(&mut lab, "file");

    // The share link, pasted into an open lab: the 3D half is shown.
    let mut lab = Lab::default();
    lab.apply(open_fragment(link).expect("the old link opens"))
        .expect("applies");
    assert_eq!(
        lab.dimension(),
        Dimension::Three,
        "link: the 3D half is shown"
    );
    assert_old_2d(&lab, "link");
    assert_old_3d(&mut lab, "link");

    // At start-up: the link in the address, and the file's JSON as the state saved in the
    // browser.
    let (mut lab, message) = persist::startup(Some(link), None, None);
    assert_eq!(message, None);
    assert_eq!(lab.dimension(), Dimension::Three);
    assert_old_2d(&lab, "link at start-up");
    assert_old_3d(&mut lab, "link at start-up");
    let (mut lab, message) = persist::startup(None, None, Some(OLD_FILE));
    assert_eq!(message, None);
    assert_eq!(lab.dimension(), Dimension::Two);
    assert_old_2d(&lab, "saved state at start-up");
    assert_old_3d(&mut lab, "saved state at start-up");
}
