//! The page's side of the lab for assistive technology ([`crate::a11y`]): a `<main
//! id="lab-a11y">` over the canvas holds one element per node of egui's accessibility tree,
//! kept in step by the mirror's operations, and what a person does to those elements goes
//! back to egui as action requests and key presses.
//!
//! - An egui plugin takes each frame's tree update (`output_hook`) and gives egui the requests
//!   and keys gathered since the last frame (`input_hook`).
//! - The page is brought up to date at most every [`MIN_GAP_MS`] (a screen reader reads
//!   slower than the lab animates), and at once after the person did something; a timer
//!   brings it up to date when the lab stops drawing. egui builds its tree only on the
//!   passes the page will take it from, so the passes between cost nothing more.
//! - The canvas leaves the Tab order: Tab moves among the elements as on any page, so it
//!   leaves the lab after its last one, and Shift+Tab before its first. Escape leaves from
//!   anywhere ([`crate::a11y::keys`]). A Tab pressed while the canvas has the focus (after a
//!   click) moves it to the element after egui's focused widget.
//! - The elements are transparent and let the pointer through (`lab.css`): sighted users see
//!   the canvas, and the focus egui draws on the widget whose element has the page's focus.
//!
//! `dom.rs` applies the mirror's operations to the page; `listen.rs` hears the page.

use std::cell::RefCell;
use std::collections::HashMap;

use egui::accesskit::NodeId;

use super::timer::{after_ms, now_ms};
use crate::a11y::mirror::Mirror;

mod dom;
mod listen;

use dom::apply;
use listen::listen;

/// The least time between two updates of the page, in milliseconds, but after a person's
/// action.
const MIN_GAP_MS: f64 = 200.0;

/// The container's id.
const CONTAINER: &str = "lab-a11y";

/// Where the focus goes to leave the lab: after every element, out of the Tab order.
const END: &str = "lab-a11y-end";

/// What the plugin keeps (the page is one thread: the plugin reaches it through [`STATE`]).
/// The page's event handlers never borrow it: the page fires events while the mirror's
/// operations are applied (a removed element's blur, a focus moved), so they go to the
/// [`INBOX`] instead, which nothing holds for long.
struct State {
    mirror: Mirror,
    container: web_sys::Element,
    elements: HashMap<NodeId, web_sys::Element>,
    /// When the page was last brought up to date (`performance.now()`).
    last_apply: f64,
    /// A timer is set to bring the page up to date.
    timer: bool,
    /// The canvas, to find its Tab.
    canvas: web_sys::HtmlCanvasElement,
}

/// What the person did since the last frame, for egui, and egui to wake.
#[derive(Default)]
struct Inbox {
    events: Vec<egui::Event>,
    /// A person's action waits to be seen on the page.
    prompt: bool,
    ctx: Option<egui::Context>,
    /// Whether a combo box's list is open, as the page was last told (Escape closes it).
    popup: bool,
    /// The node egui's focus was on, as the page was last told.
    focus: Option<NodeId>,
}

thread_local! {
    static STATE: RefCell<Option<State>> = const { RefCell::new(None) };
    static INBOX: RefCell<Inbox> = RefCell::new(Inbox::default());
}

/// Queues an event for egui's next frame and asks for that frame.
fn post(event: egui::Event) {
    let ctx = INBOX.with(|i| {
        let mut inbox = i.borrow_mut();
        inbox.events.push(event);
        inbox.prompt = true;
        inbox.ctx.clone()
    });
    if let Some(ctx) = ctx {
        ctx.request_repaint();
    }
}

/// Starts the mirror over `canvas`: turns on egui's accessibility tree, adds the plugin, makes
/// the container and listens to it. Says in the log and does nothing when the page refuses.
pub fn install(canvas: &web_sys::HtmlCanvasElement, ctx: &egui::Context) {
    let Some(document) = canvas.owner_document() else {
        return;
    };
    let Ok(container) = document.create_element("main") else {
        log::warn!("the page refused the lab's element for screen readers");
        return;
    };
    container.set_id(CONTAINER);
    let _ = container.set_attribute("aria-label", "bvh-lab");
    if canvas.after_with_node_1(&container).is_err() {
        return;
    }
    let Ok(end) = document.create_element("div") else {
        return;
    };
    end.set_id(END);
    let _ = end.set_attribute("tabindex", "-1");
    end.set_text_content(Some("End of the lab: Tab leaves it."));
    let _ = container.after_with_node_1(&end);
    // The canvas stays focusable by a click, but out of the Tab order.
    canvas.set_tab_index(-1);
    listen(&container, canvas);
    ctx.enable_accesskit();
    ctx.add_plugin(MirrorPlugin);
    INBOX.with(|i| {
        let mut inbox = i.borrow_mut();
        inbox.ctx = Some(ctx.clone());
        inbox.prompt = true;
    });
    STATE.with(|s| {
        *s.borrow_mut() = Some(State {
            mirror: Mirror::new(),
            container,
            elements: HashMap::new(),
            last_apply: f64::NEG_INFINITY,
            timer: false,
            canvas: canvas.clone(),
        });
    });
}

