//! The mesh layer: the mesh's GPU copy (uploaded once per revision, cut to the device's
//! buffer limit), drawn opaque or as x-ray, and the highlighted triangles over it.
//! Shaders: `mesh.wgsl`.

use eframe::wgpu;
use wgpu::util::DeviceExt as _;

use super::frame::{ColorTriangle, Frame3d, MeshData};
use super::instances::InstanceBuffers;
use super::mesh_chunks::{MeshUploadError, split_mesh};
use super::pipeline::{DepthUse, PipelineSpec, create_pipeline};

/// The mesh's vertex buffer: positions only (normals come from the fragment shader).
const POSITIONS: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: 12,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3],
};

/// A [`ColorTriangle`] per instance (highlights here, translucent triangles elsewhere).
pub(crate) const COLOR_TRIANGLES: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: size_of::<ColorTriangle>() as u64,
    step_mode: wgpu::VertexStepMode::Instance,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x3, 3 => Float32x4],
};

/// One piece of the mesh on the GPU, drawn with one indexed draw.
struct GpuChunk {
    /// Its own vertices, or `None` to use the mesh's shared ones.
    vertices: Option<wgpu::Buffer>,
    indices: wgpu::Buffer,
    index_count: u32,
}

/// The mesh on the GPU.
struct GpuMesh {
    shared_vertices: Option<wgpu::Buffer>,
    chunks: Vec<GpuChunk>,
}

impl GpuMesh {
    fn upload(device: &wgpu::Device, mesh: &MeshData) -> Result<Self, MeshUploadError> {
        let limit = device.limits().max_buffer_size;
        let (shared, pieces) = split_mesh(&mesh.positions, &mesh.indices, limit)?;
        let vertex_buffer = |positions: &[[f32; 3]]| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("view3d mesh vertices"),
                contents: bytemuck::cast_slice(positions),
                usage: wgpu::BufferUsages::VERTEX,
            })
        };
        let shared_vertices =
            (shared && !pieces.is_empty()).then(|| vertex_buffer(&mesh.positions));
        let chunks = pieces
            .iter()
            .map(|piece| GpuChunk {
                vertices: piece.positions.as_deref().map(vertex_buffer),
                indices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("view3d mesh indices"),
                    contents: bytemuck::cast_slice(&piece.indices),
                    usage: wgpu::BufferUsages::INDEX,
                }),
                index_count: (piece.indices.len() * 3) as u32,
            })
            .collect();
        Ok(Self {
            shared_vertices,
            chunks,
        })
    }

    fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        for chunk in &self.chunks {
            let Some(vertices) = chunk.vertices.as_ref().or(self.shared_vertices.as_ref()) else {
                continue;
            };
            pass.set_vertex_buffer(0, vertices.slice(..));
            pass.set_index_buffer(chunk.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..chunk.index_count, 0, 0..1);
        }
    }

    fn gpu_bytes(&self) -> u64 {
        let chunks: u64 = self
            .chunks
            .iter()
            .map(|c| c.indices.size() + c.vertices.as_ref().map_or(0, wgpu::Buffer::size))
            .sum();
        chunks + self.shared_vertices.as_ref().map_or(0, wgpu::Buffer::size)
    }
}

/// The mesh's pipelines, its GPU copy and this frame's highlights.
pub(crate) struct MeshLayer {
    opaque: wgpu::RenderPipeline,
    xray_back: wgpu::RenderPipeline,
    xray_front: wgpu::RenderPipeline,
    highlight: wgpu::RenderPipeline,
    /// The revision last uploaded and what came of it (kept on failure, so a bad mesh is
    /// checked once, not every frame).
    uploaded: Option<(u64, Result<GpuMesh, MeshUploadError>)>,
    highlights: InstanceBuffers,
    highlight_scratch: Vec<ColorTriangle>,
}

