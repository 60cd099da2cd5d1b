//! What the page hears: presses, focus, new values and keys on the elements, and Tab on the
//! canvas; each goes to egui as an action request or a key press ([`crate::a11y::events`],
//! [`crate::a11y::keys`]).

use egui::accesskit::NodeId;
use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

use super::dom::FOCUSABLE;
use super::{END, INBOX, STATE, post};
use crate::a11y::events::{PageEvent, requests};
use crate::a11y::keys::{Route, Target, route};
use crate::a11y::mirror::{element_id, node_of};

/// Listens to the container (presses, focus, new values, keys) and to the canvas's Tab.
pub(super) fn listen(container: &web_sys::Element, canvas: &web_sys::HtmlCanvasElement) {
    let on = |target: &web_sys::EventTarget, name: &str, f: Box<dyn FnMut(web_sys::Event)>| {
        let closure = Closure::wrap(f);
        if target
            .add_event_listener_with_callback(name, closure.as_ref().unchecked_ref())
            .is_err()
        {
            log::warn!("the lab's element for screen readers cannot hear {name}");
        }
        // The listeners live as long as the page.
        closure.forget();
    };
    on(
        container,
        "click",
        Box::new(|event| {
            if let Some(node) = target_node(&event) {
                event.prevent_default();
                send(node, PageEvent::Press);
            }
        }),
    );
    on(
        container,
        "focusin",
        Box::new(|event| {
            if let Some(node) = target_node(&event) {
                send(node, PageEvent::Focus);
            }
        }),
    );
    on(
        container,
        "input",
        Box::new(|event| {
            let Some(node) = target_node(&event) else {
                return;
            };
            let target = event.target();
            if let Some(input) = target
                .as_ref()
                .and_then(|t| t.dyn_ref::<web_sys::HtmlInputElement>())
            {
                let value = input.value();
                let page_event = if matches!(input.type_().as_str(), "range" | "number") {
                    value.trim().parse().map(PageEvent::Number).ok()
                } else {
                    Some(PageEvent::Text(value))
                };
                if let Some(page_event) = page_event {
                    send(node, page_event);
                }
            } else if let Some(area) = target
                .as_ref()
                .and_then(|t| t.dyn_ref::<web_sys::HtmlTextAreaElement>())
            {
                send(node, PageEvent::Text(area.value()));
            }
        }),
    );
    for name in ["keydown", "keyup"] {
        on(
            container,
            name,
            Box::new(move |event| {
                if let Some(key) = event.dyn_ref::<web_sys::KeyboardEvent>() {
                    on_key(key, name == "keydown");
                }
            }),
        );
    }
    // Tab on the canvas (which has the focus after a click): into the elements, before
    // eframe's own handler sees it (which keeps Tab for egui).
    let options = web_sys::AddEventListenerOptions::new();
    options.set_capture(true);
    let closure = Closure::wrap(Box::new(|event: web_sys::Event| {
        if let Some(key) = event.dyn_ref::<web_sys::KeyboardEvent>()
            && key.key() == "Tab"
            && tab_from_canvas(key.shift_key())
        {
            event.prevent_default();
            event.stop_immediate_propagation();
        }
    }) as Box<dyn FnMut(web_sys::Event)>);
    if canvas
        .add_event_listener_with_callback_and_add_event_listener_options(
            "keydown",
            closure.as_ref().unchecked_ref(),
            &options,
        )
        .is_err()
    {
        log::warn!("Tab on the canvas stays egui's");
    }
    closure.forget();
}

/// The mirrored node an event's target (or its ancestor) stands for.
fn target_node(event: &web_sys::Event) -> Option<NodeId> {
    let target = event.target()?.dyn_into::<web_sys::Element>().ok()?;
    let element = target.closest("[id^=\"a11y-\"]").ok()??;
    node_of(&element.id())
}

/// Queues what the person did, for egui's next frame, and asks for that frame.
fn send(node: NodeId, event: PageEvent) {
    for request in requests(node, event) {
        post(request);
    }
}

/// A key on one of the elements: the browser's, the lab's, a separator's step, or leaving.
fn on_key(event: &web_sys::KeyboardEvent, down: bool) {
    let Some(element) = event
        .target()
        .and_then(|t| t.dyn_into::<web_sys::Element>().ok())
    else {
        return;
    };
    let target = Target::of(
        &element.tag_name().to_ascii_lowercase(),
        element.get_attribute("type").as_deref(),
        element.get_attribute("role").as_deref(),
    );
    let popup = INBOX.with(|i| i.borrow().popup);
    match route(target, &event.key(), popup) {
        Route::Native => {}
        Route::Step(step) => {
            if down && let Some(node) = node_of(&element.id()) {
                event.prevent_default();
                send(node, PageEvent::Step(step));
            }
        }
        Route::Leave => {
            if down {
                event.prevent_default();
                leave();
            }
        }
        Route::Lab => {
            let Some(key) = egui::Key::from_name(&event.key()) else {
                return;
            };
            event.prevent_default();
            let modifiers = egui::Modifiers {
                alt: event.alt_key(),
                ctrl: event.ctrl_key(),
                shift: event.shift_key(),
                mac_cmd: event.meta_key(),
                command: event.ctrl_key() || event.meta_key(),
            };
            post(egui::Event::Key {
                key,
                physical_key: None,
                pressed: down,
                repeat: event.repeat(),
                modifiers,
            });
            if down && event.key().chars().count() == 1 && !modifiers.command {
                post(egui::Event::Text(event.key()));
            }
        }
    }
}

/// Moves the page's focus after the lab's last element: the next Tab leaves the lab.
fn leave() {
    if let Some(end) = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.get_element_by_id(END))
        .and_then(|e| e.dyn_into::<web_sys::HtmlElement>().ok())
    {
        let _ = end.focus();
    }
}

/// Tab (or Shift+Tab) on the canvas: the focus goes to the element after (before) egui's
/// focused widget, or to the first (last) one. Whether it moved.
fn tab_from_canvas(back: bool) -> bool {
    let Some(container) = STATE.with(|s| {
        s.try_borrow()
            .ok()
            .and_then(|s| s.as_ref().map(|s| s.container.clone()))
    }) else {
        return false;
    };
    let focused = INBOX.with(|i| i.borrow().focus);
    let Ok(list) = container.query_selector_all(FOCUSABLE) else {
        return false;
    };
    let elements: Vec<web_sys::HtmlElement> = (0..list.length())
        .filter_map(|i| list.item(i))
        .filter_map(|n| n.dyn_into::<web_sys::HtmlElement>().ok())
        .collect();
    if elements.is_empty() {
        return false;
    }
    let at = focused
        .map(element_id)
        .and_then(|id| elements.iter().position(|e| e.id() == id));
    let next = match (at, back) {
        (Some(i), false) => (i + 1).min(elements.len() - 1),
        (Some(i), true) => i.saturating_sub(1),
        (None, false) => 0,
        (None, true) => elements.len() - 1,
    };
    elements[next].focus().is_ok()
}
