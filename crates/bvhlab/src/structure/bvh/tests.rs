//! Unit tests that need the tree's private fields: validation must catch every kind of
//! corruption, and the pieces of the hot path (slab test, stack order) do what they say.

use glam::{Vec2, Vec3};
use rand::{RngExt, SeedableRng};

use super::walk::stack::{Entry, Stack};
use super::{Bvh, BvhNode, NodeVolume, PreparedRay};
use crate::structure::SpatialIndex;
use crate::volume::{Aabb, Obb, Sphere};
use crate::{Ray, Triangle3};

fn triangles(n: usize) -> Vec<Triangle3> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let mut v = || {
        Vec3::new(
            rng.random_range(-5.0..5.0),
            rng.random_range(-5.0..5.0),
            rng.random_range(-5.0..5.0),
        )
    };
    (0..n)
        .map(|_| {
            let a = v();
            Triangle3::new(a, a + v() * 0.1, a + v() * 0.1)
        })
        .collect()
}

/// Applies `corrupt` to a fresh valid tree and expects validation to fail with a message
/// containing `expected`.
fn expect_invalid<B: NodeVolume<Point = Vec3>>(
    expected: &str,
    corrupt: impl FnOnce(&mut Bvh<B, Triangle3>),
) {
    let mut bvh = Bvh::<B, Triangle3>::build(&triangles(100));
    bvh.validate().expect("a fresh tree is valid");
    corrupt(&mut bvh);
    let error = bvh.validate().expect_err("the corruption is noticed");
    assert!(
        error.message.contains(expected),
        "{expected:?} not in {:?}",
        error.message
    );
}

fn first_inner<B>(bvh: &Bvh<B, Triangle3>) -> usize {
    bvh.nodes
        .iter()
        .position(|n| !n.is_leaf())
        .expect("an inner node")
}

fn first_leaf<B>(bvh: &Bvh<B, Triangle3>) -> usize {
    bvh.nodes.iter().position(BvhNode::is_leaf).expect("a leaf")
}

#[test]
fn validation_catches_broken_topology() {
    expect_invalid::<Aabb<Vec3>>("children", |bvh| bvh.nodes[0].start = 0);
    expect_invalid::<Aabb<Vec3>>("children", |bvh| {
        let len = bvh.nodes.len() as u32;
        bvh.nodes[0].start = len;
    });
    expect_invalid::<Aabb<Vec3>>("reached twice", |bvh| {
        // The root's second child is the first child's second child too.
        let inner = first_inner(bvh);
        let grandchild = bvh.nodes[inner + 1].start;
        if bvh.nodes[inner + 1].is_leaf() {
            bvh.nodes[inner].start = inner as u32 + 1;
        } else {
            bvh.nodes[inner].start = grandchild;
        }
    });
    expect_invalid::<Aabb<Vec3>>("not reachable", |bvh| {
        let leaf = bvh.nodes[first_leaf(bvh)];
        bvh.nodes.push(leaf);
    });
    expect_invalid::<Aabb<Vec3>>("children", |bvh| bvh.nodes.truncate(bvh.nodes.len() - 1));
}

#[test]
fn validation_catches_broken_leaves() {
    expect_invalid::<Aabb<Vec3>>("two leaves", |bvh| {
        let leaf = first_leaf(bvh);
        let next = bvh
            .nodes
            .iter()
            .rposition(BvhNode::is_leaf)
            .expect("a leaf");
        bvh.nodes[leaf].start = bvh.nodes[next].start;
        bvh.nodes[leaf].count = bvh.nodes[next].count;
    });
    expect_invalid::<Aabb<Vec3>>("beyond", |bvh| {
        let leaf = first_leaf(bvh);
        bvh.nodes[leaf].count = 1000;
    });
    expect_invalid::<Sphere<Vec3>>("more than one", |bvh| bvh.leaf_ids[1] = bvh.leaf_ids[0]);
    expect_invalid::<Obb<Vec3>>("not a copy", |bvh| bvh.leaf_prims[3].a.x += 1.0);
    expect_invalid::<Obb<Vec3>>("out of range", |bvh| bvh.leaf_ids[2] = 10_000);
    expect_invalid::<Aabb<Vec3>>("leaf ids", |bvh| {
        bvh.leaf_ids.pop();
    });
}

