//! The native window's side of "nothing lost": the lab's state kept in a file across runs
//! (as the browser keeps it in `localStorage`), and a frame that panics caught, so that the
//! window stays open: the lab goes back to its last saved state and says what happened.
//!
//! Natively a panic unwinds (in WebAssembly it cannot, and the page's overlay offers a reload
//! instead: `web/main.js`). The state is saved at most every
//! [`AUTOSAVE_INTERVAL`](crate::persist::AUTOSAVE_INTERVAL) seconds after a change, so going
//! back loses at most the last half second.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

use crate::LabApp;
use crate::persist::{Autosave, AutosaveStep};

/// The lab in a native window.
pub struct NativeLab {
    /// The lab.
    pub app: LabApp,
    autosave: Autosave,
    /// Where the state is kept, if anywhere.
    path: Option<PathBuf>,
    /// The last state saved (also kept in memory, for when the file cannot be written).
    last_saved: Option<String>,
    /// Panics in frames in a row (a saved state that itself panics is then dropped).
    panics_in_a_row: u32,
}

impl NativeLab {
    /// The lab, restored from the state at `path` when there is one.
    pub fn open(path: Option<PathBuf>) -> Self {
        let saved = path
            .as_deref()
            .and_then(|p| std::fs::read_to_string(p).ok());
        let (lab, _) = crate::persist::startup(None, None, saved.as_deref());
        Self {
            app: LabApp::new(lab),
            autosave: Autosave::new(saved.clone()),
            path,
            last_saved: saved,
            panics_in_a_row: 0,
        }
    }

    /// Where the native lab keeps its state: `$BVHLAB_STATE`, else
    /// `$XDG_STATE_HOME/bvh-lab/state.json`, else `~/.local/state/bvh-lab/state.json`.
    pub fn state_path() -> Option<PathBuf> {
        if let Some(path) = std::env::var_os("BVHLAB_STATE") {
            return Some(PathBuf::from(path));
        }
        let base = std::env::var_os("XDG_STATE_HOME")
            .map(PathBuf::from)
            .or_else(|| std::env::var_os("HOME").map(|h| Path::new(&h).join(".local/state")))?;
        Some(base.join("bvh-lab").join("state.json"))
    }

    /// Runs one frame of the lab through `body` (the lab's own `ui`, or a test's), catching a
    /// panic; then saves the state when it changed. `now` is the time in seconds.
    pub fn frame(
        &mut self,
        ui: &mut egui::Ui,
        now: f64,
        body: impl FnOnce(&mut LabApp, &mut egui::Ui),
    ) {
        let outcome = catch_unwind(AssertUnwindSafe(|| body(&mut self.app, ui)));
        match outcome {
            Ok(()) => self.panics_in_a_row = 0,
            Err(payload) => {
                self.recover(&panic_message(payload.as_ref()));
                ui.ctx().request_repaint();
                return;
            }
        }
        match self.autosave.poll(self.app.lab(), now) {
            AutosaveStep::Idle => {}
            AutosaveStep::Wait(seconds) => ui
                .ctx()
                .request_repaint_after(std::time::Duration::from_secs_f64(seconds)),
            AutosaveStep::Save(json) => self.store(json),
        }
    }

    /// Goes back to the last saved state (or, when that panicked too, to the default lab),
    /// keeping the renderer, and says what happened.
    fn recover(&mut self, message: &str) {
        self.panics_in_a_row += 1;
        let saved = self
            .last_saved
            .as_deref()
            .filter(|_| self.panics_in_a_row < 2);
        let (lab, _) = crate::persist::startup(None, None, saved);
        // The UI (and its renderer) stays; only the lab goes back.
        self.app.replace_lab(lab);
        let said = self
            .app
            .apply(crate::model::Action::SetMessage(Some(if saved.is_some() {
                format!(
                    "The lab hit an error in its code ({message}) and went back to your last saved \
                 state."
                )
            } else {
                format!(
                    "The lab hit an error in its code ({message}) and started afresh (the saved \
                 state hit it too)."
                )
            })));
        debug_assert!(said.is_ok(), "a message always applies");
        self.autosave = Autosave::new(self.last_saved.clone());
        self.autosave.keep_current(self.app.lab());
    }

    /// Keeps `json` as the last saved state and writes it to the state file.
    fn store(&mut self, json: String) {
        if let Some(path) = &self.path {
            let written = path
                .parent()
                .map_or(Ok(()), std::fs::create_dir_all)
                .and_then(|()| std::fs::write(path, &json));
            if let Err(e) = written {
                self.autosave.write_failed();
                log::warn!(
                    "the lab's state could not be written to {}: {e}",
                    path.display()
                );
            }
        }
        self.last_saved = Some(json);
    }
}

impl eframe::App for NativeLab {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        let now = ui.input(|i| i.time);
        self.frame(ui, now, |app, ui| eframe::App::ui(app, ui, frame));
    }
}

/// A panic's message.
fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_owned())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "an unknown error".to_owned())
}
