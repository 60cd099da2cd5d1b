//! Nothing lost: the lab's state saved and restored, as scene files, share links and the
//! browser's saved state.
//!
//! One format serves all three: [`SavedState`], versioned JSON ([`FORMAT_VERSION`]) holding
//! the scene's shapes (or the name of the unmodified preset they are), both lanes' build
//! settings, the drawing switches, the ray, the query point, `k`, the radius, the task and
//! variant, the playback step and the view.
//!
//! - Scene files: [`to_file`] writes the full state as readable JSON; [`from_file`] reads one
//!   (dropped on the window, or picked with "Import scene…").
//! - Share links: [`link_fragment`] packs the state into `#s=...`; [`from_fragment`] unpacks
//!   it. Links longer than [`MAX_LINK_CHARS`] are refused ("export the scene as a file
//!   instead").
//! - Reloads: [`Autosave`] keeps the state in `localStorage` under [`STORAGE_KEY`];
//!   [`startup`] picks what the page opens with: a `#s=` link, then `?preset=`, then the saved
//!   state, then the default scene.
//!
//! # Limits
//! Every way in is checked the same way, and a state that breaks a limit changes nothing: the
//! message says what was wrong and that the current scene was kept. The limits are listed on
//! [`SavedState`] and are the constants below; hostile input (truncated, wrong types,
//! garbage, deflate bombs, deep nesting) gives an error, never a panic or an unbounded
//! allocation.

#[cfg(feature = "gui")]
mod actions;
mod file;
mod link;
mod names;
pub(crate) use names::{no_such_name, shorten};
mod restore;
mod state;
mod state3d;
mod storage;
mod volumes3d;

#[cfg(feature = "gui")]
pub use actions::{
    copy_share_link, export_scene, import_scene, pick_lesson_file, poll_imports, read_limit,
    share_link_text,
};
pub use file::{from_file, to_file};
pub use link::{LINK_PREFIX, from_fragment, link_fragment};
pub use names::{
    Coord, KdSplitName, PresetSlug, ShapeName, SphereFitName, SplitName, StoredPoint,
    StructureName, TaskName, VariantName,
};
pub use state::{
    DisplayState, FORMAT_VERSION, LessonState, PlaybackState, RayState, SavedState, SceneState,
    SettingsState, ShapeState, ViewState, VolumeState,
};
pub use state3d::{CameraState, MeshState, Ray3State, StoredPoint3, ThreeState};
pub use storage::{AUTOSAVE_INTERVAL, Autosave, AutosaveStep, STORAGE_KEY};

use crate::model::presets::Preset;
use crate::model::{Action, Action2d, Lab};

/// The largest scene file (and saved state) read, in bytes: 16 MiB, room for a scene at the
/// shape and point limits written out in full.
pub const MAX_FILE_BYTES: usize = 16 << 20;
/// The longest share-link fragment made or read, in characters. Browsers take far longer
/// addresses, but chat programs, mail and course platforms cut or refuse them.
pub const MAX_LINK_CHARS: usize = 32_000;
/// The most a link's data may inflate to, in bytes (a link of [`MAX_LINK_CHARS`] of real
/// JSON inflates to a few hundred KiB; inflation stops here, so a deflate bomb costs at most
/// this much memory).
pub const MAX_LINK_JSON_BYTES: usize = 2 << 20;
/// The most shapes a scene may have.
pub const MAX_SHAPES: usize = 100_000;
/// The most points a scene may have, all shapes together (100,000 segments, or one cloud of
/// 250,000 points).
pub const MAX_POINTS: usize = 250_000;
/// The largest coordinate, radius or view value, in absolute value: the core squares
/// distances in `f32`, and 1e15² = 1e30 stays far from `f32::MAX` (3.4e38), sums included.
pub const MAX_COORD: f32 = 1e15;
pub use crate::model::camera2d::{MAX_SCALE, MIN_SCALE};
pub use crate::model::half::MAX_K;
pub use crate::model::structures::{MAX_GRID_CELLS, MAX_LEAF_SIZE, MAX_QUADTREE_DEPTH};

/// The action that opens a scene file, or why it cannot be opened.
///
/// # Errors
/// What was wrong with the file, and that the current scene was kept.
pub fn open_file(bytes: &[u8]) -> Result<Action, String> {
    from_file(bytes)
        .and_then(|state| state.restore())
        .map_err(|e| format!("{}. The current scene was kept.", capitalized(&e)))
}

/// The action that opens a share link's fragment, or why it cannot be opened.
///
/// # Errors
/// What was wrong with the link, and that the current scene was kept.
pub fn open_fragment(fragment: &str) -> Result<Action, String> {
    from_fragment(fragment)
        .and_then(|state| state.restore())
        .map_err(|e| format!("{}. The current scene was kept.", capitalized(&e)))
}

/// The lab the page opens with, and a message when something asked for could not be opened.
///
/// In order: a share link's fragment (`#s=...`; other fragments are ignored), then the
/// `?preset=` slug, then the state saved in the browser, then the default scene. What fails
/// to load leaves the default scene and says why in the status line.
pub fn startup(
    fragment: Option<&str>,
    preset: Option<&str>,
    saved: Option<&str>,
) -> (Lab, Option<String>) {
    let mut lab = Lab::default();
    let link = fragment.filter(|f| f.trim().trim_start_matches('#').starts_with("s="));
    let action = if let Some(link) = link {
        from_fragment(link)
            .and_then(|state| state.restore())
            .map_err(|e| format!("The share link could not be opened: {e}"))
    } else if let Some(slug) = preset {
        Preset::from_slug(slug)
            .map(|p| Action2d::LoadPreset(p).into())
            .ok_or_else(|| {
                format!(
                    "The address asks for the preset \"{}\", which the lab does not have",
                    shorten(slug, 40)
                )
            })
    } else if let Some(saved) = saved {
        file::from_json(saved.as_bytes(), "the saved state")
            .and_then(|state| state.restore())
            .map_err(|e| format!("The state saved in this browser could not be restored: {e}"))
    } else {
        Ok(Action::SetMessage(None))
    };
    let message = action
        .and_then(|a| lab.apply(a))
        .err()
        .map(|e| format!("{e}. The default scene is shown."));
    if message.is_some() {
        // Setting a message always applies.
        let _ = lab.apply(Action::SetMessage(message.clone()));
    }
    (lab, message)
}

/// `text` with its first letter capitalized (messages are built from lower-case parts).
pub(crate) fn capitalized(text: &str) -> String {
    let mut chars = text.chars();
    chars.next().map_or_else(String::new, |first| {
        first.to_uppercase().chain(chars).collect()
    })
}

/// Why a file of `len` bytes is not read (over `limit`), in MiB or, for small limits (a
/// lesson's), in KiB.
pub fn too_large(len: u64, limit: usize) -> String {
    let (unit, name) = if limit >= 1 << 20 {
        (f64::from(1 << 20), "MiB")
    } else {
        (1024.0, "KiB")
    };
    format!(
        "it is {:.1} {name}; the lab reads at most {} {name}",
        len as f64 / unit,
        limit as f64 / unit
    )
}
