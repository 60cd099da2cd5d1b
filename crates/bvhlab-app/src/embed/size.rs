//! The height the lab asks of the page that embeds it: `{bvhlab: "size", height}`, posted when
//! it starts and whenever it changes (`web/bvhlab-embed.js` can size the iframe to it).
//!
//! The lab fills whatever room its frame gives it, so "preferred" is the height at which what
//! it shows fits without cramping, in CSS pixels: the panels beside the view (the controls and
//! "Step through") need [`WITH_PANELS`] to show their first sections without scrolling; the view
//! with the tree diagram under it needs [`VIEW_AND_TREE`]; the view alone needs [`VIEW_ALONE`]. It
//! changes when the student shows or hides panels (the status line's buttons) or switches
//! between 2D and 3D (the tree diagram has its own switch in each).

use crate::address::PanelsShown;
use crate::model::Dimension;

/// With the controls or "Step through" beside the view, in CSS pixels.
pub const WITH_PANELS: u32 = 720;
/// The view with the tree diagram under it, no side panel.
pub const VIEW_AND_TREE: u32 = 600;
/// The view alone (`panels=`).
pub const VIEW_ALONE: u32 = 480;

/// The height the lab would like, in CSS pixels, for these panels in this view.
pub fn preferred_height(panels: &PanelsShown, dimension: Dimension) -> u32 {
    if panels.controls || panels.stepper {
        WITH_PANELS
    } else if panels.tree_in(dimension) {
        VIEW_AND_TREE
    } else {
        VIEW_ALONE
    }
}

/// The message posted to the embedding page.
pub fn size_message(height: u32) -> String {
    format!(r#"{{"bvhlab":"size","height":{height}}}"#)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_side_panels_need_the_most_room_and_the_view_alone_the_least() {
        let all = PanelsShown::default();
        assert_eq!(preferred_height(&all, Dimension::Two), WITH_PANELS);
        let tree = PanelsShown {
            controls: false,
            stepper: false,
            ..all
        };
        assert_eq!(preferred_height(&tree, Dimension::Two), VIEW_AND_TREE);
        // The 3D view's tree diagram is off by default.
        assert_eq!(preferred_height(&tree, Dimension::Three), VIEW_ALONE);
        let none = PanelsShown {
            tree: false,
            ..tree
        };
        assert_eq!(preferred_height(&none, Dimension::Two), VIEW_ALONE);
    }

    #[test]
    fn the_message_is_json_the_page_reads() {
        let message: serde_json::Value =
            serde_json::from_str(&size_message(720)).expect("valid JSON");
        assert_eq!(message["bvhlab"], "size");
        assert_eq!(message["height"], 720);
    }
}
