//! A 4-wide copy of a built AABB tree, for the fastest unobserved queries.
//!
//! The binary tree is what the lab steps through: its nodes, ids and events stay as they
//! are. A caller that only wants answers can collapse it into [`Bvh4`], whose nodes hold up
//! to four children's boxes side by side, one array per coordinate (structure of arrays),
//! so that one slab test checks four boxes with four-lane arithmetic (Wald, Benthin and
//! Boulos, "Getting Rid of Packets", IRT 2008; Dammertz, Hanika and Keller, "Shallow
//! Bounding Volume Hierarchies for Fast SIMD Ray Tracing of Incoherent Rays", EGSR 2008).
//! A walk then meets a quarter to a half of the binary tree's levels, and the four boxes it
//! tests at once share two cache lines instead of lying in two nodes each.
//!
//! The collapse keeps the binary tree's boxes (each fitted with its slack, so every
//! conservative argument of [`volume`] still holds) and its leaves; it only
//! removes inner levels: a wide node's lanes are the binary node's children, and while there
//! are fewer than four, the inner lane with the largest surface area is replaced by its two
//! children (the greedy rule of Wald et al.), which opens the boxes most rays enter.
//!
//! [`volume`]: crate::structure::bvh::volume

use arrayvec::ArrayVec;

#[cfg(feature = "parallel")]
use super::collapse_parallel::collapse_parallel;
use super::leaves::LeafPrims;
#[cfg(feature = "parallel")]
use crate::structure::bvh::build::build_sah_box_parts_parallel;
use crate::structure::bvh::build::{TreeParts, build_sah_box_parts};
use crate::structure::bvh::layout::BvhNode;
use crate::structure::bvh::{Bvh, BvhOptions, SplitMethod};
use crate::volume::{Aabb, BoundingVolume};
use crate::{Primitive, Vector};

/// A collapse of a binary tree: its wide nodes and their depth (`collapse` or its parallel
/// twin).
type Collapse<V> = fn(&[BvhNode<Aabb<V>>]) -> (Vec<Bvh4Node>, usize);

/// Children per wide node.
///
/// Four, where issue 33 asked whether eight measures better (bunny, dragon and ogre, the
/// four-triangle blocks' tree, one core, each build's binary run three times in turn with
/// the others, in two such rounds, medians; the ratios are speed-ups over this tree built
/// with default flags; "built for AVX2" is `-C target-feature=+avx2,+fma`):
///
/// | tree | first hits (primary, shadow, diffuse, random) | overview | any hit | closest |
/// | --- | --- | --- | --- | --- |
/// | 4 wide, built for AVX2 | 0.93-1.06x | 0.97-1.06x | 1.01-1.04x | 1.01-1.02x |
/// | 8 wide, SSE2 (two 4-lane halves) | 1.00-1.20x | 0.94-0.96x | 1.02-1.12x | 0.98-0.99x |
/// | 8 wide, built for AVX2 | 1.02-1.25x | 0.96-1.11x | 1.10-1.20x | 0.98-1.04x |
///
/// So kernels picked at run time would gain nothing on this node, and the 8-wide node about
/// a tenth with AVX2 (with SSE2 less, and unevenly: overview rays are slower). Its nodes are
/// half empty (4.2-4.3 of 8 lanes used, against 3.1 of 4 here: leaves of up to 16 triangles
/// stop the collapse early), 256 bytes each, 1.1-1.7 MB of nodes for these meshes against
/// 0.8-1.4 MB here; the whole tree was 62-65 bytes per triangle. The width cannot simply be
/// changed here: the type is named for four, and the saved format, the stack sizes and the
/// mask step count on it.
///
/// Nor did smaller nodes pay: this node with its child boxes quantised to 8 bits against the
/// node's own box (as in Ylitie, Karras and Laine, "Efficient Incoherent Ray Traversal on
/// GPUs Through Compressed Wide BVHs", 2017; one power-of-two scale per axis, rounded
/// outward and checked against the decoding, 64 bytes, decoded with SSE2's byte unpacking)
/// gave the same first hits on every ray of the three meshes, at 0.71-0.85x the speed (one
/// binary, seven alternating runs): on this machine the halved node did not pay for its
/// decoding (two unpacks, a conversion, a multiply and an add per plane row), with
/// 0.8-1.4 MB of full-precision nodes for these meshes. Aligning the
/// blocks to 64 bytes was 0.84-1.09x. What is left for rays is a tree generic over its
/// width, for the eight-lane node above with kernels picked at run time.
pub const WIDTH: usize = 4;

