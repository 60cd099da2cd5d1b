//! The mesh that moves (the twisting torus), in the mesh panel: the "Animate" switch and the
//! motion's time, then refit or rebuild every frame, what the last update cost and the tree's
//! SAH cost against the last build's, with a plot of it over the frames
//! ([`super::refit::update_section`], shared with the 2D half).

use egui::RichText;

use crate::model::Action3d;
use crate::ui_state::Cx;

/// The motion's section, when the mesh moves.
pub fn motion_section(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let lab = cx.lab.three();
    if !lab.mesh.as_ref().is_some_and(crate::model::motion::moves) {
        return;
    }
    ui.separator();
    let motion = lab.motion;
    ui.horizontal(|ui| {
        let mut on = motion.on;
        if ui
            .checkbox(&mut on, "Animate")
            .on_hover_text("twist the torus a little more every frame")
            .changed()
        {
            cx.act(Action3d::Animate(on));
        }
        ui.label(
            RichText::new(format!(
                "t = {:.1} s, frame {}",
                motion.seconds, motion.frames
            ))
            .weak(),
        );
    });
    // Refit or rebuild, the SAH cost against the last build's, its plot and "Rebuild now":
    // the same section as the 2D half's.
    super::refit::update_section(cx, &lab.half, lab.revision(), "triangles", ui);
}
