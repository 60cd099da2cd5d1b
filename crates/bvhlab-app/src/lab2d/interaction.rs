//! A drag or a drawing in progress on the canvas: UI state, not the lab's (it is not saved,
//! and the lab changes only when the drag says so with an action).

use bvhlab::glam::Vec2;

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
#[derive(Clone, Debug, Default, PartialEq)]
pub enum Interaction {
    /// Nothing.
    #[default]
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
