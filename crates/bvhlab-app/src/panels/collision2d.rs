//! The collision query of two trees in 2D: the selected shapes (A) against the others (B),
//! both built as the same kind of BVH, stepped test by test; move the selection to move A.

use bvhlab::glam::Vec2;

use crate::model::Action2d;
use crate::model::collision2d::Collision2d;
use crate::ui_state::Cx;

/// The section, under the separating-axis test.
pub(super) fn collision_section(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    ui.separator();
    let lab = cx.lab.two();
    let mut on = lab.collision.is_some();
    if ui
        .checkbox(
            &mut on,
            "Collision of two trees: the selection (A) against the other shapes (B)",
        )
        .changed()
    {
        cx.act(Action2d::SetCollision(on.then(Collision2d::default)));
    }
    let Some(collision) = lab.collision else {
        return;
    };
    let mut edited = collision;
    super::collision::tree_choice(ui, &mut edited.tree);
    match lab.collision_run().and_then(|c| c.run.as_ref()) {
        None => {
            ui.label(
                "Select some shapes (Select tool) and leave others unselected: the selection \
                 is A, the rest is B.",
            );
        }
        Some(run) => {
            move_buttons(cx, ui);
            super::collision::stepper(ui, run, &mut edited.step, "segment");
        }
    }
    if edited != collision {
        cx.act(Action2d::SetCollision(Some(edited)));
    }
}

/// Drag the selection to move A; or these buttons, a twentieth of the scene a press, for
/// the keyboard.
fn move_buttons(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let step = cx
        .lab
        .two()
        .scene
        .bounds()
        .map_or(1.0, |(lo, hi)| (hi - lo).max_element() / 20.0);
    ui.horizontal_wrapped(|ui| {
        ui.label("Drag the selection to move A, or move it:");
        for (name, delta) in [
            ("left", Vec2::new(-step, 0.0)),
            ("right", Vec2::new(step, 0.0)),
            ("up", Vec2::new(0.0, step)),
            ("down", Vec2::new(0.0, -step)),
        ] {
            if ui.button(format!("A {name}")).clicked() {
                cx.act(Action2d::MoveSelection(delta));
            }
        }
    });
}
