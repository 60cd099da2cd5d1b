//! Saving and restoring the lab: every preset, with and without a comparison lane, goes
//! through JSON, scene files and share links and comes back bit for bit, answering the same
//! queries; hostile files and links (truncated, wrong types, huge numbers and counts,
//! garbage, deflate bombs, a few hundred seeded mutations) give a message and leave the lab
//! as it was; the start-up order and the autosave are checked on plain data.

mod common;

use base64::Engine as _;
use base64::engine::general_purpose::URL_SAFE_NO_PAD;
use bvhlab::glam::Vec2;
use bvhlab::structure::SplitMethod;
use bvhlab::structure::bvh::SphereFit;
use bvhlab_app::LabApp;
use bvhlab_app::app::RayHandles;
use bvhlab_app::lane::Lane;
use bvhlab_app::persist::{
    self, Autosave, AutosaveStep, MAX_FILE_BYTES, MAX_LINK_CHARS, MAX_POINTS, MAX_SHAPES,
    SavedState, from_file, from_fragment, link_fragment, open_file, open_fragment, to_file,
};
use bvhlab_app::presets::Preset;
use bvhlab_app::pseudocode::{Task, Variant};
use bvhlab_app::scene::{Scene, Shape, ShapeKind};
use bvhlab_app::structures::{BuildSettings, KdSplit, StructureKind};

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

/// A lab on `preset` with everything set away from its defaults: a structure and task that
/// depend on `variety`, a comparison lane if asked, ray, point, switches, view, and playback
/// paused half way through the recording.
fn dressed(preset: Preset, variety: usize, compare: bool) -> LabApp {
    let mut app = LabApp::with_preset(preset);
    let (lo, hi) = app.scene.bounds().expect("presets are not empty");
    let mid = (lo + hi) * 0.5;
    let kind = StructureKind::ALL[variety % StructureKind::ALL.len()];
    app.lane.settings = BuildSettings {
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
    };
    if compare {
        app.compare = Some(Lane::new(BuildSettings {
            kind: StructureKind::ALL[(variety + 3) % StructureKind::ALL.len()],
            ..BuildSettings::default()
        }));
    }
    app.task = [Task::FirstHit, Task::Nearest, Task::AllHits, Task::Range][variety % 4];
    app.variant = if kind.is_bvh() && app.task == Task::FirstHit {
        Variant::Lecture
    } else if kind.is_bvh() && app.task == Task::Nearest {
        Variant::LecturePruned
    } else {
        Variant::Full
    };
    app.ray = Some(RayHandles {
        origin: lo - Vec2::new(1.3, 0.7),
        target: mid + Vec2::new(0.13, -0.071),
    });
    app.point = Some(mid + Vec2::new(0.317, 0.173));
    app.k = 3;
    app.radius = 2.5;
    app.selection = vec![0];
    app.display.leaf_colours = true;
    app.display.max_depth = 5;
    app.display.slab_test = true;
    app.volume_toggles.ritter = true;
    app.volume_toggles.hull = false;
    app.view.center = mid + Vec2::new(0.1, -0.2);
    app.view.scale = 17.25;
    app.fit_pending = false;
    app.refresh();
    let len = app.steps();
    app.playback.go(len / 2, len);
    app.refresh();
    app
}

/// Bits of a point, for exact comparison (`-0.0 != 0.0` here, `NaN == NaN`).
fn bits(p: Vec2) -> [u32; 2] {
    [p.x.to_bits(), p.y.to_bits()]
}

