//! Every structure x every query agrees with brute force, in 2D and 3D, on the standard
//! scenes (random, degenerate, scaled) and on the real meshes.

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::structure::BruteForce;
use bvhlab::structure::bvh::{AabbTree, ObbTree, SphereTree};
use bvhlab::{BspTree, Grid, KdTree, Orthtree};
use bvhlab::{Segment2, SpatialIndex, Triangle3};
use bvhlab_tests::conformance::{Budget, check_against_brute_force};
use bvhlab_tests::scenes::{Map, random_segments, random_triangles, standard_scenes};
use bvhlab_tests::{random_vector, rng};

fn run<S>(seed: u64, generate: impl Fn(&mut rand_chacha::ChaCha8Rng, usize) -> Vec<S::Prim> + Copy)
where
    S: SpatialIndex,
    S::Prim: Map,
{
    let mut rng = rng(seed);
    let scenes = standard_scenes(&mut rng, generate);
    let other = &scenes[3];
    for scene in &scenes {
        check_against_brute_force::<S>(&mut rng, scene, other, &Budget::default());
    }
}

fn points2(rng: &mut rand_chacha::ChaCha8Rng, n: usize) -> Vec<Vec2> {
    (0..n).map(|_| random_vector(rng, 10.0)).collect()
}

fn points3(rng: &mut rand_chacha::ChaCha8Rng, n: usize) -> Vec<Vec3> {
    (0..n).map(|_| random_vector(rng, 10.0)).collect()
}

/// Instantiates the conformance tests for one structure type constructor.
macro_rules! conformance {
    ($module:ident, $structure:ident) => {
        mod $module {
            use super::*;

            #[test]
            fn segments_2d() {
                run::<$structure<Segment2>>(1, random_segments);
            }
            #[test]
            fn triangles_3d() {
                run::<$structure<Triangle3>>(2, random_triangles);
            }
            #[test]
            fn points_2d() {
                run::<$structure<Vec2>>(3, points2);
            }
            #[test]
            fn points_3d() {
                run::<$structure<Vec3>>(4, points3);
            }
        }
    };
}

// The reference against itself: checks the harness (queries, scenes, comparisons) runs.
conformance!(brute_force, BruteForce);
conformance!(aabb_tree, AabbTree);
conformance!(sphere_tree, SphereTree);
conformance!(obb_tree, ObbTree);
conformance!(kd_tree, KdTree);
conformance!(bsp_tree, BspTree);
conformance!(grid, Grid);
conformance!(orthtree, Orthtree);

/// A broken structure: brute force that forgets the last primitive. The harness must catch it.
#[derive(Debug)]
struct ForgetsOne<P: bvhlab::Primitive> {
    all: Vec<P>,
    inner: BruteForce<P>,
}

bvhlab::queries_by_observed_walks!(ForgetsOne);

impl<P: bvhlab::Primitive> SpatialIndex for ForgetsOne<P> {
    type Prim = P;
    fn build(prims: &[P]) -> Self {
        let kept = &prims[..prims.len().saturating_sub(1)];
        Self {
            all: prims.to_vec(),
            inner: BruteForce::build(kept),
        }
    }
    fn primitives(&self) -> &[P] {
        &self.all
    }
    fn ray_first_hit_observed<O: bvhlab::Observer<P::Point>>(
        &self,
        ray: &bvhlab::Ray<P::Point>,
        t_max: f32,
        o: &mut O,
    ) -> bvhlab::Traced<Option<bvhlab::Hit>> {
        self.inner.ray_first_hit_observed(ray, t_max, o)
    }
    fn ray_any_hit_observed<O: bvhlab::Observer<P::Point>>(
        &self,
        ray: &bvhlab::Ray<P::Point>,
        t_max: f32,
        o: &mut O,
    ) -> bvhlab::Traced<Option<bvhlab::Hit>> {
        self.inner.ray_any_hit_observed(ray, t_max, o)
    }
    fn ray_all_hits_observed<O: bvhlab::Observer<P::Point>>(
        &self,
        ray: &bvhlab::Ray<P::Point>,
        t_max: f32,
        o: &mut O,
    ) -> bvhlab::Traced<Vec<bvhlab::Hit>> {
        self.inner.ray_all_hits_observed(ray, t_max, o)
    }
    fn k_nearest_observed<O: bvhlab::Observer<P::Point>>(
        &self,
        p: P::Point,
        k: usize,
        o: &mut O,
    ) -> bvhlab::Traced<Vec<bvhlab::Nearest<P::Point>>> {
        self.inner.k_nearest_observed(p, k, o)
    }
    fn range_observed<O: bvhlab::Observer<P::Point>>(
        &self,
        s: &bvhlab::RangeShape<P::Point>,
        o: &mut O,
    ) -> bvhlab::Traced<Vec<usize>> {
        self.inner.range_observed(s, o)
    }
    fn collide_observed<O: bvhlab::Observer<P::Point>>(
        &self,
        other: &Self,
        o: &mut O,
    ) -> bvhlab::Traced<Vec<(usize, usize)>> {
        self.inner.collide_observed(&other.inner, o)
    }
    fn stats(&self) -> bvhlab::Stats {
        bvhlab::Stats {
            primitives: self.all.len(),
            references: self.all.len(),
            ..self.inner.stats()
        }
    }
    fn validate(&self) -> Result<(), bvhlab::structure::ValidationError> {
        Ok(())
    }
}

#[test]
#[should_panic(expected = "400 random")]
fn the_harness_catches_a_structure_that_forgets_a_primitive() {
    let mut rng = rng(5);
    let scenes = standard_scenes(&mut rng, random_triangles);
    check_against_brute_force::<ForgetsOne<Triangle3>>(
        &mut rng,
        &scenes[3],
        &scenes[3],
        &Budget {
            rays: 2000,
            points: 400,
        },
    );
}
