//! The AABB tree as the compute shader reads it: the core's depth-first nodes as they are
//! (32 bytes each, the same layout), and the triangles in leaf order with their input
//! indices, so that a leaf's `start..start + count` indexes the triangle array directly.

use bvhlab::prelude::SpatialIndex;
use bvhlab::structure::NodeId;
use bvhlab::{AabbTree3, Triangle3};

/// One node (`Node` in `trace.wgsl`): the box, then the core's `start` and `count`.
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub struct GpuNode {
    /// The box's lower corner.
    pub min: [f32; 3],
    /// Leaf: its first triangle in leaf order. Inner node: its second child.
    pub start: u32,
    /// The box's upper corner.
    pub max: [f32; 3],
    /// Leaf: its triangle count (at least 1). Inner node: 0.
    pub count: u32,
}

const _: () = assert!(size_of::<GpuNode>() == 32);

/// One triangle (`Tri` in `trace.wgsl`), 48 bytes: each corner padded to 16 as WGSL lays out
/// a `vec3<f32>`, the padding holding the input index and the flags.
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub struct GpuTriangle {
    /// First corner.
    pub a: [f32; 3],
    /// The triangle's index in the tree's input (ties between equal hits go to the lower).
    pub id: u32,
    /// Second corner.
    pub b: [f32; 3],
    /// [`DEGENERATE`] or 0.
    pub flags: u32,
    /// Third corner.
    pub c: [f32; 3],
    /// Unused.
    pub pad: u32,
}

const _: () = assert!(size_of::<GpuTriangle>() == 48);

/// Flag of a zero-area triangle ([`Triangle3::is_degenerate`], decided in `f64` once here):
/// the core never reports a hit on it, but still counts its test.
pub const DEGENERATE: u32 = 1;

/// The arrays the shader reads.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FlatTree {
    /// The nodes, depth-first, root first (empty for an empty tree).
    pub nodes: Vec<GpuNode>,
    /// The indexed triangles in leaf order.
    pub triangles: Vec<GpuTriangle>,
}

/// Flattens the tree: its nodes as they are, and each leaf's triangles (the tree's input
/// looked up by [`AabbTree3::leaf_primitives`]) at the leaf's positions in leaf order.
pub fn flatten(tree: &AabbTree3) -> FlatTree {
    let prims = tree.primitives();
    let mut triangles = Vec::new();
    let nodes = tree
        .nodes()
        .iter()
        .enumerate()
        .map(|(i, node)| {
            if node.is_leaf() {
                let start = node.start as usize;
                let ids = tree.leaf_primitives(NodeId(i as u32));
                if triangles.len() < start + ids.len() {
                    triangles.resize(start + ids.len(), GpuTriangle::default());
                }
                for (slot, &id) in triangles[start..].iter_mut().zip(ids) {
                    *slot = gpu_triangle(&prims[id as usize], id);
                }
            }
            GpuNode {
                min: node.volume.min.to_array(),
                start: node.start,
                max: node.volume.max.to_array(),
                count: node.count,
            }
        })
        .collect();
    FlatTree { nodes, triangles }
}

fn gpu_triangle(t: &Triangle3, id: u32) -> GpuTriangle {
    GpuTriangle {
        a: t.a.to_array(),
        id,
        b: t.b.to_array(),
        flags: if t.is_degenerate() { DEGENERATE } else { 0 },
        c: t.c.to_array(),
        pad: 0,
    }
}
