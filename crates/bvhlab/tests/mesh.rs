//! `Mesh::from_obj` on the real meshes of the course (triangle counts from their README, and
//! the triangles themselves against a naive reading of the triangle-only files), on the OBJ
//! features the reader supports, and on broken files, which must give errors that say where.

use std::fmt::Write;
use std::path::PathBuf;
use std::time::Instant;

use bvhlab::glam::Vec3;
use bvhlab::mesh::{IndexProblem, Mesh, MeshError};
use bvhlab::prelude::*;

/// `(file, triangles after triangulation)` as `shared/data/meshes/README.md` lists them.
const MESHES: [(&str, usize); 7] = [
    ("suzanne.obj", 968),
    ("spot.obj", 5856),
    ("teapot.obj", 6320),
    ("fandisk.obj", 12946),
    ("stanford-bunny.obj", 69451),
    ("dragon.obj", 100_000),
    ("ogre.obj", 124_008),
];

fn mesh_dir() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/meshes");
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!("skipped: no mesh folder at {}", dir.display());
        None
    }
}

/// The triangles of a triangle-only OBJ file, read the naive way: `v` and `f` lines only.
fn naive_triangles(text: &str) -> Vec<Triangle3> {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let xyz: Vec<f32> = words.take(3).map(|w| w.parse().expect("number")).collect();
                positions.push(Vec3::new(xyz[0], xyz[1], xyz[2]));
            }
            Some("f") => {
                let corner = |w: &str| {
                    let i: usize = w
                        .split('/')
                        .next()
                        .expect("index")
                        .parse()
                        .expect("integer");
                    positions[i - 1]
                };
                let c: Vec<Vec3> = words.map(corner).collect();
                assert_eq!(c.len(), 3, "not a triangle-only file");
                triangles.push(Triangle3::new(c[0], c[1], c[2]));
            }
            _ => {}
        }
    }
    triangles
}

#[test]
fn every_course_mesh_loads_with_its_triangle_count() {
    let Some(dir) = mesh_dir() else { return };
    for (name, count) in MESHES {
        let bytes = std::fs::read(dir.join(name)).expect("readable mesh");
        let start = Instant::now();
        let mesh = Mesh::from_obj(&bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
        let elapsed = start.elapsed();
        let stats = mesh.summary();
        eprintln!("{name}: {stats}, loaded in {elapsed:.2?}");
        assert_eq!(mesh.len(), count, "{name}");
        assert_eq!(stats.triangles, count);
        assert!(!stats.bounds.is_empty());
        let n = mesh.positions().len() as u32;
        assert!(mesh.indices().iter().flatten().all(|&i| i < n));
        for (t, [a, b, c]) in mesh.triangles().iter().zip(mesh.indices()) {
            let p = |i: u32| mesh.positions()[i as usize];
            assert_eq!(*t, Triangle3::new(p(*a), p(*b), p(*c)));
            assert!(stats.bounds.contains(t.a) && stats.bounds.contains(t.b));
        }
        if name == "suzanne.obj" {
            assert_eq!(stats.faces, 500);
        } else {
            assert_eq!(stats.faces, count);
            let text = std::str::from_utf8(&bytes).expect("text");
            assert!(mesh.triangles() == naive_triangles(text), "{name}");
        }
    }
}

#[test]
fn supported_obj_features() {
    let text = "# a comment\r\n\
                mtllib missing.mtl\r\n\
                o thing\n\
                v 0 0 0 1\n\
                v 1.0 0 0 0.5 0.5 0.5   # colour\n\
                \tv 1 1 0\n\
                v 0 1e0 0\n\
                vt 0 0\nvn 0 0 1\n\
                usemtl stone\ng körper\ns 1\n\
                f 1/1/1 2/1/1 3/1/1\n\
                f -4//1 -2//1 -1//1\n\
                l 1 2\np 3\n\
                f 1/1 2/1 3/1 4/1\n";
    let mesh = Mesh::from_obj(text.as_bytes()).expect("valid OBJ");
    assert_eq!(
        mesh.indices(),
        &[[0, 1, 2], [0, 2, 3], [0, 1, 2], [0, 2, 3]][..]
    );
    assert_eq!(mesh.summary().faces, 3);
    assert_eq!(
        mesh.bounds(),
        Aabb3::new(Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0))
    );
    // A Latin-1 comment is not UTF-8, but nothing reads it.
    let latin1 = b"# \xa9 guruware\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    assert_eq!(Mesh::from_obj(latin1).expect("valid").len(), 1);
    // Forward references: faces before their vertices.
    let forward = Mesh::from_obj(b"f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").expect("valid");
    assert_eq!(forward.len(), 1);
}

