//! The inputs of the side-by-side comparison with peer libraries (issue 7): scenes, rays and
//! closest-point query points, all deterministic (fixed seeds, fixed cameras), so that every
//! library, natively and in WebAssembly, answers exactly the same questions.
//!
//! - **Scenes** ([`SceneId`], in `scenes.rs`): the three real meshes of `../shared/data/meshes`
//!   (Stanford bunny, dragon, ogre; read with the core's OBJ reader), a torus of about 420k
//!   triangles and a displaced sphere of about 2M triangles ([`displaced_sphere`], seeded).
//! - **Rays** ([`RayKind`]), every direction of unit length so that `t` is a distance for
//!   every library (some normalise what they are given):
//!   - *primary*: a pinhole camera of `width × height` pixels (640 × 480) from each of a few
//!     fixed viewpoints around the mesh, framing its bounding sphere (coherent);
//!   - *shadow*: from each primary hit towards one fixed point light, limited to the light's
//!     distance (`t_max`), so a hit means "in shadow";
//!   - *diffuse*: from each primary hit, one cosine-weighted direction about the normal facing
//!     the camera (seeded; incoherent);
//!   - *random*: origins uniform in the mesh's bounding box, directions uniform on the sphere:
//!     the "300k random rays inside the bounding box";
//!   - *overview*: one more camera, far enough that the mesh is small in its frame and most
//!     rays miss it.
//!
//!   Secondary rays start a small offset (1e-3 of the bounding sphere's radius) off the surface
//!   along the facing normal, so that they do not hit their own triangle again.
//! - **Points**: uniform in the mesh's box grown to 1.5 times its size about its centre, for
//!   closest-point queries.
//!
//! The primary hits that the secondary rays start from are found with bvhlab's AABB tree; its
//! answers are exact (equal to brute force), so the rays do not depend on how fast it is.

use bvhlab::RayCast;
use bvhlab::glam::Vec3;
use bvhlab::{AabbTree3, Ray3, SpatialIndex, Triangle3};

use crate::camera_rays;
use crate::rng::SplitMix64;
pub use crate::scenes::{SceneId, displaced_sphere, triangles_from_obj};

/// A ray of the workload: unit direction, and the largest `t` that counts as a hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BenchRay {
    /// Where the ray starts.
    pub origin: Vec3,
    /// Its direction, of unit length.
    pub dir: Vec3,
    /// Hits beyond this distance do not count (infinite but for shadow rays).
    pub t_max: f32,
}

/// The kinds of rays, from coherent to incoherent.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RayKind {
    /// Camera rays through the pixels of a pinhole camera.
    Primary,
    /// From the primary hits towards a point light.
    Shadow,
    /// Cosine-weighted bounces from the primary hits.
    Diffuse,
    /// Random origins in the bounding box, random directions.
    Random,
    /// Camera rays from far away ([`OVERVIEW_DISTANCE`] bounding radii): the mesh is small in
    /// the frame and most rays miss it, so the walks are judged on rays that only touch the
    /// top of the tree too (the workload on which the first comparison's lead shrank).
    Overview,
}

impl RayKind {
    /// Every kind, in the order of the tables.
    pub const ALL: [Self; 5] = [
        Self::Primary,
        Self::Shadow,
        Self::Diffuse,
        Self::Random,
        Self::Overview,
    ];

    /// The kind's short name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Primary => "primary",
            Self::Shadow => "shadow",
            Self::Diffuse => "diffuse",
            Self::Random => "random",
            Self::Overview => "overview",
        }
    }
}

/// How much work a run asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WorkloadSize {
    /// Camera image width in pixels.
    pub width: usize,
    /// Camera image height in pixels.
    pub height: usize,
    /// Camera viewpoints (at most [`VIEWPOINTS`]`.len()`).
    pub viewpoints: usize,
    /// Random rays in the bounding box.
    pub random_rays: usize,
    /// Closest-point query points.
    pub points: usize,
}

impl WorkloadSize {
    /// The full comparison: 640 × 480 from 3 viewpoints, 300k random rays, 1M points.
    pub const FULL: Self = Self {
        width: 640,
        height: 480,
        viewpoints: 3,
        random_rays: 300_000,
        points: 1_000_000,
    };
    /// A smoke run: 160 × 120 from one viewpoint, 20k random rays, 20k points.
    pub const QUICK: Self = Self {
        width: 160,
        height: 120,
        viewpoints: 1,
        random_rays: 20_000,
        points: 20_000,
    };
}

/// Where the cameras look from: directions from the mesh's centre, scaled to frame it.
pub const VIEWPOINTS: [[f32; 3]; 3] = [[1.0, -0.7, 0.5], [-0.6, -1.0, 0.3], [0.2, 0.9, -0.6]];

/// Where the overview camera looks from (a direction from the mesh's centre).
pub const OVERVIEW_VIEWPOINT: [f32; 3] = [-0.8, 0.5, 0.7];

