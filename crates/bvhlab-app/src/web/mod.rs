//! The web page side: starting the lab on the `#lab` canvas with the state the address or the
//! browser asks for, keeping that state in `localStorage` as it changes, publishing the lab's
//! [`Report`] into `#lab-status` (its news for screen readers, `live.rs`; JSON in `data-report` for the page,
//! the browser test and course pages that embed the lab), and the browser's side of saving
//! and sharing (`files.rs`: the file dialog, dropped files and the clipboard).

use std::cell::RefCell;
use std::rc::Rc;

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

use crate::LabApp;
use crate::embed::browser::{Inbox, Origins, on_panic_tell_page};
use crate::embed::{Scripting, StartParams};
use crate::persist::{Autosave, AutosaveStep, STORAGE_KEY};
use crate::report::Report;

mod a11y;
mod files;
mod live;
mod timer;

use files::deliver;
pub use files::{News, copy_text, fetch_lesson, pick_file, read_dropped, take_news};

thread_local! {
    /// The JSON last written, so the DOM is touched only when something changed.
    static LAST: RefCell<String> = const { RefCell::new(String::new()) };
}

/// Starts the lab on the canvas `#lab`.
pub fn start() {
    eframe::WebLogger::init(log::LevelFilter::Warn).ok();
    wasm_bindgen_futures::spawn_local(async {
        let Some(document) = web_sys::window().and_then(|w| w.document()) else {
            return;
        };
        let Some(canvas) = document
            .get_element_by_id("lab")
            .and_then(|e| e.dyn_into::<web_sys::HtmlCanvasElement>().ok())
        else {
            log::error!("the page has no <canvas id=\"lab\">");
            return;
        };
        let mut start = start_state();
        let storage = start.storage;
        if !storage {
            say_no_storage(&mut start.app);
        }
        let origins = Origins::new(&start.params.origins);
        let lesson_url = lesson_to_fetch(&start);
        let inbox: Inbox = Rc::new(RefCell::new(Scripting::new(start.params.debug_panic)));
        let runner = eframe::WebRunner::new();
        let page_canvas = canvas.clone();
        // After eframe's own hook (installed by `WebRunner::new`), so that both run.
        on_panic_tell_page(start.key.clone(), origins.clone());
        let result = runner
            .start(
                canvas,
                eframe::WebOptions::default(),
                Box::new(move |cc| {
                    a11y::install(&page_canvas, &cc.egui_ctx);
                    listen_for_links(cc.egui_ctx.clone());
                    if let Some(url) = lesson_url {
                        fetch_lesson(&cc.egui_ctx, url);
                    }
                    crate::embed::browser::listen(
                        inbox.clone(),
                        origins.clone(),
                        cc.egui_ctx.clone(),
                    );
                    Ok(Box::new(WebLab {
                        app: start.app,
                        autosave: Autosave::new(start.saved),
                        key: start.key,
                        hold: start.saved_failed,
                        storage: if storage {
                            Storage::Working
                        } else {
                            Storage::Missing
                        },
                        inbox,
                        origins,
                        announced: false,
                        progress: None,
                        height: None,
                    }))
                }),
            )
            .await;
        if let Err(e) = result {
            log::error!("the lab could not start: {e:?}");
            if let Some(status) = document.get_element_by_id("status") {
                status.set_text_content(Some(&format!("The lab could not start: {e:?}")));
            }
        }
    });
}

/// What the page starts with.
struct StartState {
    app: LabApp,
    /// The state saved in this browser under `key`, as text.
    saved: Option<String>,
    /// The `localStorage` key of this lab's state (see [`StartParams::storage_key`]).
    key: String,
    /// The saved state could not be restored: keep it until the student changes something.
    saved_failed: bool,
    params: StartParams,
    /// Whether this browser frame gives the lab `localStorage` (see [`local_storage`]).
    storage: bool,
}

/// The lab the page opens with ([`crate::embed::start`]: a `#s=` link, then the state saved
/// for these parameters, then the address's parameters), read from the address and the
/// browser's storage.
///
/// A share link's fragment is removed from the address once read ([`forget_link`]).
fn start_state() -> StartState {
    let Some(window) = web_sys::window() else {
        return StartState {
            app: LabApp::default(),
            saved: None,
            key: STORAGE_KEY.to_owned(),
            saved_failed: false,
            params: StartParams::default(),
            storage: false,
        };
    };
    let location = window.location();
    let hash = location.hash().unwrap_or_default();
    let search = location.search().unwrap_or_default();
    let params = StartParams::parse(&search);
    let key = params.storage_key();
    let storage = local_storage();
    let saved = storage
        .as_ref()
        .and_then(|s| s.get_item(&key).ok().flatten());
    let fragment = (!hash.is_empty()).then_some(hash.as_str());
    let start = crate::embed::start(fragment, &params, saved.as_deref());
    if let Some(m) = &start.message {
        log::warn!("{m}");
    }
    if hash.starts_with(crate::persist::LINK_PREFIX) {
        forget_link();
    }
    if params.fresh {
        forget_fresh();
    }
    StartState {
        app: start.app,
        saved,
        key,
        saved_failed: start.saved_failed,
        params,
        storage: storage.is_some(),
    }
}

