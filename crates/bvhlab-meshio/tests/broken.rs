//! Broken files: each gives an error (never a panic) whose message starts with the file's
//! name and names the fault. Then every valid test file cut at every length, and with bytes
//! changed at random, must give `Ok` or `Err` but never panic.

use crate::support;

use std::fmt::Write as _;

use bvhlab::glam::Vec3;
use bvhlab::{Mesh, Triangle3};
use bvhlab_meshio::{Format, LoadError, MAX_BYTES, builtin, load};
use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::{Rng, SeedableRng};
use support::{Encoding, GltfBuffer, PlyStyle};

/// Loads `bytes` as `name`, which must fail with a message naming the file and holding every
/// one of `words`; returns the error.
fn refused(name: &str, bytes: &[u8], words: &[&str]) -> LoadError {
    let error = match load(name, bytes) {
        Ok(loaded) => panic!("{name} loaded as {:?}: {loaded:?}", loaded.format),
        Err(error) => error,
    };
    let message = error.to_string();
    assert!(message.starts_with(name), "{message}");
    assert_eq!(error.file(), name);
    for word in words {
        assert!(
            message.contains(word),
            "{name}: `{word}` is not in: {message}"
        );
    }
    error
}

fn cube() -> Mesh {
    builtin::cube()
}

fn ply_text(header_and_data: &str) -> Vec<u8> {
    header_and_data.replace("\n    ", "\n").into_bytes()
}

// ---- any format ----

#[test]
fn empty_files() {
    for name in ["empty.obj", "empty.stl", "empty.glb", "empty"] {
        let error = refused(name, b"", &["is empty"]);
        assert!(matches!(error, LoadError::Empty { .. }));
    }
}

#[test]
fn garbage_is_no_mesh_format() {
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let mut noise = vec![0u8; 1000];
    rng.fill_bytes(&mut noise);
    let message = "is not a mesh file this lab reads (OBJ, PLY, STL, glTF/GLB)";
    let error = refused("noise.bin", &noise, &[message]);
    assert!(matches!(error, LoadError::UnknownFormat { .. }));
    refused(
        "notes.txt",
        b"Dear student,\nthis is a letter.\n",
        &[message],
    );
}

#[test]
fn a_file_over_the_size_limit_is_refused_unread() {
    // calloc'd and never touched: the length alone decides.
    let huge = vec![0u8; MAX_BYTES + 1];
    refused("huge.stl", &huge, &["513 MiB", "up to 512 MiB"]);
}

#[test]
fn a_wrong_name_on_unreadable_content_names_the_format_it_claims() {
    refused(
        "mesh.ply",
        b"this is not\na PLY file\n",
        &["starts with the line `ply`"],
    );
    refused("scene.glb", b"not a glb at all, just text", &["`glTF`"]);
    refused("scene.gltf", b"<xml>", &["not glTF 2.0 JSON"]);
    refused("model.obj", b"v 0 0 0\0\0\0binary", &["not text"]);
}

// ---- STL ----

/// A binary STL of the cube with its count word replaced.
fn stl_with_count(count: u32, records: usize) -> Vec<u8> {
    let mut bytes = support::stl_binary(&cube().triangles()[..records], b"");
    bytes[80..84].copy_from_slice(&count.to_le_bytes());
    bytes
}

#[test]
fn binary_stl_count_lies_and_cut_off_files() {
    let error = refused(
        "file.stl",
        &stl_with_count(1200, 3),
        &["binary STL says 1,200 triangles but holds 3"],
    );
    assert!(matches!(
        error,
        LoadError::StlCount {
            declared: 1200,
            holds: 3,
            stray_bytes: 0,
            ..
        }
    ));
    let full = support::stl_binary(cube().triangles(), b"");
    let cut = &full[..84 + 7 * 50 + 20];
    refused(
        "cut.stl",
        cut,
        &["says 12 triangles but holds 7 and 20 stray bytes"],
    );
    // A header that starts with "solid" does not make a cut-off binary file ASCII.
    let mut trap = support::stl_binary(cube().triangles(), b"solid exported by CAD");
    trap.truncate(84 + 5 * 50);
    refused("trap.stl", &trap, &["says 12 triangles but holds 5"]);
    refused("tiny.stl", &[1u8; 40], &["84-byte header", "only 40 bytes"]);
}

