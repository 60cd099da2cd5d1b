//! bvh 0.13 (svenstaro): its SAH-built `Bvh` (one triangle per leaf), built single-threaded
//! (`Bvh::build`, without its `rayon` feature). The crate gives ordered candidates, not first
//! hits, so the query is what a user writes: walk `nearest_traverse_iterator` (candidates by
//! the distance at which the ray enters their box), test each triangle, stop once the next
//! box starts beyond the best hit. bvh's own `Ray::intersects_triangle` culls back faces; the
//! benchmark asks for hits on both sides, so the triangle test here is a two-sided
//! Möller-Trumbore (1997) in `f32`. Closest point: its `nearest_to`, with each triangle's
//! distance from bvhlab's exact `Triangle3::closest_point`.

use bvh::aabb::{Aabb, Bounded};
use bvh::bounding_hierarchy::BHShape;
use bvh::bvh::{Bvh, BvhNode};
use bvh::point_query::PointDistance;
use bvh::ray::Ray;
use bvhlab::Triangle3;
use bvhlab::glam::Vec3;
use bvhlab_bench::workload::BenchRay;
use nalgebra::{Point3, Vector3};

use crate::library::{Library, RayCost, SahSum, TreeFacts};

/// svenstaro's `bvh`.
pub struct SvenstaroBvh;

/// A triangle as a `bvh` shape.
#[derive(Clone, Debug)]
pub struct Shape {
    tri: Triangle3,
    aabb: Aabb<f32, 3>,
    node: usize,
}

impl Bounded<f32, 3> for Shape {
    fn aabb(&self) -> Aabb<f32, 3> {
        self.aabb
    }
}

impl BHShape<f32, 3> for Shape {
    fn set_bh_node_index(&mut self, index: usize) {
        self.node = index;
    }

    fn bh_node_index(&self) -> usize {
        self.node
    }
}

impl PointDistance<f32, 3> for Shape {
    fn distance_squared(&self, p: Point3<f32>) -> f32 {
        let q = Vec3::new(p.x, p.y, p.z);
        self.tri.project_point(q).distance_squared(q)
    }
}

/// The tree and its shapes.
pub struct Tree {
    bvh: Bvh<f32, 3>,
    shapes: Vec<Shape>,
}

fn point(p: Vec3) -> Point3<f32> {
    Point3::new(p.x, p.y, p.z)
}

/// Two-sided Möller-Trumbore: the `t` in `[0, t_max]` where the ray crosses the triangle.
fn ray_triangle(ray: &Ray<f32, 3>, tri: &Triangle3, t_max: f32) -> Option<f32> {
    let o = Vec3::new(ray.origin.x, ray.origin.y, ray.origin.z);
    let d = Vec3::new(ray.direction.x, ray.direction.y, ray.direction.z);
    let (e1, e2) = (tri.b - tri.a, tri.c - tri.a);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 {
        return None;
    }
    let inv = 1.0 / det;
    let s = o - tri.a;
    let u = s.dot(p) * inv;
    let q = s.cross(e1);
    let v = d.dot(q) * inv;
    let t = e2.dot(q) * inv;
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t >= 0.0 && t <= t_max).then_some(t)
}

impl SvenstaroBvh {
    fn walk(tree: &Tree, (ray, t_max): &(Ray<f32, 3>, f32), tested: &mut u64) -> Option<f32> {
        let mut best: Option<f32> = None;
        for shape in tree.bvh.nearest_traverse_iterator(ray, &tree.shapes) {
            let limit = best.unwrap_or(*t_max);
            match ray.intersection_slice_for_aabb(&shape.aabb) {
                Some((enter, _)) if enter > limit => break,
                _ => {}
            }
            *tested += 1;
            if let Some(t) = ray_triangle(ray, &shape.tri, limit) {
                best = Some(t);
            }
        }
        best
    }
}

impl Library for SvenstaroBvh {
    const NAME: &'static str = "bvh 0.13";
    const HAS_CLOSEST: bool = true;
    type Input = Vec<Shape>;
    type Tree<'a> = Tree;
    type Ray = (Ray<f32, 3>, f32);

    fn input(tris: &[Triangle3]) -> Self::Input {
        tris.iter()
            .map(|t| Shape {
                tri: *t,
                aabb: Aabb::with_bounds(point(t.a.min(t.b).min(t.c)), point(t.a.max(t.b).max(t.c))),
                node: 0,
            })
            .collect()
    }

    fn build(input: &Self::Input) -> Tree {
        let mut shapes = input.clone();
        let bvh = Bvh::build(&mut shapes);
        Tree { bvh, shapes }
    }

    fn ray(ray: &BenchRay) -> Self::Ray {
        let d = Vector3::new(ray.dir.x, ray.dir.y, ray.dir.z);
        (Ray::new(point(ray.origin), d), ray.t_max)
    }

    fn first_hit(tree: &Tree, ray: &Self::Ray) -> Option<f32> {
        Self::walk(tree, ray, &mut 0)
    }

    fn first_hit_cost(tree: &Tree, ray: &Self::Ray) -> RayCost {
        let mut tested = 0;
        Self::walk(tree, ray, &mut tested);
        RayCost {
            nodes: None,
            prims: Some(tested),
        }
    }

    fn closest_distance(tree: &Tree, p: Vec3) -> Option<f32> {
        tree.bvh.nearest_to(point(p), &tree.shapes).map(|(_, d)| d)
    }

    fn facts(tree: &Tree) -> TreeFacts {
        // Boxes live in the parent (`child_l_aabb`, `child_r_aabb`); the root's is the union.
        let nodes = &tree.bvh.nodes;
        let mut sah = SahSum::default();
        let arr = |p: &Point3<f32>| [p.x, p.y, p.z];
        let mut stack = Vec::new();
        match nodes.first() {
            Some(BvhNode::Node {
                child_l_aabb,
                child_r_aabb,
                ..
            }) => {
                let root = child_l_aabb.join(child_r_aabb);
                sah.add(arr(&root.min), arr(&root.max), 0);
                stack.push(0usize);
            }
            Some(BvhNode::Leaf { shape_index, .. }) => {
                let b = tree.shapes[*shape_index].aabb;
                sah.add(arr(&b.min), arr(&b.max), 1);
            }
            None => {}
        }
        while let Some(i) = stack.pop() {
            if let BvhNode::Node {
                child_l_index,
                child_l_aabb,
                child_r_index,
                child_r_aabb,
                ..
            } = &nodes[i]
            {
                for (child, b) in [
                    (*child_l_index, child_l_aabb),
                    (*child_r_index, child_r_aabb),
                ] {
                    let leaf = matches!(nodes[child], BvhNode::Leaf { .. });
                    sah.add(arr(&b.min), arr(&b.max), usize::from(leaf));
                    if !leaf {
                        stack.push(child);
                    }
                }
            }
        }
        let (cost, count) = sah.finish();
        let bytes =
            nodes.len() * size_of::<BvhNode<f32, 3>>() + tree.shapes.len() * size_of::<Shape>();
        TreeFacts {
            nodes: Some(count),
            sah: cost,
            bytes: Some(bytes),
        }
    }
}
