//! Refitting a tree after its primitives moved: the same topology, every volume fitted
//! again bottom-up, in time linear in the nodes.
//!
//! The standard refit of Wald, Boulos and Shirley, "Ray Tracing Deformable Scenes Using
//! Dynamic Bounding Volume Hierarchies" (ACM TOG 26(1), 2007), as parry (`bvh_refit.rs`),
//! tinybvh (`Refit`) and three-mesh-bvh (`refit`) do it: a leaf's volume is fitted to its
//! primitives' new positions, an inner node's to its two children's volumes
//! ([`NodeVolume::enclose`]), children before parents (the depth-first array backwards). The
//! tree keeps its shape, so its quality decays as the primitives drift from where the
//! build grouped them: [`RefitReport`] gives the SAH cost before and after, and
//! [`Bvh::needs_rebuild`] says when it has grown past what the caller accepts (Wald et al.
//! rebuild when the cost has grown by a chosen factor; Kopta et al., "Fast, Effective BVH
//! Updates for Animated Scenes", I3D 2012, measure the same ratio).

use std::fmt;

use super::Bvh;
use super::volume::NodeVolume;
use crate::Primitive;
use crate::volume::{Aabb, BoundingVolume};

/// Why a tree cannot be refitted to the primitives given: the caller must rebuild it.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum RefitError {
    /// A refit keeps the primitives; it was given a different number of them.
    LengthChanged {
        /// How many the tree was built over.
        built: usize,
        /// How many were given.
        given: usize,
    },
    /// A primitive left out of the tree (a NaN or infinite vertex) became finite, or one in
    /// the tree got a NaN or infinite vertex: the tree's set of primitives would change.
    IndexableChanged {
        /// The primitive's input index.
        prim: usize,
        /// Whether it is finite now.
        finite_now: bool,
    },
}

impl fmt::Display for RefitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::LengthChanged { built, given } => write!(
                f,
                "the tree was built over {built} primitives and refitted to {given}; a refit \
                 keeps the primitives (only their positions change): rebuild the tree instead"
            ),
            Self::IndexableChanged { prim, finite_now } => {
                let what = if *finite_now {
                    "was left out (a NaN or infinite vertex) and is finite now"
                } else {
                    "now has a NaN or infinite vertex"
                };
                write!(
                    f,
                    "primitive {prim} {what}, so the tree's set of primitives would change: \
                     rebuild the tree instead"
                )
            }
        }
    }
}

impl std::error::Error for RefitError {}

/// What a refit did to the tree's quality: its SAH cost now and when it was built.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefitReport {
    /// The SAH cost after the refit ([`Stats::sah_cost`](crate::structure::Stats::sah_cost)).
    pub sah_cost: Option<f32>,
    /// The SAH cost when the tree was built.
    pub build_sah_cost: Option<f32>,
}

impl RefitReport {
    /// The SAH cost now over the cost at build time (`None` when either is undefined: a
    /// flat root has no area to normalise by).
    pub fn cost_ratio(&self) -> Option<f32> {
        Some(self.sah_cost? / self.build_sah_cost?)
    }

    /// Whether a rebuild pays: the SAH cost has grown past `max_growth` times the cost at
    /// build time (1.5: by half). When one of the two costs is undefined and the other is
    /// not, the scene changed shape so much (it became flat, or stopped being flat) that a
    /// rebuild is advised; when both are undefined, not.
    pub fn needs_rebuild(&self, max_growth: f32) -> bool {
        match (self.sah_cost, self.build_sah_cost) {
            (Some(now), Some(built)) => now > built * max_growth,
            (None, None) => false,
            _ => true,
        }
    }
}

/// Checks that `new` can replace `old` in a refit: the same count, and the same primitives
/// indexable (all vertices finite).
pub(super) fn check_same_primitives<P: Primitive>(
    built: usize,
    indexed: impl Fn(usize) -> bool,
    new: &[P],
) -> Result<(), RefitError> {
    if new.len() != built {
        return Err(RefitError::LengthChanged {
            built,
            given: new.len(),
        });
    }
    for (prim, p) in new.iter().enumerate() {
        let finite_now = p.has_finite_coordinates();
        if finite_now != indexed(prim) {
            return Err(RefitError::IndexableChanged { prim, finite_now });
        }
    }
    Ok(())
}

