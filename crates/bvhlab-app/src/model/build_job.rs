//! Building a lane's structure without freezing the page.
//!
//! The browser runs the lab on one thread, so a million-triangle BVH cannot be built in one
//! call: [`BuildJob`] drives the core's resumable [`BvhBuild`] a few milliseconds per frame
//! and reports its progress for the progress bar. Small inputs (at most one slice) and the
//! other structures build in one call; those are offered up to
//! [`LabPrimitive::MAX_FOR_EVERY_STRUCTURE`] primitives.

use bvhlab::structure::bvh::{BvhBuild, NodeVolume};
use bvhlab::{Aabb, BruteForce, Bvh, NodeOutline, Obb, SpatialIndex, Sphere, Stats, Vector};

use super::clock::Stopwatch;
use super::dimension::{LabPrimitive, thousands};
use super::structures::{BuildSettings, Built, StructureKind};

/// How much work one call of the core's resumable build does (its unit: primitives handled);
/// inputs up to this size are built in one go.
const SLICE: usize = 20_000;

/// A run shorter than this is repeated, for [`timed`].
const MIN_TIMED_MS: f64 = 0.5;
/// The most runs [`timed`] makes.
const MAX_TIMED_RUNS: u32 = 100;

/// Runs `work` once, and again while all the runs took less than `MIN_TIMED_MS` (at most
/// `MAX_TIMED_RUNS` runs); returns the last run's result and the mean milliseconds per run.
/// The browser's clock counts in steps of 0.1 ms, too coarse to time one refit or build of a
/// few hundred segments, which take microseconds; `work` must give the same result every run.
pub fn timed<T>(mut work: impl FnMut() -> T) -> (T, f64) {
    let clock = Stopwatch::start();
    let mut runs = 1;
    let mut out = work();
    while runs < MAX_TIMED_RUNS && clock.elapsed_ms() < MIN_TIMED_MS {
        out = work();
        runs += 1;
    }
    (out, clock.elapsed_ms() / f64::from(runs))
}

/// A lane's structure, built, with what the lab reads from it once.
pub struct Structure<P: LabPrimitive> {
    /// The settings it was built with.
    pub settings: BuildSettings,
    /// The revision of the primitives it was built on.
    pub revision: u64,
    /// The structure.
    pub built: Built<P>,
    /// The baseline, over the same primitives.
    pub brute: BruteForce<P>,
    /// Every node, for drawing and the tree diagram; `None` past
    /// [`LabPrimitive::MAX_LISTED`] primitives (BVHs are then drawn from their nodes).
    pub outline: Option<Vec<NodeOutline<P::Point>>>,
    /// How many nodes there are (node ids run below this).
    pub node_count: usize,
    /// Node count, depth, SAH cost, memory.
    pub stats: Stats,
    /// Milliseconds of work the build took (spread over frames for a sliced build).
    pub build_ms: f64,
    /// In how many frames it was built.
    pub frames: usize,
    /// For leaf colouring: the first leaf listing each primitive (empty without an outline).
    pub leaf_of: Vec<Option<u32>>,
    /// The SAH cost when it was built (refits leave it: [`Stats::sah_cost`] is the cost now).
    pub build_sah_cost: Option<f32>,
    /// How many times it was refitted since it was built.
    pub refits: usize,
}

impl<P: LabPrimitive> Structure<P>
where
    Sphere<P::Point>: NodeVolume<Point = P::Point>,
    Aabb<P::Point>: NodeVolume<Point = P::Point>,
    Obb<P::Point>: NodeVolume<Point = P::Point>,
{
    fn new(
        built: Built<P>,
        prims: &[P],
        revision: u64,
        settings: BuildSettings,
        build_ms: f64,
        frames: usize,
    ) -> Self {
        let outline = (prims.len() <= P::MAX_LISTED).then(|| built.outline());
        let stats = built.stats();
        let node_count = outline.as_ref().map_or(stats.nodes, Vec::len);
        let mut leaf_of = vec![None; if outline.is_some() { prims.len() } else { 0 }];
        for node in outline.iter().flatten().filter(|n| n.is_leaf()) {
            for &p in &node.primitives {
                if let Some(slot @ None) = leaf_of.get_mut(p as usize) {
                    *slot = Some(node.id.0);
                }
            }
        }
        Self {
            settings,
            revision,
            brute: BruteForce::build(prims),
            build_sah_cost: stats.sah_cost,
            refits: 0,
            built,
            outline,
            node_count,
            stats,
            build_ms,
            frames,
            leaf_of,
        }
    }

    /// Refits a BVH to `prims` (its primitives, moved: the same count) of `revision`: the
    /// tree keeps its nodes and their primitives, its volumes, outline, statistics and
    /// baseline follow the primitives. Returns the milliseconds the core's refit took.
    ///
    /// # Errors
    /// Why it was not refitted (a structure other than a BVH, or primitives the tree cannot
    /// keep), in a sentence; it is then unchanged and must be rebuilt.
    pub fn refit(&mut self, prims: &[P], revision: u64) -> Result<f64, String> {
        // Refitting again to the same primitives gives the same tree: timed over repeats.
        let (refitted, millis) = timed(|| self.built.refit(prims));
        match refitted {
            Some(Ok(_)) => {}
            Some(Err(e)) => return Err(format!("the tree was rebuilt: {e}")),
            None => {
                let why = super::refit::refit_refused(self.settings.kind)
                    .unwrap_or("this structure updates by rebuilding");
                return Err(why.to_owned());
            }
        }
        self.revision = revision;
        self.brute = BruteForce::build(prims);
        if self.outline.is_some() {
            self.outline = Some(self.built.outline());
        }
        self.stats = self.built.stats();
        self.refits += 1;
        Ok(millis)
    }

    /// What a recording asks questions of, over `prims` (the primitives it was built on).
    pub fn subject<'a>(&'a self, prims: &'a [P]) -> super::recording::Subject<'a, P> {
        super::recording::Subject {
            structure: &self.built,
            brute: &self.brute,
            prims,
            settings: self.settings,
            revision: self.revision,
            node_count: self.node_count,
        }
    }
}

