//! Node fits in resumable passes, for a build run in slices ([`BvhBuild`]).
//!
//! An OBB-tree node's PCA box and a sphere-tree node's Ritter sphere read every vertex below
//! the node several times: the mean, the covariance and two projections for the box; two
//! farthest-point searches, the growing pass and the final radius for the sphere. At the root
//! of a million triangles (3M vertices) the PCA box alone takes about 65 ms in the test
//! profile, too long for one frame of a page that must stay responsive. Here each pass is the
//! same fold as in [`Obb::pca_fit`] and [`Sphere::ritter_fit`] followed by the node volume's
//! own growth and checks (`volume/obb.rs`, `volume/sphere.rs`), over the same points in the same
//! order and the same precision, only stopped and resumed between chunks, so the volume is
//! the same to the bit. The tests compare both, volume by volume and tree by tree.
//!
//! Welzl's sphere ([`SphereFit::Welzl`]) is not split: its move-to-front recursion restarts
//! on every point outside the current ball, so it is fitted in one go.
//!
//! [`BvhBuild`]: crate::structure::bvh::BvhBuild

mod obb;
mod sphere;
#[cfg(test)]
mod tests;

use std::any::{Any, TypeId};

use self::obb::PcaBoxPasses;
use self::sphere::RitterPasses;
use super::NodeVolume;
use crate::Vector;
use crate::structure::bvh::{BvhOptions, SphereFit};
use crate::volume::{Aabb, Obb, Sphere};

/// A node fit in progress, one pass at a time.
#[derive(Clone, Debug)]
pub(in crate::structure::bvh) enum SlicedFit<V: Vector> {
    /// The PCA box of an OBB-tree node.
    PcaBox(PcaBoxPasses<V>),
    /// Ritter's sphere of a sphere-tree node.
    Ritter(RitterPasses<V>),
}

impl<V: Vector> SlicedFit<V> {
    /// The resumable fit of node volume `B` for a node with bounds `bounds`, or `None` when
    /// `B`'s fit is fitted in one go (boxes need no vertices; Welzl's sphere). The node's
    /// vertices must be finite and not empty (the builder leaves out non-finite primitives
    /// and makes no empty nodes).
    pub fn for_volume<B: NodeVolume<Point = V>>(
        bounds: &Aabb<V>,
        options: &BvhOptions,
    ) -> Option<Self> {
        let volume = TypeId::of::<B>();
        if volume == TypeId::of::<Obb<V>>() {
            Some(Self::PcaBox(PcaBoxPasses::new(bounds)))
        } else if volume == TypeId::of::<Sphere<V>>() && options.sphere_fit == SphereFit::Ritter {
            Some(Self::Ritter(RitterPasses::new(bounds)))
        } else {
            None
        }
    }

    /// Runs the passes over `points` until about `units` points (at least one) have been
    /// read or the fit is done; returns how many were read.
    pub fn advance(&mut self, points: &[V], units: usize) -> usize {
        match self {
            Self::PcaBox(fit) => fit.advance(points, units),
            Self::Ritter(fit) => fit.advance(points, units),
        }
    }

    /// Whether every pass is done.
    pub fn is_done(&self) -> bool {
        match self {
            Self::PcaBox(fit) => fit.result().is_some(),
            Self::Ritter(fit) => fit.result().is_some(),
        }
    }

    /// The fitted volume, once every pass is done, as the node volume type it was made
    /// for.
    pub fn volume<B: Copy + 'static>(&self) -> Option<B> {
        match self {
            Self::PcaBox(fit) => fit.result().and_then(|obb| same_type(&obb)),
            Self::Ritter(fit) => fit.result().and_then(|sphere| same_type(&sphere)),
        }
    }
}

/// `value` as `B`, when `B` is its type ([`SlicedFit::for_volume`] chose the fit by it).
fn same_type<T: 'static, B: Copy + 'static>(value: &T) -> Option<B> {
    (value as &dyn Any).downcast_ref::<B>().copied()
}

/// Where a pass stands: the next point to read.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Cursor {
    next: usize,
}

impl Cursor {
    /// The next chunk of at most `units` points (at least one), and moves past it. Empty
    /// when the pass has read every point.
    pub fn chunk<'a, V>(&mut self, points: &'a [V], units: usize) -> &'a [V] {
        let start = self.next.min(points.len());
        let end = start + units.max(1).min(points.len() - start);
        self.next = end;
        &points[start..end]
    }

    /// Whether the pass has read every point.
    pub fn at_end<V>(self, points: &[V]) -> bool {
        self.next >= points.len()
    }
}