/// How far the overview camera stands, in bounding radii: with the cameras' half-angle of
/// about 24°, the bounding sphere fills about a seventh of the frame's height squared, and the
/// mesh less.
pub const OVERVIEW_DISTANCE: f32 = 6.0;

/// The rays and points of one scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Workload {
    /// One set of rays per [`RayKind`], in [`RayKind::ALL`]'s order.
    pub rays: Vec<(RayKind, Vec<BenchRay>)>,
    /// Closest-point query points.
    pub points: Vec<Vec3>,
}

/// The scene's bounding box as (min, max).
pub fn bounds(tris: &[Triangle3]) -> (Vec3, Vec3) {
    tris.iter()
        .flat_map(|t| [t.a, t.b, t.c])
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p), hi.max(p))
        })
}

impl Workload {
    /// The rays and points for `tris`, of the given size (seeded: the same every time).
    pub fn generate(tris: &[Triangle3], size: &WorkloadSize) -> Self {
        let (lo, hi) = bounds(tris);
        let center = (lo + hi) * 0.5;
        let radius = ((hi - lo).length() * 0.5).max(f32::MIN_POSITIVE);
        let tree = AabbTree3::build(tris);
        let primary = primary_rays(center, radius, size);
        let hits = surface_hits(&tree, &primary, radius);
        let light = center + Vec3::new(0.4, 0.8, 1.0).normalize() * (4.0 * radius);
        let shadow = hits
            .iter()
            .filter_map(|&(p, _)| {
                let to_light = light - p;
                let dir = to_light.try_normalize()?;
                Some(BenchRay {
                    origin: p,
                    dir,
                    t_max: to_light.length(),
                })
            })
            .collect();
        let mut rng = SplitMix64::new(0x0D1F_F05E);
        let diffuse = hits
            .iter()
            .map(|&(p, n)| BenchRay {
                origin: p,
                dir: cosine_direction(n, &mut rng),
                t_max: f32::INFINITY,
            })
            .collect();
        let mut rng = SplitMix64::new(0x0BAD_5EED);
        let random = (0..size.random_rays)
            .map(|_| BenchRay {
                origin: lo + (hi - lo) * random_unit_cube(&mut rng),
                dir: unit_vector(&mut rng),
                t_max: f32::INFINITY,
            })
            .collect();
        let mut rng = SplitMix64::new(0x0090_1775);
        let points = (0..size.points)
            .map(|_| center + (hi - lo) * 1.5 * (random_unit_cube(&mut rng) - 0.5))
            .collect();
        Self {
            rays: vec![
                (RayKind::Primary, primary),
                (RayKind::Shadow, shadow),
                (RayKind::Diffuse, diffuse),
                (RayKind::Random, random),
                (
                    RayKind::Overview,
                    overview_rays(center, radius, size.width, size.height),
                ),
            ],
            points,
        }
    }

    /// The rays of one kind.
    pub fn rays_of(&self, kind: RayKind) -> &[BenchRay] {
        self.rays
            .iter()
            .find(|(k, _)| *k == kind)
            .map_or(&[], |(_, rays)| rays.as_slice())
    }
}

/// The camera rays of every viewpoint, each camera 2 bounding radii from the centre (its
/// vertical half-angle of about 24° frames the mesh, which is smaller than its bounding
/// sphere).
fn primary_rays(center: Vec3, radius: f32, size: &WorkloadSize) -> Vec<BenchRay> {
    VIEWPOINTS
        .iter()
        .take(size.viewpoints)
        .flat_map(|d| {
            let eye = center + Vec3::from_array(*d).normalize() * (2.0 * radius);
            camera_rays(eye, center, size.width, size.height)
        })
        .map(|ray| BenchRay {
            origin: ray.origin(),
            dir: ray.dir().normalize(),
            t_max: f32::INFINITY,
        })
        .collect()
}

/// The overview camera's rays: one camera [`OVERVIEW_DISTANCE`] radii away, the mesh small in
/// its frame.
fn overview_rays(center: Vec3, radius: f32, width: usize, height: usize) -> Vec<BenchRay> {
    let eye =
        center + Vec3::from_array(OVERVIEW_VIEWPOINT).normalize() * (OVERVIEW_DISTANCE * radius);
    camera_rays(eye, center, width, height)
        .into_iter()
        .map(|ray| BenchRay {
            origin: ray.origin(),
            dir: ray.dir().normalize(),
            t_max: f32::INFINITY,
        })
        .collect()
}

/// The primary hits: each a point just off the surface on the camera's side, and the unit
/// normal facing the camera.
fn surface_hits(tree: &AabbTree3, rays: &[BenchRay], radius: f32) -> Vec<(Vec3, Vec3)> {
    let offset = 1e-3 * radius;
    rays.iter()
        .filter_map(|r| {
            let ray = Ray3::new(r.origin, r.dir).ok()?;
            let hit = tree.ray_first_hit(&ray, r.t_max)?;
            let normal = tree.primitives()[hit.prim].unit_normal()?;
            let facing = if normal.dot(r.dir) < 0.0 {
                normal
            } else {
                -normal
            };
            Some((ray.at(hit.t) + facing * offset, facing))
        })
        .collect()
}

