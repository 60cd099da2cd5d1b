//! The binned-SAH build of a box tree in one go, for [`Bvh::build_with`]: the tree the
//! resumable [`Builder`](super::Builder) makes, bit for bit, at about half its cost.
//!
//! The resumable builder keeps each node's work in a [`Stage`](super::Stage) that can stop
//! anywhere: a node reads its primitives three times (merge their boxes, bin them, partition
//! them) and moves its stage state (a few hundred bytes) at every step. A build that runs to
//! the end needs neither: this one is a plain loop over a stack of ranges. Each side's box
//! is the merge of its bins (`Cheapest::sides`) and the partition merges the sides' centres
//! as it moves them, so a child starts with its bounds known and reads its primitives twice
//! (bin, partition). Wald's binned builder does the same ("On fast Construction of
//! SAH-based Bounding Volume Hierarchies", 2007, §4.1: the children's bounds fall out of the
//! binning and the partition pass). Taking the sides' boxes from the bins rather than
//! merging them in the partition made `Bvh4::build` 1.03-1.04x as fast on the three meshes
//! (the same trees; three runs of 15 builds each, old and new binaries in turn, one core).
//!
//! Only box trees qualify: a sphere or OBB node is fitted to the vertices below it, which the
//! resumable builder gathers per node anyway. The decisions are the same in the same order
//! (the binned costs of `sah.rs`, computed as there by [`fast_bins`](super::fast_bins),
//! over the same primitives in the same order; the same partition; the same object
//! median), and a box's union is the same whatever the order of
//! its merges (minimum and maximum of finite numbers; a `-0.0` against a `0.0` is the one
//! difference, and [`NodeVolume::fit`] grows every box by at least `f32::MIN_POSITIVE`,
//! which takes the zero's sign away), so the nodes, their order and the leaf order equal
//! the resumable builder's. The tests compare the two on random scenes and the shared
//! meshes.

use super::BuildPrim;
use super::fast_bins::{AxisBins, Binner, Cheapest, LaneBox, lanes};
use super::median::object_median;
use crate::structure::bvh::layout::BvhNode;
use crate::structure::bvh::volume::NodeVolume;
use crate::structure::bvh::{Bvh, BvhOptions};
use crate::{Primitive, Vector};

/// What the build knows of a primitive, in lanes: its box, its centre, its input index.
#[derive(Clone, Copy, Debug)]
pub(super) struct Item {
    pub bounds: LaneBox,
    pub centroid: [f32; 3],
    pub index: u32,
}

impl Item {
    /// The item of input primitive `index`, or `None` when it cannot be indexed.
    #[inline]
    pub fn indexed<P: Primitive>(index: usize, prim: &P) -> Option<Self> {
        prim.has_finite_coordinates().then(|| {
            Self::of(&BuildPrim {
                bounds: prim.bounds(),
                centroid: prim.centroid(),
                index: index as u32,
            })
        })
    }

    fn of<V: Vector>(prim: &BuildPrim<V>) -> Self {
        let c = lanes(prim.centroid);
        Self {
            bounds: LaneBox::of_aabb(&prim.bounds),
            centroid: [c.x, c.y, c.z],
            index: prim.index,
        }
    }

    /// Its centre in four lanes, as [`LaneBox`] holds points (the fourth lane 0).
    #[inline]
    fn centroid_lanes(&self) -> glam::Vec4 {
        let [x, y, z] = self.centroid;
        glam::Vec4::new(x, y, z, 0.0)
    }

    fn to_build_prim<V: Vector>(self) -> BuildPrim<V> {
        let bounds = self.bounds.to_aabb();
        let mut centroid = V::ZERO;
        for (i, &c) in self.centroid.iter().enumerate().take(V::DIM) {
            centroid.set_coord(i, c);
        }
        BuildPrim {
            bounds,
            centroid,
            index: self.index,
        }
    }
}

