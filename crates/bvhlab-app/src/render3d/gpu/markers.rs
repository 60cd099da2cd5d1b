//! The marker layer: screen-facing discs over everything (hit points, query points).
//! Shader: `markers.wgsl`.

use eframe::wgpu;

use super::frame::Marker;
use super::instances::InstanceBuffers;
use super::pipeline::{DepthUse, PipelineSpec, create_pipeline};

/// A [`Marker`] per instance.
const MARKERS: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: size_of::<Marker>() as u64,
    step_mode: wgpu::VertexStepMode::Instance,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32, 2 => Float32x4],
};

/// The pipeline and this frame's markers.
pub(crate) struct MarkerLayer {
    pipeline: wgpu::RenderPipeline,
    markers: InstanceBuffers,
}

impl MarkerLayer {
    pub fn new(device: &wgpu::Device, layout: &wgpu::PipelineLayout, samples: u32) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("view3d markers.wgsl"),
            source: wgpu::ShaderSource::Wgsl(include_str!("markers.wgsl").into()),
        });
        let spec = PipelineSpec {
            label: "view3d markers",
            module: &module,
            vertex_entry: "vs_marker",
            fragment_entry: "fs_marker",
            buffer: MARKERS,
            cull: None,
            depth: DepthUse::Ignore,
            blend: true,
        };
        Self {
            pipeline: create_pipeline(device, layout, spec, samples),
            markers: InstanceBuffers::new("view3d markers", size_of::<Marker>()),
        }
    }

    /// Queues this frame's markers.
    pub fn prepare(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, markers: &[Marker]) {
        self.markers.upload(device, queue, markers);
    }

    /// Draws them.
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        if !self.markers.is_empty() {
            pass.set_pipeline(&self.pipeline);
            self.markers.draw(pass, 6);
        }
    }

    /// Bytes of GPU memory the buffers take.
    pub fn gpu_bytes(&self) -> u64 {
        self.markers.gpu_bytes()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_attributes_read_the_fields_of_marker() {
        let offsets = MARKERS
            .attributes
            .iter()
            .map(|a| a.offset as usize)
            .collect::<Vec<_>>();
        let fields = [
            std::mem::offset_of!(Marker, pos),
            std::mem::offset_of!(Marker, radius_px),
            std::mem::offset_of!(Marker, color),
        ];
        assert_eq!(offsets, fields);
    }
}
