//! Runs the `save_load` example in the tests: as a program (whose default mesh is not beside
//! the crate's folder, so it falls back to the sphere it generates), over a mesh that does not
//! exist, and over the shared suzanne mesh (when the shared folder is there).

#![cfg(feature = "serde")]

#[path = "../examples/save_load.rs"]
mod save_load;

use std::path::{Path, PathBuf};

/// One test, not several: runs share the example's scratch folder (named by the process).
#[test]
fn the_example_runs_as_a_program_and_over_generated_and_shared_meshes() {
    save_load::main().expect("the example runs as a program");

    let report = save_load::run(Path::new("no such mesh.obj")).expect("the example runs");
    // 16 rings of 32 quads, two triangles each (the poles' are degenerate but kept).
    assert_eq!(report.triangles, 16 * 32 * 2);
    assert!(report.file_bytes > report.triangles * 36, "{report:?}");
    assert!(
        report.first_hit.is_some(),
        "a ray through the sphere's centre hits it"
    );

    let mesh =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/meshes/suzanne.obj");
    if !mesh.is_file() {
        eprintln!("skipping suzanne: {} is absent", mesh.display());
        return;
    }
    let report = save_load::run(&mesh).expect("the example runs");
    assert_eq!(report.mesh, mesh);
    assert!(report.triangles > 900, "{report:?}");
    assert!(report.first_hit.is_some(), "{report:?}");
}
