//! parry3d 0.31: a `TriMesh` (its `Bvh` built with the default, binned strategy) asked with
//! its own `RayCast::cast_local_ray` and `PointQuery::project_local_point`. parry brings its
//! own glam (0.33, through glamx), so points are converted by coordinates. The mesh gets an
//! indexed vertex list (equal corners merged before timing), as a parry user would pass it.

use bvhlab::Triangle3;
use bvhlab::glam::Vec3;
use bvhlab_bench::workload::BenchRay;
use parry3d::math::Vector;
use parry3d::partitioning::TraversalAction;
use parry3d::query::{PointQuery, Ray, RayCast};
use parry3d::shape::TriMesh;

use crate::library::{Library, SahSum, TreeFacts, indexed_mesh};

/// parry3d's `TriMesh`.
pub struct Parry;

fn v(p: Vec3) -> Vector {
    Vector::new(p.x, p.y, p.z)
}

impl Library for Parry {
    const NAME: &'static str = "parry3d 0.31 TriMesh";
    const HAS_CLOSEST: bool = true;
    const HAS_OCCLUSION: bool = true;
    type Input = (Vec<Vector>, Vec<[u32; 3]>);
    type Tree<'a> = TriMesh;
    type Ray = (Ray, f32);

    fn input(tris: &[Triangle3]) -> Self::Input {
        let (vertices, indices) = indexed_mesh(tris);
        (vertices.into_iter().map(v).collect(), indices)
    }

    fn build((vertices, indices): &Self::Input) -> TriMesh {
        TriMesh::new(vertices.clone(), indices.clone())
            .unwrap_or_else(|e| panic!("parry refused the mesh: {e:?}"))
    }

    fn ray(ray: &BenchRay) -> Self::Ray {
        (Ray::new(v(ray.origin), v(ray.dir)), ray.t_max)
    }

    fn first_hit(tree: &TriMesh, (ray, t_max): &Self::Ray) -> Option<f32> {
        tree.cast_local_ray(ray, *t_max, false)
    }

    fn occluded(tree: &TriMesh, (ray, t_max): &Self::Ray) -> bool {
        tree.intersects_local_ray(ray, *t_max)
    }

    fn closest_distance(tree: &TriMesh, point: Vec3) -> Option<f32> {
        let p = v(point);
        Some(tree.project_local_point(p, false).point.distance(p))
    }

    fn facts(tree: &TriMesh) -> TreeFacts {
        // parry stores pairs of children ("wide" nodes); `traverse` visits every node below
        // the root, whose box is `root_aabb`. Each leaf holds one triangle.
        let bvh = tree.bvh();
        let mut sah = SahSum::default();
        let root = bvh.root_aabb();
        let leaf_root = bvh.leaf_count() <= 1;
        sah.add(
            root.mins.to_array(),
            root.maxs.to_array(),
            usize::from(leaf_root),
        );
        if !leaf_root {
            bvh.traverse(|node| {
                let (lo, hi) = (node.mins().to_array(), node.maxs().to_array());
                sah.add(lo, hi, usize::from(node.is_leaf()));
                TraversalAction::Continue
            });
        }
        let (cost, nodes) = sah.finish();
        TreeFacts {
            nodes: Some(nodes),
            sah: cost,
            bytes: Some(tree.total_memory_size()),
        }
    }
}
