//! bvhlab's fastest path: [`Bvh4::build`], the binned-SAH AABB tree that costs leaves by
//! blocks of four triangles, collapsed 4-wide, its triangles kept in blocks tested four at a
//! time; it answers first hits and closest points bit for bit as brute force does (the
//! core's tests check that). The build time is `Bvh4::build`'s: the binary build and the
//! collapse, without keeping the binary tree, as a program that only asks queries would. The
//! SAH cost is the binary tree's built with the same options (the wide copy has the same
//! boxes; leaves costed one per triangle, as for every library), rebuilt for the table
//! outside the timing; the node count is the wide nodes'.

use bvhlab::glam::Vec3;
use bvhlab::structure::bvh::Bvh4;
use bvhlab::{AabbTree3, Ray3, SpatialIndex, Triangle3};
use bvhlab_bench::workload::BenchRay;

use crate::library::{Library, RayCost, TreeFacts};

/// The 4-wide tree, and the input it was built from (for the SAH cost in the table).
pub struct Wide<'a> {
    tree: Bvh4<Triangle3>,
    input: &'a [Triangle3],
}

/// bvhlab's `Bvh4`.
pub struct BvhlabWide;

impl Library for BvhlabWide {
    const NAME: &'static str = "bvhlab 4-wide AABB tree (binned SAH by blocks of 4, collapsed)";
    const HAS_CLOSEST: bool = true;
    const HAS_OCCLUSION: bool = true;
    type Input = Vec<Triangle3>;
    type Tree<'a> = Wide<'a>;
    type Ray = (Ray3, f32);

    fn input(tris: &[Triangle3]) -> Self::Input {
        tris.to_vec()
    }

    fn build(input: &Self::Input) -> Wide<'_> {
        Wide {
            tree: Bvh4::build(input),
            input,
        }
    }

    fn ray(ray: &BenchRay) -> Self::Ray {
        // The workload's rays have finite origins and unit directions.
        let r = Ray3::new(ray.origin, ray.dir).unwrap_or_else(|e| panic!("bad ray {ray:?}: {e}"));
        (r, ray.t_max)
    }

    fn first_hit(tree: &Wide<'_>, (ray, t_max): &Self::Ray) -> Option<f32> {
        tree.tree.ray_first_hit(ray, *t_max).map(|hit| hit.t)
    }

    fn occluded(tree: &Wide<'_>, (ray, t_max): &Self::Ray) -> bool {
        tree.tree.ray_any_hit(ray, *t_max).is_some()
    }

    fn first_hit_cost(_tree: &Wide<'_>, _ray: &Self::Ray) -> RayCost {
        // The wide walk counts nothing; the binary tree's row has the counts.
        RayCost {
            nodes: None,
            prims: None,
        }
    }

    fn closest_distance(tree: &Wide<'_>, point: Vec3) -> Option<f32> {
        tree.tree.closest_point(point).map(|n| n.distance)
    }

    fn facts(tree: &Wide<'_>) -> TreeFacts {
        TreeFacts {
            nodes: Some(tree.tree.nodes().len()),
            sah: AabbTree3::build_with(tree.input, &Bvh4::<Triangle3>::default_options())
                .stats()
                .sah_cost
                .map(f64::from),
            bytes: Some(tree.tree.memory_bytes()),
        }
    }
}
