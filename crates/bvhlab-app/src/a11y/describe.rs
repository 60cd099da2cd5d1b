//! The drawing in words, for a person who cannot see it: the 2D canvas and the 3D view are
//! one widget each to egui, a rectangle of pixels; here each gets a role, a name and a
//! description, the summary a student can read again at any time (the scene, the structure,
//! the ray or point and its answer, the counters, the step shown and what it did, the lesson's
//! task, Predict's question: the report's text, [`Report::text`]). The screen reader finds it
//! as a described drawing (`role="application"` in the page, since its keys go to the lab: in
//! 2D, R and the arrows move the ray; in 3D, the arrows orbit, Enter casts, and R and the
//! arrows move the ray; `.` and `,` step).

use egui::accesskit::Role;

use crate::model::Dimension;
use crate::report::Report;

/// Names and describes the drawing widget `id` (shown this frame).
pub fn drawing(ctx: &egui::Context, id: egui::Id, dimension: Dimension, report: &Report) {
    let name = match dimension {
        Dimension::Two => "2D view: the scene, the structure and the query",
        Dimension::Three => "3D view: the mesh, the structure and the query",
    };
    let keys = match dimension {
        Dimension::Two => {
            "R picks the ray's start, its point or the query point, the arrow keys move it"
        }
        Dimension::Three => {
            "the arrow keys turn the camera, + and - zoom, Enter casts a ray through the middle \
             of the view or puts the query point where it meets the mesh; R picks the ray's \
             start, its point or the query point and the arrow keys move it along the \
             camera's axes, R again gives them back to the camera (the numbers are in the Ray \
             and point panel); H shows the heat map"
        }
    };
    // Only on a frame that builds the accessibility tree (the closure runs only then).
    ctx.accesskit_node_builder(id, |node| {
        let summary = report.text();
        node.set_role(Role::Canvas);
        node.set_label(name);
        node.set_description(format!(
            "{} Keys: {keys}; . and , step the query; Home and End go to its start and end.",
            summary.trim()
        ));
    });
}

/// Names a chart or diagram the lab draws (a plot, the tree diagram) and gives what it shows
/// as text, so that the numbers reach a person who cannot see the picture.
pub fn figure(ctx: &egui::Context, id: egui::Id, name: &str, description: String) {
    ctx.accesskit_node_builder(id, |node| {
        node.set_role(Role::Image);
        node.set_label(name);
        node.set_description(description);
    });
}

/// Gives a widget that shows a symbol (`|<`, `>`) or a word that means something only beside
/// its neighbours (the tree's second "SVG") a name that says what it does.
pub fn rename(response: egui::Response, name: &str) -> egui::Response {
    response
        .ctx
        .accesskit_node_builder(response.id, |node| node.set_label(name));
    response
}
