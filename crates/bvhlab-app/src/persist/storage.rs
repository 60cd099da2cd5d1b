//! Keeping the state across reloads: [`Autosave`] decides, once a frame, whether the state
//! must be written to the browser's `localStorage` (under [`STORAGE_KEY`]); the web glue
//! writes it.
//!
//! Serializing a hand-drawn 10,000-segment scene takes milliseconds, too much for every
//! frame. Every change of the lab goes through one function, which counts them
//! ([`Lab::changes`]), so each frame only compares that count, and the state is serialized
//! only after it moved, at most every [`AUTOSAVE_INTERVAL`] seconds; it is written only if the
//! JSON differs from what was stored last.

use crate::model::Lab;

use super::state::SavedState;

/// The `localStorage` key of the saved state (the format version is in the name, so that a
/// later format can keep its own).
pub const STORAGE_KEY: &str = "bvh-lab/state/v1";

/// The shortest time between two writes, in seconds.
pub const AUTOSAVE_INTERVAL: f64 = 0.5;

/// What to do this frame.
#[derive(Clone, Debug, PartialEq)]
pub enum AutosaveStep {
    /// Nothing changed since the last write.
    Idle,
    /// Write this JSON under [`STORAGE_KEY`].
    Save(String),
    /// Something changed, but the last write is recent: poll again after this many seconds
    /// (ask for a frame then, so that the change is kept even if nothing else happens).
    Wait(f64),
}

/// The autosave's memory: the last key seen, when the last write was, and what it wrote.
#[derive(Clone, Debug, Default)]
pub struct Autosave {
    key: Option<u64>,
    dirty: bool,
    last_write: Option<f64>,
    stored: Option<String>,
}

impl Autosave {
    /// An autosave that knows `stored` is already in storage (the state the lab started
    /// from), so an unchanged lab does not write it again.
    pub fn new(stored: Option<String>) -> Self {
        Self {
            stored,
            ..Self::default()
        }
    }

    /// Takes the lab's current state as kept, without writing it: after a start-up that
    /// failed, the default scene it fell back to must not overwrite the state saved earlier
    /// until the student changes something.
    pub fn keep_current(&mut self, lab: &Lab) {
        self.key = Some(lab.changes());
        self.dirty = false;
    }

    /// Called once a frame with the time in seconds: whether to write the state now.
    pub fn poll(&mut self, lab: &Lab, now: f64) -> AutosaveStep {
        let key = lab.changes();
        if self.key != Some(key) {
            self.key = Some(key);
            self.dirty = true;
        }
        if !self.dirty {
            return AutosaveStep::Idle;
        }
        if let Some(last) = self.last_write {
            let wait = last + AUTOSAVE_INTERVAL - now;
            if wait > 0.0 {
                return AutosaveStep::Wait(wait);
            }
        }
        self.dirty = false;
        self.last_write = Some(now);
        let json = serde_json::to_string(&SavedState::capture(lab)).unwrap_or_default();
        if json.is_empty() || self.stored.as_ref() == Some(&json) {
            return AutosaveStep::Idle;
        }
        self.stored = Some(json.clone());
        AutosaveStep::Save(json)
    }

    /// The write of the last [`AutosaveStep::Save`] failed (storage full or off): forget it,
    /// so that the next change tries again.
    pub fn write_failed(&mut self) {
        self.stored = None;
    }
}
