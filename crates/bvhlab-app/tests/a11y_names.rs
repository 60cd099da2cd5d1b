//! Every control the lab shows has a name a screen reader can read (WCAG 4.1.2): every node of
//! egui's accessibility tree that a person can press, focus or set, in every panel, in 2D and
//! 3D, comparing, with Predict on, and at every step of every lesson.

use bvhlab_app::LabApp;
use bvhlab_app::lessons;
use bvhlab_app::model::{Action, Action3d, HalfAction, LessonAction, mesh::MeshSource};
use egui::accesskit::{Action as AkAction, Role};
use egui_kittest::Harness;
use egui_kittest::kittest::NodeT;

use crate::common;

/// The interactive nodes without a name, each as "role at (x, y)" (with what it shows, when it
/// shows something), in `h`'s tree now.
fn unnamed(h: &Harness<'_, LabApp>) -> Vec<String> {
    let mut out = Vec::new();
    let mut stack = vec![h.root()];
    while let Some(node) = stack.pop() {
        let ak = node.accesskit_node();
        let data = ak.data();
        let interactive = [AkAction::Click, AkAction::Focus, AkAction::SetValue]
            .iter()
            .any(|a| data.supports_action(*a));
        // Scroll bars are not mirrored (the focus scrolls their panel), and a label's click
        // only selects its text.
        let exempt = matches!(ak.role(), Role::ScrollBar | Role::Label | Role::TextRun);
        let named = ak.label().is_some_and(|l| !l.trim().is_empty());
        if interactive && !exempt && !named {
            let at = ak
                .bounding_box()
                .map_or_else(String::new, |b| format!(" at ({:.0}, {:.0})", b.x0, b.y0));
            out.push(format!(
                "{:?}{at}{}",
                ak.role(),
                ak.value()
                    .map_or_else(String::new, |v| format!(" showing {v:?}"))
            ));
        }
        stack.extend(node.children());
    }
    out.sort();
    out
}

/// Fails, naming the state, when some control has no name.
fn assert_named(h: &Harness<'_, LabApp>, state: &str, found: &mut Vec<String>) {
    for u in unnamed(h) {
        found.push(format!("{state}: {u}"));
    }
}

#[test]
fn every_control_in_every_panel_has_a_name() {
    let mut found = Vec::new();
    let mut h = common::fresh_lab();
    assert_named(&h, "first screen", &mut found);

    let mut settings = h.state().lab().two().half.lane.settings;
    settings.kind = bvhlab_app::model::structures::StructureKind::KdTree;
    common::act(&mut h, HalfAction::SetStructure(settings));
    common::act(&mut h, HalfAction::SetCompare(Some(settings)));
    assert_named(&h, "2D, comparing", &mut found);

    common::act(
        &mut h,
        Action::Predict(bvhlab_app::model::predict::PredictAction::On(true)),
    );
    assert_named(&h, "2D, Predict on", &mut found);

    common::act(
        &mut h,
        Action3d::OpenMesh(MeshSource::Builtin("bunny".to_owned())),
    );
    common::settle(&mut h);
    assert_named(&h, "3D, the bunny", &mut found);
    assert!(
        found.is_empty(),
        "controls without a name:\n{}",
        found.join("\n")
    );
}

#[test]
fn every_control_at_every_step_of_every_lesson_has_a_name() {
    let mut found = Vec::new();
    let mut h = common::lab();
    for lesson in lessons::lessons() {
        for step in 0..lesson.steps.len() {
            common::act(
                &mut h,
                Action::Lesson(LessonAction::Open {
                    lesson: lesson.clone(),
                    step,
                }),
            );
            assert_named(
                &h,
                &format!("lesson {}, step {}", lesson.name, step + 1),
                &mut found,
            );
        }
    }
    assert!(
        found.is_empty(),
        "controls without a name:\n{}",
        found.join("\n")
    );
}
