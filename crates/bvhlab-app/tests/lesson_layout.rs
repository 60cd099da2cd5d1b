//! Issue 29's layout items, for every step of every lesson at 1280x720 (a laptop) and 800x500
//! (a lab embedded in a course page): the legend never covers what it explains (the ray's
//! handles, the compared views' titles; it sits outside the view), no text is cut at a
//! panel's right edge (a wide table scrolls, with a bar in view), with Predict on the
//! question is on screen with the lesson's text, and closing the lesson or moving the ray
//! moves nothing below the lesson.

use crate::common;

use bvhlab_app::LabApp;
use bvhlab_app::lessons;
use bvhlab_app::model::predict::PredictAction;
use std::sync::Arc;

use bvhlab_app::model::{Action, Dimension, Lab, Lesson, LessonAction, PlaybackAction};
use common::{act, painted, settle};
use egui::accesskit::Role;
use egui::{Rect, Vec2, vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};

/// The window sizes the review walked at.
const SIZES: [Vec2; 2] = [vec2(1280.0, 720.0), vec2(800.0, 500.0)];

/// The legend's words.
const LEGEND: [&str; 8] = [
    "visited",
    "culled",
    "pruned",
    "waiting",
    "current",
    "tested segment",
    "tested triangle",
    "answer",
];

/// The lab in a window of `size`, as a student's first visit opens it.
fn lab_at(size: Vec2) -> Harness<'static, LabApp> {
    let mut h = Harness::builder().with_size(size).build_ui_state(
        |ui, app: &mut LabApp| app.show(ui),
        LabApp::new(Lab::default()),
    );
    h.run();
    h
}

/// Every lesson's every step: (lesson, step, a name for messages).
fn steps() -> Vec<(Arc<Lesson>, usize, String)> {
    lessons::lessons()
        .flat_map(|lesson| {
            (0..lesson.steps.len()).map(move |s| {
                let name = format!("{} step {}", lesson.name, s + 1);
                (lesson.clone(), s, name)
            })
        })
        .collect()
}

/// Opens `step` of `lesson`, and lets a 3D build finish.
fn open(h: &mut Harness<'static, LabApp>, lesson: &Arc<Lesson>, step: usize) {
    act(
        h,
        Action::Lesson(LessonAction::Open {
            lesson: lesson.clone(),
            step,
        }),
    );
    for _ in 0..3 {
        act(
            h,
            Action::Tick {
                seconds: 0.0,
                build_ms: 1e6,
            },
        );
    }
}

/// The view's area: the 2D canvas, or the 3D view.
fn view(h: &Harness<'_, LabApp>) -> Rect {
    match h.state().lab().dimension() {
        Dimension::Two => h.state().ui.canvas.rect,
        Dimension::Three => h.state().ui.view3d.rect,
    }
}

/// The top of the status line (its "Controls" tab).
fn status_top(h: &Harness<'_, LabApp>) -> f32 {
    h.get_all_by_label("Controls")
        .map(|n| n.rect().min.y)
        .fold(f32::NEG_INFINITY, f32::max)
}

