//! The sliced fits give the one-go fits' volumes to the bit, whatever the chunk size: on
//! random points, duplicates, a single point, points on a line or in a plane, and points
//! beyond [`HUGE`](crate::structure::bvh::volume::HUGE), in 2D and 3D.

use glam::{Vec2, Vec3};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::SlicedFit;
use crate::Vector;
use crate::structure::bvh::volume::NodeVolume;
use crate::structure::bvh::{BvhOptions, SphereFit};
use crate::volume::{Aabb, Obb, Sphere};

/// Point sets that reach every branch of the fits.
fn point_sets<V: Vector>(seed: u64) -> Vec<Vec<V>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut random = |n: usize, scale: f32| -> Vec<V> {
        (0..n)
            .map(|_| {
                let mut v = V::ZERO;
                for i in 0..V::DIM {
                    v.set_coord(i, rng.random_range(-1.0f32..1.0) * scale);
                }
                v
            })
            .collect()
    };
    let cloud = random(200, 10.0);
    let mut duplicates = random(20, 1.0);
    duplicates.extend(duplicates.clone());
    let line: Vec<V> = cloud
        .iter()
        .map(|&v| V::unit_axis(0) * v.coord(0))
        .collect();
    let plane: Vec<V> = cloud
        .iter()
        .map(|&v| {
            let mut w = v;
            w.set_coord(V::DIM - 1, 3.0);
            w
        })
        .collect();
    vec![
        cloud,
        duplicates,
        vec![V::splat(2.5)],
        vec![V::splat(1.0); 9],
        line,
        plane,
        random(50, 1e-30),
        random(50, 3e18),
        random(50, 3e38),
    ]
}

fn bounds<V: Vector>(points: &[V]) -> Aabb<V> {
    points.iter().fold(Aabb::EMPTY, |b, &p| b.grown(p))
}

/// Runs the sliced fit of `B` in chunks of `units` and returns its volume.
fn sliced<B: NodeVolume>(points: &[B::Point], units: usize, options: &BvhOptions) -> B {
    let mut fit =
        SlicedFit::for_volume::<B>(&bounds(points), options).expect("the volume has a sliced fit");
    let mut read = 0;
    while !fit.is_done() {
        let now = fit.advance(points, units);
        assert!(now <= units.max(1), "read {now} points of {units}");
        read += now;
    }
    // Four passes over the points, a fifth for huge coordinates.
    assert!(
        read >= 4 * points.len() && read <= 5 * points.len(),
        "{read}"
    );
    fit.volume::<B>()
        .expect("the volume has the type it was made for")
}

fn check<B, V>(seed: u64, options: &BvhOptions, bits: impl Fn(&B) -> Vec<u32>)
where
    B: NodeVolume<Point = V>,
    V: Vector,
{
    for points in point_sets::<V>(seed) {
        let whole = B::fit(&bounds(&points), &points, options);
        for units in [1, 2, 7, 64, usize::MAX] {
            let chunked: B = sliced(&points, units, options);
            assert_eq!(
                bits(&chunked),
                bits(&whole),
                "{} points, units {units}",
                points.len()
            );
        }
    }
}

fn vector_bits<V: Vector>(v: V) -> impl Iterator<Item = u32> {
    (0..V::DIM).map(move |i| v.coord(i).to_bits())
}

fn obb_bits<V: Vector>(obb: &Obb<V>) -> Vec<u32> {
    let axes = obb.axes.as_ref().iter().flat_map(|&a| vector_bits(a));
    vector_bits(obb.center)
        .chain(axes)
        .chain(vector_bits(obb.half_extents))
        .collect()
}

fn sphere_bits<V: Vector>(sphere: &Sphere<V>) -> Vec<u32> {
    vector_bits(sphere.center)
        .chain([sphere.radius.to_bits()])
        .collect()
}

#[test]
fn the_sliced_pca_box_is_the_one_go_box() {
    let options = BvhOptions::default();
    check::<Obb<Vec3>, _>(1, &options, obb_bits);
    check::<Obb<Vec2>, _>(2, &options, obb_bits);
}

#[test]
fn the_sliced_ritter_sphere_is_the_one_go_sphere() {
    let options = BvhOptions::default();
    check::<Sphere<Vec3>, _>(3, &options, sphere_bits);
    check::<Sphere<Vec2>, _>(4, &options, sphere_bits);
}

#[test]
fn boxes_and_welzl_spheres_are_fitted_in_one_go() {
    let welzl = BvhOptions {
        sphere_fit: SphereFit::Welzl,
        ..BvhOptions::default()
    };
    let b = Aabb::new(Vec3::ZERO, Vec3::ONE);
    assert!(SlicedFit::for_volume::<Sphere<Vec3>>(&b, &welzl).is_none());
    assert!(SlicedFit::for_volume::<Aabb<Vec3>>(&b, &BvhOptions::default()).is_none());
}
