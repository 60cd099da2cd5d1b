//! The lecture's splits: along the longest axis of the centres' box, at its middle (spatial
//! median) or at the median centre (object median).

use super::build::{BuildPrim, Split, partition};
use crate::Vector;
use crate::volume::Aabb;

/// The lecture's split at the middle of the longest axis of the centres' box: primitives
/// whose centre lies below the middle go left. `None` when every centre falls on one side
/// (they coincide along that axis, or the extent overflowed): the caller then takes the
/// object median.
pub(super) fn spatial_median<V: Vector>(
    items: &mut [BuildPrim<V>],
    centroids: &Aabb<V>,
) -> Option<Split> {
    let axis = centroids.longest_axis();
    // Halving before adding cannot overflow.
    let position = centroids.min.coord(axis) * 0.5 + centroids.max.coord(axis) * 0.5;
    let mid = partition(items, |item| item.centroid.coord(axis) < position);
    (mid > 0 && mid < items.len()).then_some(Split {
        axis,
        position,
        left: mid,
        cost: None,
    })
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