/// One node of a [`Bvh4`]: up to four children's boxes in structure-of-arrays form, and where
/// each child is.
///
/// 128 bytes, aligned to a 64-byte cache line, so a node is exactly two lines:
///
/// ```text
/// offset   0  planes[0]  3 × [f32; 4]   per axis, the four children's lower planes (min)
/// offset  48  planes[1]  3 × [f32; 4]   per axis, their upper planes (max)
/// offset  96  child      [u32; 4]       inner child: its wide node; leaf child: first primitive
/// offset 112  count      [u32; 4]       leaf child: primitive count (>= 1); inner child: 0
/// ```
///
/// An unused lane has the empty box (`min = +inf`, `max = -inf`), which every slab test
/// misses and every distance bound puts at infinity; in 2D the third axis is unused.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
pub struct Bvh4Node {
    /// `planes[0][axis][lane]`: the lower planes of the children's boxes (their `min`);
    /// `planes[1][axis][lane]`: the upper ones (`max`). One array, so that the ray test
    /// picks the plane it enters through by an index computed once per ray.
    pub planes: [[[f32; WIDTH]; 3]; 2],
    /// Per lane: an inner child's wide node index, or a leaf child's first primitive (leaf
    /// order).
    pub child: [u32; WIDTH],
    /// Per lane: a leaf child's primitive count (at least 1), or 0 for an inner child or an
    /// unused lane.
    pub count: [u32; WIDTH],
}

const _: () = assert!(size_of::<Bvh4Node>() == 128);

impl Bvh4Node {
    /// A node with every lane unused.
    pub(super) const EMPTY: Self = Self {
        planes: [[[f32::INFINITY; WIDTH]; 3], [[f32::NEG_INFINITY; WIDTH]; 3]],
        child: [0; WIDTH],
        count: [0; WIDTH],
    };

    /// Whether lane `lane` holds a child (leaf or inner).
    pub fn is_used(&self, lane: usize) -> bool {
        self.count[lane] > 0 || self.planes[0][0][lane] <= self.planes[1][0][lane]
    }

    /// The box of lane `lane` (empty for an unused lane).
    pub fn lane_box<V: Vector>(&self, lane: usize) -> Aabb<V> {
        let (mut min, mut max) = (V::ZERO, V::ZERO);
        for axis in 0..V::DIM {
            min.set_coord(axis, self.planes[0][axis][lane]);
            max.set_coord(axis, self.planes[1][axis][lane]);
        }
        Aabb::new(min, max)
    }

    pub(super) fn set_lane<V: Vector>(&mut self, lane: usize, volume: &Aabb<V>) {
        for axis in 0..V::DIM {
            self.planes[0][axis][lane] = volume.min.coord(axis);
            self.planes[1][axis][lane] = volume.max.coord(axis);
        }
    }
}

/// The primitives of `prims` a build leaves out (a NaN or infinite coordinate), with their
/// indices.
fn left_out_of<P: Primitive>(prims: &[P]) -> Vec<(u32, P)> {
    prims
        .iter()
        .enumerate()
        .filter(|(_, p)| !p.has_finite_coordinates())
        .map(|(i, p)| (i as u32, *p))
        .collect()
}

/// A 4-wide AABB tree collapsed from a built [`AabbTree`], answering
/// [`ray_first_hit`](Self::ray_first_hit) and [`closest_point`](Self::closest_point) exactly
/// as the binary tree (and brute force) does, bit for bit, but faster. It holds its own copy
/// of the primitives in leaf order, so the binary tree can be dropped: triangles in blocks of
/// four that the ray walks test four at a time (`wide/triangle_block.rs`), and
/// [`build`](Self::build) makes leaves that fill them.
///
/// ```
/// use bvhlab::glam::Vec3;
/// use bvhlab::prelude::*;
/// use bvhlab::structure::bvh::Bvh4;
///
/// let tris: Vec<Triangle3> = (0..10)
///     .map(|i| {
///         let z = i as f32;
///         Triangle3::new(Vec3::new(0.0, 0.0, z), Vec3::new(4.0, 0.0, z), Vec3::new(0.0, 4.0, z))
///     })
///     .collect();
/// let tree = AabbTree3::build(&tris);
/// let wide = Bvh4::from_bvh(&tree);
/// let down = Ray3::new(Vec3::new(1.0, 1.0, 20.0), -Vec3::Z)?;
/// assert_eq!(wide.ray_first_hit(&down, f32::INFINITY), tree.ray_first_hit(&down, f32::INFINITY));
/// assert_eq!(wide.ray_first_hit(&down, f32::INFINITY).map(|h| h.prim), Some(9));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// [`AabbTree`]: crate::structure::bvh::AabbTree
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Debug, PartialEq)]
pub struct Bvh4<P: Primitive> {
    /// Wide nodes; the root is node 0 (when any primitive is indexed). Each node's inner
    /// children are contiguous.
    pub(super) nodes: Vec<Bvh4Node>,
    /// The indexed primitives in leaf order, one per slot (triangles in blocks of four,
    /// `leaves.rs`).
    pub(super) leaf_prims: LeafPrims<P>,
    /// `leaf_ids[slot]` is the input index of the primitive in `slot`
    /// ([`PADDING`](super::leaves::PADDING) for a padding slot after a leaf's last triangle).
    pub(super) leaf_ids: Vec<u32>,
    /// Wide levels from the root to the deepest node (1 for a root alone, 0 when empty):
    /// it sizes the walks' stacks.
    pub(super) depth: usize,
    /// How many primitives the tree was built over (indexed or left out), for a refit.
    pub(super) input_len: usize,
    /// The SAH cost of the wide tree when it was built, for [`Bvh4::needs_rebuild`].
    pub(super) build_sah_cost: Option<f32>,
    /// The primitives left out for a NaN or infinite coordinate, with their input indices:
    /// kept so that [`Bvh4::remove`] gives them back as the binary tree does.
    pub(super) left_out: Vec<(u32, P)>,
}