#[test]
fn polygons_are_ear_clipped_keeping_their_winding() {
    // A concave "L" hexagon, counter-clockwise seen from +z.
    let l = "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nf 1 2 3 4 5 6\n";
    let mesh = Mesh::from_obj(l.as_bytes()).expect("valid");
    assert_eq!(mesh.len(), 4);
    let area: f32 = mesh.triangles().iter().map(|t| t.normal().z / 2.0).sum();
    assert!(mesh.triangles().iter().all(|t| t.normal().z > 0.0));
    assert_eq!(area, 3.0);
    // A 300-gon (beyond ear clipping's budget) is fanned: still n − 2 triangles.
    let mut big = String::new();
    for i in 0..300 {
        let a = i as f32 / 300.0 * std::f32::consts::TAU;
        writeln!(big, "v {} {} 0", a.cos(), a.sin()).expect("writing to a String");
    }
    big.push('f');
    for i in 1..=300 {
        write!(big, " {i}").expect("writing to a String");
    }
    assert_eq!(Mesh::from_obj(big.as_bytes()).expect("valid").len(), 298);
}

#[test]
fn empty_input_gives_an_empty_mesh() {
    for text in [
        "",
        "\n\n",
        "# only a comment\n",
        "v 1 2 3\n",
        "g nothing\nvn 0 0 1\n",
    ] {
        let mesh = Mesh::from_obj(text.as_bytes()).expect("no faces is not an error");
        assert!(mesh.is_empty() && mesh.triangles().is_empty());
        assert_eq!(mesh.bounds(), Aabb3::EMPTY);
        assert_eq!(mesh.summary().triangles, 0);
    }
}

#[test]
fn zero_area_triangles_are_kept_and_counted() {
    let text = "v 0 0 0\nv 1 1 1\nv 2 2 2\nv 0 1 0\nf 1 2 3\nf 1 2 4\nf 1 1 1\n";
    let stats = Mesh::from_obj(text.as_bytes()).expect("valid").summary();
    assert_eq!((stats.triangles, stats.degenerate_triangles), (3, 2));
    assert_eq!(
        stats.to_string(),
        "4 vertices, 3 faces, 3 triangles (2 of zero area)"
    );
}

fn is_error<E: std::error::Error>(_: &E) {}

const TRI: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

fn error(text: &str) -> MeshError {
    error_bytes(text.as_bytes())
}

fn error_bytes(bytes: &[u8]) -> MeshError {
    let e = Mesh::from_obj(bytes).expect_err("must be refused");
    // Every error says where.
    assert!(e.to_string().starts_with("line "), "{e}");
    e
}

fn index_problem(text: &str) -> (usize, usize, String, IndexProblem) {
    match error(text) {
        MeshError::BadIndex {
            line,
            face,
            token,
            problem,
        } => (line, face, token, problem),
        other => panic!("{other:?}"),
    }
}

