//! The translucent-triangle layer (split planes, cells' faces): blended, depth-tested, writing
//! no depth, double-sided. Shader: `triangles.wgsl`.

use eframe::wgpu;

use super::frame::ColorTriangle;
use super::instances::InstanceBuffers;
use super::mesh::COLOR_TRIANGLES;
use super::pipeline::{DepthUse, PipelineSpec, create_pipeline};

/// The pipeline and this frame's triangles.
pub(crate) struct TriangleLayer {
    pipeline: wgpu::RenderPipeline,
    triangles: InstanceBuffers,
}

impl TriangleLayer {
    pub fn new(device: &wgpu::Device, layout: &wgpu::PipelineLayout, samples: u32) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("view3d triangles.wgsl"),
            source: wgpu::ShaderSource::Wgsl(include_str!("triangles.wgsl").into()),
        });
        let spec = PipelineSpec {
            label: "view3d translucent triangles",
            module: &module,
            vertex_entry: "vs_triangle",
            fragment_entry: "fs_triangle",
            buffer: COLOR_TRIANGLES,
            cull: None,
            depth: DepthUse::Test,
            blend: true,
        };
        Self {
            pipeline: create_pipeline(device, layout, spec, samples),
            triangles: InstanceBuffers::new("view3d triangles", size_of::<ColorTriangle>()),
        }
    }

    /// Queues this frame's triangles.
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        triangles: &[ColorTriangle],
    ) {
        self.triangles.upload(device, queue, triangles);
    }

    /// Draws them.
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        if !self.triangles.is_empty() {
            pass.set_pipeline(&self.pipeline);
            self.triangles.draw(pass, 3);
        }
    }

    /// Bytes of GPU memory the buffers take.
    pub fn gpu_bytes(&self) -> u64 {
        self.triangles.gpu_bytes()
    }
}