/// A range of primitives waiting for its node, with the boxes of their bounds and centres.
///
/// The boxes come first, at 16-byte offsets, so that popping a job copies them with loads
/// that match the stores that pushed them (a load that straddles two stores waits for both,
/// which cost several percent of the build).
#[derive(Clone, Copy, Debug)]
#[repr(C)]
struct Job {
    boxes: Boxes,
    start: usize,
    end: usize,
    /// Its parent, when it is a second child (whose index the parent stores).
    second_of: Option<u32>,
    depth: usize,
}

/// The bounds and centres of a run of primitives.
#[derive(Clone, Copy, Debug)]
pub(super) struct Boxes {
    pub bounds: LaneBox,
    pub centroids: LaneBox,
}

impl Boxes {
    pub const EMPTY: Self = Self {
        bounds: LaneBox::EMPTY,
        centroids: LaneBox::EMPTY,
    };

    #[inline]
    fn add(&mut self, item: &Item) {
        self.bounds = self.bounds.merge(&item.bounds);
        self.centroids = self.centroids.grown(item.centroid_lanes());
    }

    /// Adds `item`'s centre when `take`, without a branch: otherwise it merges the empty
    /// box.
    #[inline]
    fn add_centroid_if(&mut self, item: &Item, take: bool) {
        let mask = glam::BVec4A::splat(take);
        let c = item.centroid_lanes();
        let e = LaneBox::EMPTY;
        self.centroids.min = self.centroids.min.min(glam::Vec4::select(mask, c, e.min));
        self.centroids.max = self.centroids.max.max(glam::Vec4::select(mask, c, e.max));
    }

    /// The boxes around both runs (a minimum and a maximum: the order does not matter).
    #[cfg(feature = "parallel")]
    #[inline]
    pub fn merge(&self, other: &Self) -> Self {
        Self {
            bounds: self.bounds.merge(&other.bounds),
            centroids: self.centroids.merge(&other.centroids),
        }
    }

    pub fn of(items: &[Item]) -> Self {
        let mut boxes = Self::EMPTY;
        for item in items {
            boxes.add(item);
        }
        boxes
    }
}

/// Builds the binned-SAH tree with box nodes over `prims`: what
/// [`Builder::run`](super::Builder::run) makes with the same options, without its events,
/// its log and its stages.
pub(in crate::structure::bvh) fn build_sah_boxes<B, P>(
    prims: &[P],
    options: &BvhOptions,
) -> Bvh<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    build_sah_box_parts(prims, options).into_bvh(prims.to_vec(), options)
}

/// What a tree is made of besides its input and options (a [`Bvh4`](super::super::Bvh4)
/// built straight from primitives keeps these and no copy of the input).
pub(in crate::structure::bvh) struct TreeParts<B, P> {
    pub nodes: Vec<BvhNode<B>>,
    pub leaf_prims: Vec<P>,
    pub leaf_ids: Vec<u32>,
}

impl<B: NodeVolume, P: Primitive<Point = B::Point>> TreeParts<B, P> {
    /// The tree of these parts over `prims` (the input, copied), with its SAH cost.
    pub(in crate::structure::bvh) fn into_bvh(
        self,
        prims: Vec<P>,
        options: &BvhOptions,
    ) -> Bvh<B, P> {
        Bvh {
            prims,
            nodes: self.nodes,
            leaf_prims: self.leaf_prims,
            leaf_ids: self.leaf_ids,
            options: *options,
            build_sah_cost: None,
        }
        .with_build_cost()
    }
}

/// [`build_sah_boxes`]'s nodes and leaf order.
pub(in crate::structure::bvh) fn build_sah_box_parts<B, P>(
    prims: &[P],
    options: &BvhOptions,
) -> TreeParts<B, P>
where
    B: NodeVolume<Point = P::Point>,
    P: Primitive,
{
    debug_assert!(
        !B::NEEDS_VERTICES,
        "only volumes fitted to the bounds alone"
    );
    let mut items = Vec::with_capacity(prims.len());
    for (index, prim) in prims.iter().enumerate() {
        if let Some(item) = Item::indexed(index, prim) {
            items.push(item);
        }
    }
    let n = items.len();
    // A binary tree with at least one primitive per leaf has fewer than 2n nodes.
    let mut nodes = Vec::with_capacity(n.saturating_mul(2).min(1 << 24));
    if n > 0 {
        let boxes = Boxes::of(&items);
        let mut binner = Binner::new(options);
        build_nodes(&mut items, boxes, 0, &mut binner, options, &mut nodes);
    }
    nodes.shrink_to_fit();
    let leaf_prims = items
        .iter()
        .map(|item| prims[item.index as usize])
        .collect();
    let leaf_ids = items.iter().map(|item| item.index).collect();
    TreeParts {
        nodes,
        leaf_prims,
        leaf_ids,
    }
}

