//! Issue 21's reading and small-screen items, checked on what egui paints: every text at
//! least 11 points, the pseudocode's lines (and the notes under it) at WCAG AA contrast in
//! both themes, the SAH plot's axis name clear of its numbers from a node's first frame, and
//! the "Step through" panel usable at 800x500 (a lab embedded in a course page).

use crate::common;

use bvhlab::glam::Vec2;
use bvhlab::structure::SplitMethod;
use bvhlab_app::LabApp;
use bvhlab_app::model::lab2d::RayHandles;
use bvhlab_app::model::presets::Preset;
use bvhlab_app::model::{Action2d, HalfAction, Lab, PlaybackAction};
use bvhlab_app::pseudocode::Task;
use bvhlab_app::theme::{AA_CONTRAST, contrast};
use common::{Painted, act, lab, painted, settle};
use egui::accesskit::Role;
use egui::{Rect, Theme, pos2, vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};

/// The lab with the default ray across the default scene, stepped to step 4.
fn stepped(size: egui::Vec2) -> Harness<'static, LabApp> {
    let mut h = Harness::builder().with_size(size).build_ui_state(
        |ui, app: &mut LabApp| app.show(ui),
        LabApp::new(Lab::with_preset(Preset::RandomSegments)),
    );
    h.run();
    act(
        &mut h,
        Action2d::SetRay(Some(RayHandles {
            origin: Vec2::new(0.5, 9.7),
            target: Vec2::new(20.0, 11.3),
        })),
    );
    act(&mut h, PlaybackAction::GoTo(4));
    h
}

/// Whether `text` is a line of the pseudocode listing ("12  ..." or "12> ...").
fn is_code_line(text: &str) -> bool {
    let b = text.as_bytes();
    b.len() > 4
        && b[..2].iter().all(|c| c.is_ascii_digit() || *c == b' ')
        && b[1].is_ascii_digit()
        && (b[2] == b' ' || b[2] == b'>')
        && b[3] == b' '
}

#[test]
fn every_text_is_11_points_or_more_and_the_listing_is_aa_in_both_themes() {
    let mut h = stepped(common::WINDOW);
    for theme in [Theme::Dark, Theme::Light] {
        h.ctx.set_theme(theme);
        settle(&mut h);
        let texts = painted(&h);
        let small: Vec<(&str, f32)> = texts
            .iter()
            .filter(|t| t.size < 11.0 && !t.text.trim().is_empty())
            .map(|t| (t.text.as_str(), t.size))
            .collect();
        assert!(
            small.is_empty(),
            "{theme:?}: text under 11 points: {small:?}"
        );

        let code: Vec<&Painted> = texts.iter().filter(|t| is_code_line(&t.text)).collect();
        assert!(
            code.len() >= 10,
            "{theme:?}: the listing is shown: {code:#?}"
        );
        assert!(
            code.iter().any(|t| t.text.as_bytes()[2] == b'>'),
            "{theme:?}: a current line"
        );
        for line in &code {
            let behind = if line.background.a() > 0 {
                line.background
            } else {
                line.under.expect("the listing's frame is under its lines")
            };
            let ratio = contrast(line.color, behind);
            assert!(
                ratio >= AA_CONTRAST,
                "{theme:?}: {:?} is {:?} on {behind:?}: {ratio:.2}:1",
                line.text,
                line.color
            );
        }
        // The note under the listing (the slides' version, explained).
        let note = texts
            .iter()
            .find(|t| t.text.starts_with("The slides' intersect"))
            .expect("the note under the listing");
        let behind = note.under.expect("the panel is under the note");
        let ratio = contrast(note.color, behind);
        assert!(
            ratio >= AA_CONTRAST && note.size >= 11.0,
            "{theme:?}: the note is {:.0} points at {ratio:.2}:1",
            note.size
        );
    }
}