/// The address's `lesson-url=`, unless the lab starts with that lesson open already (its
/// saved progress came back: fetching it again would start it over).
fn lesson_to_fetch(start: &StartState) -> Option<String> {
    let url = start.params.lesson_url.clone()?;
    let lesson = start.app.lab().lesson();
    let open = lesson.and_then(|p| p.lesson.teacher.as_ref());
    (open.map(|t| t.file.as_str()) != Some(url.as_str())).then_some(url)
}

/// The browser's `localStorage`, if this frame may use it. A frame sandboxed without
/// `allow-same-origin` (and a browser with storage turned off) throws on the mere access.
fn local_storage() -> Option<web_sys::Storage> {
    web_sys::window()?.local_storage().ok().flatten()
}

/// Said once, when the lab starts without storage.
const NO_STORAGE: &str = "This lab cannot save in this browser frame (the browser gives it no \
                          storage here), so a reload starts over; \"Export scene\" keeps your \
                          work as a file where the page allows downloads.";

/// Adds [`NO_STORAGE`] to the status line (after what the start-up said).
fn say_no_storage(app: &mut LabApp) {
    let message = match app.lab().message() {
        Some(said) => format!("{said} {NO_STORAGE}"),
        None => NO_STORAGE.to_owned(),
    };
    let said = app.apply(crate::model::Action::SetMessage(Some(message)));
    debug_assert!(said.is_ok(), "a message always applies");
}

/// Removes a share link's fragment from the address (keeping path and query), so that a
/// reload shows the student's latest state, kept in `localStorage`, instead of the link again.
pub fn forget_link() {
    let search = web_sys::window()
        .and_then(|w| w.location().search().ok())
        .unwrap_or_default();
    replace_address(&search, "the share link");
}

/// Removes `fresh=1` from the address once the lab has started from the page's own scene, so
/// that a later reload restores what the student does from now on.
fn forget_fresh() {
    let search = web_sys::window()
        .and_then(|w| w.location().search().ok())
        .unwrap_or_default();
    let kept: Vec<&str> = search
        .trim_start_matches('?')
        .split('&')
        .filter(|pair| !pair.is_empty() && !pair.starts_with("fresh="))
        .collect();
    let search = if kept.is_empty() {
        String::new()
    } else {
        format!("?{}", kept.join("&"))
    };
    replace_address(&search, "fresh=1");
}

/// Replaces the address, without reloading, by the page's path and `search` (no fragment);
/// says in the log when the browser refuses, naming `what` was to be removed.
fn replace_address(search: &str, what: &str) {
    let Some(window) = web_sys::window() else {
        return;
    };
    let address = format!(
        "{}{search}",
        window.location().pathname().unwrap_or_default()
    );
    if let Ok(history) = window.history()
        && history
            .replace_state_with_url(&JsValue::NULL, "", Some(&address))
            .is_err()
    {
        log::warn!("could not remove {what} from the address");
    }
}

/// Opens share links pasted into the address of the page already showing the lab: the
/// browser then only changes the fragment (`hashchange`) and does not reload the page.
fn listen_for_links(ctx: egui::Context) {
    let Some(window) = web_sys::window() else {
        return;
    };
    let on_change = Closure::<dyn FnMut()>::new(move || {
        let hash = web_sys::window()
            .and_then(|w| w.location().hash().ok())
            .unwrap_or_default();
        if hash.starts_with(crate::persist::LINK_PREFIX) {
            deliver(&ctx, News::Link(hash));
        }
    });
    if window
        .add_event_listener_with_callback("hashchange", on_change.as_ref().unchecked_ref())
        .is_err()
    {
        log::warn!("share links pasted into this page's address will need a reload");
    }
    // The listener lives as long as the page.
    on_change.forget();
}

