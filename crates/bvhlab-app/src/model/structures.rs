//! The structure the student picks, its build options, and one dispatch over the concrete
//! core types so the rest of the lab handles "a structure" without knowing which.

use bvhlab::structure::bvh::{Bvh, NodeVolume, SphereFit, SplitRecord};
use bvhlab::structure::kdtree::{AxisRule, KdBuilder};
use bvhlab::structure::{
    BspOptions, BvhOptions, GridOptions, KdTreeOptions, NodeOutline, OrthtreeOptions, RangeShape,
    SplitMethod,
};
use bvhlab::{
    Aabb, BruteForce, BspTree, Grid, KdTree, Nearest, Obb, Observer, Orthtree, Outline, Primitive,
    Ray, Segment2, SpatialIndex, Sphere, Stats, Traced, Vector,
};

/// The structures the lab offers, in the lecture's order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StructureKind {
    /// No structure: test every primitive.
    BruteForce,
    /// A BVH of circles (bounding spheres).
    SphereTree,
    /// A BVH of axis-aligned boxes.
    AabbTree,
    /// A BVH of oriented boxes.
    ObbTree,
    /// A uniform grid.
    Grid,
    /// A BSP tree (autopartition).
    Bsp,
    /// A quadtree (in 3D: an octree).
    Quadtree,
    /// A k-d tree.
    KdTree,
}

impl StructureKind {
    /// Every kind, in menu order.
    pub const ALL: [Self; 8] = [
        Self::BruteForce,
        Self::SphereTree,
        Self::AabbTree,
        Self::ObbTree,
        Self::Grid,
        Self::Bsp,
        Self::Quadtree,
        Self::KdTree,
    ];

    /// The lecture's name for it in `dim` dimensions (the orthtree is a quadtree in 2D and
    /// an octree in 3D).
    pub fn label_in(self, dim: usize) -> &'static str {
        if self == Self::Quadtree && dim == 3 {
            "octree"
        } else {
            self.label()
        }
    }

    /// The lecture's name for it (in 2D).
    pub fn label(self) -> &'static str {
        match self {
            Self::BruteForce => "brute force (no structure)",
            Self::SphereTree => "sphere tree",
            Self::AabbTree => "AABB tree",
            Self::ObbTree => "OBB tree",
            Self::Grid => "uniform grid",
            Self::Bsp => "BSP tree",
            Self::Quadtree => "quadtree",
            Self::KdTree => "k-d tree",
        }
    }

    /// Whether it is a bounding volume hierarchy (object partitioning).
    pub fn is_bvh(self) -> bool {
        matches!(self, Self::SphereTree | Self::AabbTree | Self::ObbTree)
    }

    /// What its counters call a visited node: a grid's are its cells.
    pub fn nodes_name(self) -> &'static str {
        match self {
            Self::Grid => "cells visited",
            _ => "nodes visited",
        }
    }

    /// What its counters call a bound test, in the lecture's words: a BVH tests its
    /// bounding volumes (BVs), a grid and a quadtree their cells, a k-d or BSP tree its
    /// cells and splitting planes.
    pub fn bound_tests_name(self) -> &'static str {
        match self {
            Self::SphereTree | Self::AabbTree | Self::ObbTree | Self::BruteForce => "BV tests",
            Self::Quadtree | Self::Grid => "cell tests",
            Self::KdTree | Self::Bsp => "cell and plane tests",
        }
    }
}

/// How the k-d tree chooses its planes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum KdSplit {
    /// Median of the centres, axes in turn (x, y, x, ...).
    MedianRoundRobin,
    /// Median of the centres across the cell's longest axis.
    MedianLongest,
    /// Surface area heuristic.
    Sah,
}

/// Every build option the lab exposes; equal options and scene give an equal structure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BuildSettings {
    /// Which structure.
    pub kind: StructureKind,
    /// BVH split method.
    pub bvh_split: SplitMethod,
    /// Sphere-tree node fit.
    pub sphere_fit: SphereFit,
    /// BVH, k-d, BSP and quadtree leaf size.
    pub leaf_size: usize,
    /// k-d tree planes.
    pub kd_split: KdSplit,
    /// Grid cells per axis; 0 means Cleary and Wyvill's automatic resolution.
    pub grid_cells: u32,
    /// Quadtree depth limit.
    pub quadtree_depth: usize,
}

