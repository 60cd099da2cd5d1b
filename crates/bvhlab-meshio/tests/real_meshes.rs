//! The course's real meshes (`shared/data/meshes`, skipped with a message when absent): each
//! loads through `load` as the core's OBJ reader reads it, and the same triangles written by
//! the tests as PLY (three encodings), STL (binary and ASCII) and GLB load back the same.

use crate::support;

use std::time::Instant;

use bvhlab::Mesh;
use bvhlab_meshio::{Format, load};
use support::{Encoding, GltfBuffer, PlyStyle};

/// `(file, triangles)` as the folder's README lists them.
const MESHES: [(&str, usize); 7] = [
    ("suzanne.obj", 968),
    ("spot.obj", 5856),
    ("teapot.obj", 6320),
    ("fandisk.obj", 12946),
    ("stanford-bunny.obj", 69451),
    ("dragon.obj", 100_000),
    ("ogre.obj", 124_008),
];

/// The mesh as a one-node GLB with 32-bit indices.
fn as_glb(mesh: &Mesh) -> Vec<u8> {
    let mut buffer = GltfBuffer::default();
    let at = buffer.positions(mesh.positions());
    let flat: Vec<u32> = mesh.indices().iter().flatten().copied().collect();
    let ix = buffer.indices(&flat, 4);
    let meshes =
        format!(r#"{{"primitives":[{{"attributes":{{"POSITION":{at}}},"indices":{ix}}}]}}"#);
    let json = buffer.json(&meshes, r#"{"mesh":0}"#, r#"{"nodes":[0]}"#, None);
    support::glb(&json, &buffer.bytes)
}

#[test]
fn real_meshes_load_the_same_in_every_format() {
    let Some(dir) = support::mesh_dir() else {
        return;
    };
    for (name, triangles) in MESHES {
        let bytes = std::fs::read(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        let loaded = load(name, &bytes).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(loaded.format, Format::Obj);
        assert_eq!(
            loaded.mesh,
            Mesh::from_obj(&bytes).expect("the core reads it")
        );
        assert_eq!(loaded.mesh.len(), triangles, "{name}");
        let mesh = &loaded.mesh;
        let faces = support::faces_of(mesh);
        let stem = name.trim_end_matches(".obj");
        let files = [
            (
                "ascii.ply",
                support::ply(mesh.positions(), &faces, &PlyStyle::plain(Encoding::Ascii)),
            ),
            (
                "le.ply",
                support::ply(mesh.positions(), &faces, &PlyStyle::plain(Encoding::Little)),
            ),
            (
                "be.ply",
                support::ply(mesh.positions(), &faces, &PlyStyle::plain(Encoding::Big)),
            ),
            (
                "binary.stl",
                support::stl_binary(mesh.triangles(), b"solid but binary"),
            ),
            ("ascii.stl", support::stl_ascii(&[mesh.triangles()])),
            ("mesh.glb", as_glb(mesh)),
        ];
        for (kind, file) in files {
            let started = Instant::now();
            let again = load(&format!("{stem}.{kind}"), &file).unwrap_or_else(|e| panic!("{e}"));
            eprintln!("{name} as {kind}: {:?}", started.elapsed());
            assert!(
                support::same_triangles(&again.mesh, mesh),
                "{name} as {kind}"
            );
            if !kind.ends_with("stl") {
                // Formats with shared vertices keep them as they are.
                assert_eq!(again.mesh.positions(), mesh.positions(), "{name} as {kind}");
            }
        }
    }
}