/// The plugin: tree updates in, the page's events out.
struct MirrorPlugin;

impl egui::Plugin for MirrorPlugin {
    fn debug_name(&self) -> &'static str {
        "bvh-lab page mirror"
    }

    fn input_hook(&mut self, ctx: &egui::Context, input: &mut egui::RawInput) {
        let prompt = INBOX.with(|i| {
            let mut inbox = i.borrow_mut();
            input.events.append(&mut inbox.events);
            inbox.prompt
        });
        // egui builds its tree only on the passes whose tree the page takes (after a person's
        // action, or once MIN_GAP_MS have passed): the passes between cost what they cost
        // without a mirror (see `output_hook` for the pass that follows a skipped one).
        let since = with_state(|s| now_ms() - s.last_apply).unwrap_or(f64::INFINITY);
        if prompt || since >= MIN_GAP_MS {
            ctx.enable_accesskit();
        } else {
            ctx.disable_accesskit();
        }
        with_state(|s| {
            // eframe tells egui whether the canvas has the focus; the lab has it too when one
            // of its elements does (egui then draws the focus, and its keys act).
            let active = s
                .container
                .owner_document()
                .and_then(|d| d.active_element());
            if active.is_some_and(|a| s.container.contains(Some(&a))) {
                input.focused = true;
            }
        });
    }

    fn output_hook(&mut self, ctx: &egui::Context, output: &mut egui::FullOutput) {
        let Some(update) = output.platform_output.accesskit_update.take() else {
            // A pass without the tree may have changed the lab: a pass with it once the gap
            // is over, so that the change reaches the page even if the lab then stops
            // drawing. (Asked here, after the pass: egui tells eframe of a repaint only when
            // it is sooner than one already asked for, and before a pass the immediate
            // repaint that started it still is; asked then, it was lost.)
            if let Some(since) = with_state(|s| now_ms() - s.last_apply) {
                ctx.request_repaint_after(std::time::Duration::from_secs_f64(
                    (MIN_GAP_MS - since).max(0.0) / 1000.0,
                ));
            }
            return;
        };
        with_state(|s| s.mirror.update(update));
        bring_up_to_date(false);
    }
}

/// Runs `f` on the state, if the mirror is installed.
fn with_state<R>(f: impl FnOnce(&mut State) -> R) -> Option<R> {
    STATE.with(|s| s.borrow_mut().as_mut().map(f))
}

/// Applies the mirror's changes to the page, unless the last update was under [`MIN_GAP_MS`]
/// ago and nobody acted since (`timer`: called by the timer, which then always applies); a
/// timer then catches up later.
fn bring_up_to_date(timer: bool) {
    let Some(ops) = with_state(|s| {
        if timer {
            s.timer = false;
        }
        let t = now_ms();
        let prompt = INBOX.with(|i| std::mem::take(&mut i.borrow_mut().prompt));
        if !timer && !prompt && t - s.last_apply < MIN_GAP_MS {
            if !s.timer {
                s.timer = true;
                set_timer(MIN_GAP_MS);
            }
            return None;
        }
        s.last_apply = t;
        let ops = s.mirror.changes();
        let (popup, focus) = (s.mirror.popup_open(), s.mirror.focus());
        INBOX.with(|i| {
            let mut inbox = i.borrow_mut();
            inbox.popup = popup;
            inbox.focus = focus;
        });
        Some(ops)
    })
    .flatten() else {
        return;
    };
    with_state(|s| apply(s, &ops));
}

/// Calls [`bring_up_to_date`] in `ms` milliseconds.
fn set_timer(ms: f64) {
    if !after_ms(ms, || bring_up_to_date(true)) {
        with_state(|s| s.timer = false);
    }
}