impl<P: Primitive> Bvh4<P> {
    /// Builds the binned-SAH AABB tree over `prims` and collapses it: with the default
    /// options, or over triangles with [`BvhOptions::for_triangle_blocks`], whose leaves
    /// fill the blocks of four triangles this tree tests at once.
    pub fn build(prims: &[P]) -> Self {
        Self::build_with(prims, &Self::default_options())
    }

    /// The options [`build`](Self::build) uses for this primitive type.
    pub fn default_options() -> BvhOptions {
        if LeafPrims::<P>::in_blocks() {
            BvhOptions::for_triangle_blocks()
        } else {
            BvhOptions::default()
        }
    }

    /// Builds the AABB tree over `prims` with `options` and collapses it: the tree
    /// `Bvh4::from_bvh(&AabbTree::build_with(prims, options))` makes, without the binary
    /// tree's copies of the input and of the leaf order.
    pub fn build_with(prims: &[P], options: &BvhOptions) -> Self {
        if options.method != SplitMethod::BinnedSah {
            return Self::from_bvh(&Bvh::build_with(prims, options));
        }
        let parts = build_sah_box_parts::<Aabb<P::Point>, P>(prims, options);
        Self::from_parts(parts, collapse, prims)
    }

    /// [`build`](Self::build) on every core (the `parallel` feature): the same tree, bit for
    /// bit.
    #[cfg(feature = "parallel")]
    pub fn build_parallel(prims: &[P]) -> Self {
        Self::build_with_parallel(prims, &Self::default_options())
    }

    /// [`build_with`](Self::build_with) on every core (the `parallel` feature): the binary
    /// tree of [`Bvh::build_with_parallel`] (the serial build's, bit for bit), collapsed into
    /// the same wide nodes, its subtrees at once (`wide/collapse_parallel.rs`).
    #[cfg(feature = "parallel")]
    pub fn build_with_parallel(prims: &[P], options: &BvhOptions) -> Self {
        if options.method != SplitMethod::BinnedSah {
            return Self::from_bvh(&Bvh::build_with(prims, options));
        }
        let parts = build_sah_box_parts_parallel::<Aabb<P::Point>, P>(prims, options);
        Self::from_parts(parts, collapse_parallel, prims)
    }

    /// The binary tree's parts (built over `prims`), collapsed by `collapse`.
    fn from_parts(
        parts: TreeParts<Aabb<P::Point>, P>,
        collapse: Collapse<P::Point>,
        prims: &[P],
    ) -> Self {
        let (mut nodes, depth) = collapse(&parts.nodes);
        // The parts index every primitive unless some were left out.
        let left_out = if parts.leaf_ids.len() == prims.len() {
            Vec::new()
        } else {
            left_out_of(prims)
        };
        let (leaf_prims, leaf_ids) =
            LeafPrims::lay_out(parts.leaf_prims, parts.leaf_ids, &mut nodes);
        Self {
            nodes,
            leaf_prims,
            leaf_ids,
            depth,
            input_len: prims.len(),
            build_sah_cost: None,
            left_out,
        }
        .with_build_cost()
    }

    /// Collapses a built AABB tree (its boxes, leaves and primitives are kept; only inner
    /// levels go).
    pub fn from_bvh(bvh: &Bvh<Aabb<P::Point>, P>) -> Self {
        let (mut nodes, depth) = collapse(&bvh.nodes);
        let (leaf_prims, leaf_ids) =
            LeafPrims::lay_out(bvh.leaf_prims.clone(), bvh.leaf_ids.clone(), &mut nodes);
        Self {
            nodes,
            leaf_prims,
            leaf_ids,
            depth,
            input_len: bvh.prims.len(),
            build_sah_cost: None,
            left_out: left_out_of(&bvh.prims),
        }
        .with_build_cost()
    }

    /// The wide nodes; the root is node 0.
    pub fn nodes(&self) -> &[Bvh4Node] {
        &self.nodes
    }

