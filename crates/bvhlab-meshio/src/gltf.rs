//! glTF 2.0 (Khronos), as a `.glb` file or as a `.gltf` JSON file with its buffers embedded
//! as base64 data URIs: the triangles of every mesh in the default scene, each placed by the
//! transforms of the nodes above it.
//!
//! `gltf` parses and validates the JSON (references in range, required properties present);
//! the GLB container and the accessors are read here, with every offset checked (see
//! `glb` and `accessor`). A scene is a forest of nodes, each with a local transform (a matrix,
//! or translation · rotation · scale); a mesh hangs at a node and is drawn with the product of
//! the transforms from the root down. The same mesh under two nodes is two copies.
//!
//! Primitives in `TRIANGLES` mode are read with or without an index accessor; strips and fans
//! are cut into their triangles as section 3.7.2.1 of the specification defines them; points
//! and lines have no surface and are skipped with a warning. A transform that mirrors
//! (negative determinant) reverses the triangles' winding, which the specification says
//! renderers must undo; this reader undoes it, so outward faces stay counter-clockwise.
//! Skins and morph targets are not applied: a skinned mesh appears in its bind pose.

mod accessor;
mod glb;

use ::gltf::json::validation::Checked;
use ::gltf::mesh::Mode;
use ::gltf::{Document, Node, Primitive};
use bvhlab::glam::DMat4;

use self::accessor::{Buffers, Fault};
use crate::{Format, Geometry, LoadError, MAX_TRIANGLES, MAX_VERTICES};

/// Extensions that change how geometry is stored, and what the lab says about each.
const COMPRESSION: [(&str, &str); 2] = [
    ("KHR_draco_mesh_compression", "Draco-compressed geometry"),
    (
        "EXT_meshopt_compression",
        "meshoptimizer-compressed buffers",
    ),
];

/// Reads a `.gltf` (`format` is [`Format::Gltf`]) or `.glb` file.
pub(crate) fn read(
    file: &str,
    bytes: &[u8],
    format: Format,
    warnings: &mut Vec<String>,
) -> Result<Geometry, LoadError> {
    let fault = |detail: String| LoadError::malformed(file, format, detail);
    let (json, bin) = match format {
        Format::Glb => glb::split(bytes).map_err(fault)?,
        _ => (bytes, None),
    };
    let root: ::gltf::json::Root = ::gltf::json::deserialize::from_slice(json)
        .map_err(|e| fault(format!("this is not glTF 2.0 JSON: {e}")))?;
    // The reader knows no extension, so a file that requires one cannot be read right.
    if let Some(required) = root.extensions_required.first() {
        let what = COMPRESSION
            .iter()
            .find(|(name, _)| name == required)
            .map_or(String::new(), |(_, what)| format!(" ({what})"));
        return Err(fault(format!(
            "the file needs the glTF extension {required}{what}, which the lab does not \
             read; export it without that extension"
        )));
    }
    dangling_position(&root).map_or(Ok(()), |detail| Err(fault(detail)))?;
    let document = Document::from_json(root).map_err(|e| fault(validation(&e)))?;
    let buffers = Buffers::new(&document, bin);
    let mut scene = Scene {
        file,
        format,
        buffers,
        geometry: Geometry::default(),
        skipped: Vec::new(),
        skinned: false,
        ragged: 0,
    };
    if let Some(root) = document
        .default_scene()
        .or_else(|| document.scenes().next())
    {
        scene.walk(&document, root.nodes())?;
    } else {
        warnings.push(format!(
            "{file} has no scene; every mesh is read once, without transforms"
        ));
        for mesh in document.meshes() {
            scene.mesh(&mesh, &DMat4::IDENTITY)?;
        }
    }
    if !scene.skipped.is_empty() {
        warnings.push(format!(
            "{file}: skipped {} primitives that draw points or lines ({}): they have no \
             surface",
            scene.skipped.len(),
            scene.skipped.join(", ")
        ));
    }
    if scene.ragged > 0 {
        warnings.push(format!(
            "{file}: {} indices at the end of TRIANGLES primitives did not make a whole \
             triangle and were ignored",
            scene.ragged
        ));
    }
    if scene.skinned {
        warnings.push(format!(
            "{file}: skinned meshes are shown in their bind pose (skins are not applied)"
        ));
    }
    Ok(scene.geometry)
}

/// A primitive whose `POSITION` names an accessor the file does not have, said as a sentence.
///
/// Checked before `gltf` validates the document: its check of the positions' bounds looks
/// the accessor up unchecked (gltf-json 1.4.1, `mesh.rs`), a panic on such a file.
fn dangling_position(root: &::gltf::json::Root) -> Option<String> {
    let position = Checked::Valid(::gltf::json::mesh::Semantic::Positions);
    root.meshes.iter().enumerate().find_map(|(m, mesh)| {
        mesh.primitives
            .iter()
            .enumerate()
            .find_map(|(p, primitive)| {
                let accessor = primitive.attributes.get(&position)?.value();
                (accessor >= root.accessors.len()).then(|| {
                    format!(
                        "mesh {m} primitive {p}: POSITION names accessor {accessor}, but the file \
                     has only {} accessors",
                        root.accessors.len()
                    )
                })
            })
    })
}

/// `gltf`'s validation errors as one sentence.
fn validation(e: &::gltf::Error) -> String {
    match e {
        ::gltf::Error::Validation(problems) => {
            let list: Vec<String> = problems
                .iter()
                .take(3)
                .map(|(path, problem)| format!("{path}: {problem}"))
                .collect();
            format!("the glTF JSON is not valid: {}", list.join("; "))
        }
        other => format!("the glTF file is not valid: {other}"),
    }
}