#[test]
fn validation_catches_volumes_that_leave_primitives_out() {
    expect_invalid::<Aabb<Vec3>>("does not contain", |bvh| {
        let leaf = first_leaf(bvh);
        let b = &mut bvh.nodes[leaf].volume;
        b.max = b.min;
    });
    expect_invalid::<Aabb<Vec3>>("not inside its parent", |bvh| {
        let inner = first_inner(bvh);
        bvh.nodes[inner + 1].volume.max += Vec3::splat(100.0);
    });
    expect_invalid::<Sphere<Vec3>>("does not contain", |bvh| {
        let inner = first_inner(bvh);
        bvh.nodes[inner].volume.radius *= 0.5;
    });
    expect_invalid::<Obb<Vec3>>("does not contain", |bvh| {
        let leaf = first_leaf(bvh);
        bvh.nodes[leaf].volume.half_extents *= 0.5;
    });
}

#[test]
fn the_slab_test_takes_a_ray_along_a_face_as_inside() {
    let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
    let hit = |b: &Aabb<Vec3>, origin: Vec3, dir: Vec3| {
        let ray = Ray::new(origin, dir).expect("a valid ray");
        b.ray_entry(&PreparedRay::new(&ray))
    };
    // The query's slack widens intervals by about 1e-6.
    let near = |got: Option<(f32, f32)>, want: (f32, f32)| {
        got.is_some_and(|(a, b)| (a - want.0).abs() < 1e-5 && (b - want.1).abs() < 1e-5)
    };
    // Parallel to x and y, starting on the x = 0 and x = 1 planes, and on an edge.
    for origin in [
        Vec3::new(0.0, 0.5, -1.0),
        Vec3::new(1.0, 0.5, -1.0),
        Vec3::new(1.0, 1.0, -1.0),
    ] {
        for dir in [Vec3::Z, Vec3::new(-0.0, 0.0, 1.0)] {
            let got = hit(&unit, origin, dir);
            assert!(near(got, (1.0, 2.0)), "{origin} {dir}: {got:?}");
        }
        let got = hit(&unit, origin, Vec3::new(0.0, -0.0, 2.0));
        assert!(near(got, (0.5, 1.0)), "{origin}: {got:?}");
    }
    // Parallel, just outside.
    assert_eq!(hit(&unit, Vec3::new(1.01, 0.5, -1.0), Vec3::Z), None);
    assert_eq!(hit(&unit, Vec3::new(-0.01, 0.5, -1.0), Vec3::Z), None);
    // A flat box (a face) crossed straight on, and one the ray lies in.
    let flat = Aabb::new(Vec3::new(0.0, 0.0, 0.5), Vec3::new(1.0, 1.0, 0.5));
    assert!(near(
        hit(&flat, Vec3::new(0.5, 0.5, 0.0), Vec3::Z),
        (0.5, 0.5)
    ));
    assert!(near(
        hit(&flat, Vec3::new(-1.0, 0.5, 0.5), Vec3::X),
        (1.0, 2.0)
    ));
    // Behind the origin.
    assert_eq!(hit(&unit, Vec3::new(0.5, 0.5, 2.0), Vec3::Z), None);
}

#[test]
fn a_zero_radius_sphere_is_hit_by_a_ray_through_its_centre() {
    let point = Sphere::new(Vec2::new(3.0, 1.0), 0.0);
    let ray = Ray::through(Vec2::new(-7.3, 0.1), point.center).expect("valid");
    let (t_enter, _) = point
        .ray_entry(&PreparedRay::new(&ray))
        .expect("through the centre");
    assert!((t_enter - 1.0).abs() < 1e-5);
}

#[test]
fn the_stack_pops_the_nearer_child_first() {
    let entry = |node, key| {
        Some(Entry {
            node,
            depth: 1,
            key,
        })
    };
    let mut stack = Stack::new();
    let order = stack.push_pair(entry(1, 5.0), entry(2, 3.0));
    assert_eq!(order.map(|e| e.map(|e| e.node)), [Some(2), Some(1)]);
    assert_eq!(stack.pop().map(|e| e.node), Some(2));
    assert_eq!(stack.pop().map(|e| e.node), Some(1));
    assert_eq!(stack.pop(), None);
    // Ties keep the first child first; a lone survivor is pushed alone.
    stack.push_pair(entry(1, 3.0), entry(2, 3.0));
    assert_eq!(stack.pop().map(|e| e.node), Some(1));
    stack.pop();
    assert_eq!(
        stack
            .push_pair(None, entry(4, 1.0))
            .map(|e| e.map(|e| e.node)),
        [Some(4), None]
    );
    assert_eq!(stack.pop().map(|e| e.node), Some(4));
    assert_eq!(stack.pop(), None);
}
