//! The AABB tree as the compute shader reads it: the core's GPU layout
//! ([`bvhlab::structure::bvh::layout::gpu`], which `trace.wgsl` mirrors), as the words the
//! storage buffers hold.

use bvhlab::AabbTree3;
use bvhlab::structure::bvh::layout::gpu::GpuTree;

pub use bvhlab::structure::bvh::layout::gpu::{DEGENERATE, GpuNode, GpuTriangle};

/// The arrays the shader reads, as `u32` words ready to upload.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FlatTree {
    /// The nodes ([`GpuNode::to_words`]), depth-first, root first (empty for an empty tree).
    pub nodes: Vec<[u32; 8]>,
    /// The indexed triangles in leaf order ([`GpuTriangle::to_words`]).
    pub triangles: Vec<[u32; 12]>,
}

/// Flattens the tree ([`GpuTree::flatten`]) into the words of its nodes and triangles.
pub fn flatten(tree: &AabbTree3) -> FlatTree {
    let flat = GpuTree::flatten(tree);
    FlatTree {
        nodes: flat.node_words(),
        triangles: flat.triangle_words(),
    }
}
