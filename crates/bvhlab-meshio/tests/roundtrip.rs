//! Every format, written by the tests' own writers (`support`) and read back by `load`, gives
//! the triangles it was written from: in every PLY encoding and header style, binary and
//! ASCII STL (one solid or several, the `solid` header trap), and glTF as JSON and as GLB with
//! a tree of node transforms, instancing, mirroring, strips, fans, and every index type.

use crate::support;

use std::fmt::Write as _;

use bvhlab::glam::{Mat4, Quat, Vec3};
use bvhlab::{Mesh, Triangle3};
use bvhlab_meshio::{Format, builtin, load};
use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::{Rng, SeedableRng};
use support::{Encoding, GltfBuffer, PlyStyle};

/// A random triangle mesh with awkward coordinates (many digits, tiny and large, −0) and a
/// few repeated corners, so zero-area triangles come along.
fn random_mesh(seed: u64) -> Mesh {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut unit = || (rng.next_u32() >> 8) as f32 / (1u32 << 24) as f32;
    let mut positions: Vec<Vec3> = (0..60)
        .map(|_| Vec3::new(unit() - 0.5, unit() * 1e4, (unit() - 0.5) * 1e-6))
        .collect();
    positions[3] = Vec3::new(-0.0, 0.0, -0.0);
    let mut rng = ChaCha8Rng::seed_from_u64(seed + 1);
    let indices = (0..100)
        .map(|k| {
            let mut i = || rng.next_u32() % 60;
            if k % 25 == 0 {
                let a = i();
                [a, a, i()]
            } else {
                [i(), i(), i()]
            }
        })
        .collect();
    Mesh::from_indexed(positions, indices).expect("valid")
}

#[test]
fn obj_is_read_by_the_core_reader() {
    let text = b"# a quad and a triangle\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nf 1 2 3 4\nf 1 5 2\n";
    let loaded = load("quad.obj", text).expect("valid OBJ");
    assert_eq!(loaded.format, Format::Obj);
    assert_eq!(loaded.mesh, Mesh::from_obj(text).expect("valid OBJ"));
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
}

#[test]
fn ply_in_every_encoding_and_header_style() {
    let mesh = random_mesh(1);
    let faces = support::faces_of(&mesh);
    for encoding in [Encoding::Ascii, Encoding::Little, Encoding::Big] {
        let plain = PlyStyle::plain(encoding);
        let unusual = PlyStyle {
            encoding,
            coordinate: "double",
            count: "ushort",
            index: "uint",
            list_name: "vertex_index",
            extras: true,
        };
        let short = PlyStyle {
            count: "int",
            index: "ushort",
            ..PlyStyle::plain(encoding)
        };
        for style in [plain, unusual, short] {
            let bytes = support::ply(mesh.positions(), &faces, &style);
            let loaded = load("mesh.ply", &bytes).unwrap_or_else(|e| panic!("{style:?}: {e}"));
            assert_eq!(loaded.format, Format::Ply);
            assert_eq!(loaded.mesh.positions(), mesh.positions(), "{style:?}");
            assert_eq!(loaded.mesh.indices(), mesh.indices(), "{style:?}");
            // The only warning is the zero-area count.
            assert_eq!(loaded.warnings.len(), 1, "{:?}", loaded.warnings);
            assert!(
                loaded.warnings[0].contains("zero area"),
                "{:?}",
                loaded.warnings
            );
        }
    }
}

#[test]
fn ply_polygons_are_fans_like_the_obj_reader_cuts_convex_faces() {
    // A cube of quads, plus a convex pentagon: the core's ear clipping cuts convex faces as
    // the fan from their first corner, so both readers must agree.
    let cube = builtin::cube();
    let mut positions = cube.positions().to_vec();
    positions.extend((0..5).map(|k| {
        let (s, c) = (std::f32::consts::TAU * k as f32 / 5.0).sin_cos();
        Vec3::new(3.0 + c, s, 0.5)
    }));
    let faces: Vec<Vec<i64>> = vec![
        vec![0, 4, 6, 2],
        vec![1, 3, 7, 5],
        vec![0, 1, 5, 4],
        vec![2, 6, 7, 3],
        vec![0, 2, 3, 1],
        vec![4, 5, 7, 6],
        vec![8, 9, 10, 11, 12],
    ];
    let mut obj = String::new();
    for p in &positions {
        let _ = writeln!(obj, "v {:?} {:?} {:?}", p.x, p.y, p.z);
    }
    for face in &faces {
        let corners: Vec<String> = face.iter().map(|i| (i + 1).to_string()).collect();
        let _ = writeln!(obj, "f {}", corners.join(" "));
    }
    let reference = Mesh::from_obj(obj.as_bytes()).expect("valid OBJ");
    for encoding in [Encoding::Ascii, Encoding::Little, Encoding::Big] {
        let bytes = support::ply(&positions, &faces, &PlyStyle::plain(encoding));
        let loaded = load("polygons.ply", &bytes).expect("valid PLY");
        assert_eq!(loaded.mesh.len(), 6 * 2 + 3);
        assert!(support::same_triangles(&loaded.mesh, &reference));
        assert!(
            loaded.warnings.iter().any(|w| w.contains("7 faces")),
            "{:?}",
            loaded.warnings
        );
    }
}