#[test]
fn bad_indices_are_refused_with_line_face_and_reason() {
    let text = format!("{TRI}f 1 2 3\nf 1 2 4\n");
    let past = (5, 2, "4".into(), IndexProblem::PastEnd { vertices: 3 });
    assert_eq!(index_problem(&text), past);
    let text = format!("{TRI}f 0 1 2\n");
    assert_eq!(index_problem(&text), (4, 1, "0".into(), IndexProblem::Zero));
    let text = format!("{TRI}f -1 -2 -4\n");
    let before = (
        4,
        1,
        "-4".into(),
        IndexProblem::BeforeStart { preceding: 3 },
    );
    assert_eq!(index_problem(&text), before);
    // Relative indices count the vertices before the face, not all of them.
    let text = format!("v 0 0 0\nf -1 -2 -3\n{TRI}");
    let early = (
        2,
        1,
        "-2".into(),
        IndexProblem::BeforeStart { preceding: 1 },
    );
    assert_eq!(index_problem(&text), early);
    for corner in ["1.5", "x", "1/x", "1/2/3/4", "/1", "99999999999999999999"] {
        let text = format!("{TRI}f {corner} 2 3\n");
        assert_eq!(index_problem(&text).3, IndexProblem::Malformed, "{corner}");
    }
    let text = format!("{TRI}f 4294967297 2 3\n");
    assert_eq!(
        index_problem(&text).3,
        IndexProblem::PastEnd { vertices: 3 }
    );
    let message = error(&format!("{TRI}f 0 1 2\n")).to_string();
    assert!(
        message.contains("face 1") && message.contains("start at 1"),
        "{message}"
    );
}

#[test]
fn bad_vertices_and_faces_are_refused_with_their_line() {
    for (text, expected) in [
        (
            "v 1 2\n",
            MeshError::MissingCoordinates { line: 1, found: 2 },
        ),
        ("v\n", MeshError::MissingCoordinates { line: 1, found: 0 }),
        (
            "v 0 0 0\nv 1 abc 3\n",
            MeshError::BadNumber {
                line: 2,
                token: "abc".into(),
            },
        ),
        (
            "v 0 0 0\nv nan 0 0\n",
            MeshError::NonFinite {
                line: 2,
                vertex: 2,
                token: "nan".into(),
            },
        ),
        (
            "v 0 -inf 0\n",
            MeshError::NonFinite {
                line: 1,
                vertex: 1,
                token: "-inf".into(),
            },
        ),
        (
            "v 0 0 1e39\n",
            MeshError::NonFinite {
                line: 1,
                vertex: 1,
                token: "1e39".into(),
            },
        ),
        (
            "v 0 0 0\nf 1 1\n",
            MeshError::TooFewCorners {
                line: 2,
                face: 1,
                found: 2,
            },
        ),
        (
            "v 0 0 0\nf\n",
            MeshError::TooFewCorners {
                line: 2,
                face: 1,
                found: 0,
            },
        ),
        (
            "v 0 0 0\nv 1\x000 0\n",
            MeshError::NotText { line: 2, column: 4 },
        ),
    ] {
        assert_eq!(error(text), expected, "{text:?}");
    }
    let not_utf8 = error_bytes(b"v 0 0 0\nv 1 \xff 0\n");
    assert_eq!(not_utf8, MeshError::NotText { line: 2, column: 5 });
    let message = error("v 0 nan 0\n").to_string();
    assert!(
        message.contains("vertex 1") && message.contains("finite"),
        "{message}"
    );
    is_error(&error("v 1 2\n"));
}

#[test]
fn binary_and_truncated_files_are_refused_or_read_as_far_as_they_are_whole() {
    // A binary STL starts with an 80-byte header, then a count and packed floats: NULs.
    let mut stl = vec![b'x'; 80];
    stl.extend_from_slice(&1u32.to_le_bytes());
    stl.extend((0..50).map(|i| (i * 7 % 256) as u8));
    assert!(matches!(
        error_bytes(&stl),
        MeshError::NotText { line: 1, .. }
    ));
    // A file cut inside a face line.
    let cut = format!("{TRI}f 1 2 3\nf 1 2");
    assert_eq!(
        error(&cut),
        MeshError::TooFewCorners {
            line: 5,
            face: 2,
            found: 2
        }
    );
    // Cut inside a multi-byte character of a vertex line.
    let mut bytes = format!("{TRI}v 1 2 3").into_bytes();
    bytes.extend_from_slice(&"é".as_bytes()[..1]);
    assert!(matches!(
        error_bytes(&bytes),
        MeshError::NotText { line: 4, column: 8 }
    ));
    // Every prefix of a real file loads or fails cleanly.
    let Some(dir) = mesh_dir() else { return };
    let bytes = std::fs::read(dir.join("suzanne.obj")).expect("readable mesh");
    for end in (0..bytes.len()).step_by(997) {
        let _ = Mesh::from_obj(&bytes[..end]);
    }
}
