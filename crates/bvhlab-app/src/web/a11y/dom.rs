//! The mirror's operations applied to the page's elements, keeping the focus on an element
//! when the one that had it goes away.

use wasm_bindgen::JsCast;

use super::State;
use crate::a11y::mirror::{DomOp, element_id};

/// The elements a person can Tab to, as a selector.
pub(super) const FOCUSABLE: &str = "button, input, textarea, a[href], [tabindex=\"0\"]";

/// Applies the operations to the page. When the element with the focus goes away (a button
/// that opened a lesson, which replaced the list), the focus goes to the element of the
/// widget egui has focused, else to the first element the nearest surviving ancestor holds:
/// never to the page's body, where the next key would be lost.
pub(super) fn apply(s: &mut State, ops: &[DomOp]) {
    let Some(document) = s.container.owner_document() else {
        return;
    };
    hide_text_agent(&s.canvas);
    let active = document
        .active_element()
        .filter(|a| s.container.contains(Some(a)));
    let ancestors = active.as_ref().map(|a| ancestors_of(a, &s.container));
    for op in ops {
        match op {
            DomOp::Create { node, tag } => {
                if let Ok(e) = document.create_element(tag) {
                    e.set_id(&element_id(*node));
                    s.elements.insert(*node, e);
                }
            }
            DomOp::Set { node, name, value } => {
                if let Some(e) = s.elements.get(node) {
                    set(e, name, value);
                }
            }
            DomOp::Unset { node, name } => {
                if let Some(e) = s.elements.get(node) {
                    let _ = e.remove_attribute(name);
                }
            }
            DomOp::Text { node, text } => {
                if let Some(e) = s.elements.get(node) {
                    e.set_text_content(Some(text));
                }
            }
            DomOp::Place { node, rect } => {
                if let Some(e) = s
                    .elements
                    .get(node)
                    .and_then(|e| e.dyn_ref::<web_sys::HtmlElement>())
                {
                    let style = e.style();
                    for (name, value) in ["left", "top", "width", "height"].iter().zip(rect) {
                        let _ = style.set_property(name, &format!("{value}px"));
                    }
                }
            }
            DomOp::Children { node, children } => {
                let parent = match node {
                    Some(n) => s.elements.get(n).cloned(),
                    None => Some(s.container.clone()),
                };
                if let Some(parent) = parent {
                    place_children(&parent, children.iter().filter_map(|c| s.elements.get(c)));
                }
            }
            DomOp::Remove { node } => {
                if let Some(e) = s.elements.remove(node) {
                    e.remove();
                }
            }
            DomOp::Focus(Some(node)) => {
                // Follow egui's focus only while the person is among the elements (keyboard
                // or screen reader), never taking the focus from the canvas or the page.
                let active = document.active_element();
                let inside = active
                    .as_ref()
                    .is_some_and(|a| s.container.contains(Some(a)));
                if inside
                    && let Some(e) = s
                        .elements
                        .get(node)
                        .and_then(|e| e.dyn_ref::<web_sys::HtmlElement>())
                    && active.as_ref() != Some(e.as_ref())
                {
                    let _ = e.focus();
                }
            }
            DomOp::Focus(None) => {}
        }
    }
    if let Some(lost) = active.filter(|a| !a.is_connected()) {
        drop(lost);
        let egui_focus = s
            .mirror
            .focus()
            .and_then(|n| s.elements.get(&n))
            .filter(|e| e.is_connected())
            .cloned();
        let surviving = ancestors
            .unwrap_or_default()
            .into_iter()
            .filter(|a| a.is_connected())
            .chain(std::iter::once(s.container.clone()))
            .find_map(|a| a.query_selector(FOCUSABLE).ok().flatten());
        if let Some(e) = egui_focus
            .or(surviving)
            .and_then(|e| e.dyn_into::<web_sys::HtmlElement>().ok())
        {
            let _ = e.focus();
        }
    }
}

/// The mirrored elements around `element`, nearest first, up to `container`.
fn ancestors_of(element: &web_sys::Element, container: &web_sys::Element) -> Vec<web_sys::Element> {
    let mut out = Vec::new();
    let mut at = element.parent_element();
    while let Some(e) = at {
        if &e == container {
            break;
        }
        at = e.parent_element();
        out.push(e);
    }
    out
}

/// eframe's text agent (an `<input>` beside the canvas that takes typing while the canvas has
/// the focus) has no name and sits in the Tab order: a screen reader would meet an unnamed
/// field. The lab's own text fields are in the mirror, so it leaves the Tab order and the
/// accessibility tree (eframe still focuses it from code when an egui text field is edited
/// with the canvas focused).
fn hide_text_agent(canvas: &web_sys::HtmlCanvasElement) {
    let mut at = canvas.next_element_sibling();
    while let Some(e) = at {
        if e.tag_name().eq_ignore_ascii_case("input") && e.id().is_empty() {
            if e.get_attribute("aria-hidden").is_none() {
                let _ = e.set_attribute("aria-hidden", "true");
                let _ = e.set_attribute("tabindex", "-1");
                let _ = e.set_attribute("aria-label", "typing into the canvas");
            }
            return;
        }
        at = e.next_element_sibling();
    }
}

/// Sets an attribute; for a form field's `value` and `checked`, its live property too (the
/// attribute only says what it held first). A field being typed into keeps what it holds.
fn set(e: &web_sys::Element, name: &str, value: &str) {
    let _ = e.set_attribute(name, value);
    if name == "value" {
        let typing = e
            .owner_document()
            .and_then(|d| d.active_element())
            .is_some_and(|a| &a == e);
        if let Some(input) = e.dyn_ref::<web_sys::HtmlInputElement>() {
            if !typing || input.type_() != "text" {
                input.set_value(value);
            }
        } else if let Some(area) = e.dyn_ref::<web_sys::HtmlTextAreaElement>()
            && !typing
        {
            area.set_value(value);
        }
    }
}

/// Puts `children` under `parent`, in order, moving only the ones out of place, and takes
/// away the elements no longer among them.
fn place_children<'a>(
    parent: &web_sys::Element,
    children: impl Iterator<Item = &'a web_sys::Element>,
) {
    let mut at = parent.first_element_child();
    for child in children {
        if at.as_ref() == Some(child) {
            at = child.next_element_sibling();
            continue;
        }
        let _ = parent.insert_before(child, at.as_ref().map(AsRef::as_ref));
    }
    while let Some(extra) = at {
        at = extra.next_element_sibling();
        extra.remove();
    }
}