/// A point uniform in the unit cube `[0, 1)³`.
fn random_unit_cube(rng: &mut SplitMix64) -> Vec3 {
    Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32())
}

/// A direction uniform on the unit sphere (Archimedes: `z` uniform in `[-1, 1]`).
pub(crate) fn unit_vector(rng: &mut SplitMix64) -> Vec3 {
    let z = 1.0 - 2.0 * rng.next_f32();
    let phi = std::f32::consts::TAU * rng.next_f32();
    let r = (1.0 - z * z).max(0.0).sqrt();
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// A cosine-weighted direction about the unit normal `n` (Malley's method: a uniform point
/// on the disk lifted to the hemisphere), in the orthonormal basis of Duff et al., "Building an
/// Orthonormal Basis, Revisited", JCGT 6(1), 2017.
fn cosine_direction(n: Vec3, rng: &mut SplitMix64) -> Vec3 {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let t = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let s = Vec3::new(b, sign + n.y * n.y * a, -n.y);
    let u = rng.next_f32();
    let phi = std::f32::consts::TAU * rng.next_f32();
    let r = u.sqrt();
    (t * (r * phi.cos()) + s * (r * phi.sin()) + n * (1.0 - u).max(0.0).sqrt()).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::torus_with;
    use bvhlab::PointQuery;

    #[test]
    fn rays_have_unit_directions_and_secondary_rays_start_at_hits() {
        let tris = torus_with(2_000);
        let size = WorkloadSize {
            width: 40,
            height: 30,
            viewpoints: 2,
            random_rays: 500,
            points: 100,
        };
        let work = Workload::generate(&tris, &size);
        assert_eq!(work.rays_of(RayKind::Primary).len(), 2 * 40 * 30);
        assert_eq!(work.rays_of(RayKind::Random).len(), 500);
        assert_eq!(work.points.len(), 100);
        for (_, rays) in &work.rays {
            assert!(rays.iter().all(|r| (r.dir.length() - 1.0).abs() < 1e-5));
        }
        // The torus fills much of the view: many primary rays hit, each a shadow and a
        // diffuse ray; every one starts within a small distance of some triangle.
        let diffuse = work.rays_of(RayKind::Diffuse);
        assert!(diffuse.len() > 200, "{}", diffuse.len());
        assert_eq!(work.rays_of(RayKind::Shadow).len(), diffuse.len());
        let brute = bvhlab::BruteForce::build(&tris);
        for ray in diffuse.iter().step_by(17) {
            let near = brute.closest_point(ray.origin).map(|n| n.distance);
            assert!(near.is_some_and(|d| d < 1e-2), "{near:?}");
        }
    }

    #[test]
    fn the_overview_camera_sees_the_mesh_small_so_most_of_its_rays_miss() {
        let tris = shared_mesh_or_torus();
        let size = WorkloadSize {
            width: 64,
            height: 48,
            viewpoints: 1,
            random_rays: 10,
            points: 10,
        };
        let work = Workload::generate(&tris, &size);
        let overview = work.rays_of(RayKind::Overview);
        assert_eq!(overview.len(), 64 * 48);
        let tree = AabbTree3::build(&tris);
        let hits = overview
            .iter()
            .filter(|r| {
                let ray = Ray3::new(r.origin, r.dir).expect("finite unit rays");
                tree.ray_first_hit(&ray, r.t_max).is_some()
            })
            .count();
        // Some rays hit (the camera looks at the mesh), most miss.
        assert!(
            hits > 20 && hits * 4 < overview.len(),
            "{hits} of {}",
            overview.len()
        );
    }

    /// The bunny when the shared meshes are here, else a torus (both closed-ish shapes).
    fn shared_mesh_or_torus() -> Vec<Triangle3> {
        SceneId::Bunny
            .triangles()
            .unwrap_or_else(|_| torus_with(5_000))
    }

    #[test]
    fn cosine_directions_leave_the_surface_and_average_to_two_thirds() {
        let mut rng = SplitMix64::new(3);
        let n = Vec3::new(0.3, -0.5, 0.8).normalize();
        let cosines: Vec<f32> = (0..20_000)
            .map(|_| cosine_direction(n, &mut rng).dot(n))
            .collect();
        assert!(cosines.iter().all(|&c| c >= -1e-6));
        // E[cos θ] under the cosine density is 2/3.
        let mean = cosines.iter().sum::<f32>() / cosines.len() as f32;
        assert!((mean - 2.0 / 3.0).abs() < 0.01, "{mean}");
    }

    #[test]
    fn the_workload_is_the_same_every_time() {
        let tris = torus_with(1_000);
        let size = WorkloadSize {
            width: 8,
            height: 6,
            viewpoints: 1,
            random_rays: 10,
            points: 10,
        };
        assert_eq!(
            Workload::generate(&tris, &size),
            Workload::generate(&tris, &size)
        );
    }
}
