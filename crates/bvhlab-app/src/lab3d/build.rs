//! Building a structure over a mesh without freezing the page.
//!
//! The browser runs the lab on one thread, so a million-triangle BVH cannot be built in one
//! call: [`BuildJob`] drives the core's resumable [`BvhBuild`] a few milliseconds per frame
//! and reports its progress for the progress bar. The other structures build in one call,
//! and are offered up to [`MAX_TRIANGLES_ANY_STRUCTURE`] triangles (a BSP tree or an SAH k-d
//! tree over a million triangles would take minutes and gigabytes; a BVH is what one builds
//! there).

use bvhlab::glam::Vec3;
use bvhlab::structure::bvh::{BvhBuild, NodeVolume};
use bvhlab::{Aabb3, BruteForce, Bvh, NodeOutline, Obb3, SpatialIndex, Sphere3, Stats, Triangle3};
use web_time::Instant;

use super::mesh::Mesh3d;
use crate::structures::{BuildSettings, Built, StructureKind};

/// The largest mesh every structure is offered for; past it, only BVHs (and brute force).
pub const MAX_TRIANGLES_ANY_STRUCTURE: usize = 250_000;

/// The largest structure whose nodes are listed for drawing through the core's outline
/// (BVHs are drawn from their nodes directly, at any size).
const MAX_OUTLINE_TRIANGLES: usize = MAX_TRIANGLES_ANY_STRUCTURE;

/// How much work one call of the core's resumable build does (its unit: primitives handled).
const SLICE: usize = 20_000;

/// A structure built over the mesh, with what the 3D view reads from it once.
pub struct Built3d {
    /// The settings it was built with.
    pub settings: BuildSettings,
    /// The mesh revision it was built on.
    pub revision: u64,
    /// The structure.
    pub structure: Built<Triangle3>,
    /// The baseline, over the same triangles.
    pub brute: BruteForce<Triangle3>,
    /// Every node, for the structures that are not BVHs (BVHs are read directly).
    pub outline: Option<Vec<NodeOutline<Vec3>>>,
    /// How many nodes there are (node ids run below this).
    pub node_count: usize,
    /// Node count, depth, SAH cost, memory.
    pub stats: Stats,
    /// Milliseconds of work the build took (spread over frames for a sliced build).
    pub build_ms: f64,
    /// In how many frames it was built.
    pub frames: usize,
}

impl Built3d {
    fn new(
        structure: Built<Triangle3>,
        mesh: &Mesh3d,
        settings: BuildSettings,
        build_ms: f64,
        frames: usize,
    ) -> Self {
        let outline = (!settings.kind.is_bvh() && mesh.triangle_count() <= MAX_OUTLINE_TRIANGLES)
            .then(|| structure.outline());
        let stats = structure.stats();
        let node_count = outline.as_ref().map_or(stats.nodes, Vec::len);
        Self {
            settings,
            revision: mesh.revision,
            brute: BruteForce::build(mesh.mesh.triangles()),
            structure,
            outline,
            node_count,
            stats,
            build_ms,
            frames,
        }
    }

    /// What a recording asks questions of.
    pub fn subject<'a>(&'a self, mesh: &'a Mesh3d) -> crate::recording::Subject<'a, Triangle3> {
        crate::recording::Subject {
            structure: &self.structure,
            brute: &self.brute,
            prims: mesh.mesh.triangles(),
            settings: self.settings,
            revision: self.revision,
            node_count: self.node_count,
        }
    }
}

/// A sliced BVH build of one node volume.
enum Sliced {
    Sphere(BvhBuild<Sphere3, Triangle3>),
    Aabb(BvhBuild<Aabb3, Triangle3>),
    Obb(BvhBuild<Obb3, Triangle3>),
}

/// A build under way.
pub struct BuildJob {
    /// The settings being built.
    pub settings: BuildSettings,
    /// The mesh revision being built on.
    pub revision: u64,
    sliced: Option<Sliced>,
    spent_ms: f64,
    frames: usize,
    fraction: f32,
}

impl BuildJob {
    /// Starts building `settings`' structure over `mesh`.
    ///
    /// # Errors
    /// Why it is not offered: a structure other than a BVH over more than
    /// [`MAX_TRIANGLES_ANY_STRUCTURE`] triangles.
    pub fn start(mesh: &Mesh3d, settings: BuildSettings) -> Result<Self, String> {
        let n = mesh.triangle_count();
        let kind = settings.kind;
        if !kind.is_bvh() && kind != StructureKind::BruteForce && n > MAX_TRIANGLES_ANY_STRUCTURE {
            return Err(format!(
                "The {} is offered up to {} triangles; {} has {}. Pick a sphere, AABB or OBB tree, which build over any mesh.",
                kind.label_in(3),
                thousands(MAX_TRIANGLES_ANY_STRUCTURE),
                mesh.name,
                thousands(n),
            ));
        }
        let prims = || mesh.mesh.triangles().to_vec();
        let options = settings.bvh_options();
        let sliced = match kind {
            StructureKind::SphereTree => Some(Sliced::Sphere(BvhBuild::new(prims(), options))),
            StructureKind::AabbTree => Some(Sliced::Aabb(BvhBuild::new(prims(), options))),
            StructureKind::ObbTree => Some(Sliced::Obb(BvhBuild::new(prims(), options))),
            _ => None,
        };
        Ok(Self {
            settings,
            revision: mesh.revision,
            sliced,
            spent_ms: 0.0,
            frames: 0,
            fraction: 0.0,
        })
    }

    /// Works for about `budget_ms` milliseconds; the structure once it is finished.
    pub fn run(&mut self, mesh: &Mesh3d, budget_ms: f64) -> Option<Built3d> {
        let start = Instant::now();
        self.frames += 1;
        let elapsed = |s: &Instant| s.elapsed().as_secs_f64() * 1e3;
        let done = match &mut self.sliced {
            None => {
                let structure = Built::build(mesh.mesh.triangles(), &self.settings);
                self.spent_ms += elapsed(&start);
                return Some(Built3d::new(
                    structure,
                    mesh,
                    self.settings,
                    self.spent_ms,
                    self.frames,
                ));
            }
            Some(Sliced::Sphere(job)) => slice(job, &start, budget_ms, &mut self.fraction),
            Some(Sliced::Aabb(job)) => slice(job, &start, budget_ms, &mut self.fraction),
            Some(Sliced::Obb(job)) => slice(job, &start, budget_ms, &mut self.fraction),
        };
        self.spent_ms += elapsed(&start);
        if !done {
            return None;
        }
        let structure = match self.sliced.take()? {
            Sliced::Sphere(job) => Built::SphereTree(job.finish()),
            Sliced::Aabb(job) => Built::AabbTree(job.finish()),
            Sliced::Obb(job) => Built::ObbTree(job.finish()),
        };
        Some(Built3d::new(
            structure,
            mesh,
            self.settings,
            self.spent_ms,
            self.frames,
        ))
    }

    /// How far it is, from 0 to 1.
    pub fn fraction(&self) -> f32 {
        self.fraction
    }
}

/// Steps a sliced build until it is done or the frame's budget is spent; whether it is done.
fn slice<B>(
    job: &mut BvhBuild<B, Triangle3>,
    start: &Instant,
    budget_ms: f64,
    fraction: &mut f32,
) -> bool
where
    B: NodeVolume<Point = Vec3>,
    Bvh<B, Triangle3>: SpatialIndex,
{
    while !job.is_done() {
        *fraction = job.step(SLICE).fraction();
        if start.elapsed().as_secs_f64() * 1e3 >= budget_ms {
            break;
        }
    }
    job.is_done()
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