/// Asserts that `b` holds the same state as `a`, bit for bit, and answers the same.
fn assert_same(a: &LabApp, b: &LabApp, what: &str) {
    assert_eq!(a.preset, b.preset, "{what}: preset");
    let (sa, sb) = (a.scene.shapes(), b.scene.shapes());
    assert_eq!(sa.len(), sb.len(), "{what}: shape count");
    for (i, (x, y)) in sa.iter().zip(sb).enumerate() {
        assert_eq!(x.kind, y.kind, "{what}: shape {i} kind");
        let px: Vec<[u32; 2]> = x.points.iter().copied().map(bits).collect();
        let py: Vec<[u32; 2]> = y.points.iter().copied().map(bits).collect();
        assert_eq!(px, py, "{what}: shape {i} points");
    }
    assert_eq!(a.selection, b.selection, "{what}: selection");
    assert_eq!(a.lane.settings, b.lane.settings, "{what}: settings");
    assert_eq!(
        a.compare.as_ref().map(|l| l.settings),
        b.compare.as_ref().map(|l| l.settings),
        "{what}: comparison settings"
    );
    assert_eq!(a.display, b.display, "{what}: display");
    assert_eq!(a.volume_toggles, b.volume_toggles, "{what}: volumes");
    assert_eq!(
        a.ray.map(|r| (bits(r.origin), bits(r.target))),
        b.ray.map(|r| (bits(r.origin), bits(r.target))),
        "{what}: ray"
    );
    assert_eq!(a.point.map(bits), b.point.map(bits), "{what}: point");
    assert_eq!(a.k, b.k, "{what}: k");
    assert_eq!(a.radius.to_bits(), b.radius.to_bits(), "{what}: radius");
    assert_eq!(a.task, b.task, "{what}: task");
    assert_eq!(a.variant, b.variant, "{what}: variant");
    assert_eq!(a.playback.step, b.playback.step, "{what}: step");
    assert_eq!(a.playback.at_end, b.playback.at_end, "{what}: live");
    assert_eq!(
        bits(a.view.center),
        bits(b.view.center),
        "{what}: view centre"
    );
    assert_eq!(
        a.view.scale.to_bits(),
        b.view.scale.to_bits(),
        "{what}: view scale"
    );
    // The restored lab answers as the original does (both refreshed by the caller).
    assert_eq!(a.steps(), b.steps(), "{what}: recording length");
    assert_eq!(
        a.lane.ray_outcome.as_ref().map(|o| o.hit),
        b.lane.ray_outcome.as_ref().map(|o| o.hit),
        "{what}: ray answer"
    );
    assert_eq!(
        a.lane.point_outcome.as_ref().map(|o| o.nearest.clone()),
        b.lane.point_outcome.as_ref().map(|o| o.nearest.clone()),
        "{what}: nearest answer"
    );
}

/// A fresh lab (on another preset, so that nothing matches by accident) with `state`
/// applied and refreshed.
fn restored(state: SavedState) -> LabApp {
    let mut app = LabApp::with_preset(Preset::KdHandful);
    state.apply(&mut app).expect("a captured state applies");
    assert!(!app.fit_pending, "the saved view is kept, not refitted");
    app.refresh();
    app
}

#[test]
fn every_preset_round_trips_through_json_files_and_links() {
    for (variety, preset) in Preset::ALL.into_iter().enumerate() {
        for compare in [false, true] {
            let app = dressed(preset, variety, compare);
            let what = format!("{preset:?}, compare {compare}");
            let state = SavedState::capture(&app);
            assert_eq!(
                state.scene,
                persist::SceneState::Preset(persist::PresetSlug(preset)),
                "{what}: an unmodified preset is stored by name"
            );

            let json = serde_json::to_string(&state).expect("serializes");
            let back: SavedState = serde_json::from_str(&json).expect("parses");
            assert_eq!(back, state, "{what}: JSON");
            assert_same(&app, &restored(back), &format!("{what} via JSON"));

            let file = to_file(&app);
            let from = from_file(&file).expect("a written file reads back");
            assert!(
                matches!(from.scene, persist::SceneState::Shapes(_)),
                "{what}: files hold every shape"
            );
            assert_same(&app, &restored(from), &format!("{what} via file"));

            let link = link_fragment(&state).expect("presets fit in a link");
            assert!(link.starts_with("#s=") && link.len() <= MAX_LINK_CHARS);
            let from = from_fragment(&link).expect("a link made reads back");
            assert_same(&app, &restored(from), &format!("{what} via link"));
        }
    }
}

