//! The AABB tree as a GPU compute shader reads it: the layout of the app's traversal-cost heat
//! map, which traces each pixel's ray through the tree on the GPU exactly as the core's
//! observed first-hit walk does (`walk/ray.rs`) and must count the same nodes and triangles.
//!
//! **Mirrored in WGSL.** `crates/bvhlab-app/src/render3d/heatmap/trace.wgsl` declares the
//! structs `Node` ([`GpuNode`]) and `Tri` ([`GpuTriangle`]) with the same fields at the same
//! offsets, and its `STACK` is the walk's stack capacity, [`MAX_DEPTH`]` + 2`. A change here
//! must be made there too, and the reverse: the app's shader test
//! (`crates/bvhlab-app/tests/shaders.rs`, `the_gpu_tree_layout_is_the_wgsl_layout`) parses
//! the WGSL with naga and fails when a field's name, offset or size, a struct's size or the
//! stack capacity differ.
//!
//! The node is not [`BvhNode`] as it is: WGSL aligns a `vec3<f32>` to 16 bytes, so the box's
//! corners cannot follow each other, and `start` fills the gap after `min` (32 bytes either
//! way). Triangles are stored in leaf order with their input index, each corner padded to 16
//! bytes, the padding holding the index and the flags, so that a leaf's
//! `start..start + count` indexes the triangle array directly.
//!
//! The core depends on `glam` alone, so these types derive no `bytemuck` traits: the app
//! uploads [`GpuNode::to_words`] and [`GpuTriangle::to_words`] (plain `u32` arrays, in
//! field order), which the tests here hold to the structs' own layout.
//!
//! [`MAX_DEPTH`]: crate::structure::bvh::MAX_DEPTH

use glam::Vec3;

use super::{Bvh, BvhNode};
use crate::Triangle3;
use crate::structure::{NodeId, SpatialIndex};
use crate::volume::Aabb;

/// One node (`Node` in `trace.wgsl`), 32 bytes: the box, then the core's `start` and
/// `count`.
///
/// ```text
/// offset  0  min     3 × f32
/// offset 12  start   u32       leaf: first triangle (leaf order); inner: second child
/// offset 16  max     3 × f32
/// offset 28  count   u32       leaf: triangle count (>= 1); inner: 0
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
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

impl GpuNode {
    /// The node as the shader reads it: its fields in order, each as a `u32` (an `f32` by its
    /// bits).
    pub fn to_words(&self) -> [u32; 8] {
        let [x0, y0, z0] = self.min.map(f32::to_bits);
        let [x1, y1, z1] = self.max.map(f32::to_bits);
        [x0, y0, z0, self.start, x1, y1, z1, self.count]
    }
}

/// One triangle (`Tri` in `trace.wgsl`), 48 bytes: each corner padded to 16 as WGSL lays out
/// a `vec3<f32>`, the padding holding the input index and the flags.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
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

impl GpuTriangle {
    /// The triangle as the shader reads it: its fields in order, each as a `u32` (an `f32`
    /// by its bits).
    pub fn to_words(&self) -> [u32; 12] {
        let [ax, ay, az] = self.a.map(f32::to_bits);
        let [bx, by, bz] = self.b.map(f32::to_bits);
        let [cx, cy, cz] = self.c.map(f32::to_bits);
        [
            ax, ay, az, self.id, bx, by, bz, self.flags, cx, cy, cz, self.pad,
        ]
    }
}

/// Flag of a zero-area triangle ([`Triangle3::is_degenerate`], decided in `f64` once here):
/// the core never reports a hit on it, but still counts its test.
pub const DEGENERATE: u32 = 1;

/// The arrays the shader reads.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GpuTree {
    /// The nodes, depth-first, root first (empty for an empty tree).
    pub nodes: Vec<GpuNode>,
    /// The indexed triangles in leaf order.
    pub triangles: Vec<GpuTriangle>,
}

impl GpuTree {
    /// Flattens the tree: its nodes in their order, and each leaf's triangles (the tree's
    /// input looked up by [`Bvh::leaf_primitives`]) at the leaf's positions in leaf order.
    pub fn flatten(tree: &Bvh<Aabb<Vec3>, Triangle3>) -> Self {
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
                gpu_node(node)
            })
            .collect();
        Self { nodes, triangles }
    }

    /// The nodes as [`GpuNode::to_words`] gives them, ready to upload.
    pub fn node_words(&self) -> Vec<[u32; 8]> {
        self.nodes.iter().map(GpuNode::to_words).collect()
    }

    /// The triangles as [`GpuTriangle::to_words`] gives them, ready to upload.
    pub fn triangle_words(&self) -> Vec<[u32; 12]> {
        self.triangles.iter().map(GpuTriangle::to_words).collect()
    }
}

