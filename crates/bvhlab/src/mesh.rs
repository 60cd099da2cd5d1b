//! Triangle meshes from Wavefront OBJ files: the real scenes the lab's structures are built
//! over (the Stanford bunny, the Utah teapot, ...).
//!
//! Readers of other formats, and generators of procedural meshes, hand their vertices and
//! triangles to [`Mesh::from_indexed`], which checks them the same way.
//!
//! [`Mesh::from_obj`] reads vertex positions and faces, triangulates polygon faces by ear
//! clipping, and refuses broken input with a [`MeshError`] that names the line, the face and
//! the fault. Everything else in the file (normals, texture coordinates, groups, materials)
//! is skipped, so a missing `.mtl` file does not matter.
//!
//! The parser is this crate's own, about a hundred lines, rather than the `tobj` crate:
//! `tobj` 4.0 reports errors as a bare kind with no line or face, turns faces of one or two
//! corners into degenerate triangles without a word (and cannot tell `f 1 2` from a polyline
//! `l 1 2`), accepts NaN and infinite coordinates, and panics on arithmetic overflow in debug
//! builds for a texture index such as `f 1/-5 2/1 3/1`.

mod error;
mod obj;
mod triangulate;

use std::fmt;

use glam::Vec3;

pub use self::error::{IndexProblem, MeshError};
use crate::primitive::overlap::is_degenerate;
use crate::{Aabb3, Triangle3};

/// A triangle mesh: shared vertex positions, triangles as index triples into them, and the
/// same triangles as [`Triangle3`] values, ready for a structure's `build`.
///
/// Triangles keep the winding of the file's faces (counter-clockwise seen from outside, for a
/// well-made mesh). Zero-area triangles are kept, not dropped: they are part of the file, and
/// structures must cope with them anyway; [`Mesh::summary`] counts them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    positions: Vec<Vec3>,
    indices: Vec<[u32; 3]>,
    triangles: Vec<Triangle3>,
    faces: usize,
}

/// What a mesh holds, for a status line or a test: see [`Mesh::summary`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshStats {
    /// Vertex positions (`v` statements).
    pub vertices: usize,
    /// Faces as the file has them (`f` statements), before triangulation.
    pub faces: usize,
    /// Triangles after triangulation: a face of `n` corners gives `n − 2`.
    pub triangles: usize,
    /// Triangles of zero area (decided exactly): their corners are collinear or repeated.
    pub degenerate_triangles: usize,
    /// The box around all triangles ([`Aabb3::EMPTY`] without any).
    pub bounds: Aabb3,
}

impl Mesh {
    /// Reads the triangles of a Wavefront OBJ file.
    ///
    /// Faces of four or more corners are triangulated by ear clipping (so concave faces come
    /// out right). Corner indices may be positive (from 1) or negative (relative), and may
    /// carry texture and normal indices (`v/vt/vn`). Input without faces, the empty file
    /// included, gives an empty mesh, not an error.
    ///
    /// # Errors
    /// A [`MeshError`] naming the line (and face) of the first fault: a NUL byte (binary
    /// input), a `v` or `f` line that is not UTF-8 (lines the reader skips, such as comments,
    /// may be in any encoding), a vertex with fewer than three numbers or with a NaN, infinite
    /// or out-of-`f32`-range coordinate, a face with fewer than three corners, or a corner
    /// index that is malformed, zero, past the last vertex or (relative) before the first one.
    /// A forward reference (a face naming a vertex that comes later) is allowed, so an index
    /// past the end is reported after the faults found on the way.
    ///
    /// ```
    /// use bvhlab::mesh::Mesh;
    ///
    /// let quad = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    /// let mesh = Mesh::from_obj(quad)?;
    /// assert_eq!(mesh.triangles().len(), 2);
    /// assert_eq!(mesh.summary().faces, 1);
    ///
    /// let broken = Mesh::from_obj(b"v 0 0 0\nf 1 2 3\n").unwrap_err();
    /// assert!(broken.to_string().starts_with("line 2 (face 1)"));
    /// # Ok::<(), bvhlab::mesh::MeshError>(())
    /// ```
    pub fn from_obj(bytes: &[u8]) -> Result<Self, MeshError> {
        let obj = obj::parse(bytes)?;
        let mut indices = Vec::with_capacity(obj.corners.len() / 3);
        for &(start, len) in &obj.faces {
            let corners = &obj.corners[start..start + len];
            triangulate::triangulate(corners, &obj.positions, &mut indices);
        }
        let at = |i: u32| obj.positions[i as usize];
        let triangles = indices
            .iter()
            .map(|&[a, b, c]| Triangle3::new(at(a), at(b), at(c)))
            .collect();
        Ok(Self {
            positions: obj.positions,
            indices,
            triangles,
            faces: obj.faces.len(),
        })
    }

