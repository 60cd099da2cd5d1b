//! Helpers shared by the headless UI tests: the lab in a harness, and the pointer, keys
//! and widgets driven as a student drives them.
#![allow(dead_code, reason = "each test file uses its own subset")]

use bvhlab::Ray2;
use bvhlab::glam::Vec2;
use bvhlab_app::LabApp;
use egui::accesskit::Role;
use egui::epaint::Shape;
use egui::{Color32, Event, Key, Modifiers, PointerButton, Pos2, Rect, pos2, vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};

/// The counters' row names, as each structure names them (a grid visits cells; a BVH tests
/// bounding volumes, a grid or quadtree cells, a k-d or BSP tree cells and planes).
pub const COUNTER_NAMES: [&str; 6] = [
    "nodes visited",
    "cells visited",
    "BV tests",
    "cell tests",
    "cell and plane tests",
    "primitive tests",
];

/// A tall window, so that the whole control panel (down to the queries) is on screen.
pub const WINDOW: egui::Vec2 = vec2(1800.0, 1800.0);

/// The lab in a headless harness, after its first frames (the view is fitted to the scene),
/// on 200 random segments: the tests' scene (the lab itself opens on a handful of shapes,
/// which [`fresh_lab`] starts with).
pub fn lab() -> Harness<'static, LabApp> {
    let lab =
        bvhlab_app::model::Lab::with_preset(bvhlab_app::model::presets::Preset::RandomSegments);
    harness(LabApp::new(lab))
}

/// The lab as a student's first visit opens it, in a headless harness.
pub fn fresh_lab() -> Harness<'static, LabApp> {
    harness(LabApp::default())
}

fn harness(app: LabApp) -> Harness<'static, LabApp> {
    let mut h = Harness::builder()
        .with_size(WINDOW)
        .build_ui_state(|ui, app: &mut LabApp| app.show(ui), app);
    h.run();
    h
}

/// Three frames' worth of ticks on a lab without a window, so that a held playback step, a
/// 3D load and its build take effect.
pub fn tick_lab(lab: &mut bvhlab_app::model::Lab) {
    for _ in 0..3 {
        lab.apply(bvhlab_app::model::Action::Tick {
            seconds: 0.0,
            build_ms: 1e6,
        })
        .expect("a tick applies");
    }
}

/// Runs until the UI settles, then one more frame: the control panel is drawn before the
/// canvas, so a change the canvas made in the last frame shows in the panel one frame later.
pub fn settle(h: &mut Harness<'_, LabApp>) {
    h.run();
    h.step();
}

/// The texts of every label on screen, in layout order.
pub fn labels(h: &Harness<'_, LabApp>) -> Vec<String> {
    h.query_all_by_role(Role::Label)
        .filter_map(|n| n.accesskit_node().value())
        .collect()
}

/// The one label containing `part`, or a failure listing what is shown.
pub fn label_containing(h: &Harness<'_, LabApp>, part: &str) -> String {
    let all = labels(h);
    let found: Vec<&String> = all.iter().filter(|l| l.contains(part)).collect();
    assert_eq!(
        found.len(),
        1,
        "one label containing {part:?}; labels: {all:#?}"
    );
    found[0].clone()
}

/// Whether some label contains `part`.
pub fn shows(h: &Harness<'_, LabApp>, part: &str) -> bool {
    labels(h).iter().any(|l| l.contains(part))
}

/// The screen point of a world point.
pub fn screen(h: &Harness<'_, LabApp>, p: Vec2) -> Pos2 {
    h.state().canvas_screen().to_screen(p)
}

/// The world point under a screen point.
pub fn world(h: &Harness<'_, LabApp>, p: Pos2) -> Vec2 {
    h.state().canvas_screen().to_world(p)
}

/// A primary-button drag from `from` to `to`: press, eight moves (one frame each), release.
pub fn drag(h: &mut Harness<'_, LabApp>, from: Pos2, to: Pos2) {
    drag_path(h, from, &[to]);
}

/// A primary-button drag from `from` through `stops` (eight moves to each), released at the
/// last stop.
pub fn drag_path(h: &mut Harness<'_, LabApp>, from: Pos2, stops: &[Pos2]) {
    assert!(
        h.state().canvas_screen().rect.contains(from),
        "the drag starts on the canvas"
    );
    h.hover_at(from);
    h.step();
    h.drag_at(from);
    h.step();
    let mut at = from;
    for &stop in stops {
        for i in 1..=8 {
            h.hover_at(at.lerp(stop, i as f32 / 8.0));
            h.step();
        }
        at = stop;
    }
    h.drop_at(at);
    settle(h);
}

/// A primary click at `p` (press and release at one point).
pub fn click_at(h: &mut Harness<'_, LabApp>, p: Pos2) {
    h.hover_at(p);
    for pressed in [true, false] {
        h.event(Event::PointerButton {
            pos: p,
            button: PointerButton::Primary,
            pressed,
            modifiers: Modifiers::NONE,
        });
    }
    settle(h);
}

/// Clicks the widget labelled `label`.
pub fn click(h: &mut Harness<'_, LabApp>, label: &str) {
    h.get_by_label(label).click();
    settle(h);
}

/// Opens the combo box labelled `combo` and picks `option` from it.
pub fn choose(h: &mut Harness<'_, LabApp>, combo: &str, option: &str) {
    click(h, combo);
    click(h, option);
}

