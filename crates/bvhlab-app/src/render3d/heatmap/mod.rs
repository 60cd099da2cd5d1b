//! The traversal-cost heat map: an image of the mesh where each pixel shows what its camera
//! ray's first-hit query cost in the selected structure (nodes visited or triangles tested),
//! on a perceptual colour scale.
//!
//! Two paths give the same counts:
//! - [`cpu`]: the core's own [`QueryCost`](bvhlab::QueryCost) per pixel, for every
//!   structure, a slice of rays per frame.
//! - [`gpu`]: a WGSL compute shader that walks the AABB tree ([`flatten`]ed to storage
//!   buffers) exactly as the core does, where compute shaders exist (WebGPU and native, not
//!   WebGL2); then a second pass colours the counts into a texture for egui.
//!
//! ## Why the GPU gives the CPU's counts, pixel for pixel
//! Whether a node is entered or pruned turns on comparisons of `f32` values (a slab test's
//! entry against the best hit so far, grown by `GROW`), so a single bit of difference in a
//! ray direction, a box entry or a hit's `t` can change a count. The shader therefore
//! computes every value from the same operands with the same operations in the same order as
//! the core, and closes the four gaps between WGSL and Rust:
//! 1. **Fused multiply-add.** Rust never fuses `a * b + c`; GPU compilers may (Vulkan allows
//!    it unless SPIR-V says `NoContraction`, which naga does not emit). The few sums of
//!    products the core rounds twice (the pixel direction, the shear of the triangle test)
//!    pass the product through `rounded`, an OR with a zero the compiler cannot see.
//! 2. **Division.** WGSL allows `x / y` 2.5 units in the last place; the shader divides in
//!    integer arithmetic, correctly rounded (`exact.wgsl`).
//! 3. **`f64`.** The core's watertight triangle test (`Triangle3::ray_hit`) evaluates its edge
//!    functions, determinant and `t` in `f64`. The shader reproduces those binary64 results
//!    exactly with a small integer soft-float (`exact.wgsl`: multiply, add, divide, round to
//!    `f32`). Its cost is paid only where it matters: the signs of the edge functions, which
//!    reject most triangles, are decided by comparing the two `f32` products (rounding is
//!    monotonic, so unequal products decide the sign) and only equal ones go to `f64`.
//! 4. **Infinities and NaN.** WGSL implementations may assume neither occurs. A direction
//!    component of ±0 makes the core's slab test multiply by ±∞ (and `0 × ∞ = NaN` when the
//!    origin lies on a slab plane); the shader decides those cases by comparing signs, and
//!    takes +∞ from the uniform buffer where the core starts from it.
//!
//! On Mesa's lavapipe (the machine's software Vulkan) measurements showed that plain WGSL
//! already matched on points 1 and 2: `a * b + c` was not fused and `a / b`, `1 / b` were
//! correctly rounded on 65,536 random operands. The shader does not rely on it. What no
//! `f32` shader controls is subnormal numbers, which lavapipe flushes to zero: the results
//! can differ only when a coordinate, direction component or product is below 1.2e-38, which
//! no camera ray through a mesh of sensible scale produces.
//!
//! The sphere tree (whose ray test is an `f64` quadratic with a square root) is drawn by the
//! CPU path.

pub mod colormap;
pub mod cpu;
pub mod flatten;
pub mod gpu;

pub use colormap::legend;
pub use cpu::CpuHeatMap;
pub use gpu::{GpuHeatMap, HeatMapError, gpu_heatmap_supported};

pub use crate::model::heat::Metric;