#[test]
fn binary_stl_without_triangles() {
    let error = refused("none.stl", &stl_with_count(0, 0), &["has no triangles"]);
    assert!(matches!(
        error,
        LoadError::NoTriangles {
            format: Format::Stl,
            ..
        }
    ));
}

#[test]
fn stl_with_nan_or_infinity() {
    let mut triangles = cube().triangles().to_vec();
    triangles[4].b.y = f32::NAN;
    refused(
        "nan.stl",
        &support::stl_binary(&triangles, b""),
        &["triangle 4", "not a finite number"],
    );
    for bad in [f32::INFINITY, f32::NAN] {
        triangles[4].b.y = bad;
        let text = String::from_utf8(support::stl_ascii(&[&triangles])).expect("text");
        assert!(text.contains(" inf ") || text.contains(" NaN "));
        refused(
            "bad.stl",
            text.as_bytes(),
            &["solid 0, facet 4", "not a finite number"],
        );
    }
}

#[test]
fn ascii_stl_structure_faults() {
    let text = String::from_utf8(support::stl_ascii(&[cube().triangles()])).expect("text");
    let half = text.len() / 2;
    refused(
        "cut.stl",
        &text.as_bytes()[..half],
        &["ASCII STL, solid 0, facet", "expected"],
    );
    let line_end = half + text[half..].find('\n').expect("more lines") + 1;
    refused(
        "cut.stl",
        &text.as_bytes()[..line_end],
        &["ASCII STL", "ends inside the solid"],
    );
    let short_vertex = text.replacen("vertex 1.0 1.0 1.0", "vertex 1.0 1.0", 1);
    assert_ne!(short_vertex, text);
    refused(
        "short.stl",
        short_vertex.as_bytes(),
        &["ASCII STL, solid 0, facet"],
    );
    let trailing = format!("{text}this is not a solid\n");
    let line = text.lines().count() + 1;
    refused(
        "trailing.stl",
        trailing.as_bytes(),
        &[&format!("line {line}"), "expected `solid`"],
    );
}

// ---- PLY ----

fn cube_ply(encoding: Encoding) -> Vec<u8> {
    let mesh = cube();
    support::ply(
        mesh.positions(),
        &support::faces_of(&mesh),
        &PlyStyle::plain(encoding),
    )
}

#[test]
fn ply_header_faults() {
    let text = String::from_utf8(cube_ply(Encoding::Ascii)).expect("text");
    let no_end = text.split("end_header").next().expect("a header");
    refused("open.ply", no_end.as_bytes(), &["no `end_header`"]);
    let odd_format = text.replace("format ascii 1.0", "format binary_middle_endian 1.0");
    refused(
        "odd.ply",
        odd_format.as_bytes(),
        &["line 2", "binary_middle_endian"],
    );
    let no_z = text.replace("property float z\n", "");
    refused("flat.ply", no_z.as_bytes(), &["no `z` property"]);
    let cloud = ply_text(
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n",
    );
    refused("cloud.ply", &cloud, &["no `element face`", "point cloud"]);
}