/// How many distinct corner positions the triangles have (what welding must find).
fn distinct_corners(triangles: &[Triangle3]) -> usize {
    let mut corners: Vec<[u32; 3]> = triangles
        .iter()
        .flat_map(|t| [t.a, t.b, t.c])
        .map(|p| (p + Vec3::ZERO).to_array().map(f32::to_bits))
        .collect();
    corners.sort_unstable();
    corners.dedup();
    corners.len()
}

#[test]
fn stl_binary_and_ascii_give_back_the_triangles_welded() {
    for mesh in [builtin::torus(24, 12, 0.4), random_mesh(2)] {
        let triangles = mesh.triangles();
        let files = [
            (
                "plain.stl",
                support::stl_binary(triangles, b"binary STL from the tests"),
            ),
            // A binary header that starts like an ASCII file: the size decides.
            (
                "trap.stl",
                support::stl_binary(triangles, b"solid trap, yet binary"),
            ),
            ("ascii.stl", support::stl_ascii(&[triangles])),
            (
                "two.stl",
                support::stl_ascii(&[&triangles[..10], &triangles[10..]]),
            ),
        ];
        for (name, bytes) in files {
            let loaded = load(name, &bytes).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(loaded.format, Format::Stl);
            assert!(support::same_triangles(&loaded.mesh, &mesh), "{name}");
            assert_eq!(
                loaded.mesh.positions().len(),
                distinct_corners(triangles),
                "{name}"
            );
        }
    }
}

#[test]
fn ascii_stl_without_a_solid_name_and_with_windows_line_ends() {
    let mesh = builtin::cube();
    let text = String::from_utf8(support::stl_ascii(&[mesh.triangles()])).expect("text");
    let nameless = text
        .replacen("solid part0", "solid", 1)
        .replace('\n', "\r\n");
    let loaded = load("cube.stl", nameless.as_bytes()).expect("valid ASCII STL");
    assert!(support::same_triangles(&loaded.mesh, &mesh));
}

/// A regular-ish tetrahedron, wound outward.
fn tetrahedron() -> (Vec<Vec3>, Vec<u32>) {
    let positions = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
    (positions, vec![0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3])
}

/// The triangles of `positions` drawn with `indices` in glTF `mode` (4: triangles, 5: strip,
/// 6: fan), as the specification's section 3.7.2.1 lists them.
fn primitive_triangles(positions: &[Vec3], indices: &[u32], mode: u32) -> Vec<[Vec3; 3]> {
    let p = |i: u32| positions[i as usize];
    let n = indices.len();
    match mode {
        4 => indices
            .chunks(3)
            .map(|t| [p(t[0]), p(t[1]), p(t[2])])
            .collect(),
        5 => (0..n - 2)
            .map(|i| {
                let (b, c) = (i + 1 + i % 2, i + 2 - i % 2);
                [p(indices[i]), p(indices[b]), p(indices[c])]
            })
            .collect(),
        _ => (0..n - 2)
            .map(|i| [p(indices[i + 1]), p(indices[i + 2]), p(indices[0])])
            .collect(),
    }
}

/// Whether the loaded triangles are `expected`, in order, within `1e-5` (the reader composes
/// transforms in `f64` from the file's decomposition, the test in `f32`).
fn assert_close(loaded: &Mesh, expected: &[[Vec3; 3]]) {
    assert_eq!(loaded.len(), expected.len());
    for (k, (t, e)) in loaded.triangles().iter().zip(expected).enumerate() {
        for (got, want) in [t.a, t.b, t.c].iter().zip(e) {
            assert!(
                got.abs_diff_eq(*want, 1e-5),
                "triangle {k}: {got} is not {want}"
            );
        }
    }
}

