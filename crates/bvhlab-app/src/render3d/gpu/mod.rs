//! The 3D view's renderer: wgpu pipelines that draw a [`Frame3d`] (a flat-shaded mesh, thick
//! lines, translucent triangles, highlights and markers) into an offscreen image, shown inside
//! egui through a paint callback and read back headless in tests.
//!
//! Only vertex and uniform buffers are used (no storage buffers, no compute), so the same
//! pipelines run on WebGPU, WebGL2 and native backends.
//!
//! - [`frame`]: what the app hands over each frame.
//! - [`Renderer3d`] (`renderer.rs`): the offscreen drawing, layer by layer (`mesh.rs`,
//!   `lines.rs`, `triangles.rs`, `markers.rs`, each next to its `.wgsl`).
//! - [`callback`]: the egui paint callback and the blit into egui's pass.
//! - `headless.rs` (native only): a windowless device, read-back, [`render_offscreen`].

mod blit;
pub mod callback;
pub mod frame;
#[cfg(not(target_arch = "wasm32"))]
mod headless;
mod instances;
mod lines;
mod markers;
mod mesh;
mod mesh_chunks;
mod pipeline;
mod renderer;
mod targets;
mod triangles;
mod view_uniform;

pub use blit::EguiTarget;
pub use callback::{View3dCallback, install, install_in, is_installed, paint_3d};
pub use frame::{ColorTriangle, Frame3d, Line3d, Marker, MeshData};
#[cfg(not(target_arch = "wasm32"))]
pub use headless::{
    OffscreenError, RgbaImage, headless_device, headless_device_with_limits, read_back,
    render_and_read, render_offscreen,
};
pub use mesh_chunks::MeshUploadError;
pub use pipeline::COLOR_FORMAT;
pub use renderer::{DEFAULT_SAMPLES, Renderer3d, preferred_samples};
