//! Oriented boxes as node volumes: the OBB tree (Gottschalk, Lin and Manocha, "`OBBTree`: A
//! Hierarchical Structure for Rapid Interference Detection", SIGGRAPH 1996).

use super::{GROW, HUGE, NodeVolume, PreparedRange, PreparedRay, growth, magnitude};
use crate::PointQuery;
use crate::Vector;
use crate::structure::RangeShape;
use crate::structure::bvh::BvhOptions;
use crate::volume::{Aabb, BoundingVolume, Obb};

impl<V: Vector> NodeVolume for Obb<V> {
    const NAME: &'static str = "OBB";
    const NEEDS_VERTICES: bool = true;

    /// Unit axes, pairwise orthogonal, to the tolerance a BSP plane's normal has (1e-5):
    /// the OBB tests measure distances in the box's frame, which is only a rotation then.
    fn is_well_formed(&self) -> bool {
        let axes = self.axes.as_ref();
        axes.iter().enumerate().all(|(i, a)| {
            a.is_finite()
                && (a.length() - 1.0).abs() < 1e-5
                && axes[i + 1..].iter().all(|b| a.dot(*b).abs() < 1e-5)
        }) && self.center.is_finite()
    }

    /// The lecture's PCA box ([`Obb::pca_fit`]) of the node's vertices, each half extent
    /// grown by [`SLACK`](super::SLACK) of the box's scale: a flat leaf (coplanar triangles)
    /// has a zero extent, and a ray through it must still be inside it after rounding to the
    /// box's frame. As with spheres, each node is fitted to its own primitives, so the boxes
    /// need not nest.
    ///
    /// With coordinates beyond [`HUGE`] the frame's `f32` arithmetic can overflow; a box
    /// that then fails to hold a vertex is replaced by the unbounded box (identity axes,
    /// infinite half extents), which every test accepts.
    fn fit(bounds: &Aabb<V>, vertices: &[V], _options: &BvhOptions) -> Self {
        let obb = Obb::pca_fit(vertices);
        if obb.is_empty() {
            return obb;
        }
        let grow = growth(obb.center, magnitude(obb.half_extents));
        let grown = Obb::new(obb.center, obb.axes, obb.half_extents + V::splat(grow));
        let finite = grown.center.is_finite()
            && (0..V::DIM).all(|i| !grown.half_extents.coord(i).is_nan())
            && grown.axes.as_ref().iter().all(|a| a.is_finite());
        let huge = magnitude(bounds.min).max(magnitude(bounds.max)) > HUGE;
        if !finite || (huge && !vertices.iter().all(|&v| grown.contains(v))) {
            return Obb::new(V::ZERO, V::identity_axes(), V::INFINITY);
        }
        grown
    }

    /// The PCA box of both children's corners, fitted and grown as [`fit`](Self::fit)
    /// fits a node to its vertices (a box around the corners holds both boxes, so every
    /// primitive below).
    fn enclose(first: &Self, second: &Self, options: &BvhOptions) -> Self {
        if second.is_empty() {
            return *first;
        }
        if first.is_empty() {
            return *second;
        }
        let corners: Vec<V> = first.corners().chain(second.corners()).collect();
        let bounds = corners.iter().fold(Aabb::EMPTY, |b, &c| b.grown(c));
        Self::fit(&bounds, &corners, options)
    }

    /// The slab test in the box's frame ([`Obb::slab_test`]) of the box grown by the ray's
    /// slack, its far end grown by [`GROW`] as for boxes.
    fn ray_entry(&self, ray: &PreparedRay<V>) -> Option<(f32, f32)> {
        let grown = Obb::new(
            self.center,
            self.axes,
            self.half_extents + V::splat(ray.slack),
        );
        match grown.slab_test(&ray.ray) {
            Some(slabs) => {
                let (t_enter, t_exit) = (slabs.t_enter().max(0.0), slabs.t_exit());
                (t_enter <= t_exit * GROW).then_some((t_enter, t_exit))
            }
            // A direction that vanishes in the frame: the ray stays at its origin.
            None => grown.contains(ray.origin).then_some((0.0, f32::INFINITY)),
        }
    }

    fn overlaps_range(&self, range: &PreparedRange<V>) -> bool {
        match &range.shape {
            RangeShape::Box(_) => self.overlaps(&range.as_obb),
            RangeShape::Ball(s) => range
                .grown_radius()
                .is_some_and(|r| !s.is_empty() && self.distance(s.center) <= r),
        }
    }
}