/// The test scene: node 0 (translated, turned, scaled) holds mesh 0, a tetrahedron with u16
/// indices, and has child node 1 (a matrix) with mesh 1: a non-indexed pair of triangles, a
/// strip (u8 indices), a fan (u32 indices) and a line list. Node 2 holds mesh 0 again,
/// mirrored in x. The scene's roots are nodes 0 and 2.
fn scene() -> (GltfBuffer, String, String, String, Vec<[Vec3; 3]>) {
    let mut buffer = GltfBuffer::default();
    let (tet, tet_indices) = tetrahedron();
    let tet_at = buffer.positions(&tet);
    let tet_ix = buffer.indices(&tet_indices, 2);
    let pair: Vec<Vec3> = (0..6)
        .map(|k| Vec3::new(k as f32, (k % 3) as f32, 0.5))
        .collect();
    let pair_at = buffer.positions(&pair);
    let strip: Vec<Vec3> = (0..5)
        .map(|k| Vec3::new((k / 2) as f32, (k % 2) as f32, 1.0))
        .collect();
    let strip_at = buffer.positions(&strip);
    let strip_ix = buffer.indices(&[0, 1, 2, 3, 4], 1);
    let fan = vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
    let fan_at = buffer.positions(&fan);
    let fan_ix = buffer.indices(&[0, 1, 2, 3], 4);
    let meshes = format!(
        r#"{{"name":"tet","primitives":[{{"attributes":{{"POSITION":{tet_at}}},"indices":{tet_ix}}}]}},
{{"primitives":[{{"attributes":{{"POSITION":{pair_at}}}}},
{{"attributes":{{"POSITION":{strip_at}}},"indices":{strip_ix},"mode":5}},
{{"attributes":{{"POSITION":{fan_at}}},"indices":{fan_ix},"mode":6}},
{{"attributes":{{"POSITION":{pair_at}}},"mode":1}}]}}"#
    );
    let turn = Quat::from_rotation_z(std::f32::consts::FRAC_PI_2);
    let child = Mat4::from_scale_rotation_translation(
        Vec3::new(1.0, 0.5, 3.0),
        Quat::IDENTITY,
        Vec3::new(-4.0, 0.0, 1.0),
    );
    let columns: Vec<String> = child
        .to_cols_array()
        .iter()
        .map(|x| format!("{x:?}"))
        .collect();
    let nodes = format!(
        r#"{{"mesh":0,"children":[1],"translation":[1,2,3],"rotation":[{:?},{:?},{:?},{:?}],"scale":[2,2,2]}},
{{"mesh":1,"matrix":[{}]}},
{{"mesh":0,"scale":[-1,1,1]}}"#,
        turn.x,
        turn.y,
        turn.z,
        turn.w,
        columns.join(",")
    );
    let scenes = r#"{"nodes":[0,2]}"#.to_owned();

    let parent =
        Mat4::from_scale_rotation_translation(Vec3::splat(2.0), turn, Vec3::new(1.0, 2.0, 3.0));
    let placed = |m: Mat4, ts: Vec<[Vec3; 3]>| -> Vec<[Vec3; 3]> {
        ts.into_iter()
            .map(|t| t.map(|p| m.transform_point3(p)))
            .collect()
    };
    let mut expected = placed(parent, primitive_triangles(&tet, &tet_indices, 4));
    let child_world = parent * child;
    expected.extend(placed(
        child_world,
        primitive_triangles(&pair, &[0, 1, 2, 3, 4, 5], 4),
    ));
    expected.extend(placed(
        child_world,
        primitive_triangles(&strip, &[0, 1, 2, 3, 4], 5),
    ));
    expected.extend(placed(
        child_world,
        primitive_triangles(&fan, &[0, 1, 2, 3], 6),
    ));
    // Mirrored: the reader turns the winding back, so each triangle's last two corners swap.
    let mirror = Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0));
    expected.extend(
        placed(mirror, primitive_triangles(&tet, &tet_indices, 4))
            .into_iter()
            .map(|[a, b, c]| [a, c, b]),
    );
    (buffer, meshes, nodes, scenes, expected)
}

#[test]
fn gltf_and_glb_place_every_mesh_by_its_nodes() {
    let (buffer, meshes, nodes, scenes, expected) = scene();
    let embedded = buffer.json(&meshes, &nodes, &scenes, Some(""));
    let binary = support::glb(&buffer.json(&meshes, &nodes, &scenes, None), &buffer.bytes);
    for (name, bytes, format) in [
        ("scene.gltf", embedded.into_bytes(), Format::Gltf),
        ("scene.glb", binary, Format::Glb),
    ] {
        let loaded = load(name, &bytes).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(loaded.format, format);
        assert_close(&loaded.mesh, &expected);
        let skipped: Vec<_> = loaded
            .warnings
            .iter()
            .filter(|w| w.contains("Lines"))
            .collect();
        assert_eq!(skipped.len(), 1, "{:?}", loaded.warnings);
    }
}

