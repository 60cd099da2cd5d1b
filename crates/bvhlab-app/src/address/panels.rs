//! Which panels are shown beside the view: the UI's layout, which the address's `panels=`
//! chooses (so its vocabulary is the address's, and the UI state keeps one).

use crate::model::Dimension;

/// Which panels are shown beside the view.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[allow(clippy::struct_excessive_bools)] // one switch per panel
pub struct PanelsShown {
    /// The controls (left).
    pub controls: bool,
    /// "Step through" (right).
    pub stepper: bool,
    /// The tree diagram below the 2D canvas.
    pub tree: bool,
    /// The tree diagram below the 3D view (off at first: the view keeps the room).
    pub tree3d: bool,
    /// In a window too narrow for both side panels (a laptop, an embed), they share one,
    /// as tabs: the one shown.
    pub tab: SideTab,
}

/// The side panel shown when the controls and "Step through" share one (narrow windows).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SideTab {
    /// The lessons and the controls.
    #[default]
    Controls,
    /// "Step through": playback, Predict, the counters and the pseudocode.
    Stepper,
}

impl PanelsShown {
    /// Whether the tree diagram is shown below the view of `dimension`.
    pub fn tree_in(&self, dimension: Dimension) -> bool {
        match dimension {
            Dimension::Two => self.tree,
            Dimension::Three => self.tree3d,
        }
    }
}

impl Default for PanelsShown {
    fn default() -> Self {
        Self {
            controls: true,
            stepper: true,
            tree: true,
            tree3d: false,
            tab: SideTab::Controls,
        }
    }
}

/// The panels named in `panels=`: only those listed are shown.
pub(super) fn parse(value: &str) -> Result<PanelsShown, String> {
    let mut panels = PanelsShown {
        controls: false,
        stepper: false,
        tree: false,
        tree3d: false,
        tab: SideTab::Controls,
    };
    for name in value.split(',').map(str::trim).filter(|n| !n.is_empty()) {
        match name {
            "controls" => panels.controls = true,
            "stepper" => panels.stepper = true,
            "tree" => {
                panels.tree = true;
                panels.tree3d = true;
            }
            other => {
                return Err(super::unknown(
                    "panels",
                    "panel",
                    other,
                    &["controls", "stepper", "tree"],
                ));
            }
        }
    }
    Ok(panels)
}
