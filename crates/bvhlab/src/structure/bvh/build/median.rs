//! The lecture's splits: along the longest axis of the centres' box, at its middle (spatial
//! median) or at the median centre (object median).

use super::{BuildPrim, Split};
use crate::Vector;
use crate::volume::Aabb;

/// The lecture's plane at the middle of the longest axis of the centres' box, as `(axis,
/// position)`: primitives whose centre lies below `position` go left. The builder
/// partitions them (in steps, for a resumable build) and takes the object median when every
/// centre falls on one side (they coincide along that axis, or the extent overflowed).
pub(super) fn spatial_median_plane<V: Vector>(centroids: &Aabb<V>) -> (usize, f32) {
    let axis = centroids.longest_axis();
    // Halving before adding cannot overflow.
    let position = centroids.min.coord(axis) * 0.5 + centroids.max.coord(axis) * 0.5;
    (axis, position)
}

/// Half the primitives on each side, by their centres along the longest axis of the
/// centres' box (ties in any order). Needs at least two primitives; always splits them.
pub(super) fn object_median<V: Vector>(items: &mut [BuildPrim<V>], centroids: &Aabb<V>) -> Split {
    let axis = centroids.longest_axis();
    let mid = items.len() / 2;
    let key = |item: &BuildPrim<V>| item.centroid.coord(axis);
    items.select_nth_unstable_by(mid, |a, b| key(a).total_cmp(&key(b)));
    Split {
        axis,
        position: key(&items[mid]),
        left: mid,
        cost: None,
    }
}