/// The largest leaf size.
pub const MAX_LEAF_SIZE: usize = 64;
/// The most grid cells per axis (the panel's slider goes to 128).
pub const MAX_GRID_CELLS: u32 = 256;
/// The deepest quadtree (the panel's slider goes to 14).
pub const MAX_QUADTREE_DEPTH: usize = 20;

impl BuildSettings {
    /// Whether the lab builds these settings: leaf size 1 to [`MAX_LEAF_SIZE`], grid cells
    /// 0 (automatic) to [`MAX_GRID_CELLS`], quadtree depth 1 to [`MAX_QUADTREE_DEPTH`].
    ///
    /// # Errors
    /// Which setting of `what` ("the structure") is out of range.
    pub fn check(&self, what: &str) -> Result<(), String> {
        if !(1..=MAX_LEAF_SIZE).contains(&self.leaf_size) {
            return Err(format!(
                "{what}'s leaf size is {}; it must be 1 to {MAX_LEAF_SIZE}",
                self.leaf_size
            ));
        }
        if self.grid_cells > MAX_GRID_CELLS {
            return Err(format!(
                "{what}'s grid has {} cells per axis; at most {MAX_GRID_CELLS} (0: automatic)",
                self.grid_cells
            ));
        }
        if !(1..=MAX_QUADTREE_DEPTH).contains(&self.quadtree_depth) {
            return Err(format!(
                "{what}'s quadtree depth is {}; it must be 1 to {MAX_QUADTREE_DEPTH}",
                self.quadtree_depth
            ));
        }
        Ok(())
    }

    /// The core's options for a BVH built with these settings.
    pub fn bvh_options(&self) -> BvhOptions {
        BvhOptions {
            method: self.bvh_split,
            leaf_size: self.leaf_size.max(1),
            sphere_fit: self.sphere_fit,
            ..BvhOptions::default()
        }
    }
}

impl Default for BuildSettings {
    fn default() -> Self {
        Self {
            kind: StructureKind::AabbTree,
            bvh_split: SplitMethod::SpatialMedian,
            sphere_fit: SphereFit::Ritter,
            leaf_size: 2,
            kd_split: KdSplit::MedianRoundRobin,
            grid_cells: 0,
            quadtree_depth: 8,
        }
    }
}

/// A built structure of any kind, over 2D segments (the default) or triangles.
#[derive(Clone, Debug)]
pub enum Built<P: Primitive = Segment2> {
    /// See [`StructureKind::BruteForce`].
    BruteForce(BruteForce<P>),
    /// See [`StructureKind::SphereTree`].
    SphereTree(Bvh<Sphere<P::Point>, P>),
    /// See [`StructureKind::AabbTree`].
    AabbTree(Bvh<Aabb<P::Point>, P>),
    /// See [`StructureKind::ObbTree`].
    ObbTree(Bvh<Obb<P::Point>, P>),
    /// See [`StructureKind::Grid`].
    Grid(Grid<P>),
    /// See [`StructureKind::Bsp`].
    Bsp(BspTree<P>),
    /// See [`StructureKind::Quadtree`].
    Quadtree(Orthtree<P>),
    /// See [`StructureKind::KdTree`].
    KdTree(KdTree<P>),
}

/// Runs `$body` with `$s` bound to the concrete structure inside a [`Built`].
macro_rules! with_structure {
    ($built:expr, $s:ident => $body:expr) => {
        match $built {
            Built::BruteForce($s) => $body,
            Built::SphereTree($s) => $body,
            Built::AabbTree($s) => $body,
            Built::ObbTree($s) => $body,
            Built::Grid($s) => $body,
            Built::Bsp($s) => $body,
            Built::Quadtree($s) => $body,
            Built::KdTree($s) => $body,
        }
    };
}

