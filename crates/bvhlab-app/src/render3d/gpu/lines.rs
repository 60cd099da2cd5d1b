//! The line layers: depth-tested segments (boxes, splits) and overlay segments drawn over
//! everything (the ray, gizmos), both as screen-space quads. Shader: `lines.wgsl`.

use eframe::wgpu;

use super::frame::Line3d;
use super::instances::InstanceBuffers;
use super::pipeline::{DepthUse, PipelineSpec, create_pipeline};

/// A [`Line3d`] per instance.
const LINES: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: size_of::<Line3d>() as u64,
    step_mode: wgpu::VertexStepMode::Instance,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x4, 3 => Float32],
};

/// Vertices per line: two triangles.
const QUAD_VERTICES: u32 = 6;

/// The two line pipelines and their instances.
pub(crate) struct LineLayers {
    depth_tested: wgpu::RenderPipeline,
    overlay: wgpu::RenderPipeline,
    lines: InstanceBuffers,
    overlay_lines: InstanceBuffers,
}

impl LineLayers {
    pub fn new(device: &wgpu::Device, layout: &wgpu::PipelineLayout, samples: u32) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("view3d lines.wgsl"),
            source: wgpu::ShaderSource::Wgsl(include_str!("lines.wgsl").into()),
        });
        let pipeline = |label, depth| {
            let spec = PipelineSpec {
                label,
                module: &module,
                vertex_entry: "vs_line",
                fragment_entry: "fs_line",
                buffer: LINES,
                cull: None,
                depth,
                blend: true,
            };
            create_pipeline(device, layout, spec, samples)
        };
        Self {
            depth_tested: pipeline("view3d lines", DepthUse::Write),
            overlay: pipeline("view3d overlay lines", DepthUse::Ignore),
            lines: InstanceBuffers::new("view3d lines", size_of::<Line3d>()),
            overlay_lines: InstanceBuffers::new("view3d overlay lines", size_of::<Line3d>()),
        }
    }

    /// Queues this frame's lines.
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        lines: &[Line3d],
        overlay_lines: &[Line3d],
    ) {
        self.lines.upload(device, queue, lines);
        self.overlay_lines.upload(device, queue, overlay_lines);
    }

    /// Draws the depth-tested lines.
    pub fn draw_depth_tested(&self, pass: &mut wgpu::RenderPass<'_>) {
        if !self.lines.is_empty() {
            pass.set_pipeline(&self.depth_tested);
            self.lines.draw(pass, QUAD_VERTICES);
        }
    }

    /// Draws the overlay lines.
    pub fn draw_overlay(&self, pass: &mut wgpu::RenderPass<'_>) {
        if !self.overlay_lines.is_empty() {
            pass.set_pipeline(&self.overlay);
            self.overlay_lines.draw(pass, QUAD_VERTICES);
        }
    }

    /// Bytes of GPU memory the lines' buffers take.
    pub fn gpu_bytes(&self) -> u64 {
        self.lines.gpu_bytes() + self.overlay_lines.gpu_bytes()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_attributes_read_the_fields_of_line3d() {
        let offsets = LINES
            .attributes
            .iter()
            .map(|a| a.offset as usize)
            .collect::<Vec<_>>();
        let fields = [
            std::mem::offset_of!(Line3d, a),
            std::mem::offset_of!(Line3d, b),
            std::mem::offset_of!(Line3d, color),
            std::mem::offset_of!(Line3d, width_px),
        ];
        assert_eq!(offsets, fields);
    }
}