#[test]
fn a_mirrored_tetrahedron_stays_wound_outward() {
    // The signed volume of a closed mesh is positive when its faces wind counter-clockwise
    // seen from outside; mirroring must not change that.
    let (buffer, meshes, nodes, _, _) = scene();
    let json = buffer.json(&meshes, &nodes, r#"{"nodes":[2]}"#, Some(""));
    let loaded = load("mirror.gltf", json.as_bytes()).expect("valid glTF");
    let volume: f32 = loaded
        .mesh
        .triangles()
        .iter()
        .map(|t| t.a.dot(t.b.cross(t.c)) / 6.0)
        .sum();
    assert!((volume - 1.0 / 6.0).abs() < 1e-6, "volume {volume}");
}

#[test]
fn gltf_without_a_scene_reads_each_mesh_once() {
    let (buffer, meshes, _, _, _) = scene();
    let json = buffer
        .json(&meshes, "", "", Some(""))
        .replace(r#""scene":0,"#, "");
    let json = json.replace(r#""scenes":[],"nodes":[],"#, "");
    let loaded = load("flat.gltf", json.as_bytes()).expect("valid glTF");
    let (tet, tet_indices) = tetrahedron();
    assert_eq!(loaded.mesh.len(), 4 + 2 + 3 + 2);
    assert_close(
        &Mesh::from_indexed(
            loaded.mesh.positions().to_vec(),
            loaded.mesh.indices()[..4].to_vec(),
        )
        .expect("valid"),
        &primitive_triangles(&tet, &tet_indices, 4),
    );
    assert!(
        loaded.warnings.iter().any(|w| w.contains("no scene")),
        "{:?}",
        loaded.warnings
    );
}

#[test]
fn a_sparse_accessor_replaces_the_listed_positions() {
    let mut buffer = GltfBuffer::default();
    let (tet, tet_indices) = tetrahedron();
    let base = buffer.positions(&tet);
    let moved = [Vec3::new(0.0, 0.0, 5.0)];
    buffer.positions(&moved);
    buffer.indices(&[3], 4);
    let ix = buffer.indices(&tet_indices, 4);
    // Accessor `base` again, with vertex 3 replaced through the sparse section.
    let sparse = buffer.accessors[base].replacen(
        '}',
        r#","sparse":{"count":1,"indices":{"bufferView":2,"componentType":5125},"values":{"bufferView":1}}}"#,
        1,
    );
    buffer.accessors.push(sparse);
    let accessor = buffer.accessors.len() - 1;
    let meshes =
        format!(r#"{{"primitives":[{{"attributes":{{"POSITION":{accessor}}},"indices":{ix}}}]}}"#);
    let json = buffer.json(&meshes, r#"{"mesh":0}"#, r#"{"nodes":[0]}"#, Some(""));
    let loaded = load("sparse.gltf", json.as_bytes()).expect("valid glTF");
    let mut expected = tet.clone();
    expected[3] = moved[0];
    assert_close(
        &loaded.mesh,
        &primitive_triangles(&expected, &tet_indices, 4),
    );
}

#[test]
fn content_wins_over_a_wrong_name_with_a_warning() {
    let mesh = builtin::cube();
    let ply = support::ply(
        mesh.positions(),
        &support::faces_of(&mesh),
        &PlyStyle::plain(Encoding::Little),
    );
    let stl = support::stl_binary(mesh.triangles(), b"");
    for (name, bytes, format) in [
        ("cube.stl", ply, Format::Ply),
        ("cube.obj", stl, Format::Stl),
    ] {
        let loaded = load(name, &bytes).expect("valid");
        assert_eq!(loaded.format, format);
        assert!(support::same_triangles(&loaded.mesh, &mesh));
        assert_eq!(loaded.warnings.len(), 1, "{:?}", loaded.warnings);
        assert!(loaded.warnings[0].contains(name) && loaded.warnings[0].contains(format.label()));
    }
    // No extension at all: the content alone.
    let loaded = load("download", &support::stl_ascii(&[mesh.triangles()])).expect("valid");
    assert_eq!((loaded.format, loaded.warnings.len()), (Format::Stl, 0));
}

#[test]
fn zero_area_triangles_are_kept_and_counted() {
    let t = |a: Vec3, b: Vec3, c: Vec3| Triangle3::new(a, b, c);
    let triangles = [
        t(Vec3::ZERO, Vec3::X, Vec3::Y),
        t(Vec3::ZERO, Vec3::X, Vec3::new(2.0, 0.0, 0.0)),
        t(Vec3::Y, Vec3::Y, Vec3::Z),
    ];
    let loaded = load("slivers.stl", &support::stl_binary(&triangles, b"")).expect("valid");
    assert_eq!(loaded.mesh.len(), 3);
    assert_eq!(
        loaded.warnings,
        [
            "slivers.stl: 2 of its 3 triangles have zero area (kept: the structures must cope with them)"
        ]
    );
}
