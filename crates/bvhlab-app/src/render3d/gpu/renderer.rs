//! [`Renderer3d`]: draws a [`Frame3d`] into its own offscreen image with wgpu, the same way
//! inside egui (through the paint callback), on the web and headless in tests.

use eframe::wgpu;

use super::frame::Frame3d;
use super::lines::LineLayers;
use super::markers::MarkerLayer;
use super::mesh::MeshLayer;
use super::mesh_chunks::MeshUploadError;
use super::pipeline::{COLOR_FORMAT, DEPTH_FORMAT};
use super::targets::Targets;
use super::triangles::TriangleLayer;
use super::view_uniform::{ViewBinding, ViewUniform};

/// Samples per pixel of the offscreen image unless asked otherwise. Four is the count every
/// WebGPU device supports for its formats, and smooths the thick lines' and the mesh's edges
/// (the markers smooth their own).
pub const DEFAULT_SAMPLES: u32 = 4;

/// Samples per pixel for the 3D images on `adapter`: [`DEFAULT_SAMPLES`] where the adapter
/// supports them, but 1 on a CPU adapter (lavapipe, `SwiftShader`), where four samples cost
/// 2.5 to 4 times as much per frame (measured on lavapipe: 800 × 600 with a million triangles,
/// about 85 ms at one sample against 200 to 400 at four).
pub fn preferred_samples(adapter: &wgpu::Adapter) -> u32 {
    if adapter.get_info().device_type == wgpu::DeviceType::Cpu {
        return 1;
    }
    let supports = |format| {
        adapter
            .get_texture_format_features(format)
            .flags
            .sample_count_supported(DEFAULT_SAMPLES)
    };
    if supports(COLOR_FORMAT) && supports(DEPTH_FORMAT) {
        DEFAULT_SAMPLES
    } else {
        1
    }
}

/// The 3D view's renderer: pipelines, the mesh's GPU copy, per-frame buffers and the
/// offscreen colour and depth images. Keep one per view and call [`Self::render`] each frame.
pub struct Renderer3d {
    samples: u32,
    view: ViewBinding,
    mesh: MeshLayer,
    lines: LineLayers,
    triangles: TriangleLayer,
    markers: MarkerLayer,
    targets: Option<Targets>,
}

impl Renderer3d {
    /// A renderer drawing with [`DEFAULT_SAMPLES`] samples per pixel.
    pub fn new(device: &wgpu::Device) -> Self {
        Self::with_samples(device, DEFAULT_SAMPLES)
    }

    /// A renderer drawing with `samples` samples per pixel (1, or a count the device supports
    /// for `Rgba8Unorm` and `Depth32Float`, such as 4).
    pub fn with_samples(device: &wgpu::Device, samples: u32) -> Self {
        let samples = samples.max(1);
        let view = ViewBinding::new(device);
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("view3d"),
            bind_group_layouts: &[Some(&view.layout)],
            immediate_size: 0,
        });
        Self {
            samples,
            mesh: MeshLayer::new(device, &layout, samples),
            lines: LineLayers::new(device, &layout, samples),
            triangles: TriangleLayer::new(device, &layout, samples),
            markers: MarkerLayer::new(device, &layout, samples),
            view,
            targets: None,
        }
    }

    /// Records the drawing of `frame` into the offscreen image, `size` pixels (clamped to
    /// between 1 and the device's largest texture), in `encoder`; buffer uploads are queued on
    /// `queue` and happen at the next submission, before the encoder's commands.
    ///
    /// # Errors
    ///
    /// A mesh that cannot be drawn (an index past its vertices, a device too small for it).
    /// Everything else in the frame is still drawn, without the mesh.
    pub fn render(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        size: [u32; 2],
        frame: &Frame3d,
    ) -> Result<(), MeshUploadError> {
        let largest = device.limits().max_texture_dimension_2d;
        let size = size.map(|s| s.clamp(1, largest));
        if self.targets.as_ref().is_none_or(|t| t.size != size) {
            self.targets = None;
            self.targets = Some(Targets::new(device, size, self.samples));
        }
        self.view.write(queue, &ViewUniform::new(frame, size));
        let mesh = self.mesh.prepare(device, queue, frame);
        self.lines
            .prepare(device, queue, &frame.lines, &frame.overlay_lines);
        self.triangles.prepare(device, queue, &frame.triangles);
        self.markers.prepare(device, queue, &frame.markers);
        let Some(targets) = &self.targets else {
            return mesh;
        };
        let [r, g, b, a] = frame.background.map(|c| f64::from(c.clamp(0.0, 1.0)));
        let clear = wgpu::Color {
            r: r * a,
            g: g * a,
            b: b * a,
            a,
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("view3d"),
            color_attachments: &[Some(targets.color_attachment(clear))],
            depth_stencil_attachment: Some(targets.depth_attachment()),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(0, &self.view.bind_group, &[]);
        // Opaque things first, so translucent ones are tested against them; translucent ones
        // in back-to-front layers; overlays last. See `Frame3d` for the order in words.
        self.mesh.draw_opaque(&mut pass, frame);
        self.lines.draw_depth_tested(&mut pass);
        self.mesh.draw_highlights(&mut pass);
        self.mesh.draw_xray(&mut pass, frame, true);
        self.triangles.draw(&mut pass);
        self.mesh.draw_xray(&mut pass, frame, false);
        self.lines.draw_overlay(&mut pass);
        self.markers.draw(&mut pass);
        mesh
    }

    /// The finished image (`Rgba8Unorm`, sRGB-encoded premultiplied colours), once something
    /// was rendered.
    pub fn color_texture(&self) -> Option<&wgpu::Texture> {
        self.targets.as_ref().map(|t| &t.color)
    }

    /// A view of [`Self::color_texture`].
    pub fn color_view(&self) -> Option<&wgpu::TextureView> {
        self.targets.as_ref().map(|t| &t.color_view)
    }

    /// The size of the image last rendered, in pixels.
    pub fn size(&self) -> Option<[u32; 2]> {
        self.targets.as_ref().map(|t| t.size)
    }

    /// Samples per pixel.
    pub fn samples(&self) -> u32 {
        self.samples
    }

    /// Bytes of GPU buffer memory the mesh takes (vertices and indices).
    pub fn mesh_gpu_bytes(&self) -> u64 {
        self.mesh.mesh_gpu_bytes()
    }

    /// Bytes of GPU buffer memory the per-frame instances take (lines, triangles, markers,
    /// highlights), at their current, grown-only capacity.
    pub fn instance_gpu_bytes(&self) -> u64 {
        self.mesh.highlight_gpu_bytes()
            + self.lines.gpu_bytes()
            + self.triangles.gpu_bytes()
            + self.markers.gpu_bytes()
    }
}