/// Appends the subtree over `items` (whose boxes are `boxes`, its root at `depth`) to
/// `nodes`, depth-first and first child first, with node and leaf indices counted from the
/// start of `nodes` and of `items` (the whole tree, or a subtree that
/// `parallel.rs` moves into place).
pub(super) fn build_nodes<B: NodeVolume>(
    items: &mut [Item],
    boxes: Boxes,
    depth: usize,
    binner: &mut Binner,
    options: &BvhOptions,
    nodes: &mut Vec<BvhNode<B>>,
) {
    let mut jobs = vec![Job {
        start: 0,
        end: items.len(),
        second_of: None,
        depth,
        boxes,
    }];
    while let Some(job) = jobs.pop() {
        make_node(&job, items, nodes, &mut jobs, binner, options);
    }
}

/// Makes the job's node (a leaf until split) and queues its children, if it splits.
fn make_node<B: NodeVolume>(
    job: &Job,
    items: &mut [Item],
    nodes: &mut Vec<BvhNode<B>>,
    jobs: &mut Vec<Job>,
    binner: &mut Binner,
    options: &BvhOptions,
) {
    let id = nodes.len() as u32;
    let n = job.end - job.start;
    nodes.push(BvhNode {
        volume: B::fit(&job.boxes.bounds.to_aabb(), &[], options),
        start: job.start as u32,
        count: n as u32,
    });
    if let Some(parent) = job.second_of {
        let parent = &mut nodes[parent as usize];
        parent.start = id;
        parent.count = 0;
    }
    if is_leaf_unbinned(n, job.depth, options) {
        return;
    }
    let items = &mut items[job.start..job.end];
    let cheapest = binner.cheapest::<B::Point>(&job.boxes.bounds, &job.boxes.centroids, items);
    let small = n <= options.leaf_limit();
    let leaf_cost = small.then(|| options.leaf_cost(n));
    let Some((split, left, right)) = split_node::<B::Point>(items, &job.boxes, cheapest, leaf_cost)
    else {
        return;
    };
    let mid = job.start + split;
    // The first child on top: it is made next, as the recursion would.
    for (start, end, boxes, second_of) in [
        (mid, job.end, right, Some(id)),
        (job.start, mid, left, None),
    ] {
        jobs.push(Job {
            start,
            end,
            second_of,
            depth: job.depth + 1,
            boxes,
        });
    }
}

/// Whether a node of `n` primitives at `depth` is a leaf whatever its binning says, so that
/// the SAH build need not bin it: a single primitive, the depth limit, or one block's worth
/// that may stay a leaf (`n` at most [`BvhOptions::leaf_block`] and the leaf size). Such a
/// leaf costs 1 and any split `1 +` its children's costs, which are never negative (nor NaN:
/// a NaN cost is no plane), so the SAH keeps the leaf; the resumable builder bins these
/// nodes for its events and decides the same. With blocks of four, a third of a mesh's
/// nodes are such leaves.
#[inline]
pub(super) fn is_leaf_unbinned(n: usize, depth: usize, options: &BvhOptions) -> bool {
    n <= 1
        || depth >= options.depth_limit()
        || (n <= options.leaf_block.max(1) && n <= options.leaf_limit())
}