impl<P: Primitive> Built<P>
where
    Sphere<P::Point>: NodeVolume<Point = P::Point>,
    Aabb<P::Point>: NodeVolume<Point = P::Point>,
    Obb<P::Point>: NodeVolume<Point = P::Point>,
{
    /// Builds the structure `settings` describe over `prims`.
    pub fn build(prims: &[P], settings: &BuildSettings) -> Self {
        Self::build_observed(prims, settings, &mut (), false).0
    }

    /// Builds the structure, reporting each step to `observer`; with `log`, also returns a
    /// BVH's split decisions with their SAH cost curves (other structures log none).
    pub fn build_observed<O: Observer<P::Point>>(
        prims: &[P],
        settings: &BuildSettings,
        observer: &mut O,
        log: bool,
    ) -> (Self, Vec<SplitRecord>) {
        let bvh = settings.bvh_options();
        let tree = |built: Self| (built, Vec::new());
        match settings.kind {
            StructureKind::BruteForce => tree(Self::BruteForce(BruteForce::build(prims))),
            StructureKind::SphereTree => bvh_build(prims, &bvh, observer, log, Self::SphereTree),
            StructureKind::AabbTree => bvh_build(prims, &bvh, observer, log, Self::AabbTree),
            StructureKind::ObbTree => bvh_build(prims, &bvh, observer, log, Self::ObbTree),
            StructureKind::Grid => {
                let n = settings.grid_cells;
                let depth = if P::Point::DIM == 3 { n } else { 1 };
                let options = GridOptions {
                    resolution: (n > 0).then_some([n, n, depth]),
                    ..GridOptions::default()
                };
                tree(Self::Grid(Grid::build_observed(prims, &options, observer)))
            }
            StructureKind::Bsp => {
                let options = BspOptions {
                    leaf_size: settings.leaf_size.max(1),
                    ..BspOptions::default()
                };
                tree(Self::Bsp(BspTree::build_observed(
                    prims, &options, observer,
                )))
            }
            StructureKind::Quadtree => {
                let options = OrthtreeOptions {
                    leaf_size: settings.leaf_size.max(1),
                    max_depth: settings.quadtree_depth,
                };
                tree(Self::Quadtree(Orthtree::build_observed(
                    prims, &options, observer,
                )))
            }
            StructureKind::KdTree => {
                let mut options = match settings.kd_split {
                    KdSplit::MedianRoundRobin => KdTreeOptions::median(AxisRule::RoundRobin),
                    KdSplit::MedianLongest => KdTreeOptions::median(AxisRule::LongestAxis),
                    KdSplit::Sah => KdTreeOptions::sah(),
                };
                if !matches!(options.builder, KdBuilder::Sah(_)) {
                    options.leaf_size = settings.leaf_size.max(1);
                }
                tree(Self::KdTree(KdTree::build_observed(
                    prims, &options, observer,
                )))
            }
        }
    }

    /// The nodes, for drawing, indexed by the node ids events report.
    pub fn outline(&self) -> Vec<NodeOutline<P::Point>> {
        with_structure!(self, s => s.outline())
    }

    /// Node count, depth, references, SAH cost, memory.
    pub fn stats(&self) -> Stats {
        with_structure!(self, s => s.stats())
    }

    /// The first hit along `ray`, reporting each step to `observer`.
    pub fn ray_first_hit<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        observer: &mut O,
    ) -> Traced<Option<bvhlab::Hit>> {
        with_structure!(self, s => s.ray_first_hit_observed(ray, f32::INFINITY, observer))
    }

    /// Any hit along `ray` (the first one found, not necessarily the nearest).
    pub fn ray_any_hit<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        observer: &mut O,
    ) -> Traced<Option<bvhlab::Hit>> {
        with_structure!(self, s => s.ray_any_hit_observed(ray, f32::INFINITY, observer))
    }

    /// Every hit along `ray`, nearest first.
    pub fn ray_all_hits<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        observer: &mut O,
    ) -> Traced<Vec<bvhlab::Hit>> {
        with_structure!(self, s => s.ray_all_hits_observed(ray, f32::INFINITY, observer))
    }

    /// The primitives that share a point with `shape`, in increasing index order.
    pub fn range<O: Observer<P::Point>>(
        &self,
        shape: &RangeShape<P::Point>,
        observer: &mut O,
    ) -> Traced<Vec<usize>> {
        with_structure!(self, s => s.range_observed(shape, observer))
    }

    /// The slides' recursive `intersect(bvNode, ray, t)`, for BVHs; `None` for the others.
    pub fn lecture_intersect<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        observer: &mut O,
    ) -> Option<Traced<Option<bvhlab::Hit>>> {
        let t = f32::INFINITY;
        match self {
            Self::SphereTree(s) => Some(s.lecture_intersect_observed(ray, t, observer)),
            Self::AabbTree(s) => Some(s.lecture_intersect_observed(ray, t, observer)),
            Self::ObbTree(s) => Some(s.lecture_intersect_observed(ray, t, observer)),
            _ => None,
        }
    }

    /// The slides' `minDistance(bvNode, point, currentMin)`, for BVHs (with `pruned`, plus
    /// the pruning the slide leaves out); `None` for the others.
    pub fn lecture_min_distance<O: Observer<P::Point>>(
        &self,
        point: P::Point,
        pruned: bool,
        observer: &mut O,
    ) -> Option<Traced<Option<Nearest<P::Point>>>> {
        macro_rules! either {
            ($s:expr) => {
                if pruned {
                    $s.lecture_min_distance_pruned_observed(point, observer)
                } else {
                    $s.lecture_min_distance_observed(point, observer)
                }
            };
        }
        match self {
            Self::SphereTree(s) => Some(either!(s)),
            Self::AabbTree(s) => Some(either!(s)),
            Self::ObbTree(s) => Some(either!(s)),
            _ => None,
        }
    }

    /// The `k` nearest primitives to `point`, reporting each step to `observer`.
    pub fn k_nearest<O: Observer<P::Point>>(
        &self,
        point: P::Point,
        k: usize,
        observer: &mut O,
    ) -> Traced<Vec<Nearest<P::Point>>> {
        with_structure!(self, s => s.k_nearest_observed(point, k, observer))
    }
}