#[test]
fn the_legend_never_covers_the_view_it_explains() {
    for size in SIZES {
        let mut h = lab_at(size);
        for (lesson, step, name) in steps() {
            open(&mut h, &lesson, step);
            let view = view(&h);
            let texts = painted(&h);
            let legend: Vec<Rect> = texts
                .iter()
                .filter(|t| LEGEND.contains(&t.text.as_str()) && t.rect.min.x >= view.min.x - 1.0)
                .map(|t| t.rect.expand2(vec2(16.0, 2.0)))
                .collect();
            assert!(legend.len() >= 7, "{name} at {size:?}: the legend is shown");
            // What it explains: the view, the ray's and the point's handles in each half, and
            // the compared views' titles.
            let mut covered: Vec<(String, Rect)> = vec![("the view".to_owned(), view)];
            let lab = h.state().lab();
            if lab.dimension() == Dimension::Two {
                let two = lab.two();
                let split = two.half.compare.is_some();
                for (i, half) in bvhlab_app::lab2d::halves(view, split)
                    .into_iter()
                    .enumerate()
                {
                    let screen = bvhlab_app::lab2d::Screen {
                        camera: two.camera,
                        rect: half,
                    };
                    let mut handles = Vec::new();
                    if let Some(ray) = two.ray {
                        handles.extend([("ray origin", ray.origin), ("ray target", ray.target)]);
                    }
                    if let Some(point) = two.point {
                        handles.push(("query point", point));
                    }
                    for (what, at) in handles {
                        let at = screen.to_screen(at);
                        if half.contains(at) {
                            let r = Rect::from_center_size(at, vec2(14.0, 14.0));
                            covered.push((format!("{what} in view {i}"), r));
                        }
                    }
                    if split {
                        let title = two.half.lane_name(i);
                        for t in texts.iter().filter(|t| t.text == title) {
                            covered.push((format!("the title {title:?}"), t.rect));
                        }
                    }
                }
            }
            for entry in &legend {
                for (what, r) in &covered {
                    assert!(
                        !entry.intersects(*r),
                        "{name} at {size:?}: the legend at {entry:?} covers {what} at {r:?}"
                    );
                }
            }
        }
    }
}

/// The horizontal scroll bars on screen.
fn horizontal_bars(h: &Harness<'_, LabApp>) -> Vec<Rect> {
    h.query_all_by_role(Role::ScrollBar)
        .map(|n| n.rect())
        .filter(|r| r.width() > r.height())
        .collect()
}

/// Checks that no text of the side panel (left of `view`) is cut at its right edge, unless
/// it scrolls sideways with a bar in view under it.
fn nothing_cut(h: &Harness<'_, LabApp>, view: Rect, what: &str) {
    let bars = horizontal_bars(h);
    // egui's floating bars are drawn only under the pointer: no sign that more is there.
    let shown = h
        .ctx
        .style_of(h.ctx.theme())
        .spacing
        .scroll
        .dormant_handle_opacity
        > 0.0;
    for t in painted(h) {
        let seen = t.rect.intersect(t.clip);
        let in_panel = t.clip.max.x <= view.min.x + 1.0;
        if !in_panel || seen.height() <= 1.0 || seen.width() <= 1.0 || t.text.trim().is_empty() {
            continue;
        }
        if t.rect.max.x <= t.clip.max.x + 0.5 {
            continue;
        }
        let scrolls = shown
            && bars.iter().any(|b| {
                b.min.x <= t.clip.min.x + 12.0
                    && b.max.x >= t.clip.max.x - 12.0
                    && b.center().y >= t.rect.min.y - 14.0
                    && b.center().y <= t.clip.max.y + 14.0
            });
        assert!(
            scrolls,
            "{what}: {:?} at {:?} is cut at {} (its clip {:?}); bars: {bars:?}, shown: {shown}",
            t.text, t.rect, t.clip.max.x, t.clip
        );
    }
}

#[test]
fn no_text_is_cut_at_a_panels_right_edge() {
    use bvhlab_app::ui_state::SideTab;
    for size in SIZES {
        let mut h = lab_at(size);
        for (lesson, step, name) in steps() {
            open(&mut h, &lesson, step);
            for tab in [SideTab::Controls, SideTab::Stepper] {
                h.state_mut().ui.panels.tab = tab;
                settle(&mut h);
                let view = view(&h);
                nothing_cut(&h, view, &format!("{name} at {size:?}, {tab:?}"));
            }
            h.state_mut().ui.panels.tab = SideTab::Controls;
        }
    }
}

/// The one label reading `text` (its first, when the text shows twice).
fn label_rect(h: &Harness<'_, LabApp>, text: &str) -> Option<Rect> {
    h.query_all_by_role(Role::Label)
        .find(|n| n.accesskit_node().value().is_some_and(|v| v == text))
        .map(|n| n.rect())
}

