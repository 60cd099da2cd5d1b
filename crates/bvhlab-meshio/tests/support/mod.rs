//! Writers of every format the crate reads, written here from the formats' specifications and
//! independent of the crate, so a round trip tests the reader against a second reading of the
//! specification; and a comparison of triangle sets.

#![allow(dead_code, reason = "each test file uses a different part")]

use std::fmt::Write as _;
use std::path::PathBuf;

use base64::Engine;
use bvhlab::glam::Vec3;
use bvhlab::{Mesh, Triangle3};

/// A PLY file's data encoding.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Encoding {
    Ascii,
    Little,
    Big,
}

/// How a PLY file is written: the header's types and names, and extras a reader must skip.
#[derive(Clone, Debug)]
pub struct PlyStyle {
    pub encoding: Encoding,
    /// `float` or `double`.
    pub coordinate: &'static str,
    /// The list's count type: `uchar`, `ushort`, `int`...
    pub count: &'static str,
    /// The list's item type: `int`, `uint`, `ushort`...
    pub index: &'static str,
    /// `vertex_indices` or `vertex_index`.
    pub list_name: &'static str,
    /// A normal and a colour on each vertex, a flag on each face, and an `edge` element.
    pub extras: bool,
}

impl PlyStyle {
    pub fn plain(encoding: Encoding) -> Self {
        Self {
            encoding,
            coordinate: "float",
            count: "uchar",
            index: "int",
            list_name: "vertex_indices",
            extras: false,
        }
    }
}

fn put(out: &mut Vec<u8>, encoding: Encoding, ty: &str, value: f64) {
    macro_rules! bytes {
        ($v:expr) => {
            match encoding {
                Encoding::Big => out.extend_from_slice(&$v.to_be_bytes()),
                _ => out.extend_from_slice(&$v.to_le_bytes()),
            }
        };
    }
    match ty {
        "char" => bytes!(value as i8),
        "uchar" => bytes!(value as u8),
        "short" => bytes!(value as i16),
        "ushort" => bytes!(value as u16),
        "int" => bytes!(value as i32),
        "uint" => bytes!(value as u32),
        "float" => bytes!(value as f32),
        "double" => bytes!(value),
        other => panic!("no PLY type {other}"),
    }
}

/// A PLY file of `positions` and polygon `faces`, written as `style` says.
pub fn ply(positions: &[Vec3], faces: &[Vec<i64>], style: &PlyStyle) -> Vec<u8> {
    let format = match style.encoding {
        Encoding::Ascii => "ascii",
        Encoding::Little => "binary_little_endian",
        Encoding::Big => "binary_big_endian",
    };
    let mut header = format!("ply\nformat {format} 1.0\ncomment written by the tests\n");
    let c = style.coordinate;
    let _ = write!(
        header,
        "element vertex {}\nproperty {c} x\nproperty {c} y\nproperty {c} z\n",
        positions.len()
    );
    if style.extras {
        header += "property float nx\nproperty float ny\nproperty float nz\nproperty uchar red\n";
    }
    let _ = write!(
        header,
        "element face {}\nproperty list {} {} {}\n",
        faces.len(),
        style.count,
        style.index,
        style.list_name
    );
    if style.extras {
        header +=
            "property uchar flags\nelement edge 2\nproperty int vertex1\nproperty int vertex2\n";
    }
    header += "end_header\n";
    let mut out = header.into_bytes();
    let enc = style.encoding;
    for p in positions {
        let mut values: Vec<(&str, f64)> =
            p.to_array().iter().map(|&v| (c, f64::from(v))).collect();
        if style.extras {
            values.extend([
                ("float", 0.0),
                ("float", 0.0),
                ("float", 1.0),
                ("uchar", 200.0),
            ]);
        }
        row(&mut out, enc, &values);
    }
    for face in faces {
        let mut values = vec![(style.count, face.len() as f64)];
        values.extend(face.iter().map(|&i| (style.index, i as f64)));
        if style.extras {
            values.push(("uchar", 7.0));
        }
        row(&mut out, enc, &values);
    }
    if style.extras {
        for _ in 0..2 {
            row(&mut out, enc, &[("int", 0.0), ("int", 1.0)]);
        }
    }
    out
}

