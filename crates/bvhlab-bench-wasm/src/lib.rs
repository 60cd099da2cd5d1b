//! The WebAssembly half of the peer comparison (issue 7): bvhlab's AABB tree (its 4-wide
//! copy, [`Bvh4`], which answers the queries, as natively) and the
//! comparison's workload ([`bvhlab_bench::workload`]) compiled for `wasm32-unknown-unknown`
//! (with `-C target-feature=+simd128`), for `js/run.mjs` to time in node beside
//! three-mesh-bvh on exactly the same triangles, rays and points.
//!
//! The module hands its inputs to JavaScript as flat `Float32Array`s (9 floats per triangle,
//! 7 per ray: origin, unit direction, `t_max`; 3 per point), and answers as one float per
//! query (`-1` for no hit). Timing is done by the caller around [`WasmBench::build`],
//! [`WasmBench::first_hits`] and [`WasmBench::closest`].

use bvhlab::structure::bvh::Bvh4;
use bvhlab::{Ray3, Triangle3};
use bvhlab_bench::workload::{RayKind, Workload, WorkloadSize, triangles_from_obj};
use wasm_bindgen::prelude::*;

/// One scene: its triangles, its workload, its rays as bvhlab's [`Ray3`] (prepared before
/// any timing, as the native comparison converts every library's rays untimed), and (once
/// built) bvhlab's tree.
#[wasm_bindgen]
pub struct WasmBench {
    tris: Vec<Triangle3>,
    work: Workload,
    /// Per ray kind, each ray and its `t_max` (`None` for a ray `Ray3::new` refuses).
    prepared: Vec<Vec<(Option<Ray3>, f32)>>,
    tree: Option<Bvh4<Triangle3>>,
}

#[wasm_bindgen]
impl WasmBench {
    /// Reads an OBJ file and generates the workload: the full one (or the quick one), with
    /// at most `max_points` closest-point queries.
    ///
    /// # Errors
    /// The OBJ reader's message.
    #[wasm_bindgen(constructor)]
    pub fn new(obj: &[u8], quick: bool, max_points: usize) -> Result<WasmBench, JsError> {
        let tris = triangles_from_obj(obj).map_err(|e| JsError::new(&e))?;
        let mut size = if quick {
            WorkloadSize::QUICK
        } else {
            WorkloadSize::FULL
        };
        size.points = size.points.min(max_points);
        let work = Workload::generate(&tris, &size);
        let prepared = RayKind::ALL
            .iter()
            .map(|&kind| {
                work.rays_of(kind)
                    .iter()
                    .map(|r| (Ray3::new(r.origin, r.dir).ok(), r.t_max))
                    .collect()
            })
            .collect();
        Ok(Self {
            tris,
            work,
            prepared,
            tree: None,
        })
    }

    /// The number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.tris.len()
    }

    /// The triangles' corners, 9 floats per triangle (a non-indexed position buffer).
    pub fn positions(&self) -> Vec<f32> {
        self.tris
            .iter()
            .flat_map(|t| [t.a, t.b, t.c])
            .flat_map(|p| p.to_array())
            .collect()
    }

    /// The ray kinds' names, in the order `rays` and `first_hits` take them.
    pub fn kind_names() -> Vec<String> {
        RayKind::ALL.iter().map(|k| k.name().to_owned()).collect()
    }

    /// The rays of kind `kind` (an index into `kind_names`), 7 floats each.
    pub fn rays(&self, kind: usize) -> Vec<f32> {
        self.kind_rays(kind)
            .iter()
            .flat_map(|r| {
                let (o, d) = (r.origin, r.dir);
                [o.x, o.y, o.z, d.x, d.y, d.z, r.t_max]
            })
            .collect()
    }

    /// The closest-point query points, 3 floats each.
    pub fn points(&self) -> Vec<f32> {
        self.work
            .points
            .iter()
            .flat_map(bvhlab::glam::Vec3::to_array)
            .collect()
    }

    /// Builds bvhlab's AABB tree (binned SAH) and collapses it into the 4-wide tree that
    /// answers, replacing the previous one.
    pub fn build(&mut self) {
        self.tree = Some(Bvh4::build(&self.tris));
    }

    /// The first-hit distance of every ray of kind `kind`, `-1` for a miss (empty before
    /// `build`).
    pub fn first_hits(&self, kind: usize) -> Vec<f32> {
        self.per_ray(kind, -1.0, |tree, ray, t_max| {
            tree.ray_first_hit(ray, t_max).map_or(-1.0, |hit| hit.t)
        })
    }

    /// Whether each ray of kind `kind` is blocked within its `t_max` (1) or not (0), by the
    /// 4-wide tree's any-hit walk (occlusion; empty before `build`).
    pub fn any_hits(&self, kind: usize) -> Vec<u8> {
        self.per_ray(kind, 0, |tree, ray, t_max| {
            u8::from(tree.ray_any_hit(ray, t_max).is_some())
        })
    }

    /// The distance from every query point to the nearest triangle (`-1` before `build`).
    pub fn closest(&self) -> Vec<f32> {
        let Some(tree) = &self.tree else {
            return Vec::new();
        };
        self.work
            .points
            .iter()
            .map(|&p| tree.closest_point(p).map_or(-1.0, |n| n.distance))
            .collect()
    }
}

impl WasmBench {
    /// `answer` for every ray of kind `kind` (with its `t_max`), `refused` for a ray that
    /// `Ray3::new` refused; empty before `build` or for an unknown kind.
    fn per_ray<T: Copy>(
        &self,
        kind: usize,
        refused: T,
        answer: impl Fn(&Bvh4<Triangle3>, &Ray3, f32) -> T,
    ) -> Vec<T> {
        let (Some(tree), Some(rays)) = (&self.tree, self.prepared.get(kind)) else {
            return Vec::new();
        };
        rays.iter()
            .map(|(ray, t_max)| {
                ray.as_ref()
                    .map_or(refused, |ray| answer(tree, ray, *t_max))
            })
            .collect()
    }

    fn kind_rays(&self, kind: usize) -> &[bvhlab_bench::workload::BenchRay] {
        RayKind::ALL
            .get(kind)
            .map_or(&[], |&k| self.work.rays_of(k))
    }
}
