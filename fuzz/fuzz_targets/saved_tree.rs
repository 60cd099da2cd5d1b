//! Saved trees, as a program reads them from a file it did not write: any bytes given to
//! `bvhlab::saved::load`. The first byte picks the structure asked for (its low three bits)
//! and how the rest reaches the loader (its top bit):
//!
//! - as the whole file (hostile headers: wrong magic, version, kind, lengths, checksums);
//! - as the payload behind a valid header for that structure, with the length and checksum
//!   made to match (`saved::reseal`), so that the bytes reach the decoder and the structure's
//!   own checks instead of the checksum's refusal.
//!
//! Besides "no panic, no hang, no unbounded allocation", a tree that loads must pass its
//! check again and answer a few queries as brute force over its own primitives does.

#![no_main]

use bvhlab::glam::Vec3;
use bvhlab::saved::{self, HEADER_LEN, Saved};
use bvhlab::structure::{BruteForce, PointOf, RangeShape};
use bvhlab::{
    Aabb, AabbTree2, AabbTree3, Bsp3, Bvh4, Grid2, KdTree, ObbTree3, Octree3, Ray, RayCast,
    SpatialIndex, SpatialQuery, Sphere, SphereTree2, Triangle3, Vector,
};
use libfuzzer_sys::fuzz_target;

bvhlab_fuzz::same_hash_keys_every_run!();

fuzz_target!(|data: &[u8]| {
    let Some((&mode, rest)) = data.split_first() else {
        return;
    };
    let as_payload = mode & 0x80 != 0;
    match mode & 7 {
        0 => try_index::<AabbTree3>(rest, as_payload),
        1 => try_index::<SphereTree2>(rest, as_payload),
        2 => try_index::<ObbTree3>(rest, as_payload),
        3 => try_index::<KdTree<Vec3>>(rest, as_payload),
        4 => try_index::<Bsp3>(rest, as_payload),
        5 => try_index::<Grid2>(rest, as_payload),
        6 => try_index::<Octree3>(rest, as_payload),
        _ => try_wide(rest, as_payload),
    }
    // A file for another structure is refused, not misread.
    if !as_payload {
        let _ = saved::load::<AabbTree2>(rest);
    }
});

/// The file to load: `rest` itself, or `rest` as the payload behind `T`'s header.
fn file_for<T: Saved>(empty: &T, rest: &[u8], as_payload: bool) -> Vec<u8> {
    if !as_payload {
        return rest.to_vec();
    }
    let mut bytes = saved::save(empty).expect("an empty structure saves");
    bytes.truncate(HEADER_LEN);
    bytes.extend_from_slice(rest);
    saved::reseal(&mut bytes);
    bytes
}

fn try_index<S: SpatialIndex + Saved>(rest: &[u8], as_payload: bool) {
    let bytes = file_for(&S::build(&[]), rest, as_payload);
    let Ok(tree) = saved::load::<S>(&bytes) else {
        return;
    };
    assert_eq!(tree.validate(), Ok(()), "a loaded tree fails its check");
    let prims = tree.primitives();
    let brute = BruteForce::build(prims);
    for (i, point) in probes::<PointOf<S>>().into_iter().enumerate() {
        let dir = probes::<PointOf<S>>()[(i + 1) % 4] - point;
        if let Ok(ray) = Ray::new(point, dir) {
            let (hit, expected) = (
                tree.ray_first_hit(&ray, f32::INFINITY),
                brute.ray_first_hit(&ray, f32::INFINITY),
            );
            assert_eq!(
                hit.map(|h| h.t),
                expected.map(|h| h.t),
                "first hit against brute force"
            );
            assert_eq!(
                tree.ray_all_hits(&ray, f32::INFINITY),
                brute.ray_all_hits(&ray, f32::INFINITY),
                "all hits against brute force"
            );
        }
        assert_eq!(
            tree.k_nearest(point, 2),
            brute.k_nearest(point, 2),
            "k nearest"
        );
        let shape = RangeShape::Ball(Sphere::new(point, 1.0));
        assert_eq!(tree.range(&shape), brute.range(&shape), "range");
    }
}

/// The 4-wide tree, which answers through its own methods.
fn try_wide(rest: &[u8], as_payload: bool) {
    let bytes = file_for(&Bvh4::<Triangle3>::build(&[]), rest, as_payload);
    let Ok(tree) = saved::load::<Bvh4<Triangle3>>(&bytes) else {
        return;
    };
    assert_eq!(tree.validate(), Ok(()), "a loaded tree fails its check");
    for point in probes::<Vec3>() {
        if let Ok(ray) = Ray::new(point, Vec3::ONE - point) {
            let _ = (
                tree.ray_first_hit(&ray, f32::INFINITY),
                tree.ray_all_hits(&ray, f32::INFINITY),
            );
        }
        let _ = (tree.closest_point(point), tree.k_nearest(point, 2));
        let _ = tree.range(&RangeShape::Box(Aabb::new(point, point + Vec3::ONE)));
    }
}

/// Four fixed query points, in either dimension.
fn probes<V: Vector>() -> [V; 4] {
    [-1.0f32, 0.25, 0.5, 3.0].map(|s| {
        let mut v = V::splat(s);
        v.set_coord(0, s * 0.5 + 0.1);
        v
    })
}