impl MeshLayer {
    pub fn new(device: &wgpu::Device, layout: &wgpu::PipelineLayout, samples: u32) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("view3d mesh.wgsl"),
            source: wgpu::ShaderSource::Wgsl(include_str!("mesh.wgsl").into()),
        });
        let mesh = |label, cull, depth, blend| {
            let spec = PipelineSpec {
                label,
                module: &module,
                vertex_entry: "vs_mesh",
                fragment_entry: "fs_lit",
                buffer: POSITIONS,
                cull,
                depth,
                blend,
            };
            create_pipeline(device, layout, spec, samples)
        };
        // X-ray draws back faces, then (after the translucent triangles) front faces: the
        // right back-to-front order for convex meshes, and a fixed one for the rest.
        let opaque = mesh("view3d mesh opaque", None, DepthUse::Write, false);
        let xray_back = mesh(
            "view3d mesh x-ray back",
            Some(wgpu::Face::Front),
            DepthUse::Test,
            true,
        );
        let xray_front = mesh(
            "view3d mesh x-ray front",
            Some(wgpu::Face::Back),
            DepthUse::Test,
            true,
        );
        let highlight = create_pipeline(
            device,
            layout,
            PipelineSpec {
                label: "view3d highlights",
                module: &module,
                vertex_entry: "vs_highlight",
                fragment_entry: "fs_lit",
                buffer: COLOR_TRIANGLES,
                cull: None,
                depth: DepthUse::TestNudged,
                blend: true,
            },
            samples,
        );
        Self {
            opaque,
            xray_back,
            xray_front,
            highlight,
            uploaded: None,
            highlights: InstanceBuffers::new("view3d highlights", size_of::<ColorTriangle>()),
            highlight_scratch: Vec::new(),
        }
    }

    /// Uploads the mesh if its revision is new, and this frame's highlights.
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        frame: &Frame3d,
    ) -> Result<(), MeshUploadError> {
        self.highlight_scratch.clear();
        let Some(mesh) = frame.mesh.as_deref() else {
            self.highlights
                .upload(device, queue, &self.highlight_scratch);
            return Ok(());
        };
        if self
            .uploaded
            .as_ref()
            .is_none_or(|(r, _)| *r != mesh.revision)
        {
            // Drop the old copy first, so two copies of a big mesh never coexist.
            self.uploaded = None;
            self.uploaded = Some((mesh.revision, GpuMesh::upload(device, mesh)));
        }
        // Highlights naming a triangle the mesh lacks are left out.
        self.highlight_scratch
            .extend(frame.highlights.iter().filter_map(|&(index, color)| {
                let [a, b, c] = mesh.triangle(index)?;
                Some(ColorTriangle { a, b, c, color })
            }));
        self.highlights
            .upload(device, queue, &self.highlight_scratch);
        match &self.uploaded {
            Some((_, Err(error))) => Err(error.clone()),
            _ => Ok(()),
        }
    }

    fn gpu_mesh(&self, frame: &Frame3d) -> Option<&GpuMesh> {
        let revision = frame.mesh.as_ref()?.revision;
        match &self.uploaded {
            Some((r, Ok(mesh))) if *r == revision => Some(mesh),
            _ => None,
        }
    }

    /// Draws the mesh opaque (nothing when it is x-ray).
    pub fn draw_opaque(&self, pass: &mut wgpu::RenderPass<'_>, frame: &Frame3d) {
        if let Some(mesh) = self.gpu_mesh(frame).filter(|_| !frame.is_xray()) {
            pass.set_pipeline(&self.opaque);
            mesh.draw(pass);
        }
    }

    /// Draws the x-ray mesh's back faces (`back`) or front faces (nothing when opaque).
    pub fn draw_xray(&self, pass: &mut wgpu::RenderPass<'_>, frame: &Frame3d, back: bool) {
        if let Some(mesh) = self.gpu_mesh(frame).filter(|_| frame.is_xray()) {
            pass.set_pipeline(if back {
                &self.xray_back
            } else {
                &self.xray_front
            });
            mesh.draw(pass);
        }
    }

    /// Draws the highlighted triangles.
    pub fn draw_highlights(&self, pass: &mut wgpu::RenderPass<'_>) {
        if !self.highlights.is_empty() {
            pass.set_pipeline(&self.highlight);
            self.highlights.draw(pass, 3);
        }
    }

    /// Bytes of GPU memory the mesh's buffers take (0 when there is none).
    pub fn mesh_gpu_bytes(&self) -> u64 {
        match &self.uploaded {
            Some((_, Ok(mesh))) => mesh.gpu_bytes(),
            _ => 0,
        }
    }

    /// Bytes of GPU memory the highlights' buffers take.
    pub fn highlight_gpu_bytes(&self) -> u64 {
        self.highlights.gpu_bytes()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_attributes_read_the_fields_of_color_triangle() {
        let offsets = COLOR_TRIANGLES
            .attributes
            .iter()
            .map(|a| a.offset as usize)
            .collect::<Vec<_>>();
        let fields = [
            std::mem::offset_of!(ColorTriangle, a),
            std::mem::offset_of!(ColorTriangle, b),
            std::mem::offset_of!(ColorTriangle, c),
            std::mem::offset_of!(ColorTriangle, color),
        ];
        assert_eq!(offsets, fields);
    }
}
