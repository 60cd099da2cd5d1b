//! A primitive of your own: balls (solid spheres) that implement [`Primitive`], so that every
//! structure indexes them and answers ray, nearest-point, range and collision queries over
//! them. The trait's documentation (`crates/bvhlab/src/primitive/mod.rs`) states the contract these
//! methods keep; [`check_enclosed_by_vertices`] and [`check_bounds_hold`] check the two
//! clauses a ball most easily breaks (vertices that enclose it, bounds that hold it). The ray test is the quadratic of Shirley and Marschner's
//! *Fundamentals of Computer Graphics*, §4.4.1.
//!
//! Run: `cargo run -p bvhlab --example custom_primitive`.
#![expect(clippy::print_stdout, reason = "an example that prints what it found")]

use std::error::Error;
use std::f32::consts::PI;

use bvhlab::glam::{BVec3, Vec3};
use bvhlab::prelude::*;
use bvhlab::primitive::{check_bounds_hold, check_enclosed_by_vertices};
use bvhlab::structure::bvh::SphereTree;
use bvhlab::{Aabb, Bvh4, RangeShape, Ray};

/// A solid ball: every point within `radius` of `center`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Ball {
    center: Vec3,
    radius: f32,
}

impl Primitive for Ball {
    type Point = Vec3;

    /// The box from `center - radius` to `center + radius` holds the whole ball (contract 2:
    /// the structures cull by it).
    fn bounds(&self) -> Aabb<Vec3> {
        Aabb::new(self.center - self.radius, self.center + self.radius)
    }

    /// Where the builders sort the ball: any point of its box keeps answers exact; its
    /// centre makes good trees.
    fn centroid(&self) -> Vec3 {
        self.center
    }

    /// The least `t >= 0` with `|origin + t dir - center| <= radius`: the smaller root of
    /// `(d.d) t^2 + 2 (e.d) t + (e.e - r^2) = 0` with `e = origin - center`, or 0 when the
    /// ray starts inside. In `f64`, because the two terms of the root nearly cancel for a
    /// ray that starts far away.
    fn ray_hit(&self, ray: &Ray<Vec3>) -> Option<f32> {
        let e = (ray.origin() - self.center).as_dvec3();
        let d = ray.dir().as_dvec3();
        let r = f64::from(self.radius);
        let (a, half_b, c) = (d.dot(d), e.dot(d), e.dot(e) - r * r);
        let discriminant = half_b * half_b - a * c;
        if discriminant < 0.0 {
            return None;
        }
        let root = discriminant.sqrt();
        let (enter, exit) = ((-half_b - root) / a, (-half_b + root) / a);
        // Behind the ray (exit < 0): a miss; inside the ball (enter < 0 <= exit): t = 0.
        (exit >= 0.0).then(|| enter.max(0.0) as f32)
    }

    /// What [`Hit::u`](bvhlab::Hit::u) and `v` report: here the hit's longitude and
    /// latitude on the ball, in [0, 1], the texture coordinates of a globe.
    fn hit_coordinates(&self, ray: &Ray<Vec3>, t: f32) -> [f32; 2] {
        let along = (ray.at(t) - self.center).normalize_or(Vec3::Y);
        let longitude = along.z.atan2(along.x) / (2.0 * PI) + 0.5;
        let latitude = along.y.clamp(-1.0, 1.0).acos() / PI;
        [longitude, latitude]
    }

    /// The point of the ball nearest to `point`: `point` itself when it is inside, else
    /// the point on the surface towards it.
    fn project_point(&self, point: Vec3) -> Vec3 {
        let offset = point - self.center;
        let length = offset.length();
        if length <= self.radius {
            point
        } else {
            self.center + offset * (self.radius / length)
        }
    }

    /// The volume; structures report it and never prune by it.
    fn measure(&self) -> f32 {
        4.0 / 3.0 * PI * self.radius.powi(3)
    }

    /// No plane holds a ball: zero, so a BSP tree splits it by other primitives' planes.
    fn normal(&self) -> Vec3 {
        Vec3::ZERO
    }

    /// Points whose convex hull holds the whole ball (contract 1): the eight corners of its
    /// box. Not its centre alone: the sphere and OBB trees fit their nodes to these points,
    /// and a node fitted around centres would cut the balls and miss their hits.
    fn vertices(&self) -> impl Iterator<Item = Vec3> {
        let (low, high) = (self.center - self.radius, self.center + self.radius);
        (0..8).map(move |corner: u32| {
            Vec3::select(
                BVec3::new(corner & 1 != 0, corner & 2 != 0, corner & 4 != 0),
                high,
                low,
            )
        })
    }

