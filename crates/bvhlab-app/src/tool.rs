//! The canvas tools and the interaction in progress.

use bvhlab::glam::Vec2;

/// What a primary-button press on the canvas does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Tool {
    /// Click a shape to select it (shift adds), drag a selected shape to move it.
    Select,
    /// Drag to draw a segment.
    Segment,
    /// Click points; double-click or Enter ends the polyline.
    Polyline,
    /// Click points; double-click or Enter closes the polygon.
    Polygon,
    /// Click to add points to a cloud.
    Points,
    /// Drag from the ray's origin toward its direction; drag either handle to adjust.
    Ray,
    /// Click or drag to place the closest-point query.
    Point,
    /// Drag the two boxes of the separating-axis demo, or their rotation handles.
    Obb,
    /// Drag to pan (the right or middle button pans with any tool).
    Pan,
}

impl Tool {
    /// Every tool, in toolbar order.
    pub const ALL: [Self; 9] = [
        Self::Select,
        Self::Segment,
        Self::Polyline,
        Self::Polygon,
        Self::Points,
        Self::Ray,
        Self::Point,
        Self::Obb,
        Self::Pan,
    ];

    /// The toolbar label.
    pub fn label(self) -> &'static str {
        match self {
            Self::Select => "Select / move",
            Self::Segment => "Segment",
            Self::Polyline => "Polyline",
            Self::Polygon => "Polygon",
            Self::Points => "Points",
            Self::Ray => "Ray",
            Self::Point => "Query point",
            Self::Obb => "Two OBBs (SAT)",
            Self::Pan => "Pan",
        }
    }

    /// What to do with it, for the status line.
    pub fn hint(self) -> &'static str {
        match self {
            Self::Select => {
                "Click a shape to select it (shift: add to the selection), drag it to move it, Delete removes it."
            }
            Self::Segment => "Drag to draw a segment.",
            Self::Polyline => "Click to add points; double-click or Enter finishes, Esc cancels.",
            Self::Polygon => "Click to add corners; double-click or Enter closes it, Esc cancels.",
            Self::Points => "Click to add points to the cloud.",
            Self::Ray => {
                "Drag from the ray's origin e toward its direction; drag e or s to adjust."
            }
            Self::Point => "Click or drag to move the query point.",
            Self::Obb => "Drag a box to move it, drag its round handle to turn it.",
            Self::Pan => "Drag to pan; scroll to zoom.",
        }
    }
}

/// Which end of the ray a drag holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RayEnd {
    /// The origin e.
    Origin,
    /// The point s the ray passes through.
    Target,
}

/// Which part of the separating-axis demo a drag holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BoxGrip {
    /// Box `0` or `1`, moved.
    Move(usize),
    /// Box `0` or `1`, turned.
    Turn(usize),
}

/// A drag or drawing in progress.
#[derive(Clone, Debug, PartialEq)]
pub enum Interaction {
    /// Nothing.
    None,
    /// A segment from this point to the pointer.
    Segment(Vec2),
    /// A polyline or polygon's points so far.
    Chain(Vec<Vec2>),
    /// Adding to the point cloud with this shape index.
    Cloud(usize),
    /// Moving the selected shapes; the last pointer position.
    Move(Vec2),
    /// Dragging an end of the ray.
    Ray(RayEnd),
    /// Dragging the query point.
    Point,
    /// Dragging a box of the separating-axis demo.
    Box(BoxGrip),
}
