//! What a press on the view does: the 2D canvas's tools and the 3D view's.

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

/// What a click on the 3D view does.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Tool3d {
    /// Cast a ray from the camera through the clicked pixel.
    #[default]
    Ray,
    /// Put the query point where the click meets the mesh.
    Point,
}
