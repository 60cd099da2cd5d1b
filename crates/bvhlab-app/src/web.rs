//! The web page side: starting the lab on the `#lab` canvas, and publishing its
//! [`Report`] into `#lab-status` (text for screen readers, JSON in `data-report` for the page,
//! the browser test and course pages that embed the lab).

use std::cell::RefCell;

use wasm_bindgen::JsCast;

use crate::presets::Preset;
use crate::report::Report;

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
        let result = eframe::WebRunner::new()
            .start(
                canvas,
                eframe::WebOptions::default(),
                Box::new(|_cc| Ok(Box::new(crate::LabApp::with_preset(start_preset())))),
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

/// The preset the page's address asks for (`?preset=duplicate-triangle`), else the default.
fn start_preset() -> Preset {
    let search = web_sys::window()
        .and_then(|w| w.location().search().ok())
        .unwrap_or_default();
    let asked = search
        .trim_start_matches('?')
        .split('&')
        .find_map(|pair| pair.strip_prefix("preset="));
    match asked {
        Some(slug) => Preset::from_slug(slug).unwrap_or_else(|| {
            log::warn!("unknown preset {slug:?} in the address; opening the default scene");
            Preset::default()
        }),
        None => Preset::default(),
    }
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
    element.set_text_content(Some(&report.text()));
    if element.set_attribute("data-report", &json).is_err() {
        log::warn!("could not write the lab's report to the page");
    }
}
