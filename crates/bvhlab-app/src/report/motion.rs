//! The report of the mesh that moves: how far into its motion, how its tree follows (refit or
//! rebuild, how long each took, the SAH cost against the last build's), and how often the heat
//! map shows a new image.

use serde::Serialize;

use crate::model::Lab;
use crate::model::refit::EditKind;
use crate::ui_state::UiState;

/// The motion of a mesh that moves, when the mesh shown does.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MotionReport {
    /// Whether it moves now (the "Animate" switch).
    pub on: bool,
    /// How far into its motion, in seconds.
    pub seconds: f64,
    /// Frames it has moved since it opened.
    pub frames: u64,
    /// What the structure does every frame: "refit" or "rebuild".
    pub update: &'static str,
    /// The last update: "refit" or "rebuild", and its milliseconds.
    pub last: Option<(&'static str, f64)>,
    /// The mean milliseconds of the refits and of the rebuilds kept in the lane's log.
    pub mean_ms: [Option<f64>; 2],
    /// The SAH cost now, and when the tree was last built.
    pub sah_cost: [Option<f32>; 2],
    /// Every how many frames the heat map shows a new image (when it is on).
    pub heat_every: Option<u32>,
}

impl MotionReport {
    /// The report, when the mesh shown moves.
    pub fn of(lab: &Lab, ui: &UiState) -> Option<Self> {
        let three = lab.three();
        three
            .mesh
            .as_ref()
            .filter(|m| crate::model::motion::moves(m))?;
        let lane = &three.half.lane;
        let word = |how: EditKind| match how {
            EditKind::Refit => "refit",
            EditKind::Rebuild => "rebuild",
        };
        let built = lane.current(three.revision());
        Some(Self {
            on: three.motion.on,
            seconds: three.motion.seconds,
            frames: three.motion.frames,
            update: lane.update.label(),
            last: lane.log.last().map(|e| (word(e.how), e.millis)),
            mean_ms: [EditKind::Refit, EditKind::Rebuild].map(|k| lane.log.mean_millis(k)),
            sah_cost: [
                built.and_then(|s| s.stats.sah_cost),
                built.and_then(|s| s.build_sah_cost),
            ],
            heat_every: ui.view3d.heat.moving_every(),
        })
    }
}
