//! The heat map on the GPU: the AABB tree in storage buffers, one compute invocation per
//! pixel tracing its ray (`trace.wgsl`), then one colouring it (`colorize.wgsl`) into an
//! `Rgba8Unorm` texture that egui can show. Why the counts equal the CPU's is explained in
//! the [module documentation](super).

use std::sync::Arc;
use std::sync::atomic::{AtomicU8, Ordering};

use bvhlab::AabbTree3;
use bvhlab::Ray3;
use bvhlab::glam::Vec3;
use bvhlab::structure::bvh::PreparedRay;
use bvhlab::structure::bvh::volume::GROW;
use eframe::egui_wgpu;
use eframe::wgpu;
use wgpu::util::DeviceExt;

use super::flatten::{FlatTree, GpuNode, GpuTriangle, flatten};
use super::{Metric, colormap};
use crate::model::orbit_camera::RayFrame;
use resources::{bind_group, check_buffer, make_target, pipeline};

#[cfg(not(target_arch = "wasm32"))]
mod readback;
mod resources;

/// Pixels per workgroup side (8 × 8 = 64 invocations, within every WebGPU device's limits).
const WORKGROUP: u32 = 8;

/// Bytes per pixel of the trace buffer (`Trace` in `params.wgsl`).
const TRACE_BYTES: u64 = 16;

/// Why the GPU heat map cannot be made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum HeatMapError {
    /// [`GpuHeatMap::dispatch`] before any [`GpuHeatMap::upload`].
    NoTree,
    /// A buffer or the texture exceeds the device's limit (a tree of some million
    /// triangles, or a huge image): use the CPU path.
    TooBig {
        /// Which buffer ("nodes", "triangles", "pixel traces") or "image".
        what: &'static str,
        /// Its size in bytes (pixels for the image side).
        size: u64,
        /// The device's limit in the same unit.
        limit: u64,
    },
    /// The camera's eye is not finite.
    BadCamera,
}

impl std::fmt::Display for HeatMapError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::NoTree => write!(f, "no tree uploaded to the GPU"),
            Self::TooBig { what, size, limit } => write!(
                f,
                "the heat map's {what} ({size}) exceed the GPU's limit ({limit}): use the CPU"
            ),
            Self::BadCamera => write!(f, "the camera's eye is not finite"),
        }
    }
}

impl std::error::Error for HeatMapError {}

/// Whether this device can run the heat map's shaders: compute shaders with storage buffers
/// and a storage texture (WebGPU and native backends; not WebGL2).
pub fn gpu_heatmap_supported(caps: &wgpu::DownlevelCapabilities, limits: &wgpu::Limits) -> bool {
    caps.flags.contains(wgpu::DownlevelFlags::COMPUTE_SHADERS)
        && limits.max_storage_buffers_per_shader_stage >= 4
        && limits.max_storage_textures_per_shader_stage >= 1
        && limits.max_compute_invocations_per_workgroup >= WORKGROUP * WORKGROUP
        && limits.max_compute_workgroup_size_x >= WORKGROUP
        && limits.max_compute_workgroup_size_y >= WORKGROUP
}

/// The WGSL of the tracing pass (parameters, exact arithmetic, traversal).
pub fn trace_shader_source() -> String {
    [
        include_str!("params.wgsl"),
        include_str!("exact.wgsl"),
        include_str!("trace.wgsl"),
    ]
    .join("\n")
}

/// The WGSL of the colouring pass (parameters, the colour ramp, colouring).
pub fn colorize_shader_source() -> String {
    [
        include_str!("params.wgsl"),
        &colormap::ramp_wgsl(),
        include_str!("colorize.wgsl"),
    ]
    .join("\n")
}

/// `Params` in `params.wgsl`, 128 bytes.
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
struct Params {
    origin: [f32; 4],
    origin_plus: [f32; 4],
    origin_minus: [f32; 4],
    corner: [f32; 4],
    step_x: [f32; 4],
    step_y: [f32; 4],
    size: [u32; 2],
    metric: u32,
    fixed_max: u32,
    inf: f32,
    grow: f32,
    zero: u32,
    node_count: u32,
}

const _: () = assert!(size_of::<Params>() == 128);

