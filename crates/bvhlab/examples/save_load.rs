//! Saving and loading a tree: builds an AABB tree over a mesh file, saves it to a file in the
//! temporary folder, loads it back, and checks that the copy answers a ray and a closest-point
//! query as the tree it was saved from. A tree is built once and loaded many times: a load
//! skips the build and checks the file instead (`bvhlab::saved`).
//!
//! Run: `cargo run -p bvhlab --features serde --example save_load -- [MESH.obj]` (default: the
//! shared suzanne.obj beside the repository; where it is absent, a sphere mesh the example
//! writes itself). `tests/example_save_load.rs` runs it in the tests.
#![expect(clippy::print_stdout, reason = "an example that reports what it did")]

use std::error::Error;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use bvhlab::glam::Vec3;
use bvhlab::prelude::*;
use bvhlab::saved;

/// What one run did.
#[derive(Debug)]
pub struct Report {
    /// The mesh file the tree was built over.
    pub mesh: PathBuf,
    /// Its triangles.
    pub triangles: usize,
    /// The saved file's size.
    pub file_bytes: usize,
    /// The loaded tree's answer to a ray through the mesh's centre.
    pub first_hit: Option<usize>,
}

/// Runs [`run`] on the mesh named by the first argument, or the default, and reports.
///
/// # Errors
/// As [`run`].
pub fn main() -> Result<(), Box<dyn Error>> {
    let mesh = std::env::args().nth(1).map_or_else(
        || PathBuf::from("../shared/data/meshes/suzanne.obj"),
        PathBuf::from,
    );
    let report = run(&mesh)?;
    println!(
        "{}: {} triangles, saved in {} bytes ({:.1} per triangle); the loaded tree's first hit: {:?}",
        report.mesh.display(),
        report.triangles,
        report.file_bytes,
        report.file_bytes as f64 / report.triangles as f64,
        report.first_hit
    );
    Ok(())
}

/// Builds, saves, loads and compares; uses a generated sphere mesh when `mesh` is absent.
///
/// # Errors
/// A mesh that does not parse, a file that cannot be written or read, a refused load, or a
/// loaded tree that answers otherwise than the saved one.
pub fn run(mesh: &Path) -> Result<Report, Box<dyn Error>> {
    let scratch = std::env::temp_dir().join(format!("bvhlab-save-load-{}", std::process::id()));
    std::fs::create_dir_all(&scratch)?;
    let mesh = if mesh.is_file() {
        mesh.to_path_buf()
    } else {
        let generated = scratch.join("sphere.obj");
        std::fs::write(&generated, sphere_obj(16, 32))?;
        generated
    };
    let triangles = Mesh::from_obj(&std::fs::read(&mesh)?)?.triangles().to_vec();
    let tree = AabbTree3::build(&triangles);

    // Save, then load from the file as another program would.
    let file = scratch.join(format!("{}.bvhtree", stem(&mesh)));
    std::fs::write(&file, saved::save(&tree)?)?;
    let bytes = std::fs::read(&file)?;
    let loaded: AabbTree3 = saved::load(&bytes)?;
    // The scratch folder holds only this run's files: the saved tree, a generated mesh.
    std::fs::remove_dir_all(&scratch)?;

    // The copy answers as the original: a ray through the mesh's centre, and the nearest
    // triangle to a point beside it.
    let center = triangles.iter().map(|t| t.a).sum::<Vec3>() / triangles.len().max(1) as f32;
    let ray = Ray3::new(center + Vec3::new(0.0, 0.0, 100.0), -Vec3::Z)?;
    let first_hit = loaded.ray_first_hit(&ray, f32::INFINITY);
    let beside = center + Vec3::X * 0.1;
    if first_hit != tree.ray_first_hit(&ray, f32::INFINITY)
        || loaded.closest_point(beside) != tree.closest_point(beside)
        || loaded.stats().nodes != tree.stats().nodes
    {
        return Err("the loaded tree answers otherwise than the saved one".into());
    }
    Ok(Report {
        mesh,
        triangles: triangles.len(),
        file_bytes: bytes.len(),
        first_hit: first_hit.map(|hit| hit.prim),
    })
}

fn stem(path: &Path) -> String {
    path.file_stem()
        .map_or_else(|| "mesh".to_owned(), |s| s.to_string_lossy().into_owned())
}

/// A unit UV sphere as OBJ text: `rings` bands from pole to pole, `segments` around.
fn sphere_obj(rings: usize, segments: usize) -> String {
    let mut obj = String::new();
    for ring in 0..=rings {
        let polar = std::f32::consts::PI * ring as f32 / rings as f32;
        for segment in 0..segments {
            let azimuth = std::f32::consts::TAU * segment as f32 / segments as f32;
            let (x, y, z) = (
                polar.sin() * azimuth.cos(),
                polar.sin() * azimuth.sin(),
                polar.cos(),
            );
            let _ = writeln!(obj, "v {x} {y} {z}");
        }
    }
    // OBJ counts vertices from 1.
    let vertex = |ring: usize, segment: usize| ring * segments + segment % segments + 1;
    for ring in 0..rings {
        for segment in 0..segments {
            let (a, b) = (vertex(ring, segment), vertex(ring, segment + 1));
            let (c, d) = (vertex(ring + 1, segment + 1), vertex(ring + 1, segment));
            let _ = writeln!(obj, "f {a} {b} {c}\nf {a} {c} {d}");
        }
    }
    obj
}
