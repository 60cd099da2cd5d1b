//! The line at the bottom: the last message (or what the tool does, or the mesh and its
//! build), the renderer and the frame rate, and the buttons that show or hide the side
//! panels (small windows and embedded labs fold them away).

use egui::RichText;

use crate::model::Dimension;
use crate::model::dimension::thousands;
use crate::model::lab3d::Lab3d;
use crate::ui_state::Cx;

/// The status line. `shared`: the controls and "Step through" share one panel as tabs (a
/// narrow window), and the buttons choose the tab.
pub fn status_line(cx: &mut Cx<'_>, ui: &mut egui::Ui, shared: bool) {
    let lab = cx.lab;
    // Two rows in a narrow window, where a message wraps; one in a wide one.
    let rows = if ui.available_width() < crate::app::NARROW {
        2
    } else {
        1
    };
    let row = ui.text_style_height(&egui::TextStyle::Body);
    // A little over: a wrapped label is a fraction of a point taller than its rows.
    ui.set_min_height(rows as f32 * row + 2.0);
    let three = lab.dimension() == Dimension::Three;
    let message = lab
        .message()
        .map(str::to_owned)
        .or_else(|| lab.three().message.clone().filter(|_| three));
    let panels = &mut cx.ui.panels;
    let clock = &cx.ui.clock;
    let renderer = &cx.ui.renderer;
    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
        if shared {
            use crate::ui_state::SideTab;
            ui.selectable_value(&mut panels.tab, SideTab::Stepper, "Step through")
                .on_hover_text("Show the \"Step through\" tab");
            ui.selectable_value(&mut panels.tab, SideTab::Controls, "Controls")
                .on_hover_text("Show the controls tab");
        } else {
            ui.toggle_value(&mut panels.stepper, "Step through")
                .on_hover_text("Show or hide the \"Step through\" panel");
            ui.toggle_value(&mut panels.controls, "Controls")
                .on_hover_text("Show or hide the controls");
        }
        if let (Some(ms), Some(fps)) = (clock.median_ms(), clock.fps()) {
            ui.label(format!("frame {ms:.1} ms ({fps:.0} fps)"));
        }
        if let Some(r) = renderer {
            ui.label(format!("{r} ·"));
        }
        // What is left, from the left: a message wraps (it must be read whole), a hint is
        // cut short. The line keeps its height whatever it says: a message appearing moved
        // the view and the tree diagram above it.
        ui.with_layout(egui::Layout::left_to_right(egui::Align::Center), |ui| {
            match message {
                Some(m) => ui.add(message_label(ui, m, rows)),
                None if three => ui.add(egui::Label::new(mesh_status(lab.three())).truncate()),
                None => ui.add(egui::Label::new(lab.two().tool.hint()).truncate()),
            };
        });
    });
}

/// A message wrapped to at most `rows` rows (the status line's height), cut with "…" past
/// them; a screen reader reads it whole (the label's text is the whole message).
fn message_label(ui: &egui::Ui, message: String, rows: usize) -> egui::Label {
    let text = RichText::new(message).color(crate::theme::message_text(ui.ctx().theme()));
    let mut job = std::sync::Arc::unwrap_or_clone(egui::WidgetText::from(text).into_layout_job(
        ui.style(),
        egui::FontSelection::Default,
        egui::Align::Center,
    ));
    job.wrap.max_rows = rows;
    job.wrap.overflow_character = Some('…');
    egui::Label::new(job).wrap()
}

/// The 3D half's status: the mesh and its build.
pub fn mesh_status(lab: &Lab3d) -> String {
    let lane = &lab.half.lane;
    match (&lab.mesh, &lane.job, lane.current(lab.revision())) {
        (None, _, _) => "Loading the mesh…".to_owned(),
        (Some(m), Some(job), _) => format!(
            "{}: building the {} ({:.0}%)",
            m.name,
            job.settings.kind.label_in(3),
            job.fraction() * 100.0
        ),
        (Some(m), None, Some(b)) => format!(
            "{}: {} triangles, {} built in {:.0} ms",
            m.name,
            thousands(m.triangle_count()),
            b.settings.kind.label_in(3),
            b.build_ms
        ),
        (Some(m), None, None) => format!("{}: no structure", m.name),
    }
}