impl Params {
    /// The frame's rays as the core prepares them: the eye moved by the query's slack, taken
    /// from the core's own `PreparedRay` of a ray with all-positive and one with
    /// all-negative direction components.
    fn new(
        frame: &RayFrame,
        metric: Metric,
        fixed_max: Option<u32>,
        node_count: u32,
    ) -> Option<Self> {
        let up = PreparedRay::new(&Ray3::new(frame.origin, Vec3::ONE).ok()?);
        let down = PreparedRay::new(&Ray3::new(frame.origin, -Vec3::ONE).ok()?);
        let v4 = |v: Vec3| v.extend(0.0).to_array();
        Some(Self {
            origin: v4(frame.origin),
            origin_plus: v4(up.origin_near),
            origin_minus: v4(down.origin_near),
            corner: v4(frame.corner),
            step_x: v4(frame.step_x),
            step_y: v4(frame.step_y),
            size: [frame.width, frame.height],
            metric: metric.index(),
            fixed_max: fixed_max.unwrap_or(0),
            inf: f32::INFINITY,
            grow: GROW,
            zero: 0,
            node_count,
        })
    }
}

/// The tree's buffers.
struct TreeBuffers {
    nodes: wgpu::Buffer,
    triangles: wgpu::Buffer,
    node_count: u32,
}

/// The per-image resources, remade when the image size changes.
struct Target {
    size: [u32; 2],
    traces: wgpu::Buffer,
    #[cfg_attr(
        target_arch = "wasm32",
        expect(dead_code, reason = "read back natively only; the views keep it alive")
    )]
    texture: wgpu::Texture,
    /// `Rgba8Unorm`, written by the colouring pass.
    storage_view: wgpu::TextureView,
    /// The same texels for sampling: sRGB-encoded bytes, which egui-wgpu samples as they
    /// are, as it does its own textures.
    display_view: wgpu::TextureView,
}

/// The largest counts' read-back: idle, copy recorded, mapping, mapped.
const IDLE: u8 = 0;
const COPIED: u8 = 1;
const MAPPING: u8 = 2;
const MAPPED: u8 = 3;

/// The GPU heat map: pipelines, the uploaded tree and the last image.
pub struct GpuHeatMap {
    trace_pipeline: wgpu::ComputePipeline,
    colorize_pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    /// The largest count of each metric in the last image (atomic maxima).
    maxima: wgpu::Buffer,
    maxima_staging: wgpu::Buffer,
    readback: Arc<AtomicU8>,
    last_maxima: Option<[u32; 2]>,
    tree: Option<TreeBuffers>,
    target: Option<Target>,
    metric: Metric,
}

impl GpuHeatMap {
    /// Compiles the two passes. Check [`gpu_heatmap_supported`] first.
    pub fn new(device: &wgpu::Device) -> Self {
        let trace_pipeline = pipeline(device, "heat map trace", &trace_shader_source(), "trace");
        let colorize_pipeline = pipeline(
            device,
            "heat map colorize",
            &colorize_shader_source(),
            "colorize",
        );
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("heat map params"),
            size: size_of::<Params>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let maxima = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("heat map maxima"),
            size: 8,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let maxima_staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("heat map maxima read-back"),
            size: 8,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self {
            trace_pipeline,
            colorize_pipeline,
            params,
            maxima,
            maxima_staging,
            readback: Arc::new(AtomicU8::new(IDLE)),
            last_maxima: None,
            tree: None,
            target: None,
            metric: Metric::Nodes,
        }
    }