    /// How many primitives are indexed (every one it was built over and given since, but
    /// those left out).
    pub fn len(&self) -> usize {
        self.input_len - self.left_out.len()
    }

    /// Whether no primitive is indexed.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The heap memory it holds: nodes, primitives (their blocks, for triangles), their ids
    /// and the primitives left out.
    pub fn memory_bytes(&self) -> usize {
        self.nodes.capacity() * size_of::<Bvh4Node>()
            + self.leaf_prims.memory_bytes()
            + self.leaf_ids.capacity() * size_of::<u32>()
            + self.left_out.capacity() * size_of::<(u32, P)>()
    }

    /// Wide levels from the root to the deepest node (0 when empty).
    pub fn depth(&self) -> usize {
        self.depth
    }

    /// The bytes of its nodes alone.
    pub fn node_bytes(&self) -> usize {
        self.nodes.len() * size_of::<Bvh4Node>()
    }

    /// The average number of used lanes per node (at most [`WIDTH`]).
    pub fn mean_fill(&self) -> f32 {
        let used: usize = self
            .nodes
            .iter()
            .map(|n| (0..WIDTH).filter(|&lane| n.is_used(lane)).count())
            .sum();
        used as f32 / self.nodes.len().max(1) as f32
    }
}

/// The wide nodes of a binary tree (depth-first from the root, each node's inner children
/// given consecutive indices when the node is made), and their depth.
pub(super) fn collapse<V: Vector>(binary: &[BvhNode<Aabb<V>>]) -> (Vec<Bvh4Node>, usize) {
    let Some(root) = binary.first() else {
        return (Vec::new(), 0);
    };
    // A leaf root becomes a wide root with one leaf lane.
    let root_lanes = if root.is_leaf() {
        Lanes::from_iter([0])
    } else {
        lanes_of(binary, 0)
    };
    collapse_from(binary, root_lanes, binary.len())
}

/// The wide subtree whose root has the binary nodes `root_lanes` as lanes, in
/// [`collapse`]'s order with the root at index 0, and its depth in wide levels. `size`
/// bounds the binary nodes below `root_lanes`.
pub(super) fn collapse_from<V: Vector>(
    binary: &[BvhNode<Aabb<V>>],
    root_lanes: Lanes,
    size: usize,
) -> (Vec<Bvh4Node>, usize) {
    // Each wide node stands for at least one binary inner node, and fewer than half of a
    // binary tree's nodes are inner: the vector does not move while it grows (pushed one by
    // one, it was copied at every doubling; a piece of the parallel collapse, whose size is
    // a bound give or take a few nodes, may still grow once), and what is left over is given
    // back at the end.
    let mut nodes = Vec::with_capacity(size / 2 + 1);
    nodes.push(Bvh4Node::EMPTY);
    let mut waiting = vec![(0usize, 1usize, root_lanes)];
    let mut depth = 0;
    while let Some((index, level, lanes)) = waiting.pop() {
        depth = depth.max(level);
        let mut node = Bvh4Node::EMPTY;
        for (lane, &id) in lanes.iter().enumerate() {
            let b = &binary[id as usize];
            node.set_lane(lane, &b.volume);
            if b.is_leaf() {
                (node.child[lane], node.count[lane]) = (b.start, b.count);
            } else {
                let child = nodes.len();
                nodes.push(Bvh4Node::EMPTY);
                node.child[lane] = u32::try_from(child).unwrap_or(u32::MAX);
                waiting.push((child, level + 1, lanes_of(binary, id)));
            }
        }
        nodes[index] = node;
    }
    nodes.shrink_to_fit();
    (nodes, depth)
}

/// The binary nodes that make one wide node's lanes.
pub(super) type Lanes = ArrayVec<u32, WIDTH>;

/// The binary nodes that become the lanes of the wide node made for inner node `id`: its two
/// children, then, while there are fewer than [`WIDTH`], the inner one with the largest
/// surface area replaced by its two children (in place, so lanes keep the binary tree's
/// left-to-right order).
pub(super) fn lanes_of<V: Vector>(binary: &[BvhNode<Aabb<V>>], id: u32) -> Lanes {
    let children = |id: u32| (id + 1, binary[id as usize].start);
    let (first, second) = children(id);
    let mut lanes = Lanes::new();
    lanes.extend([first, second]);
    while lanes.len() < WIDTH {
        let widest = lanes
            .iter()
            .enumerate()
            .filter(|&(_, &lane)| !binary[lane as usize].is_leaf())
            .map(|(i, &lane)| (i, binary[lane as usize].volume.boundary_measure()))
            .reduce(|a, b| if b.1 > a.1 { b } else { a });
        let Some((i, _)) = widest else { break };
        let (first, second) = children(lanes[i]);
        lanes[i] = first;
        lanes.insert(i + 1, second);
    }
    lanes
}