/// The screen rect of the one label reading exactly `text` right of `middle` (the "Step
/// through" panel; the controls have counters of their own).
fn label_rect(h: &Harness<'_, LabApp>, text: &str, middle: f32) -> Rect {
    let found: Vec<Rect> = h
        .query_all_by_role(Role::Label)
        // A narrow panel stacks a header's or a counter's words on two lines.
        .filter(|n| {
            n.accesskit_node()
                .value()
                .is_some_and(|v| v.replace('\n', " ") == text)
        })
        .map(|n| n.rect())
        .filter(|r| r.min.x > middle)
        .collect();
    assert_eq!(found.len(), 1, "one label {text:?} in the panel: {found:?}");
    found[0]
}

#[test]
fn at_800_by_500_the_step_its_counters_and_the_brute_force_column_are_in_view_together() {
    let mut h = stepped(vec2(800.0, 500.0));
    // The view keeps most of the width: the controls and "Step through" share one panel,
    // as tabs (side by side they left the view a third, and once 70 px).
    let view = h.state().canvas_screen().rect;
    assert!(
        view.width() >= 800.0 / 2.0,
        "the view is {} px wide at 800x500",
        view.width()
    );
    // ...and half of its height: the tree diagram below it starts at a third.
    assert!(
        view.height() >= 250.0,
        "the view is {} px tall at 800x500",
        view.height()
    );
    // The "Step through" tab, chosen on the status line.
    let tab = h
        .get_all_by_label("Step through")
        .max_by(|a, b| a.rect().min.y.total_cmp(&b.rect().min.y))
        .expect("the status line's tab")
        .rect();
    common::click_at(&mut h, tab.center());
    let view = h.state().canvas_screen().rect;
    // The panel's view ends where the status line (with its "Controls" tab) starts.
    let status = h
        .get_all_by_label("Controls")
        .map(|n| n.rect())
        .max_by(|a, b| a.min.y.total_cmp(&b.min.y))
        .expect("the status line's Controls tab");
    let visible = Rect::from_min_max(pos2(0.0, 0.0), pos2(view.left(), status.min.y));
    let step = h
        .query_all_by_role(Role::Label)
        .find(|n| {
            n.accesskit_node()
                .value()
                .is_some_and(|v| v.starts_with("step 4: "))
        })
        .expect("the step's sentence")
        .rect();
    let brute = label_rect(&h, "brute force", -1.0);
    let last_row = label_rect(&h, "primitive tests", -1.0);
    // Nothing of the panel spills right over the view (a row wider than the panel pushed
    // its contents out).
    for text in painted(&h) {
        if text.rect.center().x < view.left() && text.rect.center().y < status.min.y {
            assert!(
                text.rect.max.x <= view.left() + 1.0 || !text.clip.intersects(view),
                "{:?} at {:?} reaches over the view (it starts at {})",
                text.text,
                text.rect,
                view.left()
            );
        }
    }
    for (what, r) in [
        ("the step", step),
        ("brute force", brute),
        ("the last counter", last_row),
    ] {
        assert!(
            visible.contains_rect(r),
            "{what} at {r:?} is outside the panel's view {visible:?}"
        );
    }
    // The counters' numbers are in view too: the brute force column's 200 primitive tests.
    let texts = painted(&h);
    let count = texts
        .iter()
        .find(|t| t.text == "200" && (t.rect.center().y - last_row.center().y).abs() < 4.0)
        .expect("brute force's count of primitive tests");
    assert!(
        count.clip.contains_rect(count.rect) && visible.contains_rect(count.rect),
        "brute force's 200 at {:?} is cut by {:?}",
        count.rect,
        count.clip
    );
}

/// The first step at or after `from` whose current node has an SAH cost curve, other than
/// `not`'s node.
fn curve_step(h: &mut Harness<'_, LabApp>, from: usize, not: Option<u32>) -> (usize, u32) {
    let steps = h.state().lab().two().half.steps();
    for s in from..=steps {
        h.state_mut()
            .apply(PlaybackAction::GoTo(s))
            .expect("a step");
        let half = &h.state().lab().two().half;
        let rec = half.lane.recorded().expect("recorded");
        let Some(node) = half.lane.snapshot.as_ref().and_then(|snap| snap.current) else {
            continue;
        };
        let curve = rec
            .splits
            .iter()
            .any(|r| r.node == node && r.bin_costs.len() > 1);
        if curve && Some(node.0) != not {
            return (s, node.0);
        }
    }
    panic!("no node with a cost curve after step {from}");
}

