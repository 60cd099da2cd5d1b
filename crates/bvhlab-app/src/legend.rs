//! The view's legend: what its colours mean, in a strip above the view, never over it
//! (drawn in the view's corner it hid the second view's ray origin, cut a view's title, and
//! covered a third of an embedded lab's canvas). Each entry is a swatch and its word (the
//! word says it without the colour); screen readers read the words as one label. Seven
//! entries take one row at 800 points; the 2D half's bounding volumes may add a second.

use egui::{Color32, RichText};

use crate::model::Dimension;
use crate::paint::colors;
use crate::ui_state::Cx;

/// The marks of a query or build, in both halves; `tested` names what a primitive test is
/// of ("tested segment", "tested triangle").
fn marks(tested: &'static str) -> [(Color32, &'static str); 7] {
    [
        (colors::VISITED, "visited"),
        (colors::CULLED, "culled"),
        (colors::PRUNED, "pruned"),
        (colors::WAITING, "waiting"),
        (colors::CURRENT, "current"),
        (colors::TESTED, tested),
        (colors::ANSWER, "answer"),
    ]
}

/// The entries for the half shown: the marks, then (2D) the split planes, the bounding
/// volumes drawn (and in 3D the brush and the slabs), then what Predict asks about.
pub fn entries(cx: &Cx<'_>) -> Vec<(Color32, &'static str)> {
    let mut all = match cx.lab.dimension() {
        Dimension::Two => {
            let mut all = marks("tested segment").to_vec();
            all.extend(crate::lab2d::legend_volumes(cx.lab.two()));
            if cx
                .lab
                .two()
                .collision_run()
                .is_some_and(|c| c.run.is_some())
            {
                all.extend([
                    (colors::VISITED, "node pair overlaps"),
                    (colors::CULLED, "node pair disjoint"),
                    (colors::ANSWER, "segments meeting"),
                ]);
            }
            all
        }
        Dimension::Three => {
            let mut all = marks("tested triangle").to_vec();
            all.extend(crate::lab3d::volumes::legend(cx.lab.three()));
            all.extend(crate::lab3d::sat::legend(cx.lab.three()));
            all.extend(crate::lab3d::collision::legend(cx.lab.three()));
            all
        }
    };
    // What Predict's question is about is lit while it waits.
    if !cx.lab.predict_about().is_empty() {
        all.push((colors::ASKED, "asked about"));
    }
    all
}

/// The strip, at the top of `ui` (the view's area), across its width; the view takes the
/// rest. Its rect goes to [`crate::ui_state::UiState::legend_rect`].
pub fn strip(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let entries = entries(cx);
    let rect = egui::Frame::NONE
        .fill(Color32::from_gray(30))
        .inner_margin(egui::Margin::symmetric(8, 1))
        .show(ui, |ui| {
            ui.set_width(ui.available_width());
            ui.horizontal_wrapped(|ui| {
                ui.spacing_mut().item_spacing = egui::vec2(10.0, 1.0);
                for &(color, word) in &entries {
                    entry(ui, color, word);
                }
            });
        })
        .response
        .rect;
    // One label for screen readers, the words in the strip's order (its squares are
    // drawn, not widgets).
    let words: Vec<&str> = entries.iter().map(|(_, w)| *w).collect();
    let text = format!("Colours on the view: {}", words.join(", "));
    ui.interact(rect, ui.make_persistent_id("legend"), egui::Sense::hover())
        .widget_info(|| egui::WidgetInfo::labeled(egui::Role::Label, true, &text));
    cx.ui.legend_rect = Some(rect);
}

/// One entry: a square of `color`, then `word`, as one item (they wrap to a new row
/// together).
fn entry(ui: &mut egui::Ui, color: Color32, word: &str) {
    let galley = egui::WidgetText::from(RichText::new(word).small()).into_galley(
        ui,
        Some(egui::TextWrapMode::Extend),
        f32::INFINITY,
        egui::TextStyle::Small,
    );
    let size = egui::vec2(SQUARE + GAP + galley.size().x, galley.size().y.max(SQUARE));
    let (_, rect) = ui.allocate_space(size);
    let square = egui::Rect::from_center_size(
        egui::pos2(rect.min.x + SQUARE / 2.0, rect.center().y),
        egui::vec2(SQUARE, SQUARE),
    );
    if color == colors::SPLIT {
        // The split planes' entry is drawn as they are: a dashed line.
        ui.painter().extend(egui::Shape::dashed_line(
            &[square.left_center(), square.right_center()],
            egui::Stroke::new(2.0, color),
            3.0,
            2.0,
        ));
    } else {
        ui.painter().rect_filled(square, 2.0, color);
    }
    let at = egui::pos2(square.max.x + GAP, rect.center().y - galley.size().y / 2.0);
    ui.painter().galley(at, galley, Color32::LIGHT_GRAY);
}

/// An entry's square, in points.
const SQUARE: f32 = 10.0;
/// Between the square and its word.
const GAP: f32 = 4.0;
