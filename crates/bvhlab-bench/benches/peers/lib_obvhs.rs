//! obvhs 0.4: its binary BVH (`Bvh2`) from the PLOC builder with reinsertion and leaf
//! collapsing, `BvhBuildParams::medium_build()` (the choice), traversed with its own
//! `ray_traverse` and its own Möller-Trumbore `Triangle::intersect`. The triangles are put in
//! the tree's leaf order after the build, as its documentation recommends (timed with the
//! build). obvhs has no closest-point query.

use std::cell::Cell;
use std::time::Duration;

use bvhlab::Triangle3;
use bvhlab::glam::Vec3A;
use bvhlab_bench::workload::BenchRay;
use obvhs::BvhBuildParams;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::builder::build_bvh2_from_tris;
use obvhs::ray::{Ray, RayHit};
use obvhs::triangle::Triangle;

use crate::library::{Library, RayCost, SahSum, TreeFacts};

/// obvhs's `Bvh2`, medium build.
pub struct Obvhs;

/// The tree and the triangles in its leaf order.
pub struct Obvhs2 {
    bvh: Bvh2,
    tris: Vec<Triangle>,
}

impl Obvhs {
    fn traverse(tree: &Obvhs2, ray: &Ray, tested: &Cell<u64>) -> Option<f32> {
        let mut hit = RayHit::none();
        let found = tree.bvh.ray_traverse(*ray, &mut hit, |r, id| {
            tested.set(tested.get() + 1);
            tree.tris[id].intersect(r)
        });
        found.then_some(hit.t)
    }
}

impl Library for Obvhs {
    const NAME: &'static str = "obvhs 0.4 BVH2 (medium build)";
    const HAS_CLOSEST: bool = false;
    const HAS_OCCLUSION: bool = true;
    type Input = Vec<Triangle>;
    type Tree<'a> = Obvhs2;
    type Ray = Ray;

    fn input(tris: &[Triangle3]) -> Self::Input {
        tris.iter()
            .map(|t| Triangle {
                v0: Vec3A::from(t.a),
                v1: Vec3A::from(t.b),
                v2: Vec3A::from(t.c),
            })
            .collect()
    }

    fn build(input: &Self::Input) -> Obvhs2 {
        let mut core_time = Duration::ZERO;
        let bvh = build_bvh2_from_tris(input, BvhBuildParams::medium_build(), &mut core_time);
        let tris = bvh
            .primitive_indices
            .iter()
            .map(|&i| input[i as usize])
            .collect();
        Obvhs2 { bvh, tris }
    }

    fn ray(ray: &BenchRay) -> Ray {
        Ray::new(
            Vec3A::from(ray.origin),
            Vec3A::from(ray.dir),
            0.0,
            ray.t_max,
        )
    }

    fn first_hit(tree: &Obvhs2, ray: &Ray) -> Option<f32> {
        let mut hit = RayHit::none();
        let found = tree
            .bvh
            .ray_traverse(*ray, &mut hit, |r, id| tree.tris[id].intersect(r));
        found.then_some(hit.t)
    }

    fn occluded(tree: &Obvhs2, ray: &Ray) -> bool {
        !tree
            .bvh
            .ray_traverse_miss(*ray, |r, id| tree.tris[id].intersect(r))
    }

    fn first_hit_cost(tree: &Obvhs2, ray: &Ray) -> RayCost {
        let tested = Cell::new(0);
        Self::traverse(tree, ray, &tested);
        RayCost {
            nodes: None,
            prims: Some(tested.get()),
        }
    }

    fn facts(tree: &Obvhs2) -> TreeFacts {
        let nodes = &tree.bvh.nodes;
        let mut sah = SahSum::default();
        let mut stack = vec![0usize];
        while let Some(i) = stack.pop() {
            let Some(node) = nodes.get(i) else { continue };
            let (lo, hi) = (node.aabb.min, node.aabb.max);
            sah.add(lo.to_array(), hi.to_array(), node.prim_count as usize);
            if node.prim_count == 0 {
                stack.extend([node.first_index as usize, node.first_index as usize + 1]);
            }
        }
        let (cost, count) = sah.finish();
        let bytes = nodes.len() * size_of::<obvhs::bvh2::node::Bvh2Node>()
            + tree.bvh.primitive_indices.len() * size_of::<u32>()
            + tree.tris.len() * size_of::<Triangle>();
        TreeFacts {
            nodes: Some(count),
            sah: cost,
            bytes: Some(bytes),
        }
    }
}
