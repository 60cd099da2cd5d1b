//! The one uniform block every 3D shader reads (`struct View` at group 0, binding 0 in each
//! `.wgsl` file): the camera, the viewport's size and the mesh's colour.

use bytemuck::{Pod, Zeroable};
use eframe::wgpu;

use super::frame::Frame3d;

/// The uniform block, laid out as WGSL's `struct View` (a `mat4x4<f32>` then three
/// `vec4<f32>`: 112 bytes, no padding).
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub(crate) struct ViewUniform {
    /// World to clip space, column by column.
    pub view_proj: [[f32; 4]; 4],
    /// The eye in world space (w unused).
    pub eye: [f32; 4],
    /// Width, height, 1 / width, 1 / height, in pixels.
    pub viewport: [f32; 4],
    /// The mesh's colour (sRGB-encoded rgb, straight alpha).
    pub mesh_color: [f32; 4],
}

impl ViewUniform {
    /// The block for drawing `frame` into a `size`-pixel image.
    pub fn new(frame: &Frame3d, size: [u32; 2]) -> Self {
        let (w, h) = (size[0].max(1) as f32, size[1].max(1) as f32);
        let camera = &frame.camera;
        Self {
            view_proj: camera.view_projection(w / h).to_cols_array_2d(),
            eye: camera.eye().extend(1.0).to_array(),
            viewport: [w, h, 1.0 / w, 1.0 / h],
            mesh_color: frame.mesh_color,
        }
    }
}

/// The uniform buffer and the bind group that exposes it to every 3D pipeline.
pub(crate) struct ViewBinding {
    buffer: wgpu::Buffer,
    /// The layout every 3D pipeline is created with (group 0).
    pub layout: wgpu::BindGroupLayout,
    /// The bind group to set at group 0.
    pub bind_group: wgpu::BindGroup,
}

impl ViewBinding {
    /// A zeroed uniform buffer and its bind group.
    pub fn new(device: &wgpu::Device) -> Self {
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("view3d view uniform"),
            size: size_of::<ViewUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("view3d view"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: wgpu::BufferSize::new(size_of::<ViewUniform>() as u64),
                },
                count: None,
            }],
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("view3d view"),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: buffer.as_entire_binding(),
            }],
        });
        Self {
            buffer,
            layout,
            bind_group,
        }
    }

    /// Queues the block's new contents (applied at the next submission, before its commands).
    pub fn write(&self, queue: &wgpu::Queue, uniform: &ViewUniform) {
        queue.write_buffer(&self.buffer, 0, bytemuck::bytes_of(uniform));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render3d::gpu::blit::BlitUniform;

    /// The size and member offsets of struct `name` in the WGSL `source`, as naga lays it out.
    fn wgsl_layout(source: &str, name: &str) -> (u32, Vec<u32>) {
        let module = naga::front::wgsl::parse_str(source).expect("valid WGSL");
        module
            .types
            .iter()
            .find_map(|(_, ty)| match &ty.inner {
                naga::TypeInner::Struct { members, span } if ty.name.as_deref() == Some(name) => {
                    Some((*span, members.iter().map(|m| m.offset).collect()))
                }
                _ => None,
            })
            .expect("the struct is declared")
    }

    #[test]
    fn every_shaders_view_block_is_laid_out_as_the_rust_struct() {
        let rust = (
            size_of::<ViewUniform>() as u32,
            vec![
                std::mem::offset_of!(ViewUniform, view_proj) as u32,
                std::mem::offset_of!(ViewUniform, eye) as u32,
                std::mem::offset_of!(ViewUniform, viewport) as u32,
                std::mem::offset_of!(ViewUniform, mesh_color) as u32,
            ],
        );
        for source in [
            include_str!("mesh.wgsl"),
            include_str!("lines.wgsl"),
            include_str!("triangles.wgsl"),
            include_str!("markers.wgsl"),
        ] {
            assert_eq!(wgsl_layout(source, "View"), rust);
        }
    }

    #[test]
    fn the_blit_block_is_laid_out_as_the_rust_struct() {
        let rust = (
            size_of::<BlitUniform>() as u32,
            vec![
                std::mem::offset_of!(BlitUniform, uv_min) as u32,
                std::mem::offset_of!(BlitUniform, uv_max) as u32,
            ],
        );
        assert_eq!(wgsl_layout(include_str!("blit.wgsl"), "Blit"), rust);
    }
}
