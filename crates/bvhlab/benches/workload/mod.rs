//! Issue 7's workload on one mesh, shared by `benches/speed.rs` and `examples/speed.rs`:
//! the primary rays of a 640x480 camera that frames the mesh (coherent), random rays inside
//! its bounding box (incoherent) and random points in it (closest point), all seeded.
#![allow(dead_code, reason = "the bench and the example each use a part")]

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// `../shared/data/meshes/NAME` beside the repository, loaded, or `None` with a message.
pub fn shared_mesh(name: &str) -> Option<Mesh> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data/meshes")
        .join(name);
    let Ok(bytes) = std::fs::read(&path) else {
        eprintln!("skipping {name}: {} is absent", path.display());
        return None;
    };
    match Mesh::from_obj(&bytes) {
        Ok(mesh) => Some(mesh),
        Err(e) => {
            eprintln!("skipping {name}: {e}");
            None
        }
    }
}

/// Primary rays of a 640x480 pinhole camera (60° vertical field of view) that frames the box,
/// looking at its centre from the +z side, a little from above.
pub fn camera_rays(bounds: &Aabb3) -> Vec<Ray3> {
    let (w, h) = (640, 480);
    let center = (bounds.min + bounds.max) * 0.5;
    let extent = bounds.max - bounds.min;
    // Far enough that the box's front fills the view's height (or width) with a margin.
    let half_height = extent.y.max(extent.x * h as f32 / w as f32) * 0.55;
    let distance = half_height / 30f32.to_radians().tan() + extent.z * 0.5;
    let eye = center + Vec3::new(0.0, 0.2, 1.0).normalize() * distance;
    let forward = (center - eye).normalize();
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    let half = 30f32.to_radians().tan();
    let mut rays = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            let u = ((x as f32 + 0.5) / w as f32 * 2.0 - 1.0) * half * w as f32 / h as f32;
            let v = (1.0 - (y as f32 + 0.5) / h as f32 * 2.0) * half;
            rays.extend(Ray3::new(eye, forward + right * u + up * v));
        }
    }
    rays
}

/// Rays from uniform points in the box toward uniform directions (seeded).
pub fn random_rays(bounds: &Aabb3, n: usize) -> Vec<Ray3> {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    (0..n)
        .map(|_| {
            let origin = point_in(bounds, &mut rng);
            let dir = loop {
                let d = Vec3::new(
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                );
                if (0.01..=1.0).contains(&d.length_squared()) {
                    break d;
                }
            };
            Ray3::new(origin, dir)
        })
        .filter_map(Result::ok)
        .collect()
}

/// Uniform points in the box (seeded).
pub fn random_points(bounds: &Aabb3, n: usize) -> Vec<Vec3> {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    (0..n).map(|_| point_in(bounds, &mut rng)).collect()
}

fn point_in(bounds: &Aabb3, rng: &mut ChaCha8Rng) -> Vec3 {
    let r = Vec3::new(
        rng.random_range(0.0..1.0),
        rng.random_range(0.0..1.0),
        rng.random_range(0.0..1.0),
    );
    bounds.min + (bounds.max - bounds.min) * r
}