/// The union of the primitives' boxes.
pub(super) fn bounds_of<P: Primitive>(prims: &[P]) -> Aabb<P::Point> {
    prims
        .iter()
        .fold(Aabb::EMPTY, |bounds, p| bounds.merge(&p.bounds()))
}

impl<B, P> Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    /// Refits the tree to `prims`, the primitives it was built over after they moved (the
    /// same count, in the same order): every node keeps its children and primitives, and
    /// its volume is fitted again, leaves to their primitives ([`NodeVolume::fit`]) and
    /// inner nodes to their children ([`NodeVolume::enclose`]), bottom-up, in time linear in
    /// the nodes (Wald, Boulos and Shirley 2007). Every query then answers as brute force
    /// on the moved primitives, and [`validate`](crate::SpatialIndex::validate) holds.
    ///
    /// The tree's quality decays as primitives move away from where the build grouped
    /// them; the report gives the SAH cost now and at build time, and
    /// [`needs_rebuild`](Self::needs_rebuild) compares them.
    ///
    /// ```
    /// use bvhlab::glam::Vec3;
    /// use bvhlab::prelude::*;
    ///
    /// let mut tris: Vec<Triangle3> = (0..100)
    ///     .map(|i| {
    ///         let p = Vec3::new(i as f32, 0.0, 0.0);
    ///         Triangle3::new(p, p + Vec3::X * 0.8, p + Vec3::Z)
    ///     })
    ///     .collect();
    /// let mut tree = AabbTree3::build(&tris);
    /// for t in &mut tris {
    ///     t.a.y += 5.0; // every triangle moves up...
    ///     t.b.y += 5.0;
    ///     t.c.y += 5.0;
    /// }
    /// let report = tree.refit(&tris)?;
    /// tree.validate()?;
    /// let down = Ray3::new(Vec3::new(7.1, 9.0, 0.1), -Vec3::Y)?;
    /// assert_eq!(tree.ray_first_hit(&down, f32::INFINITY).map(|h| h.prim), Some(7));
    /// // ...together: the boxes keep their shapes, so no rebuild is needed.
    /// assert!(!report.needs_rebuild(1.5));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// [`RefitError`] when the count differs or a primitive became (or stopped being)
    /// non-finite; the tree is then left unchanged.
    pub fn refit(&mut self, prims: &[P]) -> Result<RefitReport, RefitError> {
        check_same_primitives(
            self.prims.len(),
            |i| self.prims[i].has_finite_coordinates(),
            prims,
        )?;
        self.prims.copy_from_slice(prims);
        for (slot, &id) in self.leaf_prims.iter_mut().zip(&self.leaf_ids) {
            *slot = prims[id as usize];
        }
        let mut vertices = Vec::new();
        // Children come after their parent in the depth-first array: backwards, both
        // children are refitted before their parent.
        for i in (0..self.nodes.len()).rev() {
            let node = self.nodes[i];
            let volume = if node.is_leaf() {
                let leaf = &self.leaf_prims[node.leaf_range()];
                vertices.clear();
                if B::NEEDS_VERTICES {
                    vertices.extend(leaf.iter().flat_map(Primitive::vertices));
                }
                B::fit(&bounds_of(leaf), &vertices, &self.options)
            } else {
                let (first, second) = (&self.nodes[i + 1], &self.nodes[node.start as usize]);
                B::enclose(&first.volume, &second.volume, &self.options)
            };
            self.nodes[i].volume = volume;
        }
        Ok(self.refit_report())
    }

    /// The SAH cost now and at build time.
    pub fn refit_report(&self) -> RefitReport {
        RefitReport {
            sah_cost: self.sah_cost(),
            build_sah_cost: self.build_sah_cost,
        }
    }

    /// Whether a rebuild pays: the SAH cost has grown past `max_growth` times what it was
    /// when the tree was built ([`RefitReport::needs_rebuild`]). A freshly built tree never
    /// needs one for `max_growth >= 1`.
    pub fn needs_rebuild(&self, max_growth: f32) -> bool {
        self.refit_report().needs_rebuild(max_growth)
    }
}
