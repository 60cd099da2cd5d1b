//! What differs between the lab's two halves, as far as the model goes: the primitive the
//! structures are built on (a 2D segment or a 3D triangle), and how much of each job is
//! offered at that size. Everything else (lanes, questions, recordings, playback) is one
//! generic implementation over [`LabPrimitive`].

use bvhlab::{Primitive, Segment2, Triangle3};

/// Which half of the lab is shown.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Dimension {
    /// Segments drawn on the 2D canvas.
    #[default]
    Two,
    /// Meshes in the 3D view.
    Three,
}

/// A primitive the lab builds structures on, with the limits of its half.
pub trait LabPrimitive: Primitive + Copy + std::fmt::Debug + 'static {
    /// Its half.
    const DIMENSION: Dimension;
    /// The most primitives every structure is offered for; past it, only BVHs (a BSP tree
    /// or an SAH k-d tree over a million triangles would take minutes and gigabytes) and
    /// brute force.
    const MAX_FOR_EVERY_STRUCTURE: usize;
    /// The most primitives whose structure's nodes are all listed ([`bvhlab::Outline`]) for
    /// drawing and for the tree diagram; past it, BVHs are drawn from their nodes directly
    /// and the diagram says the tree is too large to draw.
    const MAX_LISTED: usize;
    /// The most primitives whose build can be stepped through (a build's recording holds a
    /// few events per node).
    const MAX_BUILD_STEPPING: usize;
    /// What the primitives are called in messages ("segments", "triangles").
    const NAME: &'static str;
}

impl LabPrimitive for Segment2 {
    const DIMENSION: Dimension = Dimension::Two;
    const MAX_FOR_EVERY_STRUCTURE: usize = usize::MAX;
    const MAX_LISTED: usize = usize::MAX;
    const MAX_BUILD_STEPPING: usize = usize::MAX;
    const NAME: &'static str = "segments";
}

impl LabPrimitive for Triangle3 {
    const DIMENSION: Dimension = Dimension::Three;
    const MAX_FOR_EVERY_STRUCTURE: usize = 250_000;
    const MAX_LISTED: usize = 250_000;
    const MAX_BUILD_STEPPING: usize = 30_000;
    const NAME: &'static str = "triangles";
}

/// The plural ending for `n` things: `""` for one, `"s"` otherwise.
pub fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

/// `1234567` as `1,234,567`.
pub fn thousands(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}