/// Builds a BVH of any node volume, with its split log when asked (the log costs a vector
/// per node, so plain builds skip it).
fn bvh_build<P, B, O>(
    prims: &[P],
    options: &BvhOptions,
    observer: &mut O,
    log: bool,
    wrap: fn(Bvh<B, P>) -> Built<P>,
) -> (Built<P>, Vec<SplitRecord>)
where
    P: Primitive,
    B: NodeVolume<Point = P::Point>,
    O: Observer<P::Point>,
{
    if log {
        let mut with_splits = SplitLog {
            events: observer,
            splits: Vec::new(),
        };
        let tree = Bvh::build_observed(prims, options, &mut with_splits);
        (wrap(tree), with_splits.splits)
    } else {
        (wrap(Bvh::build_with(prims, options)), Vec::new())
    }
}

/// Passes the events on to `events` and keeps the builder's split decisions.
struct SplitLog<'a, O> {
    events: &'a mut O,
    splits: Vec<SplitRecord>,
}

impl<V: Vector, O: Observer<V>> Observer<V> for SplitLog<'_, O> {
    fn on(&mut self, event: bvhlab::Event<V>) {
        self.events.on(event);
    }

    fn wants_splits(&self) -> bool {
        true
    }

    fn on_split(&mut self, record: &SplitRecord) {
        self.splits.push(record.clone());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bvhlab::RayCast;
    use bvhlab::glam::Vec2;
    use bvhlab::{Ray2, Segment2};

    #[test]
    fn every_kind_builds_and_answers_like_brute_force() {
        let prims: Vec<Segment2> = (0..40)
            .map(|i| {
                let x = (i % 8) as f32 * 2.0;
                let y = (i / 8) as f32 * 2.0;
                Segment2::new(Vec2::new(x, y), Vec2::new(x + 1.0, y + 0.5))
            })
            .collect();
        let ray = Ray2::through(Vec2::new(-1.0, 0.3), Vec2::new(20.0, 8.0)).expect("ray");
        let reference = BruteForce::build(&prims).ray_first_hit(&ray, f32::INFINITY);
        for kind in StructureKind::ALL {
            let settings = BuildSettings {
                kind,
                ..BuildSettings::default()
            };
            let built = Built::build(&prims, &settings);
            assert_eq!(
                built.ray_first_hit(&ray, &mut ()).answer,
                reference,
                "{kind:?}"
            );
            assert_eq!(
                built.outline().is_empty(),
                kind == StructureKind::BruteForce
            );
        }
    }
}