#[test]
fn with_predict_on_the_question_shows_with_the_lessons_text() {
    let mut checked = 0;
    for size in SIZES {
        let mut h = lab_at(size);
        for (lesson, step, name) in steps() {
            open(&mut h, &lesson, step);
            act(&mut h, PredictAction::On(true));
            // Step on to the first question, if the recording has one.
            for _ in 0..h.state().lab().steps() {
                if h.state().lab().predict_question().is_some() {
                    break;
                }
                act(&mut h, PlaybackAction::StepBy(1));
            }
            let Some(question) = h.state().lab().predict_question() else {
                act(&mut h, PredictAction::On(false));
                continue;
            };
            let view = view(&h);
            let screen =
                Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(view.min.x, status_top(&h)));
            let text = &lesson.steps[step].text;
            let text_rect = label_rect(&h, text)
                .unwrap_or_else(|| panic!("{name} at {size:?}: the lesson's text is shown"));
            assert!(
                screen.contains(text_rect.left_top()),
                "{name} at {size:?}: the lesson's text at {text_rect:?} is off {screen:?}"
            );
            let prompt = label_rect(&h, &question.prompt).unwrap_or_else(|| {
                panic!(
                    "{name} at {size:?}: the question {:?} is not on the lesson's screen",
                    question.prompt
                )
            });
            let first = &question.choices[0].1;
            let button = h
                .query_all_by_role(Role::Button)
                .find(|n| {
                    n.accesskit_node()
                        .label()
                        .is_some_and(|l| l.ends_with(first.as_str()))
                })
                .map_or_else(
                    || panic!("{name} at {size:?}: the answer {first:?}"),
                    |n| n.rect(),
                );
            for (what, r) in [("the question", prompt), ("its first answer", button)] {
                assert!(
                    screen.contains_rect(r),
                    "{name} at {size:?}: {what} at {r:?} is off {screen:?}"
                );
            }
            checked += 1;
            act(&mut h, PredictAction::On(false));
        }
    }
    assert!(checked >= 4, "questions checked: {checked}");
}

/// The rects of the controls below the lesson: the 2D / 3D switch and, in 2D, "Reload
/// preset" and "Undo".
fn below(h: &Harness<'_, LabApp>) -> Vec<(String, Rect)> {
    let mut out = Vec::new();
    for label in ["2D: segments", "3D: meshes", "Reload preset", "Undo"] {
        if let Some(n) = h.query_by_label(label) {
            out.push((label.to_owned(), n.rect()));
        }
    }
    out
}

#[test]
fn closing_a_lesson_or_moving_its_ray_moves_nothing_below_it() {
    for size in SIZES {
        let mut h = lab_at(size);
        for (lesson, step, name) in steps() {
            open(&mut h, &lesson, step);
            let before = below(&h);
            assert!(before.len() >= 2, "{name} at {size:?}: {before:?}");
            // The ray moved (a field typed in, a drag): the goals' marks change.
            if let Some(mut ray) = h.state().lab().two().ray
                && h.state().lab().dimension() == Dimension::Two
            {
                ray.target += bvhlab::glam::Vec2::new(0.0, 3.0);
                act(&mut h, bvhlab_app::model::Action2d::SetRay(Some(ray)));
                assert_eq!(
                    below(&h),
                    before,
                    "{name} at {size:?}: after moving the ray"
                );
            }
            h.get_by_label("Close").click();
            settle(&mut h);
            assert!(h.state().lab().lesson().is_none(), "{name}: closed");
            assert_eq!(below(&h), before, "{name} at {size:?}: after Close");
        }
    }
}

#[test]
fn a_message_on_the_status_line_moves_nothing_above_it() {
    for size in SIZES {
        let mut h = lab_at(size);
        let before = (view(&h), h.state().ui.tree_rect);
        act(
            &mut h,
            Action::SetMessage(Some(
                "Predict is on: before each step that decides something, say what happens \
                 next; the lab then shows the step and says whether you were right."
                    .to_owned(),
            )),
        );
        let after = (view(&h), h.state().ui.tree_rect);
        assert!(before.1.is_some(), "the tree diagram is shown");
        assert_eq!(after, before, "at {size:?}: the view and the tree diagram");
    }
}
