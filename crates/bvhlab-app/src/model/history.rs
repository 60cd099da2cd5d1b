//! Undo and redo for the 2D scene's edits: adding, moving and deleting shapes, clearing the
//! scene and loading a preset ([`Action2d::Undo`](super::Action2d::Undo) and
//! [`Action2d::Redo`](super::Action2d::Redo)).
//!
//! Each edit keeps the part of the 2D half it changed, as it was before (the scene, the
//! selection and the preset; for a preset also the structure, the ray, the point and the
//! volumes switch it replaced). Undo puts that back and keeps what it replaced for redo; a new
//! edit forgets what could be redone. A drag moves the selection many times: consecutive
//! moves of one selection are one edit, until any other change of the 2D half (the canvas
//! selects the shapes again when a new drag starts). At most [`MAX_UNDO`] edits are kept.

use std::collections::VecDeque;

use bvhlab::glam::Vec2;

use super::lab2d::RayHandles;
use super::presets::Preset;
use super::scene::Scene;
use super::structures::BuildSettings;

/// How many edits can be undone; the oldest is forgotten past this.
pub const MAX_UNDO: usize = 50;

/// The part of the 2D half a scene edit changes.
#[derive(Clone, Debug)]
pub(super) struct SceneState {
    pub(super) scene: Scene,
    pub(super) selection: Vec<usize>,
    pub(super) preset: Preset,
    /// What loading a preset replaces besides the scene (`None` for the other edits).
    pub(super) setup: Option<PresetSetup>,
}

/// What loading a preset replaces besides the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct PresetSetup {
    pub(super) settings: BuildSettings,
    pub(super) ray: Option<RayHandles>,
    pub(super) point: Option<Vec2>,
    pub(super) volumes_shown: bool,
}

/// One edit that can be undone (or redone): the state it replaced, and what it was.
#[derive(Clone, Debug)]
pub(super) struct Edit {
    /// The state to put back.
    pub(super) state: SceneState,
    /// What the edit did, for the status line: "clearing the scene".
    pub(super) what: String,
}

/// The edits that can be undone and redone.
#[derive(Clone, Debug, Default)]
pub struct History {
    undo: VecDeque<Edit>,
    redo: Vec<Edit>,
    /// The last edit is a move of this selection that the next move of it joins.
    open_move: Option<Vec<usize>>,
}

impl History {
    /// What the next undo undoes ("clearing the scene"), if anything.
    pub fn next_undo(&self) -> Option<&str> {
        self.undo.back().map(|e| e.what.as_str())
    }

    /// What the next redo redoes, if anything.
    pub fn next_redo(&self) -> Option<&str> {
        self.redo.last().map(|e| e.what.as_str())
    }

    /// How many edits can be undone.
    pub fn undo_len(&self) -> usize {
        self.undo.len()
    }

    /// How many undone edits can be redone.
    pub fn redo_len(&self) -> usize {
        self.redo.len()
    }

    /// Keeps `state`, as it was before the edit `what`: it can be undone, and nothing can be
    /// redone any more.
    pub(super) fn record(&mut self, state: SceneState, what: String) {
        self.open_move = None;
        self.redo.clear();
        self.undo.push_back(Edit { state, what });
        while self.undo.len() > MAX_UNDO {
            self.undo.pop_front();
        }
    }

    /// Whether a move of `selection` joins the last edit (the same drag).
    pub(super) fn continues_move(&self, selection: &[usize]) -> bool {
        self.open_move.as_deref() == Some(selection)
    }

    /// Keeps the state before a move of `selection`; the moves that follow join it.
    pub(super) fn record_move(&mut self, state: SceneState, selection: &[usize]) {
        let n = selection.len();
        let what = if n == 1 {
            "moving a shape".to_owned()
        } else {
            format!("moving {n} shapes")
        };
        self.record(state, what);
        self.open_move = Some(selection.to_vec());
    }

    /// The next move starts a new edit.
    pub(super) fn close_move(&mut self) {
        self.open_move = None;
    }

    /// Takes the edit to undo.
    pub(super) fn take_undo(&mut self) -> Option<Edit> {
        self.open_move = None;
        self.undo.pop_back()
    }

    /// Takes the edit to redo.
    pub(super) fn take_redo(&mut self) -> Option<Edit> {
        self.open_move = None;
        self.redo.pop()
    }

    /// Keeps an undone edit for redo (`state`: what the undo replaced).
    pub(super) fn push_redo(&mut self, edit: Edit) {
        self.redo.push(edit);
    }

    /// Keeps a redone edit for undo again, without forgetting what else can be redone.
    pub(super) fn push_undo(&mut self, edit: Edit) {
        self.undo.push_back(edit);
        while self.undo.len() > MAX_UNDO {
            self.undo.pop_front();
        }
    }
}