    /// Exact: the ball meets the closed box when the box's nearest point to its centre is
    /// within `radius` (touching counts). A grid lists the ball in exactly these cells.
    fn intersects_aabb(&self, aabb: &Aabb<Vec3>) -> bool {
        aabb.distance(self.center) <= self.radius
    }

    /// Two balls share a point when their centres are within the sum of their radii.
    fn intersects(&self, other: &Self) -> bool {
        self.center.distance(other.center) <= self.radius + other.radius
    }
}

fn main() -> Result<(), Box<dyn Error>> {
    let balls = ball_grid(10);
    // The cheap part of the contract, checked before building (every structure's
    // `validate()` checks it too).
    for ball in &balls {
        check_enclosed_by_vertices(ball)?;
        check_bounds_hold(ball)?;
    }

    // A sphere tree (its nodes fitted to the vertices) and the 4-wide box tree: both take
    // any `Primitive`.
    let sphere_tree = SphereTree::<Ball>::build(&balls);
    sphere_tree.validate()?;
    let fast_tree = Bvh4::build(&balls);

    let ray = Ray3::new(Vec3::new(-5.0, 4.2, 4.6), Vec3::X)?;
    if let Some(hit) = sphere_tree.ray_first_hit(&ray, f32::INFINITY) {
        println!(
            "the ray first hits ball #{} at t = {:.3}, longitude {:.3}, latitude {:.3}",
            hit.prim, hit.t, hit.u, hit.v
        );
    }
    let query = Vec3::new(4.5, 4.5, 20.0);
    if let Some(nearest) = fast_tree.closest_point(query) {
        println!(
            "nearest to {query}: ball #{} at {:.3}, its point {}",
            nearest.prim, nearest.distance, nearest.point
        );
    }
    let ball = RangeShape::Ball(Sphere3::new(Vec3::splat(4.5), 2.0));
    println!(
        "{} balls within 2 of the centre",
        sphere_tree.range(&ball).len()
    );
    // Collision of two structures: which balls touch (each touches itself, too).
    let touching = sphere_tree
        .collide(&sphere_tree)
        .into_iter()
        .filter(|(a, b)| a < b)
        .count();
    println!("{touching} pairs of distinct balls touch");
    Ok(())
}

/// `n^3` balls on a unit grid, their radii varying from 0.2 to 0.6 so that some neighbours
/// touch.
fn ball_grid(n: u32) -> Vec<Ball> {
    let mut balls = Vec::new();
    for x in 0..n {
        for y in 0..n {
            for z in 0..n {
                let i = (x * 7 + y * 3 + z * 5) % 11;
                balls.push(Ball {
                    center: Vec3::new(x as f32, y as f32, z as f32),
                    radius: 0.2 + 0.04 * i as f32,
                });
            }
        }
    }
    balls
}

#[cfg(test)]
mod tests {
    use super::*;
    use bvhlab::BruteForce;

    #[test]
    fn example_runs_and_agrees_with_brute_force() -> Result<(), Box<dyn Error>> {
        main()?;
        let balls = ball_grid(5);
        let sphere_tree = SphereTree::<Ball>::build(&balls);
        sphere_tree.validate()?;
        let fast_tree = Bvh4::build(&balls);
        let brute = BruteForce::build(&balls);
        let mut hits = 0;
        for i in 0..100 {
            // Rays from outside the grid towards points inside it.
            let s = i as f32;
            let from = Vec3::new(-3.0, (s * 0.37) % 6.0, (s * 0.73) % 6.0);
            let to = Vec3::new(2.0, (s * 0.51) % 4.0, (s * 0.29) % 4.0);
            let ray = Ray3::through(from, to)?;
            let want = brute.ray_first_hit(&ray, f32::INFINITY);
            hits += usize::from(want.is_some());
            assert_eq!(sphere_tree.ray_first_hit(&ray, f32::INFINITY), want);
            assert_eq!(fast_tree.ray_first_hit(&ray, f32::INFINITY), want);
            if let Some(hit) = want {
                // The hit point is on the ball's surface (the ray starts outside).
                let ball = balls[hit.prim];
                let gap = ray.at(hit.t).distance(ball.center) - ball.radius;
                assert!(gap.abs() < 1e-4, "{hit:?} is {gap} off the surface");
            }
            let point = to + Vec3::Z * (s * 0.1);
            assert_eq!(sphere_tree.closest_point(point), brute.closest_point(point));
            assert_eq!(fast_tree.k_nearest(point, 3), brute.k_nearest(point, 3));
        }
        assert!(hits > 50, "the rays must hit ({hits})");
        let ball = RangeShape::Ball(Sphere3::new(Vec3::splat(2.0), 1.5));
        assert_eq!(sphere_tree.range(&ball), brute.range(&ball));
        assert_eq!(sphere_tree.collide(&sphere_tree), brute.collide(&brute));
        Ok(())
    }
}