#[test]
fn an_edited_scene_round_trips_with_its_shapes() {
    let mut app = dressed(Preset::KdHandful, 2, true);
    app.scene.add(
        Shape::new(
            ShapeKind::Polyline,
            vec![
                Vec2::new(-0.0, 1e-30),
                Vec2::new(0.1, 0.2),
                Vec2::new(-3.5, 1e7),
            ],
        )
        .expect("valid"),
    );
    app.scene.translate(0, Vec2::new(0.3, -0.1));
    app.playback.go(2, app.steps());
    app.refresh();
    let state = SavedState::capture(&app);
    assert!(matches!(state.scene, persist::SceneState::Shapes(_)));
    let link = link_fragment(&state).expect("a small scene fits in a link");
    assert_same(
        &app,
        &restored(from_fragment(&link).expect("reads")),
        "link",
    );
    assert_same(
        &app,
        &restored(from_file(&to_file(&app)).expect("reads")),
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
    let app = LabApp {
        scene: Scene::from_shapes(vec![Shape::new(ShapeKind::Points, points).expect("ok")]),
        ..LabApp::default()
    };
    let back = restored(from_file(&to_file(&app)).expect("reads"));
    let want: Vec<[u32; 2]> = app.scene.shapes()[0]
        .points
        .iter()
        .copied()
        .map(bits)
        .collect();
    let got: Vec<[u32; 2]> = back.scene.shapes()[0]
        .points
        .iter()
        .copied()
        .map(bits)
        .collect();
    assert_eq!(want, got);
}

#[test]
fn scene_files_are_readable_json_with_a_shape_per_line() {
    let app = LabApp::with_preset(Preset::KdHandful);
    let text = String::from_utf8(to_file(&app)).expect("UTF-8");
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
    open_file(&mut lab, minimal).expect("a minimal hand-written file opens");
    assert_eq!(lab.scene.shapes().len(), 1);
    assert_eq!(lab.lane.settings.kind, StructureKind::Bsp);
    assert_eq!(
        lab.lane.settings.leaf_size,
        BuildSettings::default().leaf_size
    );
}

#[test]
fn the_10k_preset_fits_in_a_link_but_a_drawn_10k_scene_does_not() {
    let app = LabApp::with_preset(Preset::TenThousand);
    let link = link_fragment(&SavedState::capture(&app)).expect("stored by name");
    assert!(link.len() < 1_000, "{} characters", link.len());
    let back = restored(from_fragment(&link).expect("reads"));
    assert_eq!(back.scene.shapes(), app.scene.shapes());

    // The same segments, drawn by hand (moved by a hair, so no longer the preset).
    let mut drawn = LabApp::with_preset(Preset::TenThousand);
    drawn.scene.translate(0, Vec2::new(1e-3, 0.0));
    let err = link_fragment(&SavedState::capture(&drawn)).expect_err("too long");
    assert!(err.contains("export the scene as a file instead"), "{err}");
    // ...which works.
    let file = to_file(&drawn);
    let back = restored(from_file(&file).expect("the file reads"));
    assert_eq!(back.scene.shapes(), drawn.scene.shapes());
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
    let mut app = LabApp {
        scene: Scene::from_shapes(shapes),
        ..LabApp::default()
    };
    let file = to_file(&app);
    assert!(file.len() <= MAX_FILE_BYTES, "{} bytes", file.len());
    let state = from_file(&file).expect("a scene at the shape limit reads back");
    assert!(matches!(&state.scene, persist::SceneState::Shapes(s) if s.len() == MAX_SHAPES));

    let cloud: Vec<Vec2> = (0..MAX_POINTS).map(|_| Vec2::new(long(), long())).collect();
    app.scene = Scene::from_shapes(vec![Shape::new(ShapeKind::Points, cloud).expect("ok")]);
    let file = to_file(&app);
    assert!(file.len() <= MAX_FILE_BYTES, "{} bytes", file.len());
    from_file(&file).expect("a scene at the point limit reads back");
}

/// A small valid file with every field, to break.
fn valid_file() -> Vec<u8> {
    to_file(&dressed(Preset::KdHandful, 1, true))
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
    let mut app = LabApp::with_preset(Preset::DuplicateTriangle);
    let (revision, shapes) = (app.scene.revision(), app.scene.shapes().to_vec());
    let message = open_file(&mut app, bytes).expect_err(what);
    assert!(
        message.ends_with("The current scene was kept."),
        "{what}: {message}"
    );
    assert_eq!(app.scene.revision(), revision, "{what}: scene untouched");
    assert_eq!(app.scene.shapes(), &shapes[..], "{what}: shapes untouched");
    assert_eq!(
        app.lane.settings.kind,
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
    ("\"sphere-tree\"", "\"octree\"", "unknown variant"),
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
    let mut app = LabApp::with_preset(Preset::QuadtreeHandful);
    let revision = app.scene.revision();
    let mut state = SavedState::capture_full(&dressed(Preset::KdHandful, 0, false));
    if let persist::SceneState::Shapes(shapes) = &mut state.scene {
        shapes[2].points[1][0] = persist::Coord(f32::NAN);
    }
    let err = state.clone().apply(&mut app).expect_err("NaN");
    assert!(
        err.starts_with("Point 1 of shape 2 is [NaN")
            && err.ends_with("The current scene was kept."),
        "{err}"
    );
    assert_eq!(app.scene.revision(), revision);
    state.scene = persist::SceneState::Preset(persist::PresetSlug(Preset::RandomPoints));
    state.ray = Some(persist::RayState {
        origin: [persist::Coord(0.0), persist::Coord(f32::INFINITY)],
        target: [persist::Coord(1.0), persist::Coord(1.0)],
    });
    let err = state.apply(&mut app).expect_err("infinite ray");
    assert!(err.contains("ray's origin"), "{err}");
    assert_eq!(app.scene.revision(), revision);
    assert_eq!(app.preset, Preset::QuadtreeHandful);
}

/// Asserts that `fragment` is refused, and that `open_fragment` leaves the lab's scene.
fn refused_link(fragment: &str, what: &str) -> String {
    let err = from_fragment(fragment).expect_err(what);
    let mut app = LabApp::default();
    let revision = app.scene.revision();
    let message = open_fragment(&mut app, fragment).expect_err(what);
    assert!(
        message.ends_with("The current scene was kept."),
        "{what}: {message}"
    );
    assert_eq!(app.scene.revision(), revision, "{what}");
    err
}

#[test]
fn hostile_links_are_refused_with_a_message() {
    let good =
        link_fragment(&SavedState::capture(&dressed(Preset::KdHandful, 1, false))).expect("fits");
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
    let link =
        link_fragment(&SavedState::capture(&dressed(Preset::KdHandful, 1, true))).expect("fits");
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
        let mut app = LabApp::with_preset(Preset::DuplicateTriangle);
        let revision = app.scene.revision();
        match open_file(&mut app, &bytes) {
            Ok(()) => {
                opened += 1;
                // Whatever passed the checks must be a lab that works.
                for s in app.scene.shapes() {
                    Shape::new(s.kind, s.points.clone()).expect("opened shapes are valid");
                }
                app.refresh();
            }
            Err(e) => {
                refused_count += 1;
                assert!(e.ends_with("The current scene was kept."), "{e}");
                assert_eq!(app.scene.revision(), revision);
            }
        }
        // And the link, one character changed.
        let mut chars: Vec<char> = link.chars().collect();
        let i = 3 + rng.below(chars.len() - 3);
        chars[i] = ['A', 'z', '_', '-', '0', '#', '%'][rng.below(7)];
        let mutated: String = chars.into_iter().collect();
        let mut app = LabApp::default();
        if open_fragment(&mut app, &mutated).is_ok() {
            app.refresh();
        }
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
    let link = link_fragment(&SavedState::capture(&linked)).expect("fits");
    let saved_app = dressed(Preset::RandomPoints, 5, true);
    let saved = serde_json::to_string(&SavedState::capture(&saved_app)).expect("json");

    let (mut app, message) = persist::startup(Some(&link), Some("quadtree"), Some(&saved));
    assert_eq!(message, None);
    app.refresh();
    assert_same(&linked, &app, "the link wins");

    let (app, message) = persist::startup(Some("#section-2"), Some("quadtree"), Some(&saved));
    assert_eq!(message, None);
    assert_eq!(
        app.preset,
        Preset::QuadtreeHandful,
        "other fragments are not links"
    );
    assert_eq!(
        app.scene.shapes(),
        Preset::QuadtreeHandful.build().0.shapes()
    );

    let (mut app, message) = persist::startup(None, None, Some(&saved));
    assert_eq!(message, None);
    app.refresh();
    assert_same(&saved_app, &app, "the saved state");

    let (app, message) = persist::startup(None, None, None);
    assert_eq!(message, None);
    assert_eq!(app.preset, Preset::default());

    let default_shapes = LabApp::default().scene.shapes().to_vec();
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
        let (app, message) = persist::startup(fragment, preset, saved);
        let message = message.expect("a failure is said");
        assert!(message.contains(expected), "{message}");
        assert!(
            message.ends_with("The default scene is shown."),
            "{message}"
        );
        assert_eq!(app.message.as_deref(), Some(message.as_str()));
        assert_eq!(app.scene.shapes(), &default_shapes[..]);
        assert_eq!(app.preset, Preset::default());
    }
}

#[test]
fn autosave_writes_changes_at_most_every_half_second() {
    let mut app = dressed(Preset::RandomSegments, 1, false);
    let mut autosave = Autosave::default();
    let AutosaveStep::Save(first) = autosave.poll(&app, 0.0) else {
        panic!("the first poll saves");
    };
    assert_eq!(autosave.poll(&app, 0.01), AutosaveStep::Idle);
    // A write at 5.0 (the preset's view moved), then nothing for a while.
    app.view.scale = 20.0;
    assert!(matches!(autosave.poll(&app, 5.0), AutosaveStep::Save(_)));
    assert_eq!(
        autosave.poll(&app, 5.1),
        AutosaveStep::Idle,
        "nothing changed"
    );

    app.point = Some(Vec2::new(1.0, 2.0));
    app.refresh();
    let AutosaveStep::Wait(wait) = autosave.poll(&app, 5.2) else {
        panic!("a change waits for the interval since the last write");
    };
    assert!((wait - (5.5 - 5.2)).abs() < 1e-9, "{wait}");
    let AutosaveStep::Save(second) = autosave.poll(&app, 5.5) else {
        panic!("then it is written");
    };
    assert_ne!(first, second);
    let mut back = LabApp::default();
    open_file(&mut back, second.as_bytes()).expect("the saved JSON opens");
    back.refresh();
    assert_same(&app, &back, "autosaved");

    // A change undone before the write: the JSON is the same, nothing is written.
    app.k = 5;
    assert!(matches!(autosave.poll(&app, 5.6), AutosaveStep::Wait(_)));
    app.k = 3;
    assert_eq!(autosave.poll(&app, 6.2), AutosaveStep::Idle);

    // After a failed start, the default scene does not overwrite the saved state until the
    // student changes something.
    let (mut fallen_back, message) = persist::startup(Some("#s=broken"), None, Some(&second));
    assert!(message.is_some());
    let mut held = Autosave::new(Some(second.clone()));
    held.keep_current(&fallen_back);
    assert_eq!(held.poll(&fallen_back, 0.0), AutosaveStep::Idle);
    fallen_back.k = 2;
    assert!(matches!(
        held.poll(&fallen_back, 0.1),
        AutosaveStep::Save(_)
    ));

    // A lab started from the stored state does not write it again.
    let mut fresh = Autosave::new(Some(second.clone()));
    assert_eq!(fresh.poll(&app, 0.0), AutosaveStep::Idle);
    fresh.write_failed();
    app.k = 4;
    assert!(matches!(fresh.poll(&app, 1.0), AutosaveStep::Save(_)));
}

#[test]
fn a_file_dropped_on_the_window_opens_and_a_bad_one_is_refused() {
    use egui_kittest::Harness;
    use egui_kittest::kittest::Queryable as _;

    let dir = std::env::temp_dir().join(format!("bvhlab-persist-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let good = dir.join("scene.json");
    let source = dressed(Preset::KdHandful, 3, false);
    std::fs::write(&good, to_file(&source)).expect("write");
    let bad = dir.join("bad.json");
    std::fs::write(&bad, b"{\"version\": 1, \"k\": \"many\"}").expect("write");

    let mut h = Harness::builder()
        .with_size(egui::vec2(1800.0, 1800.0))
        .build_ui_state(|ui, app: &mut LabApp| app.show(ui), LabApp::default());
    h.run();
    common::drop_file(&mut h, &good);
    h.run();
    let app = h.state();
    assert_eq!(app.scene.shapes(), source.scene.shapes());
    assert_eq!(app.lane.settings, source.lane.settings);
    assert!(
        app.message
            .as_deref()
            .is_some_and(|m| m.starts_with("Opened")),
        "{:?}",
        app.message
    );

    let revision = h.state().scene.revision();
    common::drop_file(&mut h, &bad);
    h.run();
    let message = h.state().message.clone().unwrap_or_default();
    assert!(
        message.contains("invalid type") && message.ends_with("kept."),
        "{message}"
    );
    assert_eq!(h.state().scene.revision(), revision);

    // The share link appears in a field natively.
    h.get_by_label("Copy share link").click();
    h.run();
    let shown = persist::share_link_text(&h.ctx).expect("a link is shown");
    assert!(from_fragment(&shown).is_ok());
    std::fs::remove_dir_all(&dir).ok();
}
