//! tinybvh through tinybvh-rs 0.1.0-beta.3: its binary `BVH` (`BVH::new`: tinybvh's default
//! binned SAH build) and, when the Rust side is compiled with AVX2 (`-C target-cpu=native`),
//! its 8-wide `BVH8_CPU` converted from it. tinybvh-rs always compiles the C++ with
//! `-march=native`. tinybvh has no closest-point query; `Intersect` returns its traversal
//! steps, reported as nodes visited.
//!
//! A layout mismatch in tinybvh-rs 0.1.0-beta.3: its Rust `Ray` is 64 bytes, while the
//! bundled `tiny_bvh.h`'s `Ray` is 128 (64-aligned; the hit record gained an `auxData`
//! pointer and 56 bytes of user data). `Ray::new` returns 128 bytes into a 64-byte value and
//! smashes the stack. The first 64 bytes agree (origin, mask, direction, instance, reciprocal
//! direction, then the hit's instance, t, u, v, prim), so the adapter fills them itself, as
//! tinybvh's constructor does, inside a 128-byte, 64-aligned [`TinyRay`] whose tail tinybvh
//! may use.

use bvhlab::Triangle3;
use bvhlab_bench::workload::BenchRay;
use tinybvh_rs::{Intersector, Ray, bvh};

use crate::library::{Library, RayCost, SahSum, TreeFacts};

/// tinybvh's binary BVH.
pub struct TinyBvh;

/// Three `[x, y, z, 0]` corners per triangle: tinybvh's vertex format.
pub fn corners(tris: &[Triangle3]) -> Vec<[f32; 4]> {
    tris.iter()
        .flat_map(|t| [t.a, t.b, t.c])
        .map(|p| [p.x, p.y, p.z, 0.0])
        .collect()
}

/// A tinybvh ray with room for the C++ side's 128 bytes.
#[derive(Clone, Copy)]
#[repr(C, align(64))]
pub struct TinyRay {
    ray: Ray,
    tail: [u8; 64],
}

/// tinybvh's `RAY_MASK_INTERSECT_ALL`.
const MASK_ALL: u32 = 0xFFFF;

/// tinybvh's `tinybvh_safercp`: `1/x`, or ±1e30 for |x| <= 1e-12.
fn safe_rcp(x: f32) -> f32 {
    if x.abs() > 1e-12 {
        1.0 / x
    } else {
        tinybvh_rs::INFINITE.copysign(x)
    }
}

fn tiny_ray(ray: &BenchRay) -> TinyRay {
    let d = ray.dir.normalize();
    let mut hit = tinybvh_rs::Intersection::new();
    // tinybvh only takes hits nearer than `hit.t`, which starts at `t_max`.
    hit.t = ray.t_max.min(tinybvh_rs::INFINITE);
    TinyRay {
        ray: Ray {
            origin: ray.origin.to_array(),
            padding_0: MASK_ALL,
            dir: d.to_array(),
            padding_1: 0,
            r_d: d.to_array().map(safe_rcp),
            padding_2: 0,
            hit,
        },
        tail: [0; 64],
    }
}

fn hit<I: Intersector>(tree: &I, ray: &TinyRay) -> (Option<f32>, u32) {
    let mut r = *ray;
    let steps = tree.intersect(&mut r.ray);
    ((r.ray.hit.t < ray.ray.hit.t).then_some(r.ray.hit.t), steps)
}

impl Library for TinyBvh {
    const NAME: &'static str = "tinybvh BVH (tinybvh-rs)";
    const HAS_CLOSEST: bool = false;
    type Input = Vec<[f32; 4]>;
    type Tree<'a> = bvh::BVH<'a>;
    type Ray = TinyRay;

    fn input(tris: &[Triangle3]) -> Self::Input {
        corners(tris)
    }

    fn build(input: &Self::Input) -> bvh::BVH<'_> {
        bvh::BVH::new(input.as_slice().into())
            .unwrap_or_else(|e| panic!("tinybvh refused the mesh: {e}"))
    }

    fn ray(ray: &BenchRay) -> Self::Ray {
        tiny_ray(ray)
    }

    fn first_hit(tree: &bvh::BVH<'_>, ray: &Self::Ray) -> Option<f32> {
        hit(tree, ray).0
    }

    fn first_hit_cost(tree: &bvh::BVH<'_>, ray: &Self::Ray) -> RayCost {
        RayCost {
            nodes: Some(u64::from(hit(tree, ray).1)),
            prims: None,
        }
    }

    fn facts(tree: &bvh::BVH<'_>) -> TreeFacts {
        let nodes = tree.nodes();
        let mut sah = SahSum::default();
        let mut stack = vec![0usize];
        while let Some(i) = stack.pop() {
            let Some(node) = nodes.get(i) else { continue };
            sah.add(node.min, node.max, node.tri_count as usize);
            if !node.is_leaf() {
                stack.extend([node.left_first as usize, node.left_first as usize + 1]);
            }
        }
        let (cost, count) = sah.finish();
        let bytes = size_of_val(nodes) + size_of_val(tree.indices()) + tree.indices().len() * 48;
        TreeFacts {
            nodes: Some(count),
            sah: cost,
            bytes: Some(bytes),
        }
    }
}

/// tinybvh's 8-wide CPU layout (AVX2), converted from a binary BVH split to leaves of at most
/// 4 triangles (what the conversion requires); the conversion is timed with the build. Its
/// `Intersect` returns 0 rather than a step count, so it reports no cost.
#[cfg(target_feature = "avx2")]
pub struct TinyBvh8;

#[cfg(target_feature = "avx2")]
impl Library for TinyBvh8 {
    const NAME: &'static str = "tinybvh BVH8_CPU (tinybvh-rs)";
    const HAS_CLOSEST: bool = false;
    type Input = Vec<[f32; 4]>;
    type Tree<'a> = tinybvh_rs::bvh8_cpu::BVH;
    type Ray = TinyRay;

    fn input(tris: &[Triangle3]) -> Self::Input {
        corners(tris)
    }

    fn build(input: &Self::Input) -> tinybvh_rs::bvh8_cpu::BVH {
        let mut base = bvh::BVH::new(input.as_slice().into())
            .unwrap_or_else(|e| panic!("tinybvh refused the mesh: {e}"));
        base.split_leaves(4);
        let wide = tinybvh_rs::mbvh::BVH::new(&base);
        tinybvh_rs::bvh8_cpu::BVH::new(&wide)
            .unwrap_or_else(|e| panic!("tinybvh could not convert to BVH8_CPU: {e}"))
    }

    fn ray(ray: &BenchRay) -> Self::Ray {
        tiny_ray(ray)
    }

    fn first_hit(tree: &tinybvh_rs::bvh8_cpu::BVH, ray: &Self::Ray) -> Option<f32> {
        hit(tree, ray).0
    }

    fn facts(_tree: &tinybvh_rs::bvh8_cpu::BVH) -> TreeFacts {
        // tinybvh-rs does not expose BVH8_CPU's nodes.
        TreeFacts::default()
    }
}