/// How a node over `items` (with `boxes`) splits, given its cheapest binned plane: the size
/// of its first child and both children's boxes, after moving the first child's primitives
/// to the front; or `None` for a leaf. `leaf_cost` is the SAH's cost of a leaf of them when
/// they are few enough for one (at most `leaf_size`).
#[inline]
pub(super) fn split_node<V: Vector>(
    items: &mut [Item],
    boxes: &Boxes,
    cheapest: Option<Cheapest>,
    leaf_cost: Option<f32>,
) -> Option<(usize, Boxes, Boxes)> {
    match (cheapest, leaf_cost) {
        // Splitting does not pay, or cannot be costed: a leaf, if it is small enough.
        (Some(cheapest), Some(leaf_cost)) if cheapest.cost >= leaf_cost => None,
        (None, Some(_)) => None,
        (Some(cheapest), _) => {
            let (count, left, right) = partition(items, &cheapest);
            debug_assert_eq!(count, cheapest.left, "binning and partition disagree");
            Some((count, left, right))
        }
        (None, None) => {
            let left = median::<V>(items, &boxes.centroids);
            Some((left, Boxes::of(&items[..left]), Boxes::of(&items[left..])))
        }
    }
}

/// The resumable builder's object median (rare: only where the centres coincide on every
/// axis the SAH could bin), on its own primitive type so that the selection permutes them
/// exactly as it does there. Returns the size of the first half.
fn median<V: Vector>(items: &mut [Item], centroids: &LaneBox) -> usize {
    let mut prims: Vec<BuildPrim<V>> = items.iter().map(|item| item.to_build_prim()).collect();
    let split = object_median(&mut prims, &centroids.to_aabb());
    for (item, prim) in items.iter_mut().zip(&prims) {
        *item = Item::of(prim);
    }
    split.left
}

/// Moves the primitives whose centre's bin is at most the cheapest plane's to the front, in
/// the resumable builder's order (one pass, each such primitive swapped with the first that
/// is not), merging each side's centres on the way. Returns how many went to the front, and
/// the boxes of both sides (their bounds from the bins).
///
/// "The bin is at most `best`" is `((c - lo) * scale) as usize <= best` (then clamped to
/// the last bin, which is beyond `best`). A product that is not negative truncates to at
/// most `best` exactly when it is below `best + 1`, a small integer that `f32` holds
/// exactly; a NaN product (`0 * inf`, when the centres' extent is so small that `scale`
/// overflows) converts to bin 0, so it goes to the front too: the test is "not at least
/// `best + 1`". The comparison saves the conversion.
///
/// The loop has no branch on the side: near the root an item's side is close to a coin
/// toss, and a branch on it is often mispredicted. Without the branch, `Bvh4::build` was
/// 1.14x as fast on the bunny, 1.24x on the dragon and 1.01x on the ogre (the same trees;
/// the median of three runs of 15 builds each, old and new binaries in turn, one core).
fn partition(items: &mut [Item], cheapest: &Cheapest) -> (usize, Boxes, Boxes) {
    let AxisBins {
        axis, lo, scale, ..
    } = cheapest.bins;
    let limit = (cheapest.best + 1) as f32;
    // The sides' bounds are their bins' (`Cheapest::sides`); only the centres' boxes are
    // merged here.
    let [left_bounds, right_bounds] = cheapest.sides;
    let mut left = Boxes {
        bounds: left_bounds,
        centroids: LaneBox::EMPTY,
    };
    let mut right = Boxes {
        bounds: right_bounds,
        centroids: LaneBox::EMPTY,
    };
    let mut mid = 0;
    for i in 0..items.len() {
        // A NaN position fails the comparison: bin 0, the front.
        let to_back = (items[i].centroid[axis] - lo) * scale >= limit;
        let to_front = !to_back;
        let item = items[i];
        left.add_centroid_if(&item, to_front);
        right.add_centroid_if(&item, to_back);
        // Swaps items `i` and `mid` when the item goes to the front, else writes both back
        // where they are.
        let (a, b) = std::hint::select_unpredictable(to_front, (i, mid), (mid, i));
        let (at_a, at_b) = (items[a], items[b]);
        items[mid] = at_a;
        items[i] = at_b;
        mid += usize::from(to_front);
    }
    (mid, left, right)
}