#[test]
fn ply_headers_that_promise_more_than_the_file_holds() {
    let text = String::from_utf8(cube_ply(Encoding::Ascii)).expect("text");
    let more = text.replace("element vertex 8", "element vertex 30");
    refused(
        "more.ply",
        more.as_bytes(),
        &["declares 42 elements", "only 20 lines"],
    );
    let binary = cube_ply(Encoding::Little);
    let header_end = binary
        .windows(11)
        .position(|w| w == b"end_header\n")
        .expect("header")
        + 11;
    let cut = &binary[..header_end + 5 * 12];
    refused(
        "cut.ply",
        cut,
        &[
            "declares 8 `vertex` elements of at least 12 bytes each",
            "only 60 bytes follow",
        ],
    );
    // Room for every face's count byte, but not for the indices.
    let cut = &binary[..header_end + 8 * 12 + 5 * 13];
    refused(
        "cut.ply",
        cut,
        &["declares 12 `face` elements, but the data ends after 5"],
    );
    // Fits the smallest sizes, but the lists are longer: the data ends early.
    let header = String::from_utf8_lossy(&binary[..header_end]).replace("face 12", "face 13");
    let mut lying_binary = binary.clone();
    lying_binary[..header_end].copy_from_slice(header.as_bytes());
    lying_binary.push(3);
    refused(
        "lying.ply",
        &lying_binary,
        &["declares 13 `face` elements", "ends after 12"],
    );
}

#[test]
fn ply_too_many_faces_is_refused_before_reading() {
    let header = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 12000000\nproperty list uchar int vertex_indices\nend_header\n";
    let error = refused(
        "huge.ply",
        header.as_bytes(),
        &["has 12,000,000 triangles; the lab's limit is 4,000,000"],
    );
    assert!(matches!(
        error,
        LoadError::TooManyTriangles {
            triangles: 12_000_000,
            ..
        }
    ));
}

#[test]
fn ply_bad_indices_and_corners() {
    let mesh = cube();
    for encoding in [Encoding::Ascii, Encoding::Little, Encoding::Big] {
        let style = PlyStyle::plain(encoding);
        let mut faces = support::faces_of(&mesh);
        faces[5][1] = 8;
        refused(
            "past.ply",
            &support::ply(mesh.positions(), &faces, &style),
            &["face 5 names vertex 8", "only 8 vertices (0 to 7)"],
        );
        faces[5][1] = -2;
        refused(
            "negative.ply",
            &support::ply(mesh.positions(), &faces, &style),
            &["face 5 names vertex -2", "cannot be negative"],
        );
        faces[5] = vec![1, 2];
        refused(
            "two.ply",
            &support::ply(mesh.positions(), &faces, &style),
            &["face 5 has 2 corners"],
        );
    }
}

#[test]
fn ply_with_nan_or_infinity() {
    let mesh = cube();
    let faces = support::faces_of(&mesh);
    for (encoding, bad) in [
        (Encoding::Ascii, f32::NAN),
        (Encoding::Little, f32::NAN),
        (Encoding::Big, f32::NEG_INFINITY),
        (Encoding::Ascii, f32::INFINITY),
    ] {
        let mut positions = mesh.positions().to_vec();
        positions[6].x = bad;
        let bytes = support::ply(&positions, &faces, &PlyStyle::plain(encoding));
        let error = refused(
            "nan.ply",
            &bytes,
            &["vertex` element 6", "not a finite number"],
        );
        assert!(matches!(
            error,
            LoadError::NonFinite {
                format: Format::Ply,
                ..
            }
        ));
    }
}

#[test]
fn ply_data_that_is_not_numbers() {
    let text = String::from_utf8(cube_ply(Encoding::Ascii)).expect("text");
    let words = text.replacen("\n1.0 1.0 1.0\n", "\n1.0 one 1.0\n", 1);
    assert_ne!(words, text);
    refused(
        "words.ply",
        words.as_bytes(),
        &["PLY line 18, `vertex` element 7"],
    );
}

// ---- glTF ----

fn tetra_buffer() -> (GltfBuffer, String) {
    let mut buffer = GltfBuffer::default();
    let at = buffer.positions(&[Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z]);
    let ix = buffer.indices(&[0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3], 2);
    let meshes = format!(
        r#"{{"name":"tet","primitives":[{{"attributes":{{"POSITION":{at}}},"indices":{ix}}}]}}"#
    );
    (buffer, meshes)
}

