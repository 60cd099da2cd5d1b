//! What a person does to an element of the mirror, as the request egui's widgets answer: the
//! same AccessKit action requests a platform's screen reader sends a native app. A pressed
//! button or check box asks for a click, a focused element for the focus, a moved slider or a
//! typed number for the new value, typed text for the new text, a separator's arrow keys for
//! a step. egui turns each into the widget's own response (`clicked()`, a changed value), so
//! the lab changes through its model's actions exactly as it does for a mouse.

use egui::accesskit::{Action, ActionData, ActionRequest, NodeId, TreeId};

/// What happened to a mirrored element.
#[derive(Clone, Debug, PartialEq)]
pub enum PageEvent {
    /// It was pressed (a click, Enter or Space on a button, a screen reader's "activate").
    Press,
    /// It received the page's focus.
    Focus,
    /// A slider or number field now holds this number.
    Number(f64),
    /// A text field now holds this text.
    Text(String),
    /// A separator (a panel's edge) was moved one step, by `+1` or `-1`.
    Step(i32),
}

/// The egui input events for `event` on `node`'s element; none for a number that is not one.
/// The focus also asks egui to scroll the widget into its panel's view, so that the focus a
/// keyboard user follows is always drawn where they can see it (WCAG 2.4.11).
pub fn requests(node: NodeId, event: PageEvent) -> Vec<egui::Event> {
    let request = |action, data| {
        egui::Event::AccessKitActionRequest(ActionRequest {
            action,
            target_tree: TreeId::ROOT,
            target_node: node,
            data,
        })
    };
    match event {
        PageEvent::Press => vec![request(Action::Click, None)],
        PageEvent::Focus => vec![
            request(Action::Focus, None),
            request(Action::ScrollIntoView, None),
        ],
        PageEvent::Number(x) if x.is_finite() => {
            vec![request(Action::SetValue, Some(ActionData::NumericValue(x)))]
        }
        PageEvent::Number(_) => Vec::new(),
        PageEvent::Text(text) => vec![request(
            Action::SetValue,
            Some(ActionData::Value(text.into())),
        )],
        PageEvent::Step(s) if s > 0 => vec![request(Action::Increment, None)],
        PageEvent::Step(_) => vec![request(Action::Decrement, None)],
    }
}
