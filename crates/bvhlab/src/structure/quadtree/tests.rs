//! Unit tests of the 2^D tree's internals; the queries are tested against brute force in
//! `tests/octree.rs`.

use glam::{Vec2, Vec3};

use super::build::{Split, child_mask, cube_around};
use super::layout::{child_box_at, child_count, split_point};
use super::ray::HalfSlabs;
use crate::structure::grid::tolerance::ray_box_interval;
use crate::volume::Aabb;
use crate::{BoundingVolume, Ray, Segment2, Triangle3};

#[test]
fn the_root_is_a_cube_around_the_scene() {
    let b = Aabb::new(Vec3::new(-1.0, 0.0, 2.0), Vec3::new(3.0, 1.0, 2.0));
    let cube = cube_around(&b);
    assert!(cube.contains(b.min) && cube.contains(b.max));
    assert_eq!(cube.size(), Vec3::splat(4.0));
    let huge = Aabb::new(Vec3::splat(-3e38), Vec3::new(3e38, 0.0, 0.0));
    let cube = cube_around(&huge);
    assert!(cube.min.is_finite() && cube.max.is_finite() && cube.contains(huge.max));
}

#[test]
fn children_tile_their_parent() {
    let cell = Aabb::new(Vec2::new(0.0, 0.0), Vec2::new(4.0, 2.0));
    let mid = split_point(&cell);
    let boxes: Vec<_> = (0..child_count::<Vec2>())
        .map(|k| child_box_at(&cell, mid, k))
        .collect();
    assert_eq!(boxes[0], Aabb::new(Vec2::ZERO, Vec2::new(2.0, 1.0)));
    assert_eq!(
        boxes[3],
        Aabb::new(Vec2::new(2.0, 1.0), Vec2::new(4.0, 2.0))
    );
    let area: f32 = boxes.iter().map(BoundingVolume::measure).sum();
    assert_eq!(area, cell.measure());
}

#[test]
fn a_primitive_goes_to_the_children_it_touches() {
    let cell = Aabb::new(Vec2::ZERO, Vec2::splat(4.0));
    let split = Split::new(&cell);
    // Inside child 0 only; on the vertical mid-line (children 0 and 1); across the
    // corner region of child 3 without touching it.
    assert_eq!(
        child_mask(&Segment2::new(Vec2::splat(0.5), Vec2::ONE), &split),
        0b0001
    );
    assert_eq!(
        child_mask(
            &Segment2::new(Vec2::new(2.0, 0.5), Vec2::new(2.0, 1.0)),
            &split
        ),
        0b0011
    );
    let cut = Segment2::new(Vec2::new(0.5, 2.5), Vec2::new(2.5, 0.5));
    assert_eq!(child_mask(&cut, &split), 0b0111);
    // Its hypotenuse x + z = 4 passes exactly through the corner of child 5: touching counts.
    let cube = Split::new(&Aabb::new(Vec3::ZERO, Vec3::splat(4.0)));
    let a = Vec3::splat(0.5);
    let tri = Triangle3::new(a, Vec3::new(3.5, 0.5, 0.5), Vec3::new(0.5, 0.5, 3.5));
    assert_eq!(child_mask(&tri, &cube), 0b0011_0011);
    let short = Triangle3::new(a, Vec3::new(3.5, 0.5, 0.5), Vec3::new(0.5, 0.5, 3.4));
    assert_eq!(child_mask(&short, &cube), 0b0001_0011);
}

#[test]
fn half_slabs_give_the_slab_test_of_every_child() {
    let cell = Aabb::new(Vec3::new(-1.0, 0.0, 2.0), Vec3::new(3.0, 4.0, 6.0));
    let mid = split_point(&cell);
    let rays = [
        Ray::new(Vec3::new(-5.0, 1.0, 3.0), Vec3::new(1.0, 0.3, 0.2)),
        Ray::new(Vec3::new(1.0, 2.0, 9.0), Vec3::new(0.0, -0.0, -1.0)),
        Ray::new(Vec3::new(0.0, 1.0, 4.0), Vec3::new(-1.0, 2.0, 0.5)),
    ];
    for ray in rays {
        let ray = ray.expect("valid ray");
        for grow in [0.0, 1e-3] {
            let halves = HalfSlabs::new(&ray, &cell, mid, grow);
            for k in 0..8 {
                let child = child_box_at(&cell, mid, k);
                assert_eq!(
                    halves.child_interval::<Vec3>(k),
                    ray_box_interval(&ray, &child, grow),
                    "child {k} of {ray:?}"
                );
            }
        }
    }
}
