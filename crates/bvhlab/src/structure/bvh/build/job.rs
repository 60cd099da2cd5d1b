//! A BVH build that runs in slices, with progress: the browser lab is single-threaded
//! WebAssembly, and a million-triangle mesh must build without freezing the page. The app
//! calls [`BvhBuild::step`] with a budget every frame and draws [`BuildProgress::fraction`].
//!
//! The slices run the one builder that [`Bvh::build_with`] runs in one go (`build.rs`), so
//! the tree is the same to the bit whatever the budgets were: the same nodes in the same
//! order, the same volumes, the same leaf order.

use std::fmt;

use super::{Builder, Fits};
use crate::Primitive;
use crate::structure::bvh::volume::NodeVolume;
use crate::structure::bvh::{Bvh, BvhOptions};

/// What a build in slices is doing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BuildPhase {
    /// Computing each primitive's box and centre, and leaving out those with a NaN or
    /// infinite coordinate.
    Preparing,
    /// Fitting a node's volume: merging its primitives' boxes, gathering their vertices,
    /// fitting the sphere or oriented box around them.
    Fitting,
    /// Choosing a node's split plane (SAH binning or a median) and partitioning its
    /// primitives.
    Splitting,
    /// Copying the primitives into leaf order.
    Ordering,
    /// The tree is complete.
    Done,
}

/// How far a build is: `done` of `total` units, where every input primitive counts three
/// units, one when its box is computed, one when it reaches a finished leaf and one when it
/// is copied into leaf order (a primitive left out for a non-finite coordinate counts all
/// three at once). `done` never decreases and equals `total` exactly when the tree is
/// complete.
///
/// These are progress units, not [`BvhBuild::step`]'s work units: a primitive is read once
/// per level of the tree while its leaf is not finished, so the fraction moves slowly at
/// first (the first leaf is finished after the whole left spine, about `2n` work) and
/// roughly linearly after.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BuildProgress {
    /// Units done.
    pub done: usize,
    /// Units in the whole build: three per input primitive.
    pub total: usize,
    /// What the build is doing now.
    pub phase: BuildPhase,
}

impl BuildProgress {
    /// `done / total` in `[0, 1]`: never decreasing during a build, `1` exactly when the
    /// tree is complete (an empty input is complete from the start).
    pub fn fraction(&self) -> f32 {
        if self.done >= self.total {
            return 1.0;
        }
        // Rounding must not show 100% before the end.
        ((self.done as f64 / self.total as f64) as f32).min(1.0f32.next_down())
    }

    /// Whether the tree is complete.
    pub fn is_done(&self) -> bool {
        self.phase == BuildPhase::Done
    }
}

/// A [`Bvh`] build that can be run in slices of bounded work ([`step`](Self::step)), for a
/// single-threaded caller that must stay responsive. It owns its input.
///
/// The tree is exactly the one [`Bvh::build_with`] builds from the same input and options,
/// whatever the budgets of the steps.
///
/// ```
/// use bvhlab::glam::Vec3;
/// use bvhlab::prelude::*;
/// use bvhlab::structure::bvh::{BvhBuild, BvhOptions, ObbTree};
///
/// let tris: Vec<Triangle3> = (0..100)
///     .map(|i| {
///         let a = Vec3::new(i as f32, 0.0, 0.0);
///         Triangle3::new(a, a + Vec3::Y, a + Vec3::Z)
///     })
///     .collect();
/// let mut build = BvhBuild::new(tris.clone(), BvhOptions::default());
/// let mut last = 0.0;
/// while !build.is_done() {
///     let progress = build.step(50);
///     assert!(progress.fraction() >= last);
///     last = progress.fraction();
/// }
/// let tree: ObbTree<Triangle3> = build.finish();
/// assert_eq!(tree, ObbTree::build_with(&tris, &BvhOptions::default()));
/// ```
pub struct BvhBuild<B, P: Primitive> {
    prims: Vec<P>,
    builder: Builder<B, P>,
}

impl<B, P> BvhBuild<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    /// A build of `prims` with `options` that has not started (an empty input is complete
    /// at once).
    pub fn new(prims: Vec<P>, options: BvhOptions) -> Self {
        Self {
            builder: Builder::new(prims.len(), options, Fits::Sliced, false),
            prims,
        }
    }

    /// Works on the build until about `budget` work units are done or the tree is complete,
    /// and returns the progress.
    ///
    /// A work unit is one primitive (or, in a sphere or OBB fit, one vertex) read in one
    /// pass: computing its box, merging it into a node's box, gathering its vertices,
    /// binning it, partitioning it, copying it into leaf order. Every pass over a node's
    /// primitives stops when the budget is spent and resumes at the next step, including the
    /// PCA box and Ritter sphere fits (four passes over the vertices each) and the SAH
    /// binning. In the test profile (opt-level 1, native) a unit takes 10-50 ns, so a budget
    /// of 50,000 is a step of 0.5-2.5 ms.
    ///
    /// Two pieces are done in one go: a node's object median (a selection, one unit per
    /// primitive; about 6 ms for the root of a million triangles in the test profile), and
    /// a node's Welzl sphere ([`SphereFit::Welzl`]; up to 200 ms
    /// near the root of a million triangles: prefer Ritter's for large inputs). Such a piece
    /// does not start in a step that has already used part of its budget unless it fits in
    /// the rest, so a step takes at most the larger of its budget and one such piece.
    ///
    /// A budget of 0 does nothing; any positive budget does at least one unit.
    ///
    /// [`SphereFit::Welzl`]: crate::structure::bvh::SphereFit::Welzl
    pub fn step(&mut self, budget: usize) -> BuildProgress {
        self.builder.run(&self.prims, budget, &mut ());
        self.progress()
    }

    /// How far the build is.
    pub fn progress(&self) -> BuildProgress {
        self.builder.progress()
    }

    /// Whether the tree is complete ([`finish`](Self::finish) then only assembles it).
    pub fn is_done(&self) -> bool {
        self.builder.is_done()
    }

    /// The tree: does whatever work is left in one go (none after the last step) and
    /// assembles it. Assembling trims the node array to its length, which copies it on
    /// some allocators (WebAssembly's among them).
    pub fn finish(mut self) -> Bvh<B, P> {
        self.builder.run(&self.prims, usize::MAX, &mut ());
        self.builder.into_bvh(self.prims).0
    }
}

impl<B, P: Primitive> fmt::Debug for BvhBuild<B, P> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("BvhBuild")
            .field("prims", &self.prims.len())
            .finish_non_exhaustive()
    }
}
