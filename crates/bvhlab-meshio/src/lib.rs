//! # bvhlab-meshio: mesh files and built-in meshes for bvh-lab's 3D view
//!
//! The 3D lab builds its structures over a triangle mesh: one of the [`builtin`] meshes (a
//! cube, a sphere, a torus, a cloud of tetrahedra, the Stanford bunny, a million-triangle
//! lumpy sphere) or a file the student drops on the page. [`load`] turns a file's bytes into
//! the core's [`Mesh`], whatever its format:
//!
//! | format | read by | notes |
//! | --- | --- | --- |
//! | OBJ | the core's [`Mesh::from_obj`] | polygons ear-clipped; errors name line and face |
//! | PLY | `ply-rs-bw` | ASCII, binary little- and big-endian; polygons cut as fans |
//! | STL | `stl_io` | ASCII (one or more solids) and binary; corners welded into vertices |
//! | glTF, GLB | `gltf` (JSON), this crate (GLB container, accessors) | default scene, node transforms applied; embedded buffers only |
//!
//! The format is told by the content first (see [`Format::from_content`]) and by the name's
//! extension second, so a renamed file still loads (with a warning). Nothing here touches the
//! file system or spawns a thread: the crate runs the same natively and in the browser
//! (`wasm32-unknown-unknown`), where the bytes come from a dropped file.
//!
//! Every fault in a file is a [`LoadError`] whose message names the file and the fault in
//! words a student can act on; no input makes [`load`] panic. Sizes are bounded by
//! [`MAX_BYTES`], [`MAX_TRIANGLES`] and [`MAX_VERTICES`], checked against what a file declares
//! before anything is allocated for it.
//!
//! ```
//! use bvhlab_meshio::{Format, LoadError, builtin, load};
//!
//! let obj = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
//! let loaded = load("square.obj", obj)?;
//! assert_eq!(loaded.format, Format::Obj);
//! assert_eq!(loaded.mesh.len(), 2);
//! assert!(loaded.warnings.is_empty());
//!
//! // A binary STL cut off after 3 of the 1,200 triangles its header promises.
//! let mut stl = vec![0; 84 + 3 * 50];
//! stl[80..84].copy_from_slice(&1200u32.to_le_bytes());
//! let cut_off = load("part.stl", &stl).unwrap_err();
//! assert!(
//!     cut_off
//!         .to_string()
//!         .starts_with("part.stl: binary STL says 1,200 triangles but holds 3")
//! );
//!
//! let cube = builtin::make("cube").expect("a built-in mesh");
//! assert_eq!(cube.len(), 12);
//! # Ok::<(), LoadError>(())
//! ```

pub mod builtin;
mod error;
mod format;
mod gltf;
mod ply;
mod spliced;
mod stl;
mod weld;

pub use bvhlab::Mesh;

pub use self::error::LoadError;
pub use self::format::Format;

use bvhlab::MeshError;
use bvhlab::glam::Vec3;

/// The largest file [`load`] reads: 512 MiB.
///
/// Larger files would not fit the browser's memory next to the structures built over them.
pub const MAX_BYTES: usize = 512 << 20;

/// The most triangles a mesh may have: 4,000,000.
///
/// Enough for the lab's largest scenes, and a bound on the memory of the structures built over
/// them. Files that declare more are refused before their data is read.
pub const MAX_TRIANGLES: usize = 4_000_000;

/// The most vertices a mesh may have: three per triangle of [`MAX_TRIANGLES`].
pub const MAX_VERTICES: usize = 3 * MAX_TRIANGLES;

/// A mesh read from a file, with what the reader had to say about it.
#[derive(Clone, Debug)]
pub struct Loaded {
    /// The triangles.
    pub mesh: Mesh,
    /// The format the file was read as.
    pub format: Format,
    /// Things worth telling the student that did not stop the reading: a name that does not
    /// match the content, skipped primitives, polygons cut into fans, zero-area triangles...
    pub warnings: Vec<String>,
}

/// Vertices and index triples, as the readers other than OBJ produce them.
#[derive(Debug, Default)]
pub(crate) struct Geometry {
    pub positions: Vec<Vec3>,
    pub indices: Vec<[u32; 3]>,
}

