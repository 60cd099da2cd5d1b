//! What the app hands the 3D renderer each frame: plain data, no GPU types, so the app can
//! build it anywhere and the renderer (natively, on the web, or headless in tests) draws it.
//!
//! Colours are `[r, g, b, a]` with `rgb` sRGB-encoded ("gamma space", as egui's colours
//! are) and `a` straight (not premultiplied) coverage, all in `0..=1`.
//!
//! [`Line3d`], [`ColorTriangle`] and [`Marker`] are `#[repr(C)]` plain old data: the renderer
//! uploads the app's slices to GPU instance buffers as they are, without a conversion pass.

use std::sync::Arc;

use bytemuck::{Pod, Zeroable};

use crate::model::orbit_camera::OrbitCamera;

/// A triangle mesh as shared with the renderer: positions and triangles of indices into them.
///
/// The renderer keeps its GPU copy until `revision` changes, so whoever edits a mesh must give
/// the edited one a new revision; two meshes with the same revision are taken to be the same.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshData {
    /// Changes whenever `positions` or `indices` change (see the type's comment).
    pub revision: u64,
    /// The vertices, in world space.
    pub positions: Vec<[f32; 3]>,
    /// The triangles, as three indices into `positions` each (counter-clockwise seen from
    /// outside, for the front/back tint and the x-ray's back-to-front order).
    pub indices: Vec<[u32; 3]>,
}

impl MeshData {
    /// The three corners of triangle `index`, or `None` when the triangle or one of its
    /// vertices does not exist.
    pub fn triangle(&self, index: u32) -> Option<[[f32; 3]; 3]> {
        let [a, b, c] = *self.indices.get(index as usize)?;
        let corner = |i: u32| self.positions.get(i as usize).copied();
        Some([corner(a)?, corner(b)?, corner(c)?])
    }
}

/// A world-space segment drawn `width_px` pixels wide whatever its distance (a screen-space
/// quad, so thick lines look the same on every backend, unlike line primitives).
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct Line3d {
    /// One end, in world space.
    pub a: [f32; 3],
    /// The other end, in world space.
    pub b: [f32; 3],
    /// The colour (see the module comment).
    pub color: [f32; 4],
    /// The width on screen, in physical pixels.
    pub width_px: f32,
}

/// A world-space triangle in one colour, drawn double-sided and unlit (split planes, cells'
/// faces): usually translucent.
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct ColorTriangle {
    /// The first corner, in world space.
    pub a: [f32; 3],
    /// The second corner.
    pub b: [f32; 3],
    /// The third corner.
    pub c: [f32; 3],
    /// The colour (see the module comment).
    pub color: [f32; 4],
}

/// A disc facing the screen, drawn on top of everything (hit points, query points).
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct Marker {
    /// The centre, in world space.
    pub pos: [f32; 3],
    /// The radius on screen, in physical pixels.
    pub radius_px: f32,
    /// The fill colour (see the module comment); the rim is a darker shade of it.
    pub color: [f32; 4],
}

// The shaders read these structs as vertex attributes at fixed offsets (see `instances.rs`).
const _: () = assert!(size_of::<Line3d>() == 44);
const _: () = assert!(size_of::<ColorTriangle>() == 52);
const _: () = assert!(size_of::<Marker>() == 32);

/// Everything the 3D view shows in one frame, drawn in this order: the opaque mesh, the
/// depth-tested lines, the highlights, the x-ray mesh's back faces, the translucent
/// triangles, the x-ray mesh's front faces, the overlay lines and the markers.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame3d {
    /// Where the view looks from.
    pub camera: OrbitCamera,
    /// The colour the view is cleared to (see the module comment).
    pub background: [f32; 4],
    /// The mesh, if any (shared with the app; uploaded again only when its revision changes).
    pub mesh: Option<Arc<MeshData>>,
    /// The mesh's colour. Alpha below 1 is x-ray: the mesh is translucent (and writes no
    /// depth), so lines and triangles inside it show through.
    pub mesh_color: [f32; 4],
    /// Triangles of the mesh (by index into [`MeshData::indices`]) drawn over it in a colour
    /// (tested, hit), lit like the mesh and nudged towards the eye so they win the depth test.
    pub highlights: Vec<(u32, [f32; 4])>,
    /// Segments hidden by what is in front of them (boxes, splits).
    pub lines: Vec<Line3d>,
    /// Segments drawn over everything (the ray, gizmos).
    pub overlay_lines: Vec<Line3d>,
    /// Translucent triangles: depth-tested against opaque things, blended, writing no depth.
    pub triangles: Vec<ColorTriangle>,
    /// Discs drawn on top of everything.
    pub markers: Vec<Marker>,
}

impl Default for Frame3d {
    fn default() -> Self {
        Self {
            camera: OrbitCamera::default(),
            background: [0.1, 0.1, 0.12, 1.0],
            mesh: None,
            mesh_color: [0.75, 0.75, 0.78, 1.0],
            highlights: Vec::new(),
            lines: Vec::new(),
            overlay_lines: Vec::new(),
            triangles: Vec::new(),
            markers: Vec::new(),
        }
    }
}

impl Frame3d {
    /// Whether the mesh is drawn translucent (x-ray) rather than opaque.
    pub fn is_xray(&self) -> bool {
        self.mesh_color[3] < 1.0
    }
}
