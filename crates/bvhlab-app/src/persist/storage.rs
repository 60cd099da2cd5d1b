//! Keeping the state across reloads: [`Autosave`] decides, once a frame, whether the state
//! must be written to the browser's `localStorage` (under [`STORAGE_KEY`]); the web glue
//! writes it.
//!
//! Serializing a hand-drawn 10,000-segment scene takes milliseconds, too much for every
//! frame. So each frame only compares a [`ChangeKey`] (the scene's revision, the settings,
//! the ray and point, the step, the view: a few dozen bytes), and the state is serialized
//! only after the key changed, at most every [`AUTOSAVE_INTERVAL`] seconds; it is written
//! only if the JSON differs from what was stored last.

use bvhlab::glam::Vec2;

use crate::app::{Display, LabApp, RayHandles};
use crate::presets::Preset;
use crate::pseudocode::{Task, Variant};
use crate::structures::BuildSettings;
use crate::volumes::VolumeToggles;

use super::state::SavedState;

/// The `localStorage` key of the saved state (the format version is in the name, so that a
/// later format can keep its own).
pub const STORAGE_KEY: &str = "bvh-lab/state/v1";

/// The shortest time between two writes, in seconds.
pub const AUTOSAVE_INTERVAL: f64 = 0.5;

/// Everything [`SavedState::capture`] reads, cheaply: equal keys mean an equal saved state
/// (the scene by its revision, which changes with every edit).
#[derive(Clone, Debug, PartialEq)]
struct ChangeKey {
    revision: u64,
    preset: Preset,
    selection: Vec<usize>,
    settings: BuildSettings,
    compare: Option<BuildSettings>,
    display: Display,
    volumes: VolumeToggles,
    ray: Option<RayHandles>,
    point: Option<Vec2>,
    k: usize,
    radius: f32,
    task: Task,
    variant: Variant,
    step: usize,
    live: bool,
    center: Vec2,
    scale: f32,
    /// The 3D half (a few strings and numbers: cheap to compare each frame).
    three: super::ThreeState,
}

impl ChangeKey {
    fn of(app: &LabApp) -> Self {
        Self {
            revision: app.scene.revision(),
            preset: app.preset,
            selection: app.selection.clone(),
            settings: app.lane.settings,
            compare: app.compare.as_ref().map(|l| l.settings),
            display: app.display,
            volumes: app.volume_toggles,
            ray: app.ray,
            point: app.point,
            k: app.k,
            radius: app.radius,
            task: app.task,
            variant: app.variant,
            step: app.playback.step,
            live: app.playback.at_end,
            center: app.view.center,
            scale: app.view.scale,
            three: super::ThreeState::capture(app),
        }
    }
}

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
    key: Option<ChangeKey>,
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
    pub fn keep_current(&mut self, app: &LabApp) {
        self.key = Some(ChangeKey::of(app));
        self.dirty = false;
    }

    /// Called once a frame with the time in seconds: whether to write the state now.
    pub fn poll(&mut self, app: &LabApp, now: f64) -> AutosaveStep {
        let key = ChangeKey::of(app);
        if self.key.as_ref() != Some(&key) {
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
        let json = serde_json::to_string(&SavedState::capture(app)).unwrap_or_default();
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
