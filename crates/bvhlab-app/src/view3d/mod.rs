//! The 3D view: meshes, an orbit camera, rays cast by clicking, and the structures and their
//! traversals drawn with wgpu.
//!
//! - [`camera`]: the orbit camera and the one definition of a pixel's ray.
//! - [`gpu`]: the wgpu renderer that draws the view, inside egui or headless.
//! - [`heatmap`]: the traversal-cost heat map, on the GPU (WGSL compute) and on the CPU.

pub mod camera;
pub mod gpu;
pub mod heatmap;
