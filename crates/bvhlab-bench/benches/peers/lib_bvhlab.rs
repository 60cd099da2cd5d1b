//! bvhlab's AABB tree (binned SAH, the default `Bvh` options) through its public query API.
//! To measure another entry point (a faster traversal), change `first_hit` and
//! `closest_distance` here.

use bvhlab::glam::Vec3;
use bvhlab::{AabbTree3, Ray3, SpatialIndex, Triangle3};
use bvhlab::{PointQuery, RayCast};
use bvhlab_bench::workload::BenchRay;

use crate::library::{Library, RayCost, TreeFacts};

/// bvhlab's `AabbTree3`.
pub struct Bvhlab;

impl Library for Bvhlab {
    const NAME: &'static str = "bvhlab AABB tree (binned SAH)";
    const HAS_CLOSEST: bool = true;
    const HAS_OCCLUSION: bool = true;
    type Input = Vec<Triangle3>;
    type Tree<'a> = AabbTree3;
    type Ray = (Ray3, f32);

    fn input(tris: &[Triangle3]) -> Self::Input {
        tris.to_vec()
    }

    fn build(input: &Self::Input) -> AabbTree3 {
        AabbTree3::build(input)
    }

    fn ray(ray: &BenchRay) -> Self::Ray {
        // The workload's rays have finite origins and unit directions.
        let r = Ray3::new(ray.origin, ray.dir).unwrap_or_else(|e| panic!("bad ray {ray:?}: {e}"));
        (r, ray.t_max)
    }

    fn first_hit(tree: &AabbTree3, (ray, t_max): &Self::Ray) -> Option<f32> {
        tree.ray_first_hit(ray, *t_max).map(|hit| hit.t)
    }

    fn occluded(tree: &AabbTree3, (ray, t_max): &Self::Ray) -> bool {
        tree.ray_any_hit(ray, *t_max).is_some()
    }

    fn first_hit_cost(tree: &AabbTree3, (ray, t_max): &Self::Ray) -> RayCost {
        let cost = tree.ray_first_hit_observed(ray, *t_max, &mut ()).cost;
        RayCost {
            nodes: Some(cost.nodes_visited),
            prims: Some(cost.prim_tests),
        }
    }

    fn closest_distance(tree: &AabbTree3, point: Vec3) -> Option<f32> {
        tree.closest_point(point).map(|n| n.distance)
    }

    fn facts(tree: &AabbTree3) -> TreeFacts {
        let stats = tree.stats();
        TreeFacts {
            nodes: Some(stats.nodes),
            sah: stats.sah_cost.map(f64::from),
            bytes: Some(stats.memory_bytes),
        }
    }
}
