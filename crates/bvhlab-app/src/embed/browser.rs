//! The browser's side of embedding: the `message` listener that takes commands from the
//! course page (checking the sender's origin), the replies, the `ready` announcement, and the
//! panic hook that tells the page the lab stopped (`web/main.js` then shows what happened and
//! offers a reload with the last saved state).

use std::cell::RefCell;
use std::rc::Rc;

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

use super::Scripting;

/// Where a reply goes: the window that sent the command, and its origin (the reply's
/// `targetOrigin`, so that nobody else can read it).
pub struct ReplyTo {
    source: web_sys::Window,
    origin: String,
}

/// The origins allowed to script the lab (its own and those the address names), and what
/// it knows of its parent's origin ([`super::target`]).
#[derive(Clone)]
pub struct Origins(std::sync::Arc<Known>);

struct Known {
    /// The lab's own origin, then those the address names.
    allowed: Vec<String>,
    /// The parent's origin as the browser tells it (`location.ancestorOrigins[0]`).
    ancestor: Option<String>,
    /// The origin of the first command from the parent window.
    first_command: std::sync::OnceLock<String>,
}

impl Origins {
    /// The page's own origin and `extra`.
    pub fn new(extra: &[String]) -> Self {
        let location = web_sys::window().map(|w| w.location());
        let own = location
            .as_ref()
            .and_then(|l| l.origin().ok())
            .unwrap_or_default();
        // `location.ancestorOrigins` (a DOMStringList; Firefox has none), read by name:
        // web-sys does not bind it.
        let ancestor = location
            .and_then(|l| js_sys::Reflect::get(&l, &"ancestorOrigins".into()).ok())
            .filter(|list| !list.is_undefined() && !list.is_null())
            .and_then(|list| js_sys::Reflect::get(&list, &0.into()).ok())
            .and_then(|first| first.as_string());
        let mut allowed = vec![own];
        allowed.extend(extra.iter().cloned());
        Self(std::sync::Arc::new(Known {
            allowed,
            ancestor,
            first_command: std::sync::OnceLock::new(),
        }))
    }

    fn allows(&self, origin: &str) -> bool {
        self.0.allowed.iter().any(|o| o == origin)
    }

    /// Where a message to the parent goes ([`super::target::ParentOrigin::targets`]).
    fn parent_targets(&self) -> Vec<String> {
        let known = &self.0;
        super::target::ParentOrigin {
            own: &known.allowed[0],
            named: &known.allowed[1..],
            first_command: known.first_command.get().map(String::as_str),
            ancestor: known.ancestor.as_deref(),
        }
        .targets()
    }
}

/// The commands received, shared between the listener and the lab.
pub type Inbox = Rc<RefCell<Scripting<ReplyTo>>>;

/// Listens for the page's commands; they wait in `inbox` for the lab's next frame.
pub fn listen(inbox: Inbox, origins: Origins, ctx: egui::Context) {
    let Some(window) = web_sys::window() else {
        return;
    };
    let warned = RefCell::new(false);
    let on_message = Closure::<dyn FnMut(web_sys::MessageEvent)>::new(
        move |event: web_sys::MessageEvent| {
            let data = event.data();
            let kind = js_sys::Reflect::get(&data, &"bvhlab".into()).ok();
            if kind.and_then(|k| k.as_string()).as_deref() != Some("command") {
                return; // Someone else's message (other scripts use postMessage too).
            }
            let origin = event.origin();
            if !origins.allows(&origin) {
                if !warned.replace(true) {
                    log::warn!(
                        "a command from {origin} was ignored: add origin={origin} to the lab's address to allow it"
                    );
                }
                return;
            }
            // Unchecked: the sender is a window of another realm (the parent page), which is not
            // an `instanceof` this realm's `Window`.
            let Some(source) = event
                .source()
                .map(JsCast::unchecked_into::<web_sys::Window>)
            else {
                return;
            };
            // The parent's first command tells its origin: the lab's own messages go there.
            if web_sys::window()
                .and_then(|w| w.parent().ok().flatten())
                .is_some_and(|parent| parent == source)
            {
                origins.0.first_command.get_or_init(|| origin.clone());
            }
            let id = js_sys::Reflect::get(&data, &"id".into())
                .ok()
                .and_then(|id| js_sys::JSON::stringify(&id).ok())
                .and_then(|text| text.as_string())
                .unwrap_or_else(|| "null".to_owned());
            let command = js_sys::Reflect::get(&data, &"command".into())
                .ok()
                .and_then(|c| js_sys::JSON::stringify(&c).ok())
                .and_then(|text| text.as_string())
                .unwrap_or_default();
            inbox
                .borrow_mut()
                .receive(ReplyTo { source, origin }, &id, &command);
            ctx.request_repaint();
        },
    );
    if window
        .add_event_listener_with_callback("message", on_message.as_ref().unchecked_ref())
        .is_err()
    {
        log::warn!("the lab cannot be scripted by its page");
    }
    // The listener lives as long as the page.
    on_message.forget();
}

/// Sends a reply's JSON to where its command came from.
pub fn send(reply_to: &ReplyTo, json: &str) {
    let Ok(message) = js_sys::JSON::parse(json) else {
        return;
    };
    if reply_to
        .source
        .post_message(&message, &reply_to.origin)
        .is_err()
    {
        log::warn!("a reply to {} could not be sent", reply_to.origin);
    }
}

/// Tells the embedding page, if there is one, a message of the lab's own (`{bvhlab:
/// "ready"}`, progress, size, panic): posted to the parent's origin once known, else to each
/// allowed origin (the browser delivers it only to a parent of that origin).
pub fn announce(origins: &Origins, message: &str) {
    let Some(window) = web_sys::window() else {
        return;
    };
    let Ok(Some(parent)) = window.parent() else {
        return;
    };
    if parent == window {
        return;
    }
    let Ok(message) = js_sys::JSON::parse(message) else {
        return;
    };
    for origin in origins.parent_targets() {
        // A parent of another origin does not receive it; that is not an error.
        parent.post_message(&message, &origin).ok();
    }
}

/// Chains a panic hook after eframe's: it calls the page's `bvhlabPanicked(message,
/// storageKey)` (see `web/main.js`) and tells an embedding page `{bvhlab: "panic", message}`.
pub fn on_panic_tell_page(storage_key: String, origins: Origins) {
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        previous(info);
        let message = info.to_string();
        if let Some(window) = web_sys::window() {
            let handler = js_sys::Reflect::get(&window, &"bvhlabPanicked".into())
                .ok()
                .and_then(|f| f.dyn_into::<js_sys::Function>().ok());
            if let Some(handler) = handler {
                handler
                    .call2(
                        &JsValue::NULL,
                        &message.clone().into(),
                        &storage_key.clone().into(),
                    )
                    .ok();
            }
        }
        let note = serde_json::json!({"bvhlab": "panic", "message": message}).to_string();
        announce(&origins, &note);
    }));
}
