//! The mesh the 3D half shows: the core's [`Mesh`] for the structures, where it came from,
//! and what its loader noticed. (The view keeps the GPU's copy of its triangles.)

use std::sync::Arc;

use bvhlab::{Aabb3, Mesh, MeshStats};

/// Where a mesh comes from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum MeshSource {
    /// A built-in mesh, by slug (see `bvhlab_meshio::builtin`).
    Builtin(String),
    /// A file the student dropped or picked.
    File {
        /// Its name, for messages and the format guess.
        name: String,
        /// Its bytes.
        bytes: Arc<[u8]>,
    },
}

/// A loaded mesh.
pub struct Mesh3d {
    /// Its name: the built-in's or the file's.
    pub name: String,
    /// The built-in's slug, when it is one (saved states name it instead of the triangles).
    pub slug: Option<String>,
    /// The triangles.
    pub mesh: Mesh,
    /// Vertex, face and triangle counts, degenerate triangles, bounds.
    pub stats: MeshStats,
    /// What the loader noticed and let pass (skipped primitives, degenerate triangles).
    pub warnings: Vec<String>,
    /// Changes whenever another mesh is loaded, or the mesh moves
    /// ([`Mesh3d::replace`]).
    pub revision: u64,
}

impl Mesh3d {
    /// Wraps a loaded mesh.
    pub fn new(
        name: String,
        slug: Option<String>,
        mesh: Mesh,
        warnings: Vec<String>,
        revision: u64,
    ) -> Self {
        Self {
            name,
            slug,
            stats: mesh.summary(),
            mesh,
            warnings,
            revision,
        }
    }

    /// Puts `mesh` (the same mesh moved: [`super::motion`]) in place of the triangles, with
    /// `revision`; the name, source and warnings stay.
    pub fn replace(&mut self, mesh: Mesh, revision: u64) {
        self.stats = mesh.summary();
        self.mesh = mesh;
        self.revision = revision;
    }

    /// The number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.mesh.triangles().len()
    }

    /// The box around the mesh.
    pub fn bounds(&self) -> Aabb3 {
        self.stats.bounds
    }

    /// The length of the bounds' diagonal (at least a tiny positive number): the scale
    /// handles, markers and default radii are measured in.
    pub fn size(&self) -> f32 {
        let b = self.bounds();
        (b.max - b.min).length().max(1e-6)
    }
}

/// Loads `source`: a built-in mesh, or a file in any format `bvhlab_meshio` reads.
///
/// # Errors
/// The loader's message (naming the file and the fault), or an unknown built-in.
pub fn load(source: &MeshSource, revision: u64) -> Result<Mesh3d, String> {
    match source {
        MeshSource::Builtin(slug) => {
            let builtin = bvhlab_meshio::builtin::list()
                .iter()
                .find(|b| b.slug == slug)
                .ok_or_else(|| format!("There is no built-in mesh called \"{slug}\"."))?;
            let mesh = bvhlab_meshio::builtin::make(slug)
                .ok_or_else(|| format!("The built-in mesh \"{slug}\" could not be made."))?;
            Ok(Mesh3d::new(
                builtin.name.to_owned(),
                Some(slug.clone()),
                mesh,
                Vec::new(),
                revision,
            ))
        }
        MeshSource::File { name, bytes } => {
            let loaded = bvhlab_meshio::load(name, bytes).map_err(|e| e.to_string())?;
            Ok(Mesh3d::new(
                name.clone(),
                None,
                loaded.mesh,
                loaded.warnings,
                revision,
            ))
        }
    }
}
