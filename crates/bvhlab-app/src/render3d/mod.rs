//! Drawing the 3D view with wgpu: the renderer and the traversal-cost heat map. (The orbit
//! camera and the one definition of a pixel's ray are the model's:
//! [`crate::model::orbit_camera`].)
//!
//! - [`gpu`]: the wgpu renderer that draws the view, inside egui or headless.
//! - [`heatmap`]: the traversal-cost heat map, on the GPU (WGSL compute) and on the CPU.

pub mod gpu;
pub mod heatmap;
