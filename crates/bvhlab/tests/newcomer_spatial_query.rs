//! What a newcomer ran into in issue 33: the fast tree, `Bvh4`, was no `SpatialIndex`, so code
//! written for any structure could not take it. `SpatialQuery` (all hits, the k nearest,
//! range, with `RayCast` and `PointQuery`) is the trait such code takes: every structure and
//! `Bvh4` implement it, with brute force's answers.

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::structure::{BruteForce, RangeShape};
use bvhlab::{BspTree, Grid, KdTree, Orthtree};
use rand::RngExt;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use crate::batch_queries::{random_vec3, triangles_and_rays};

/// Everything a program might ask of "some structure", through the trait alone.
pub(crate) fn answers(
    index: &impl SpatialQuery<Vec3>,
    rays: &[Ray3],
    points: &[Vec3],
) -> Vec<String> {
    let mut out = Vec::new();
    for ray in rays {
        out.push(format!("{:?}", index.ray_first_hit(ray, f32::INFINITY)));
        out.push(format!("{:?}", index.ray_any_hit(ray, 30.0).is_some()));
        out.push(format!("{:?}", index.ray_all_hits(ray, f32::INFINITY)));
    }
    for &point in points {
        out.push(format!("{:?}", index.closest_point(point)));
        out.push(format!("{:?}", index.k_nearest(point, 5)));
        let ball = RangeShape::Ball(Sphere3::new(point, 2.5));
        let cube = RangeShape::Box(Aabb3::new(point - 1.5, point + 1.5));
        out.push(format!("{:?} {:?}", index.range(&ball), index.range(&cube)));
    }
    out
}

#[test]
fn every_structure_and_bvh4_answer_spatial_query_as_brute_force() {
    let mut rng = ChaCha8Rng::seed_from_u64(61);
    let (tris, rays) = triangles_and_rays(&mut rng, 1500, 150);
    let points: Vec<Vec3> = (0..100)
        .map(|_| {
            let extent = rng.random_range(5.0..13.0);
            random_vec3(&mut rng, extent)
        })
        .collect();
    let want = answers(&BruteForce::build(&tris), &rays, &points);
    assert!(
        want.iter().filter(|a| a.starts_with("Some(Hit")).count() > 20,
        "the rays must hit"
    );
    let got: [(&str, Vec<String>); 6] = [
        ("Bvh4", answers(&Bvh4::build(&tris), &rays, &points)),
        (
            "AABB tree",
            answers(&AabbTree3::build(&tris), &rays, &points),
        ),
        ("k-d tree", answers(&KdTree::build(&tris), &rays, &points)),
        ("grid", answers(&Grid::build(&tris), &rays, &points)),
        ("octree", answers(&Orthtree::build(&tris), &rays, &points)),
        ("BSP tree", answers(&BspTree::build(&tris), &rays, &points)),
    ];
    for (name, answers) in got {
        for (i, (a, b)) in answers.iter().zip(&want).enumerate() {
            assert_eq!(a, b, "{name}, answer {i}");
        }
    }
}
