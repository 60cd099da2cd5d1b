//! Timings, not tests: run with `cargo test -p bvhlab-meshio --test all timings -- --ignored
//! --nocapture`. They print how long the large built-in mesh takes to make and how long the
//! ogre (124,008 triangles) takes to load from OBJ, PLY and STL, each the best of three.

use crate::support;

use std::time::{Duration, Instant};

use bvhlab_meshio::{builtin, load};
use support::{Encoding, PlyStyle};

/// The best of three runs of `f`.
fn best_of_three(mut f: impl FnMut()) -> Duration {
    (0..3)
        .map(|_| {
            let started = Instant::now();
            f();
            started.elapsed()
        })
        .min()
        .unwrap_or_default()
}

#[test]
#[ignore = "a timing, not a test"]
fn time_the_large_built_in_mesh() {
    let mut triangles = 0;
    let took = best_of_three(|| triangles = builtin::make("lumpy-sphere").map_or(0, |m| m.len()));
    eprintln!("lumpy-sphere, {triangles} triangles: {took:?}");
}

#[test]
#[ignore = "a timing, not a test"]
fn time_the_ogre_in_each_format() {
    let Some(dir) = support::mesh_dir() else {
        return;
    };
    let obj = std::fs::read(dir.join("ogre.obj")).expect("ogre.obj");
    let mesh = load("ogre.obj", &obj).expect("valid").mesh;
    let faces = support::faces_of(&mesh);
    let files = [
        ("ogre.obj", obj.clone()),
        (
            "ogre-ascii.ply",
            support::ply(mesh.positions(), &faces, &PlyStyle::plain(Encoding::Ascii)),
        ),
        (
            "ogre-binary.ply",
            support::ply(mesh.positions(), &faces, &PlyStyle::plain(Encoding::Little)),
        ),
        ("ogre-ascii.stl", support::stl_ascii(&[mesh.triangles()])),
        (
            "ogre-binary.stl",
            support::stl_binary(mesh.triangles(), b""),
        ),
    ];
    for (name, bytes) in files {
        let took = best_of_three(|| assert!(load(name, &bytes).is_ok()));
        eprintln!("{name} ({} KiB): {took:?}", bytes.len() / 1024);
    }
}