/// Presses a key.
pub fn press(h: &mut Harness<'_, LabApp>, key: Key) {
    h.key_press(key);
    settle(h);
}

/// Drags the default test ray across the default scene (world (0.5, 9.7) toward (20, 11.3)).
pub fn drag_test_ray(h: &mut Harness<'_, LabApp>) -> Ray2 {
    let from = screen(h, Vec2::new(0.5, 9.7));
    let to = screen(h, Vec2::new(20.0, 11.3));
    drag(h, from, to);
    let expected = Ray2::through(world(h, from), world(h, to)).expect("a proper ray");
    let handles = h.state().lab().two().ray.expect("the drag placed a ray");
    assert_eq!(
        handles.ray().expect("valid"),
        expected,
        "the ray runs from the press to the release"
    );
    expected
}

/// Counts the events of a prefix, as the lecture counts them: nodes entered (cells for a
/// grid), bounding-volume or plane tests, exact primitive tests (mailboxed ones excluded).
pub fn count<V: bvhlab::Vector>(events: &[bvhlab::Event<V>]) -> [u64; 3] {
    use bvhlab::Event;
    use bvhlab::structure::PrimitiveResult;
    let mut c = [0; 3];
    for e in events {
        match e {
            Event::EnterNode { .. } | Event::CellEnter { .. } => c[0] += 1,
            Event::RayBoundTest { .. }
            | Event::DistanceBoundTest { .. }
            | Event::PlaneCrossed { .. } => {
                c[1] += 1;
            }
            Event::PrimitiveTest { result, .. } if *result != PrimitiveResult::AlreadyTested => {
                c[2] += 1;
            }
            _ => {}
        }
    }
    c
}

/// A file on disk dropped on the window, as the native app receives one.
#[derive(Debug)]
pub struct DroppedFile(pub std::path::PathBuf);

impl egui::DroppedFile for DroppedFile {
    fn path(&self) -> &std::path::Path {
        &self.0
    }
    fn bytes(&self) -> Result<Vec<u8>, String> {
        std::fs::read(&self.0).map_err(|e| e.to_string())
    }
}

/// Applies `action` to the lab in the harness (as a panel or the page would ask for it), and
/// lets the UI settle.
pub fn act(h: &mut Harness<'_, LabApp>, action: impl Into<bvhlab_app::model::Action>) {
    let action = action.into();
    if let Err(e) = h.state_mut().apply(action.clone()) {
        panic!("{action:?} was refused: {e}");
    }
    settle(h);
}

/// Drops the file at `path` on the window (it is opened in the next frames).
pub fn drop_file(h: &mut Harness<'_, LabApp>, path: &std::path::Path) {
    h.input_mut()
        .dropped_files
        .push(std::sync::Arc::new(DroppedFile(path.to_path_buf())));
}

/// A text egui painted in the last frame.
#[derive(Clone, Debug)]
pub struct Painted {
    pub text: String,
    /// Its smallest font size, in points.
    pub size: f32,
    /// Its (first section's) colour.
    pub color: Color32,
    /// The background its format paints behind it (transparent when none).
    pub background: Color32,
    /// Where it is on screen (turned when the text is).
    pub rect: Rect,
    /// What it is clipped to.
    pub clip: Rect,
    /// The opaque filled rectangle painted last before it under its middle (its panel, its
    /// frame, a grid stripe).
    pub under: Option<Color32>,
}

/// Every text painted in the last frame, in painting order.
pub fn painted(h: &Harness<'_, LabApp>) -> Vec<Painted> {
    let mut fills: Vec<(Rect, Color32)> = Vec::new();
    let mut out = Vec::new();
    for clipped in &h.output().shapes {
        walk(&clipped.shape, clipped.clip_rect, &mut fills, &mut out);
    }
    out
}

fn walk(shape: &Shape, clip: Rect, fills: &mut Vec<(Rect, Color32)>, out: &mut Vec<Painted>) {
    match shape {
        Shape::Vec(shapes) => {
            for s in shapes {
                walk(s, clip, fills, out);
            }
        }
        Shape::Rect(r) if r.fill.a() == 255 => fills.push((r.rect.intersect(clip), r.fill)),
        Shape::Text(t) => {
            let job = &t.galley.job;
            let Some(first) = job.sections.first() else {
                return;
            };
            let size = job
                .sections
                .iter()
                .map(|s| s.format.font_id.size)
                .fold(f32::INFINITY, f32::min);
            let color =
                t.override_text_color
                    .unwrap_or(if first.format.color == Color32::PLACEHOLDER {
                        t.fallback_color
                    } else {
                        first.format.color
                    });
            let r = t.galley.rect;
            let rect = if t.angle == 0.0 {
                r.translate(t.pos.to_vec2())
            } else {
                // Turned a quarter (the plot's y axis name): x from pos across its height,
                // y upwards by its width.
                Rect::from_min_max(
                    pos2(t.pos.x, t.pos.y - r.width()),
                    pos2(t.pos.x + r.height(), t.pos.y),
                )
            };
            let under = fills
                .iter()
                .rev()
                .find(|(f, _)| f.contains(rect.center()))
                .map(|(_, c)| *c);
            out.push(Painted {
                text: job.text.clone(),
                size,
                color,
                background: first.format.background,
                rect,
                clip,
                under,
            });
        }
        _ => {}
    }
}