/// Reads a mesh file: `file_name` (for its extension, and for messages) and its bytes.
///
/// # Errors
/// A [`LoadError`] when the file is empty, larger than [`MAX_BYTES`], of no format the lab
/// reads, broken (each variant says how), without triangles, or over [`MAX_TRIANGLES`] or
/// [`MAX_VERTICES`]. Zero-area triangles are not errors: they are kept, and counted in a
/// warning.
pub fn load(file_name: &str, bytes: &[u8]) -> Result<Loaded, LoadError> {
    let file = file_name;
    if bytes.len() > MAX_BYTES {
        return Err(LoadError::TooLarge {
            file: file.to_owned(),
            bytes: bytes.len(),
        });
    }
    if bytes.is_empty() {
        return Err(LoadError::Empty {
            file: file.to_owned(),
        });
    }
    let Some((format, renamed)) = format::detect(file, bytes) else {
        return Err(LoadError::UnknownFormat {
            file: file.to_owned(),
        });
    };
    let mut warnings: Vec<String> = renamed.into_iter().collect();
    let mesh = match format {
        Format::Obj => read_obj(file, bytes)?,
        Format::Ply => indexed(file, format, ply::read(file, bytes, &mut warnings)?)?,
        Format::Stl => indexed(file, format, stl::read(file, bytes)?)?,
        Format::Gltf | Format::Glb => indexed(
            file,
            format,
            gltf::read(file, bytes, format, &mut warnings)?,
        )?,
    };
    if mesh.is_empty() {
        return Err(LoadError::NoTriangles {
            file: file.to_owned(),
            format,
        });
    }
    if mesh.len() > MAX_TRIANGLES {
        return Err(LoadError::TooManyTriangles {
            file: file.to_owned(),
            triangles: mesh.len(),
        });
    }
    let stats = mesh.summary();
    if stats.degenerate_triangles > 0 {
        warnings.push(format!(
            "{file}: {} of its {} triangles have zero area (kept: the structures must cope \
             with them)",
            error::grouped(stats.degenerate_triangles),
            error::grouped(stats.triangles)
        ));
    }
    Ok(Loaded {
        mesh,
        format,
        warnings,
    })
}

/// The format [`load`] would read the file as, without reading it: by content first, then by
/// the name's extension.
pub fn detect_format(file_name: &str, bytes: &[u8]) -> Option<Format> {
    format::detect(file_name, bytes).map(|(format, _)| format)
}

/// An OBJ file, through the core's reader, refused early when its `f` lines alone exceed
/// [`MAX_TRIANGLES`] (each gives at least one triangle).
fn read_obj(file: &str, bytes: &[u8]) -> Result<Mesh, LoadError> {
    let faces = bytes
        .split(|&b| b == b'\n')
        .filter(|line| {
            let line = format::trim_start(line);
            line.first() == Some(&b'f') && line.get(1).is_some_and(u8::is_ascii_whitespace)
        })
        .count();
    if faces > MAX_TRIANGLES {
        return Err(LoadError::TooManyTriangles {
            file: file.to_owned(),
            triangles: faces,
        });
    }
    Mesh::from_obj(bytes).map_err(|error| LoadError::Obj {
        file: file.to_owned(),
        error,
    })
}

/// The core's mesh from a reader's vertices and triangles. The readers have checked both, so
/// an error here is a reader's bug, reported rather than hidden.
fn indexed(file: &str, format: Format, geometry: Geometry) -> Result<Mesh, LoadError> {
    if geometry.positions.len() > MAX_VERTICES {
        return Err(LoadError::TooManyVertices {
            file: file.to_owned(),
            vertices: geometry.positions.len(),
        });
    }
    Mesh::from_indexed(geometry.positions, geometry.indices).map_err(|e| match e {
        MeshError::NonFiniteVertex { vertex } => {
            LoadError::non_finite(file, format, format!("vertex {vertex}"))
        }
        other => LoadError::malformed(file, format, other.to_string()),
    })
}
