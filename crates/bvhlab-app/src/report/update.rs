//! How each lane of the half shown follows moving primitives, for the report: its update
//! mode, its last update and the times of its refits and rebuilds ([`crate::model::refit`]).

use serde::Serialize;

use crate::model::dimension::LabPrimitive;
use crate::model::half::Half;
use crate::model::lane::Lane;
use crate::model::refit::{EditKind, UpdateMode};

/// One lane's updates.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct UpdateReport {
    /// The lane's name ("AABB tree, refitted").
    pub structure: String,
    /// What it does when the primitives move: "refit" or "rebuild".
    pub mode: &'static str,
    /// Its last update: "refit" or "rebuild".
    pub last: Option<&'static str>,
    /// The last update's time, in milliseconds.
    pub last_ms: Option<f64>,
    /// The SAH cost now.
    pub sah_cost: Option<f32>,
    /// The SAH cost now over the cost at the last build.
    pub cost_ratio: Option<f32>,
    /// Refits among the updates kept.
    pub refits: usize,
    /// Rebuilds among them.
    pub rebuilds: usize,
    /// The mean refit time, in milliseconds.
    pub refit_ms: Option<f64>,
    /// The mean rebuild time, in milliseconds.
    pub rebuild_ms: Option<f64>,
}

impl UpdateReport {
    /// Every lane of `half` that was updated at least once.
    pub fn of_half<P: LabPrimitive>(half: &Half<P>) -> Vec<Self> {
        (0..half.lane_count())
            .filter(|&i| !half.lane_at(i).log.is_empty())
            .map(|i| Self::of(half.lane_at(i), half.lane_name(i)))
            .collect()
    }

    fn of<P: LabPrimitive>(lane: &Lane<P>, structure: String) -> Self {
        let word = |how: EditKind| match how {
            EditKind::Refit => "refit",
            EditKind::Rebuild => "rebuild",
        };
        let built = lane.structure.as_ref();
        let sah_cost = built.and_then(|s| s.stats.sah_cost);
        Self {
            structure,
            mode: match lane.update {
                UpdateMode::Refit => "refit",
                UpdateMode::Rebuild => "rebuild",
            },
            last: lane.log.last().map(|e| word(e.how)),
            last_ms: lane.log.last().map(|e| e.millis),
            sah_cost,
            cost_ratio: built.and_then(|s| Some(sah_cost? / s.build_sah_cost?)),
            refits: lane.log.count(EditKind::Refit),
            rebuilds: lane.log.count(EditKind::Rebuild),
            refit_ms: lane.log.mean_millis(EditKind::Refit),
            rebuild_ms: lane.log.mean_millis(EditKind::Rebuild),
        }
    }
}
