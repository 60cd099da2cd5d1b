//! The Stanford bunny, from the asset `assets/bunny.obj` compiled into the crate (see
//! `assets/README.md` for its source, licence and conversion).

use bvhlab::Mesh;

/// The bunny as OBJ text: 1,839 vertices, 3,674 triangles, y up.
const BUNNY_OBJ: &[u8] = include_bytes!("../../assets/bunny.obj");

/// The Stanford bunny (closed, 3,674 triangles, about 10 units tall).
pub(super) fn bunny() -> Mesh {
    Mesh::from_obj(BUNNY_OBJ).unwrap_or_default()
}