/// The lab, the autosave that keeps its state in `localStorage`, and the commands of the
/// page that embeds it.
struct WebLab {
    app: LabApp,
    autosave: Autosave,
    /// Where the state is kept.
    key: String,
    /// The page's commands and the replies owed.
    inbox: Inbox,
    /// Who may send commands (and hears `ready`).
    origins: Origins,
    /// Whether `ready` was posted to the embedding page.
    announced: bool,
    /// The last lesson progress posted to the embedding page.
    progress: Option<String>,
    /// The start-up failed and fell back to the default scene: keep the state saved earlier
    /// until the student changes something (taken after the first frame, which fits the view).
    hold: bool,
    /// Whether the state reaches `localStorage`.
    storage: Storage,
    /// The preferred height last posted to the embedding page ([`crate::embed::size`]).
    height: Option<u32>,
}

impl eframe::App for WebLab {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        let now = ui.input(|i| i.time);
        self.inbox.borrow_mut().before_frame(&mut self.app, now);
        // The lab publishes its report itself.
        eframe::App::ui(&mut self.app, ui, frame);
        let replies = self.inbox.borrow_mut().after_frame(&self.app, now);
        for (reply_to, json) in replies {
            crate::embed::browser::send(&reply_to, &json);
        }
        if self.inbox.borrow().pending() {
            ui.ctx().request_repaint();
        }
        if !self.announced {
            self.announced = true;
            crate::embed::browser::announce(&self.origins, r#"{"bvhlab":"ready"}"#);
        }
        // The course page hears of a step moved to, a goal reached or a prediction scored.
        let report = &self.app.report;
        let progress = crate::report::predict::progress_message(
            report.lesson.as_ref(),
            report.predict.as_ref(),
        );
        if progress != self.progress
            && let Some(message) = &progress
        {
            crate::embed::browser::announce(&self.origins, message);
        }
        self.progress = progress;
        // The embedding page hears of the height the lab would like (bvhlab-embed.js's
        // fitHeight applies it to the iframe).
        let height =
            crate::embed::size::preferred_height(&self.app.ui.panels, self.app.lab().dimension());
        if self.height != Some(height) {
            self.height = Some(height);
            crate::embed::browser::announce(
                &self.origins,
                &crate::embed::size::size_message(height),
            );
        }
        if self.storage == Storage::Missing {
            return;
        }
        if std::mem::take(&mut self.hold) {
            self.autosave.keep_current(self.app.lab());
        }
        match self.autosave.poll(self.app.lab(), now) {
            AutosaveStep::Idle => {}
            AutosaveStep::Wait(seconds) => {
                ui.ctx()
                    .request_repaint_after(std::time::Duration::from_secs_f64(seconds));
            }
            AutosaveStep::Save(json) => self.store(&json),
        }
    }
}

impl WebLab {
    /// Writes the state to `localStorage`; says once when that fails (storage full, or off).
    fn store(&mut self, json: &str) {
        let written = local_storage().is_some_and(|s| s.set_item(&self.key, json).is_ok());
        if written {
            self.storage = Storage::Working;
            return;
        }
        self.autosave.write_failed();
        if self.storage == Storage::Working {
            self.storage = Storage::Failing;
            let said = self.app.apply(crate::model::Action::SetMessage(Some(
                "This browser did not keep the lab's state (storage full or off): export the \
                 scene to keep it."
                    .to_owned(),
            )));
            debug_assert!(said.is_ok(), "a message always applies");
        }
    }
}

/// Whether the lab's state reaches the browser's `localStorage`.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Storage {
    /// The frame has none: nothing is saved (the status line said so at the start).
    Missing,
    /// The last write worked (or none was tried yet).
    Working,
    /// The last write failed (said once in the status line, not every frame).
    Failing,
}

/// Writes the report into `#lab-status` when it changed.
pub fn publish(report: &Report) {
    let json = report.json();
    let changed = LAST.with(|last| {
        let mut last = last.borrow_mut();
        if *last == json {
            false
        } else {
            last.clone_from(&json);
            true
        }
    });
    if !changed {
        return;
    }
    let Some(element) = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.get_element_by_id("lab-status"))
    else {
        return;
    };
    live::tell(report.sentences());
    if element.set_attribute("data-report", &json).is_err() {
        log::warn!("could not write the lab's report to the page");
    }
}

/// The page's address without query or fragment (origin and path), for share links.
pub fn page_address() -> String {
    web_sys::window()
        .map(|w| {
            let location = w.location();
            format!(
                "{}{}",
                location.origin().unwrap_or_default(),
                location.pathname().unwrap_or_default()
            )
        })
        .unwrap_or_default()
}