/// A sliced BVH build of one node volume.
enum Sliced<P: LabPrimitive> {
    Sphere(BvhBuild<Sphere<P::Point>, P>),
    Aabb(BvhBuild<Aabb<P::Point>, P>),
    Obb(BvhBuild<Obb<P::Point>, P>),
}

/// A build under way.
pub struct BuildJob<P: LabPrimitive> {
    /// The settings being built.
    pub settings: BuildSettings,
    /// The revision of the primitives being built on.
    pub revision: u64,
    sliced: Option<Sliced<P>>,
    spent_ms: f64,
    frames: usize,
    fraction: f32,
}

impl<P: LabPrimitive> BuildJob<P>
where
    Sphere<P::Point>: NodeVolume<Point = P::Point>,
    Aabb<P::Point>: NodeVolume<Point = P::Point>,
    Obb<P::Point>: NodeVolume<Point = P::Point>,
    Bvh<Sphere<P::Point>, P>: SpatialIndex,
    Bvh<Aabb<P::Point>, P>: SpatialIndex,
    Bvh<Obb<P::Point>, P>: SpatialIndex,
{
    /// Starts building `settings`' structure over `prims` (of `revision`).
    ///
    /// # Errors
    /// Why it is not offered: a structure other than a BVH over more than
    /// [`LabPrimitive::MAX_FOR_EVERY_STRUCTURE`] primitives.
    pub fn start(prims: &[P], revision: u64, settings: BuildSettings) -> Result<Self, String> {
        let n = prims.len();
        let kind = settings.kind;
        let dim = <P::Point as Vector>::DIM;
        if !kind.is_bvh() && kind != StructureKind::BruteForce && n > P::MAX_FOR_EVERY_STRUCTURE {
            return Err(format!(
                "The {} is offered up to {} {}; this one has {}. Pick a sphere, AABB or OBB tree, which build over any mesh.",
                kind.label_in(dim),
                thousands(P::MAX_FOR_EVERY_STRUCTURE),
                P::NAME,
                thousands(n),
            ));
        }
        let options = settings.bvh_options();
        let owned = || prims.to_vec();
        let sliced = if n <= SLICE {
            None
        } else {
            match kind {
                StructureKind::SphereTree => Some(Sliced::Sphere(BvhBuild::new(owned(), options))),
                StructureKind::AabbTree => Some(Sliced::Aabb(BvhBuild::new(owned(), options))),
                StructureKind::ObbTree => Some(Sliced::Obb(BvhBuild::new(owned(), options))),
                _ => None,
            }
        };
        Ok(Self {
            settings,
            revision,
            sliced,
            spent_ms: 0.0,
            frames: 0,
            fraction: 0.0,
        })
    }

    /// Works for about `budget_ms` milliseconds on `prims` (the primitives it was started
    /// on); the structure once it is finished.
    pub fn run(&mut self, prims: &[P], budget_ms: f64) -> Option<Structure<P>> {
        let clock = Stopwatch::start();
        self.frames += 1;
        let done = match &mut self.sliced {
            None => {
                // A build in one go: timed over repeats when it takes microseconds.
                let (built, millis) = timed(|| Built::build(prims, &self.settings));
                self.spent_ms += millis;
                return Some(self.finish(built, prims));
            }
            Some(Sliced::Sphere(job)) => slice(job, &clock, budget_ms, &mut self.fraction),
            Some(Sliced::Aabb(job)) => slice(job, &clock, budget_ms, &mut self.fraction),
            Some(Sliced::Obb(job)) => slice(job, &clock, budget_ms, &mut self.fraction),
        };
        self.spent_ms += clock.elapsed_ms();
        if !done {
            return None;
        }
        let built = match self.sliced.take()? {
            Sliced::Sphere(job) => Built::SphereTree(job.finish()),
            Sliced::Aabb(job) => Built::AabbTree(job.finish()),
            Sliced::Obb(job) => Built::ObbTree(job.finish()),
        };
        Some(self.finish(built, prims))
    }

    fn finish(&self, built: Built<P>, prims: &[P]) -> Structure<P> {
        Structure::new(
            built,
            prims,
            self.revision,
            self.settings,
            self.spent_ms,
            self.frames,
        )
    }

    /// How far it is, from 0 to 1.
    pub fn fraction(&self) -> f32 {
        self.fraction
    }
}

/// Steps a sliced build until it is done or the frame's budget is spent; whether it is done.
fn slice<B, P>(
    job: &mut BvhBuild<B, P>,
    clock: &Stopwatch,
    budget_ms: f64,
    fraction: &mut f32,
) -> bool
where
    P: LabPrimitive,
    B: NodeVolume<Point = P::Point>,
    Bvh<B, P>: SpatialIndex,
{
    while !job.is_done() {
        *fraction = job.step(SLICE).fraction();
        if clock.elapsed_ms() >= budget_ms {
            break;
        }
    }
    job.is_done()
}
