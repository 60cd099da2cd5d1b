//! Mesh files, as a student drops them on the lab: any bytes under any of the names the lab
//! reads. The first input byte picks the file name's extension, so the fuzzer reaches every
//! reader whatever the content (the content decides first, the name only when the content
//! shows no format: see `bvhlab_meshio::Format::from_content`); the rest is the file.
//!
//! Besides "no panic, no hang, no unbounded allocation", it checks what `load` promises: an
//! error names the file first, and a mesh has triangles, within the limit, at finite
//! coordinates.

#![no_main]

use bvhlab_meshio::{MAX_TRIANGLES, load};
use libfuzzer_sys::fuzz_target;

/// The names the first byte picks from: each format's extension, an upper-case one, and
/// names that leave the content alone to decide.
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

bvhlab_fuzz::same_hash_keys_every_run!();

fuzz_target!(|data: &[u8]| {
    let Some((&pick, bytes)) = data.split_first() else {
        return;
    };
    let name = NAMES[usize::from(pick) % NAMES.len()];
    match load(name, bytes) {
        Ok(loaded) => {
            let mesh = &loaded.mesh;
            assert!(!mesh.is_empty(), "{name}: loaded without triangles");
            assert!(
                mesh.len() <= MAX_TRIANGLES,
                "{name}: {} triangles",
                mesh.len()
            );
            assert!(
                mesh.positions().iter().all(|p| p.is_finite()),
                "{name}: a vertex is not finite"
            );
            assert!(
                mesh.indices()
                    .iter()
                    .flatten()
                    .all(|&i| (i as usize) < mesh.positions().len()),
                "{name}: an index is out of range"
            );
        }
        Err(error) => {
            let message = error.to_string();
            assert!(message.starts_with(name), "{message}");
        }
    }
});