fn gpu_node(node: &BvhNode<Aabb<Vec3>>) -> GpuNode {
    GpuNode {
        min: node.volume.min.to_array(),
        start: node.start,
        max: node.volume.max.to_array(),
        count: node.count,
    }
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

#[cfg(test)]
mod tests {
    use std::mem::offset_of;

    use super::*;
    use crate::structure::bvh::AabbTree;

    /// The word at the byte `offset` of the struct.
    fn word(words: &[u32], offset: usize) -> u32 {
        assert_eq!(offset % 4, 0, "fields lie on 4-byte boundaries");
        words[offset / 4]
    }

    #[test]
    fn node_words_follow_the_structs_layout() {
        let node = GpuNode {
            min: [1.0, 2.0, 3.0],
            start: 7,
            max: [4.0, 5.0, 6.0],
            count: 9,
        };
        let words = node.to_words();
        assert_eq!(words.len() * 4, size_of::<GpuNode>());
        for i in 0..3 {
            let at = |field: usize| field + 4 * i;
            assert_eq!(
                word(&words, at(offset_of!(GpuNode, min))),
                node.min[i].to_bits()
            );
            assert_eq!(
                word(&words, at(offset_of!(GpuNode, max))),
                node.max[i].to_bits()
            );
        }
        assert_eq!(word(&words, offset_of!(GpuNode, start)), 7);
        assert_eq!(word(&words, offset_of!(GpuNode, count)), 9);
    }

    #[test]
    fn triangle_words_follow_the_structs_layout() {
        let tri = GpuTriangle {
            a: [1.0, 2.0, 3.0],
            id: 11,
            b: [4.0, 5.0, 6.0],
            flags: DEGENERATE,
            c: [7.0, 8.0, 9.0],
            pad: 13,
        };
        let words = tri.to_words();
        assert_eq!(words.len() * 4, size_of::<GpuTriangle>());
        for i in 0..3 {
            let at = |field: usize| field + 4 * i;
            assert_eq!(
                word(&words, at(offset_of!(GpuTriangle, a))),
                tri.a[i].to_bits()
            );
            assert_eq!(
                word(&words, at(offset_of!(GpuTriangle, b))),
                tri.b[i].to_bits()
            );
            assert_eq!(
                word(&words, at(offset_of!(GpuTriangle, c))),
                tri.c[i].to_bits()
            );
        }
        assert_eq!(word(&words, offset_of!(GpuTriangle, id)), 11);
        assert_eq!(word(&words, offset_of!(GpuTriangle, flags)), DEGENERATE);
        assert_eq!(word(&words, offset_of!(GpuTriangle, pad)), 13);
    }

    #[test]
    fn flattening_keeps_the_nodes_and_puts_each_leafs_triangles_at_its_start() {
        let mut tris: Vec<Triangle3> = (0..40)
            .map(|i| {
                let o = Vec3::new((i % 7) as f32, (i / 7) as f32, (i % 3) as f32);
                Triangle3::new(o, o + Vec3::X, o + Vec3::Y)
            })
            .collect();
        // A zero-area triangle is flagged.
        tris.push(Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0));
        let tree = AabbTree::<Triangle3>::build(&tris);
        let flat = GpuTree::flatten(&tree);
        assert_eq!(flat.nodes.len(), tree.nodes().len());
        assert_eq!(flat.triangles.len(), tris.len());
        for (i, (gpu, node)) in flat.nodes.iter().zip(tree.nodes()).enumerate() {
            assert_eq!(*gpu, gpu_node(node));
            for (k, &id) in tree.leaf_primitives(NodeId(i as u32)).iter().enumerate() {
                let t = &flat.triangles[node.start as usize + k];
                assert_eq!(t.id, id);
                assert_eq!(t.a, tris[id as usize].a.to_array());
                assert_eq!(t.flags == DEGENERATE, id == 40);
            }
        }
        assert_eq!(flat.node_words().len(), flat.nodes.len());
        assert_eq!(flat.triangle_words()[0], flat.triangles[0].to_words());
    }
}
