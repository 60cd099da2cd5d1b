//! The fuzzer's corpus (`fuzz/corpus/mesh_load`, seeds and what the fuzzer found, crashes
//! included once fixed) replayed through [`load`] by plain `cargo test`, so every input the
//! corpus keeps is checked on stable Rust without the instrumented build of `tests/fuzz.sh`.

use std::fs;
use std::path::PathBuf;

use bvhlab_meshio::{Format, MAX_TRIANGLES, load};

/// The names the fuzz target's first input byte picks from: the same table as in
/// `fuzz/fuzz_targets/mesh_load.rs`, which must stay equal to it for a replay to read each
/// file as the fuzzer did.
const NAMES: [&str; 8] = [
    "m.obj",
    "m.ply",
    "m.stl",
    "m.gltf",
    "m.glb",
    "M.STL",
    "mesh",
    "notes.txt",
];

fn corpus() -> Vec<(PathBuf, Vec<u8>)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/corpus/mesh_load");
    let mut files: Vec<(PathBuf, Vec<u8>)> = fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| {
            let path = entry.expect("a directory entry").path();
            let bytes = fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            (path, bytes)
        })
        .collect();
    files.sort();
    files
}

#[test]
fn every_corpus_file_loads_or_is_refused_with_its_name() {
    let files = corpus();
    assert!(files.len() >= 10, "the corpus has {} files", files.len());
    let mut loaded_formats = Vec::new();
    for (path, data) in &files {
        let Some((&pick, bytes)) = data.split_first() else {
            continue;
        };
        let name = NAMES[usize::from(pick) % NAMES.len()];
        let what = format!("{} (as {name})", path.display());
        match load(name, bytes) {
            Ok(loaded) => {
                let mesh = &loaded.mesh;
                assert!(!mesh.is_empty() && mesh.len() <= MAX_TRIANGLES, "{what}");
                assert!(mesh.positions().iter().all(|p| p.is_finite()), "{what}");
                let vertices = mesh.positions().len();
                assert!(
                    mesh.indices()
                        .iter()
                        .flatten()
                        .all(|&i| (i as usize) < vertices),
                    "{what}"
                );
                loaded_formats.push(loaded.format);
            }
            Err(error) => assert!(error.to_string().starts_with(name), "{what}: {error}"),
        }
    }
    // The seeds keep a valid file of every format in the corpus, so the fuzzer starts inside
    // every reader.
    for format in Format::ALL {
        assert!(
            loaded_formats.contains(&format),
            "no corpus file loads as {format:?}"
        );
    }
}