/// The walk through a scene, gathering triangles.
struct Scene<'a> {
    file: &'a str,
    format: Format,
    buffers: Buffers<'a>,
    geometry: Geometry,
    /// The primitives skipped for their mode, as "mesh 2 primitive 0 (LINES)".
    skipped: Vec<String>,
    /// Whether a node with a mesh has a skin.
    skinned: bool,
    /// Indices left over at the end of `TRIANGLES` primitives (fewer than three).
    ragged: usize,
}

impl Scene<'_> {
    /// Visits the nodes under `roots`, depth first, each once (the specification forbids a
    /// node with two parents and cycles; a broken file with either is read as a tree).
    fn walk<'d>(
        &mut self,
        document: &'d Document,
        roots: impl Iterator<Item = Node<'d>>,
    ) -> Result<(), LoadError> {
        let mut seen = vec![false; document.nodes().len()];
        let mut stack: Vec<(Node<'d>, DMat4)> = roots.map(|n| (n, DMat4::IDENTITY)).collect();
        stack.reverse();
        while let Some((node, parent)) = stack.pop() {
            if std::mem::replace(&mut seen[node.index()], true) {
                continue;
            }
            let local = node
                .transform()
                .matrix()
                .map(|column| column.map(f64::from));
            let world = parent * DMat4::from_cols_array_2d(&local);
            if let Some(mesh) = node.mesh() {
                self.skinned |= node.skin().is_some();
                self.mesh(&mesh, &world)?;
            }
            let first_child = stack.len();
            stack.extend(node.children().map(|child| (child, world)));
            // Reversed, so that the first child is taken next: triangles come in file order.
            stack[first_child..].reverse();
        }
        Ok(())
    }

    /// Adds the triangles of `mesh`, placed by `world`.
    fn mesh(&mut self, mesh: &::gltf::Mesh<'_>, world: &DMat4) -> Result<(), LoadError> {
        for primitive in mesh.primitives() {
            let name = match mesh.name() {
                Some(name) => format!(
                    "mesh {} (`{name}`) primitive {}",
                    mesh.index(),
                    primitive.index()
                ),
                None => format!("mesh {} primitive {}", mesh.index(), primitive.index()),
            };
            self.primitive(&primitive, world, &name)?;
        }
        Ok(())
    }

    fn accessor_fault(&self, name: &str, fault: Fault) -> LoadError {
        match fault {
            Fault::External(uri) => LoadError::ExternalBuffer {
                file: self.file.to_owned(),
                uri,
            },
            Fault::Broken(why) => {
                LoadError::malformed(self.file, self.format, format!("{name}: {why}"))
            }
        }
    }

    fn primitive(
        &mut self,
        primitive: &Primitive<'_>,
        world: &DMat4,
        name: &str,
    ) -> Result<(), LoadError> {
        let mode = primitive.mode();
        if !matches!(
            mode,
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        ) {
            self.skipped.push(format!("{name}, {mode:?}"));
            return Ok(());
        }
        // Validation guarantees a POSITION accessor.
        let Some(accessor) = primitive.get(&::gltf::Semantic::Positions) else {
            return Ok(());
        };
        let local = accessor::positions(&accessor, &self.buffers)
            .map_err(|f| self.accessor_fault(name, f))?;
        let corners = match primitive.indices() {
            Some(indices) => accessor::indices(&indices, &self.buffers)
                .map_err(|f| self.accessor_fault(name, f))?,
            None => (0..local.len() as u32).collect(),
        };
        let base = self.geometry.positions.len();
        if base + local.len() > MAX_VERTICES {
            return Err(LoadError::TooManyVertices {
                file: self.file.to_owned(),
                vertices: base + local.len(),
            });
        }
        for (k, p) in local.iter().enumerate() {
            let placed = world.transform_point3(p.as_dvec3()).as_vec3();
            if !placed.is_finite() {
                let after = if p.is_finite() {
                    ", once its nodes' transforms are applied"
                } else {
                    ""
                };
                return Err(LoadError::non_finite(
                    self.file,
                    self.format,
                    format!("vertex {k} of {name}{after}"),
                ));
            }
            self.geometry.positions.push(placed);
        }
        if let Some((k, &index)) = corners
            .iter()
            .enumerate()
            .find(|(_, i)| **i as usize >= local.len())
        {
            return Err(LoadError::malformed(
                self.file,
                self.format,
                format!(
                    "{name}: index {k} names vertex {index}, but the primitive has only {} vertices",
                    local.len()
                ),
            ));
        }
        let mirrored = world.determinant() < 0.0;
        let base = base as u32;
        let mut push = |[a, b, c]: [u32; 3]| {
            let (a, b, c) = (base + a, base + b, base + c);
            self.geometry
                .indices
                .push(if mirrored { [a, c, b] } else { [a, b, c] });
        };
        match mode {
            Mode::TriangleStrip => {
                for (i, w) in corners.windows(3).enumerate() {
                    push(if i % 2 == 0 {
                        [w[0], w[1], w[2]]
                    } else {
                        [w[0], w[2], w[1]]
                    });
                }
            }
            Mode::TriangleFan => {
                for w in corners.get(1..).unwrap_or_default().windows(2) {
                    push([w[0], w[1], corners[0]]);
                }
            }
            _ => {
                let triangles = corners.chunks_exact(3);
                self.ragged += triangles.remainder().len();
                triangles.for_each(|t| push([t[0], t[1], t[2]]));
            }
        }
        if self.geometry.indices.len() > MAX_TRIANGLES {
            return Err(LoadError::TooManyTriangles {
                file: self.file.to_owned(),
                triangles: self.geometry.indices.len(),
            });
        }
        Ok(())
    }
}
