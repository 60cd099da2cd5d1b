//! `Mesh::from_indexed`, the door through which other file formats and procedural meshes
//! enter the core: it must give the same mesh as the OBJ reader for the same triangles, and
//! refuse non-finite vertices and out-of-range indices with the first offender named.

use std::fmt::Write;

use bvhlab::glam::Vec3;
use bvhlab::mesh::{Mesh, MeshError};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Random vertices (a few unused) and random triangles over them.
fn random_mesh(seed: u64) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let n = 40;
    let positions: Vec<Vec3> = (0..n)
        .map(|_| {
            Vec3::new(
                rng.random_range(-5.0..5.0),
                rng.random_range(-5.0..5.0),
                rng.random_range(-5.0..5.0),
            )
        })
        .collect();
    let indices = (0..60)
        .map(|_| {
            [
                rng.random_range(0..n - 3),
                rng.random_range(0..n - 3),
                rng.random_range(0..n - 3),
            ]
        })
        .collect();
    (positions, indices)
}

/// The same mesh written as OBJ text (1-based indices; `{:?}` prints an `f32` exactly).
fn as_obj(positions: &[Vec3], indices: &[[u32; 3]]) -> String {
    let mut text = String::new();
    for p in positions {
        writeln!(text, "v {:?} {:?} {:?}", p.x, p.y, p.z).expect("writing to a String");
    }
    for [a, b, c] in indices {
        writeln!(text, "f {} {} {}", a + 1, b + 1, c + 1).expect("writing to a String");
    }
    text
}

#[test]
fn the_same_mesh_as_the_obj_reader_gives() {
    for seed in 0..5 {
        let (positions, indices) = random_mesh(seed);
        let from_obj = Mesh::from_obj(as_obj(&positions, &indices).as_bytes()).expect("valid");
        let indexed = Mesh::from_indexed(positions, indices).expect("valid");
        assert_eq!(indexed, from_obj, "seed {seed}");
        assert_eq!(indexed.summary(), from_obj.summary(), "seed {seed}");
    }
}

#[test]
fn triangles_are_the_indexed_corners_in_order() {
    let (positions, indices) = random_mesh(7);
    let mesh = Mesh::from_indexed(positions.clone(), indices.clone()).expect("valid");
    assert_eq!(mesh.len(), indices.len());
    for (t, [a, b, c]) in mesh.triangles().iter().zip(&indices) {
        let at = |i: &u32| positions[*i as usize];
        assert_eq!((t.a, t.b, t.c), (at(a), at(b), at(c)));
    }
    // The three unused vertices are kept but do not widen the bounds.
    assert_eq!(mesh.positions().len(), 40);
    let used = indices.iter().flatten().map(|&i| positions[i as usize]);
    let (lo, hi) = used.fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| {
        (lo.min(p), hi.max(p))
    });
    assert_eq!((mesh.bounds().min, mesh.bounds().max), (lo, hi));
}

#[test]
fn nothing_in_gives_an_empty_mesh() {
    let mesh = Mesh::from_indexed(Vec::new(), Vec::new()).expect("empty is valid");
    assert!(mesh.is_empty());
    assert_eq!(mesh.summary().faces, 0);
}

#[test]
fn zero_area_triangles_are_kept_and_counted() {
    let positions = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(2.0, 0.0, 0.0)];
    let mesh = Mesh::from_indexed(positions, vec![[0, 1, 2], [0, 1, 3], [2, 2, 2]]).expect("ok");
    assert_eq!(mesh.len(), 3);
    assert_eq!(mesh.summary().degenerate_triangles, 2);
}

#[test]
fn the_first_non_finite_vertex_is_named() {
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let (mut positions, indices) = random_mesh(3);
        positions[17].y = bad;
        positions[30].z = bad;
        let err = Mesh::from_indexed(positions, indices).expect_err("non-finite");
        assert_eq!(err, MeshError::NonFiniteVertex { vertex: 17 });
        assert!(err.to_string().starts_with("vertex 17 "), "{err}");
    }
}

#[test]
fn a_non_finite_vertex_is_refused_even_when_unused() {
    let (mut positions, indices) = random_mesh(4);
    positions[39] = Vec3::splat(f32::NAN);
    let err = Mesh::from_indexed(positions, indices).expect_err("non-finite");
    assert_eq!(err, MeshError::NonFiniteVertex { vertex: 39 });
}

#[test]
fn the_first_out_of_range_index_is_named() {
    let (positions, mut indices) = random_mesh(5);
    indices[12][2] = 40;
    indices[20][0] = u32::MAX;
    let err = Mesh::from_indexed(positions, indices).expect_err("out of range");
    assert_eq!(
        err,
        MeshError::IndexOutOfRange {
            triangle: 12,
            index: 40,
            vertices: 40
        }
    );
    let message = err.to_string();
    assert!(
        message.contains("triangle 12") && message.contains("0 to 39"),
        "{message}"
    );

    let none = Mesh::from_indexed(Vec::new(), vec![[0, 0, 0]]).expect_err("no vertices");
    assert!(
        none.to_string().ends_with("there are no vertices"),
        "{none}"
    );
}
