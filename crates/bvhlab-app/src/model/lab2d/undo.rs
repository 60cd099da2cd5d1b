//! Undo and redo of the 2D scene's edits: what an edit changes, put back and taken again
//! (the history itself is [`crate::model::history`]).

use super::Lab2d;
use crate::model::Note;
use crate::model::history::{Edit, PresetSetup, SceneState};

impl Lab2d {
    /// The part of the half a scene edit changes (`setup`: and what a preset replaces).
    pub(super) fn scene_state(&self, setup: bool) -> SceneState {
        SceneState {
            scene: self.scene.clone(),
            selection: self.selection.clone(),
            preset: self.preset,
            setup: setup.then(|| self.preset_setup()),
        }
    }

    /// What loading a preset replaces besides the scene.
    pub(super) fn preset_setup(&self) -> PresetSetup {
        PresetSetup {
            settings: self.half.lane.settings,
            ray: self.ray,
            point: self.point,
            volumes_shown: self.display.volumes,
        }
    }

    /// Puts `state` back; returns the state it replaced (with as much of the setup).
    fn swap_scene_state(&mut self, state: SceneState) -> SceneState {
        let replaced = self.scene_state(state.setup.is_some());
        self.scene = state.scene;
        self.selection = state.selection;
        self.preset = state.preset;
        if let Some(setup) = state.setup {
            self.half.lane.settings = setup.settings;
            self.ray = setup.ray;
            self.point = setup.point;
            self.display.volumes = setup.volumes_shown;
            // Another scene: frame it, as loading a preset does.
            self.fit_pending = true;
        }
        replaced
    }

    /// Undoes the last scene edit.
    pub(super) fn undo(&mut self) -> Result<Note, String> {
        let Some(edit) = self.history.take_undo() else {
            return Err("there is no scene edit to undo".to_owned());
        };
        let state = self.swap_scene_state(edit.state);
        let said = format!("Undid {} (Ctrl+Shift+Z redoes it).", edit.what);
        self.history.push_redo(Edit {
            state,
            what: edit.what,
        });
        Ok(Note::Say(said))
    }

    /// Redoes the last scene edit undone.
    pub(super) fn redo(&mut self) -> Result<Note, String> {
        let Some(edit) = self.history.take_redo() else {
            return Err("there is no undone scene edit to redo".to_owned());
        };
        let state = self.swap_scene_state(edit.state);
        let said = format!("Redid {}.", edit.what);
        self.history.push_undo(Edit {
            state,
            what: edit.what,
        });
        Ok(Note::Say(said))
    }
}