    /// Uploads the tree (replacing any earlier one).
    ///
    /// # Errors
    /// [`HeatMapError::TooBig`] when the nodes or the triangles exceed the device's storage
    /// buffer binding size (with wgpu's default limit of 128 MiB: about 2.8 million
    /// triangles, or 4 million nodes).
    pub fn upload(&mut self, device: &wgpu::Device, tree: &AabbTree3) -> Result<(), HeatMapError> {
        let FlatTree {
            mut nodes,
            mut triangles,
        } = flatten(tree);
        let node_count = nodes.len() as u32;
        check_buffer(device, "nodes", (nodes.len() * size_of::<GpuNode>()) as u64)?;
        check_buffer(
            device,
            "triangles",
            (triangles.len() * size_of::<GpuTriangle>()) as u64,
        )?;
        // A binding cannot be empty: an empty tree gets one unused element of each.
        if nodes.is_empty() {
            nodes.push(GpuNode::default().to_words());
        }
        if triangles.is_empty() {
            triangles.push(GpuTriangle::default().to_words());
        }
        let buffer = |label, contents: &[u8]| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: wgpu::BufferUsages::STORAGE,
            })
        };
        self.tree = Some(TreeBuffers {
            nodes: buffer("heat map nodes", bytemuck::cast_slice(&nodes)),
            triangles: buffer("heat map triangles", bytemuck::cast_slice(&triangles)),
            node_count,
        });
        Ok(())
    }

    /// Records the two passes for `frame` into `encoder`: the counts of `metric` coloured on
    /// a scale up to `fixed_max`, or up to the image's largest count when `None`.
    ///
    /// # Errors
    /// [`HeatMapError::NoTree`] before [`upload`](Self::upload); [`HeatMapError::TooBig`]
    /// for an image beyond the device's texture or buffer limits;
    /// [`HeatMapError::BadCamera`] for a non-finite eye.
    pub fn dispatch(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        frame: &RayFrame,
        metric: Metric,
        fixed_max: Option<u32>,
    ) -> Result<(), HeatMapError> {
        let tree = self.tree.as_ref().ok_or(HeatMapError::NoTree)?;
        let params = Params::new(frame, metric, fixed_max, tree.node_count)
            .ok_or(HeatMapError::BadCamera)?;
        let size = [frame.width, frame.height];
        if self.target.as_ref().is_none_or(|t| t.size != size) {
            self.target = Some(make_target(device, size)?);
        }
        let (Some(tree), Some(target)) = (self.tree.as_ref(), self.target.as_ref()) else {
            return Err(HeatMapError::NoTree);
        };
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        encoder.clear_buffer(&self.maxima, 0, None);
        let trace_group = bind_group(
            device,
            &self.trace_pipeline,
            &[
                self.params.as_entire_binding(),
                tree.nodes.as_entire_binding(),
                tree.triangles.as_entire_binding(),
                target.traces.as_entire_binding(),
                self.maxima.as_entire_binding(),
            ],
        );
        let colorize_group = bind_group(
            device,
            &self.colorize_pipeline,
            &[
                self.params.as_entire_binding(),
                target.traces.as_entire_binding(),
                self.maxima.as_entire_binding(),
                wgpu::BindingResource::TextureView(&target.storage_view),
            ],
        );
        let groups = [size[0].div_ceil(WORKGROUP), size[1].div_ceil(WORKGROUP)];
        for (pipeline, group) in [
            (&self.trace_pipeline, &trace_group),
            (&self.colorize_pipeline, &colorize_group),
        ] {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("heat map"),
                timestamp_writes: None,
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, group, &[]);
            pass.dispatch_workgroups(groups[0], groups[1], 1);
        }
        // The staging buffer can be copied into unless it is being mapped or is mapped; a
        // copy recorded earlier but not yet mapped is overwritten by this newer one.
        let state = self.readback.load(Ordering::Acquire);
        if state == IDLE || state == COPIED {
            encoder.copy_buffer_to_buffer(&self.maxima, 0, &self.maxima_staging, 0, 8);
            self.readback.store(COPIED, Ordering::Release);
        }
        self.metric = metric;
        Ok(())
    }

    /// Starts reading back the largest counts copied by the last [`dispatch`](Self::dispatch);
    /// call it once the encoder given to `dispatch` has been submitted (e.g. on the next
    /// frame). [`largest_count`](Self::largest_count) shows the value once it arrives.
    pub fn after_submit(&self) {
        if self
            .readback
            .compare_exchange(COPIED, MAPPING, Ordering::AcqRel, Ordering::Acquire)
            .is_ok()
        {
            let state = Arc::clone(&self.readback);
            self.maxima_staging
                .slice(..)
                .map_async(wgpu::MapMode::Read, move |result| {
                    state.store(
                        if result.is_ok() { MAPPED } else { IDLE },
                        Ordering::Release,
                    );
                });
        }
    }

    /// The largest count of the last dispatched metric in the latest image whose read-back
    /// arrived (for the legend when the scale follows the image), or `None` before any.
    pub fn largest_count(&mut self) -> Option<u32> {
        if self.readback.load(Ordering::Acquire) == MAPPED {
            let slice = self.maxima_staging.slice(..);
            if let Ok(view) = slice.get_mapped_range() {
                let words: &[u32] = bytemuck::cast_slice(&view);
                self.last_maxima = Some([words[0], words[1]]);
            }
            self.maxima_staging.unmap();
            self.readback.store(IDLE, Ordering::Release);
        }
        self.last_maxima.map(|m| m[self.metric.index() as usize])
    }

    /// The coloured image's texture (sRGB view), once a dispatch made one.
    pub fn texture_view(&self) -> Option<&wgpu::TextureView> {
        self.target.as_ref().map(|t| &t.display_view)
    }

    /// Shows the coloured image in egui: registers its texture with the renderer, or, given
    /// the id of an earlier registration, points that id at the current texture (which a
    /// change of size replaces). Call after each dispatch; `None` before the first.
    pub fn register(
        &self,
        renderer: &mut egui_wgpu::Renderer,
        device: &wgpu::Device,
        previous: Option<egui::TextureId>,
    ) -> Option<egui::TextureId> {
        let view = self.texture_view()?;
        Some(match previous {
            Some(id) => {
                renderer.update_egui_texture_from_wgpu_texture(
                    device,
                    view,
                    wgpu::FilterMode::Nearest,
                    id,
                );
                id
            }
            None => renderer.register_native_texture(device, view, wgpu::FilterMode::Nearest),
        })
    }
}