    /// A mesh from vertex positions and triangles given as index triples into them: what a
    /// reader of another file format (PLY, STL, glTF) or a generator of procedural meshes
    /// hands over once it has triangulated its faces.
    ///
    /// Each index triple counts as one face in [`Mesh::summary`]. Triangles keep their corner
    /// order (their winding), and zero-area triangles are kept, as in [`Mesh::from_obj`].
    /// Vertices that no triangle uses are allowed.
    ///
    /// # Errors
    /// [`MeshError::NonFiniteVertex`] for the first vertex with a NaN or infinite coordinate,
    /// and [`MeshError::IndexOutOfRange`] for the first triangle naming a vertex past the last
    /// one, both counted from 0 as the slices count.
    ///
    /// ```
    /// use bvhlab::glam::Vec3;
    /// use bvhlab::mesh::{Mesh, MeshError};
    ///
    /// let square = vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
    /// let mesh = Mesh::from_indexed(square.clone(), vec![[0, 1, 2], [0, 2, 3]])?;
    /// assert_eq!(mesh.triangles()[1].c, Vec3::Y);
    ///
    /// let broken = Mesh::from_indexed(square, vec![[0, 1, 4]]).unwrap_err();
    /// assert_eq!(
    ///     broken,
    ///     MeshError::IndexOutOfRange { triangle: 0, index: 4, vertices: 4 }
    /// );
    /// # Ok::<(), MeshError>(())
    /// ```
    pub fn from_indexed(positions: Vec<Vec3>, indices: Vec<[u32; 3]>) -> Result<Self, MeshError> {
        if let Some(vertex) = positions.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFiniteVertex { vertex });
        }
        let vertices = positions.len();
        let mut triangles = Vec::with_capacity(indices.len());
        for (triangle, corners) in indices.iter().enumerate() {
            let corner = |k: usize| {
                positions
                    .get(corners[k] as usize)
                    .copied()
                    .ok_or(MeshError::IndexOutOfRange {
                        triangle,
                        index: corners[k],
                        vertices,
                    })
            };
            triangles.push(Triangle3::new(corner(0)?, corner(1)?, corner(2)?));
        }
        Ok(Self {
            positions,
            faces: indices.len(),
            indices,
            triangles,
        })
    }

    /// The triangles, in file order (a polygon's triangles in a row).
    pub fn triangles(&self) -> &[Triangle3] {
        &self.triangles
    }

    /// The vertex positions, in file order (OBJ index `i` is `positions()[i - 1]`).
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Each triangle's corners as indices into [`positions`](Self::positions).
    pub fn indices(&self) -> &[[u32; 3]] {
        &self.indices
    }

    /// The number of triangles.
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// Whether the mesh has no triangles.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// The box around all triangles ([`Aabb3::EMPTY`] for an empty mesh). Vertices that no
    /// face uses do not count.
    pub fn bounds(&self) -> Aabb3 {
        self.triangles
            .iter()
            .flat_map(|t| [t.a, t.b, t.c])
            .fold(Aabb3::EMPTY, |b, p| b.grown(p))
    }

    /// Counts of vertices, faces, triangles and zero-area triangles, and the bounds.
    pub fn summary(&self) -> MeshStats {
        MeshStats {
            vertices: self.positions.len(),
            faces: self.faces,
            triangles: self.triangles.len(),
            degenerate_triangles: self.triangles.iter().filter(|t| is_degenerate(t)).count(),
            bounds: self.bounds(),
        }
    }
}

impl fmt::Display for MeshStats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} vertices, {} faces, {} triangles ({} of zero area)",
            self.vertices, self.faces, self.triangles, self.degenerate_triangles
        )
    }
}