fn row(out: &mut Vec<u8>, encoding: Encoding, values: &[(&str, f64)]) {
    if encoding == Encoding::Ascii {
        let words: Vec<String> = values
            .iter()
            .map(|&(ty, v)| match ty {
                // `{:?}` writes the shortest decimal that reads back to the same float.
                "float" => format!("{:?}", v as f32),
                "double" => format!("{v:?}"),
                _ => format!("{}", v as i64),
            })
            .collect();
        out.extend_from_slice(words.join(" ").as_bytes());
        out.push(b'\n');
    } else {
        for &(ty, v) in values {
            put(out, encoding, ty, v);
        }
    }
}

/// A binary STL file of `triangles`, whose 80-byte header starts with `header`.
pub fn stl_binary(triangles: &[Triangle3], header: &[u8]) -> Vec<u8> {
    let mut out = vec![0u8; 80];
    out[..header.len()].copy_from_slice(header);
    out.extend_from_slice(&(triangles.len() as u32).to_le_bytes());
    for t in triangles {
        let normal = (t.b - t.a).cross(t.c - t.a).normalize_or_zero();
        for v in [normal, t.a, t.b, t.c] {
            for x in v.to_array() {
                out.extend_from_slice(&x.to_le_bytes());
            }
        }
        out.extend_from_slice(&[0, 0]);
    }
    out
}

/// An ASCII STL file with one solid per slice of `solids`.
pub fn stl_ascii(solids: &[&[Triangle3]]) -> Vec<u8> {
    let mut out = String::new();
    for (k, triangles) in solids.iter().enumerate() {
        let _ = writeln!(out, "solid part{k}");
        for t in *triangles {
            let n = (t.b - t.a).cross(t.c - t.a).normalize_or_zero();
            let _ = writeln!(out, "  facet normal {:?} {:?} {:?}", n.x, n.y, n.z);
            out += "    outer loop\n";
            for v in [t.a, t.b, t.c] {
                let _ = writeln!(out, "      vertex {:?} {:?} {:?}", v.x, v.y, v.z);
            }
            out += "    endloop\n  endfacet\n";
        }
        let _ = writeln!(out, "endsolid part{k}");
    }
    out.into_bytes()
}

/// A glTF buffer being filled: positions and indices, with the JSON of their views and
/// accessors.
#[derive(Default)]
pub struct GltfBuffer {
    pub bytes: Vec<u8>,
    pub views: Vec<String>,
    pub accessors: Vec<String>,
}