fn tetra_json(uri: Option<&str>) -> String {
    let (buffer, meshes) = tetra_buffer();
    buffer.json(&meshes, r#"{"mesh":0}"#, r#"{"nodes":[0]}"#, uri)
}

fn tetra_glb() -> Vec<u8> {
    let (buffer, meshes) = tetra_buffer();
    support::glb(
        &buffer.json(&meshes, r#"{"mesh":0}"#, r#"{"nodes":[0]}"#, None),
        &buffer.bytes,
    )
}

#[test]
fn gltf_with_a_separate_buffer_file_names_it() {
    let json = tetra_json(Some("tetra.bin"));
    let error = refused(
        "tetra.gltf",
        json.as_bytes(),
        &["`tetra.bin`", "export as .glb"],
    );
    assert_eq!(
        error,
        LoadError::ExternalBuffer {
            file: "tetra.gltf".into(),
            uri: "tetra.bin".into()
        }
    );
}

#[test]
fn glb_cut_off_anywhere_is_refused() {
    let glb = tetra_glb();
    assert!(load("ok.glb", &glb).is_ok());
    for cut in [4, 11, 12, 19, 20, 40, glb.len() - 20, glb.len() - 1] {
        let error = refused("cut.glb", &glb[..cut], &[]);
        assert!(
            matches!(
                error,
                LoadError::Malformed {
                    format: Format::Glb,
                    ..
                }
            ),
            "{error}"
        );
    }
    refused(
        "cut.glb",
        &glb[..glb.len() - 1],
        &["the GLB header says the file has", "a cut-off file?"],
    );
    let mut version_one = glb.clone();
    version_one[4] = 1;
    refused("old.glb", &version_one, &["glTF 1.0"]);
}

#[test]
fn gltf_that_is_not_valid() {
    refused(
        "syntax.gltf",
        b"{\"asset\": {\"version\": \"2.0\"",
        &["not glTF 2.0 JSON", "EOF"],
    );
    let json = tetra_json(Some("")).replace(r#""indices":1"#, r#""indices":7"#);
    refused("dangling.gltf", json.as_bytes(), &["not valid", "indices"]);
    // gltf-json's own validation would index out of bounds here.
    let json = tetra_json(Some("")).replace(r#""POSITION":0"#, r#""POSITION":9"#);
    refused(
        "position.gltf",
        json.as_bytes(),
        &["POSITION names accessor 9", "only 2 accessors"],
    );
    let draco = tetra_json(Some("")).replacen('{', r#"{"extensionsRequired":["KHR_draco_mesh_compression"],"extensionsUsed":["KHR_draco_mesh_compression"],"#, 1);
    refused(
        "draco.gltf",
        draco.as_bytes(),
        &["KHR_draco_mesh_compression", "Draco"],
    );
}

#[test]
fn gltf_accessors_outside_their_data() {
    let json =
        tetra_json(Some("")).replace(r#""count":4,"type":"VEC3""#, r#""count":40,"type":"VEC3""#);
    refused(
        "long.gltf",
        &json.into_bytes(),
        &["accessor 0", "do not fit in its buffer view"],
    );
    let json = tetra_json(Some("")).replace(
        r#""byteOffset":0,"byteLength":48"#,
        r#""byteOffset":0,"byteLength":4800"#,
    );
    refused(
        "view.gltf",
        &json.into_bytes(),
        &["buffer view 0 reaches past the end of buffer 0"],
    );
    let json = tetra_json(Some("")).replace(r#""componentType":5123"#, r#""componentType":5126"#);
    refused(
        "floats.gltf",
        &json.into_bytes(),
        &["indices as Scalar of F32"],
    );
}

#[test]
fn gltf_index_past_the_vertices() {
    let (mut buffer, _) = tetra_buffer();
    let ix = buffer.indices(&[0, 1, 9], 4);
    let meshes = format!(
        r#"{{"name":"tet","primitives":[{{"attributes":{{"POSITION":0}},"indices":{ix}}}]}}"#
    );
    let json = buffer.json(&meshes, r#"{"mesh":0}"#, r#"{"nodes":[0]}"#, Some(""));
    refused(
        "index.gltf",
        json.as_bytes(),
        &[
            "mesh 0 (`tet`) primitive 0",
            "names vertex 9",
            "only 4 vertices",
        ],
    );
}

#[test]
fn gltf_with_nan_and_with_a_transform_that_overflows() {
    let mut buffer = GltfBuffer::default();
    let at = buffer.positions(&[Vec3::ZERO, Vec3::X, Vec3::new(0.0, f32::NAN, 0.0)]);
    let meshes = format!(r#"{{"primitives":[{{"attributes":{{"POSITION":{at}}}}}]}}"#);
    let json = buffer.json(&meshes, r#"{"mesh":0}"#, r#"{"nodes":[0]}"#, Some(""));
    let error = refused(
        "nan.gltf",
        json.as_bytes(),
        &["vertex 2 of mesh 0 primitive 0", "not a finite number"],
    );
    assert!(matches!(
        error,
        LoadError::NonFinite {
            format: Format::Gltf,
            ..
        }
    ));
    let json = buffer.json(&meshes, r#"{"mesh":0}"#, r#"{"nodes":[0]}"#, None);
    let error = refused(
        "nan.glb",
        &support::glb(&json, &buffer.bytes),
        &["vertex 2 of mesh 0 primitive 0", "not a finite number"],
    );
    assert!(matches!(
        error,
        LoadError::NonFinite {
            format: Format::Glb,
            ..
        }
    ));
    let huge = tetra_json(Some("")).replace(
        r#"{"mesh":0}"#,
        r#"{"mesh":0,"scale":[1e38,1e38,1e38],"translation":[3e38,0,0]}"#,
    );
    refused(
        "huge.gltf",
        huge.as_bytes(),
        &["vertex 1 of mesh 0 (`tet`) primitive 0, once its nodes' transforms are applied"],
    );
}

#[test]
fn gltf_of_lines_only_has_no_triangles() {
    let json = tetra_json(Some("")).replace(r#""indices":1"#, r#""indices":1,"mode":1"#);
    let error = refused(
        "lines.gltf",
        json.as_bytes(),
        &["has no triangles (read as glTF)"],
    );
    assert!(matches!(
        error,
        LoadError::NoTriangles {
            format: Format::Gltf,
            ..
        }
    ));
}

// ---- OBJ ----

#[test]
fn obj_faults_keep_the_core_readers_line_and_face() {
    let error = refused(
        "bad.obj",
        b"v 0 0 0\nv 1 0 0\nf 1 2 3\n",
        &["line 3 (face 1)", "refers past the last vertex"],
    );
    assert!(matches!(error, LoadError::Obj { .. }));
    refused(
        "nan.obj",
        b"v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n",
        &["line 2 (vertex 2)", "not a finite"],
    );
    refused(
        "empty.obj",
        b"# nothing but a comment\nv 0 0 0\n",
        &["has no triangles"],
    );
}

// ---- never a panic ----

/// Valid files of every format and encoding.
fn valid_files() -> Vec<(&'static str, Vec<u8>)> {
    let mesh = builtin::torus(6, 4, 0.3);
    let triangles: &[Triangle3] = mesh.triangles();
    let faces = support::faces_of(&mesh);
    let mut obj = String::new();
    for p in mesh.positions() {
        let _ = writeln!(obj, "v {} {} {}", p.x, p.y, p.z);
    }
    for [a, b, c] in mesh.indices() {
        let _ = writeln!(obj, "f {} {} {}", a + 1, b + 1, c + 1);
    }
    vec![
        ("m.obj", obj.into_bytes()),
        (
            "m.ply",
            support::ply(mesh.positions(), &faces, &PlyStyle::plain(Encoding::Ascii)),
        ),
        (
            "m.ply",
            support::ply(mesh.positions(), &faces, &PlyStyle::plain(Encoding::Little)),
        ),
        (
            "m.ply",
            support::ply(mesh.positions(), &faces, &PlyStyle::plain(Encoding::Big)),
        ),
        ("m.stl", support::stl_binary(triangles, b"solid but binary")),
        ("m.stl", support::stl_ascii(&[triangles])),
        ("m.gltf", tetra_json(Some("")).into_bytes()),
        ("m.glb", tetra_glb()),
    ]
}

#[test]
fn cut_off_files_never_panic() {
    for (name, bytes) in valid_files() {
        assert!(load(name, &bytes).is_ok(), "{name} is valid");
        for cut in 0..bytes.len() {
            // Ok is possible (a cut at a line end of a text format); a panic is not.
            let _ = load(name, &bytes[..cut]);
        }
    }
}

/// Bytes that keep a text file looking like its format while breaking it.
const TOKENS: &[u8] = b"0123456789-.e \n{}[]\",:";

#[test]
fn files_with_changed_bytes_never_panic() {
    let mut rng = ChaCha8Rng::seed_from_u64(2504);
    for (name, bytes) in valid_files() {
        for _ in 0..rounds() {
            let mut mutated = bytes.clone();
            for _ in 0..=rng.next_u32() % 4 {
                let at = rng.next_u32() as usize % mutated.len();
                mutated[at] = match rng.next_u32() % 3 {
                    0 => rng.next_u32() as u8,
                    1 => mutated[at] ^ (1 << (rng.next_u32() % 8)),
                    _ => TOKENS[rng.next_u32() as usize % TOKENS.len()],
                };
            }
            if let Err(error) = load(name, &mutated) {
                assert!(error.to_string().starts_with(name));
            }
        }
    }
}

#[test]
fn gltf_with_any_number_changed_never_panics() {
    // Every number of the JSON (indices, counts, offsets, types, modes, bounds) set in turn
    // to values that point past arrays, overflow, or name other types.
    const VALUES: [&str; 17] = [
        "0",
        "1",
        "2",
        "3",
        "5",
        "7",
        "9",
        "100",
        "-1",
        "4294967295",
        "18446744073709551615",
        "1e30",
        "5121",
        "5123",
        "5126",
        "34963",
        "0.5",
    ];
    let (buffer, meshes) = tetra_buffer();
    let nodes = r#"{"mesh":0,"children":[1]},{"mesh":0,"scale":[-1,1,1]}"#;
    let json = buffer.json(&meshes, nodes, r#"{"nodes":[0]}"#, None);
    let numbers: Vec<(usize, usize)> = json
        .char_indices()
        .filter(|&(i, c)| {
            c.is_ascii_digit()
                && !json[..i].ends_with(|p: char| p.is_ascii_alphanumeric() || p == '.')
        })
        .map(|(start, _)| {
            let len = json[start..]
                .find(|c: char| !(c.is_ascii_digit() || c == '.'))
                .unwrap_or(0);
            (start, len)
        })
        .collect();
    assert!(numbers.len() > 30, "{} numbers", numbers.len());
    for &(start, len) in &numbers {
        for value in VALUES {
            let changed = format!("{}{value}{}", &json[..start], &json[start + len..]);
            let _ = load("n.glb", &support::glb(&changed, &buffer.bytes));
        }
    }
}

/// Mutations per valid file: 1500, or `MESHIO_FUZZ_ROUNDS` for a longer search.
fn rounds() -> usize {
    std::env::var("MESHIO_FUZZ_ROUNDS")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(1500)
}