#[test]
fn the_sah_plots_axis_names_clear_its_numbers_from_a_nodes_first_frame() {
    let mut h = lab();
    let mut settings = h.state().lab().two().half.lane.settings;
    settings.bvh_split = SplitMethod::BinnedSah;
    act(&mut h, HalfAction::SetStructure(settings));
    act(&mut h, HalfAction::SetTask(Task::Build));
    let (first, node) = curve_step(&mut h, 1, None);
    settle(&mut h);
    // Another node: one frame only, as a browser draws after a click on ">".
    let (second, _) = curve_step(&mut h, first + 1, Some(node));
    assert!(second > first);
    h.step();
    let texts = painted(&h);
    let numbers: Vec<&Painted> = texts
        .iter()
        .filter(|t| t.text.trim().parse::<f64>().is_ok())
        .collect();
    let names: Vec<&Painted> = texts
        .iter()
        .filter(|t| t.text.contains("cost") && t.rect.height() > t.rect.width())
        .chain(
            texts
                .iter()
                .filter(|t| t.text.starts_with("plane position")),
        )
        .collect();
    assert_eq!(names.len(), 2, "the plot's two axis names: {names:#?}");
    // The plot lies right of the y axis's name, above the bottom of the x axis's.
    let (y_name, x_name) = (names[0].rect, names[1].rect);
    let ticks: Vec<&&Painted> = numbers
        .iter()
        .filter(|n| {
            n.rect.min.x >= y_name.min.x - 1.0
                && n.rect.max.y <= x_name.max.y + 1.0
                && n.rect.min.y >= y_name.center().y - 150.0
        })
        .collect();
    assert!(ticks.len() >= 3, "the plot's numbers: {ticks:#?}");
    for name in &names {
        for n in &ticks {
            let both = name.rect.intersect(n.rect);
            assert!(
                both.width() <= 0.5 || both.height() <= 0.5,
                "{:?} at {:?} overlaps {:?} at {:?}",
                name.text,
                name.rect,
                n.text,
                n.rect
            );
        }
    }
    for n in &ticks {
        assert!(
            n.clip.expand(0.5).contains_rect(n.rect),
            "{:?} at {:?} is clipped by {:?}",
            n.text,
            n.rect,
            n.clip
        );
    }
}

/// WCAG 2.1's 1.4.11 (non-text contrast): the focus egui draws on a widget (its "active"
/// outline, which the page's mirror turns on for the widget whose element has the focus) at
/// 3:1 or more against the panel behind it, in both themes, as the lab installs them.
#[test]
fn the_focus_outline_is_3_to_1_on_the_panels_in_both_themes() {
    let ctx = egui::Context::default();
    bvhlab_app::theme::install(&ctx);
    for theme in [Theme::Dark, Theme::Light] {
        let visuals = ctx.style_of(theme).visuals.clone();
        let ring = visuals.widgets.active.bg_stroke;
        assert!(
            ring.width >= 1.0,
            "{theme:?}: the focus outline is {} points wide",
            ring.width
        );
        for behind in [visuals.panel_fill, visuals.window_fill] {
            let ratio = contrast(ring.color, behind);
            assert!(
                ratio >= 3.0,
                "{theme:?}: the focus outline {:?} is {ratio:.2}:1 on {behind:?}",
                ring.color
            );
        }
    }
}

/// A 1280x720 laptop at 200% browser zoom is a 640x360 window to the lab (WCAG 1.4.4): the
/// view keeps room to work in beside the panels (half the width, a third of the height),
/// and the controls still show (the tab row and a lesson button).
#[test]
fn at_200_percent_zoom_on_a_laptop_the_view_and_the_controls_both_keep_room() {
    let h = stepped(vec2(640.0, 360.0));
    let view = h.state().canvas_screen().rect;
    assert!(
        view.width() >= 640.0 * 0.45 && view.height() >= 360.0 / 3.0,
        "the view is {}x{} at 640x360",
        view.width(),
        view.height()
    );
    let tab = h.get_by_label("Lessons and controls").rect();
    assert!(
        tab.max.x <= view.min.x + 1.0,
        "the tabs sit beside the view"
    );
}