impl GltfBuffer {
    /// Appends positions; returns the accessor's index.
    pub fn positions(&mut self, positions: &[Vec3]) -> usize {
        let offset = self.bytes.len();
        for p in positions {
            for x in p.to_array() {
                self.bytes.extend_from_slice(&x.to_le_bytes());
            }
        }
        let (lo, hi) = positions
            .iter()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            });
        let bound = |v: Vec3| {
            let v = if v.is_finite() { v } else { Vec3::ZERO };
            format!("[{:?},{:?},{:?}]", v.x, v.y, v.z)
        };
        self.view(offset, 34962);
        self.accessors.push(format!(
            r#"{{"bufferView":{},"componentType":5126,"count":{},"type":"VEC3","min":{},"max":{}}}"#,
            self.views.len() - 1,
            positions.len(),
            bound(lo),
            bound(hi)
        ));
        self.accessors.len() - 1
    }

    /// Appends indices as `u8`, `u16` or `u32` (`size` 1, 2 or 4); returns the accessor.
    pub fn indices(&mut self, indices: &[u32], size: usize) -> usize {
        let offset = self.bytes.len();
        for &i in indices {
            self.bytes.extend_from_slice(&i.to_le_bytes()[..size]);
        }
        while !self.bytes.len().is_multiple_of(4) {
            self.bytes.push(0);
        }
        let component = match size {
            1 => 5121,
            2 => 5123,
            _ => 5125,
        };
        self.view(offset, 34963);
        self.accessors.push(format!(
            r#"{{"bufferView":{},"componentType":{component},"count":{},"type":"SCALAR"}}"#,
            self.views.len() - 1,
            indices.len()
        ));
        self.accessors.len() - 1
    }

    fn view(&mut self, offset: usize, target: u32) {
        self.views.push(format!(
            r#"{{"buffer":0,"byteOffset":{offset},"byteLength":{},"target":{target}}}"#,
            self.bytes.len() - offset
        ));
    }

    /// The JSON document with these buffers, `meshes`, `nodes` and scenes (JSON arrays'
    /// contents), the buffer given by `uri` (`None`: the GLB binary chunk; `Some("")`: this
    /// buffer as a base64 data URI).
    pub fn json(&self, meshes: &str, nodes: &str, scenes: &str, uri: Option<&str>) -> String {
        let uri = match uri {
            None => String::new(),
            Some("") => format!(
                r#","uri":"data:application/octet-stream;base64,{}""#,
                base64::engine::general_purpose::STANDARD.encode(&self.bytes)
            ),
            Some(uri) => format!(r#","uri":"{uri}""#),
        };
        format!(
            r#"{{"asset":{{"version":"2.0","generator":"bvhlab-meshio tests"}},
"scene":0,"scenes":[{scenes}],"nodes":[{nodes}],"meshes":[{meshes}],
"buffers":[{{"byteLength":{}{uri}}}],"bufferViews":[{}],"accessors":[{}]}}"#,
            self.bytes.len(),
            self.views.join(","),
            self.accessors.join(",")
        )
    }
}

/// A GLB file of `json` and the binary chunk `bin` (each padded to four bytes as the
/// specification asks: JSON with spaces, binary with zeros).
pub fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut json = json.as_bytes().to_vec();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let mut bin = bin.to_vec();
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let length = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = b"glTF".to_vec();
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(length as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend(json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend(bin);
    out
}

/// A triangle as comparable bits: corners in its own cyclic order (so the winding counts),
/// started at the smallest, and −0 taken as +0.
pub fn key(t: &Triangle3) -> [[u32; 3]; 3] {
    let corners = [t.a, t.b, t.c].map(|p| (p + Vec3::ZERO).to_array().map(f32::to_bits));
    let first = (0..3).min_by_key(|&i| corners[i]).unwrap_or(0);
    [0, 1, 2].map(|k| corners[(first + k) % 3])
}

/// The triangles as a sorted multiset of [`key`]s.
pub fn triangle_set(triangles: &[Triangle3]) -> Vec<[[u32; 3]; 3]> {
    let mut keys: Vec<_> = triangles.iter().map(key).collect();
    keys.sort_unstable();
    keys
}

/// Whether two meshes have the same triangles (as multisets, windings included).
pub fn same_triangles(a: &Mesh, b: &Mesh) -> bool {
    triangle_set(a.triangles()) == triangle_set(b.triangles())
}

/// A mesh's polygons as index lists (its triangles, one face each).
pub fn faces_of(mesh: &Mesh) -> Vec<Vec<i64>> {
    mesh.indices()
        .iter()
        .map(|t| t.iter().map(|&i| i64::from(i)).collect())
        .collect()
}

/// The shared folder of real meshes, if it is there (else a message says the test skips).
pub fn mesh_dir() -> Option<PathBuf> {
    let candidates = [
        std::env::var_os("BVHLAB_MESHES").map(PathBuf::from),
        Some(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/meshes")),
    ];
    let found = candidates.into_iter().flatten().find(|dir| dir.is_dir());
    if found.is_none() {
        eprintln!(
            "skipped: no mesh folder (set BVHLAB_MESHES, or put shared/ beside the checkout)"
        );
    }
    found
}
