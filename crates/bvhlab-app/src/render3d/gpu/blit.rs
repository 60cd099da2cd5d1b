//! Drawing a finished 3D image inside egui's render pass: a pipeline made for egui's target
//! (its format, sample count and depth buffer, which must all match egui's pass), and per view
//! a bind group naming that view's image. Shader: `blit.wgsl`.

use bytemuck::{Pod, Zeroable};
use eframe::wgpu;

/// What egui's render pass draws into: the blit pipeline must match it exactly.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EguiTarget {
    /// The colour format (`egui_wgpu::RenderState::target_format`).
    pub format: wgpu::TextureFormat,
    /// Samples per pixel: `NativeOptions::multisampling` natively (at least 1); 1 on the
    /// web, where eframe does not multisample.
    pub msaa_samples: u32,
    /// The depth format when the app asked eframe for a depth buffer
    /// (`NativeOptions::depth_buffer` / `WebOptions::depth_buffer` above 0), else `None`.
    pub depth_format: Option<wgpu::TextureFormat>,
}

impl EguiTarget {
    /// egui's target as eframe makes it with default options: `format`, one sample, no depth.
    pub fn new(format: wgpu::TextureFormat) -> Self {
        Self {
            format,
            msaa_samples: 1,
            depth_format: None,
        }
    }
}

/// Which part of the image the on-screen viewport shows, in 0..1 texture coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub(crate) struct BlitUniform {
    pub uv_min: [f32; 2],
    pub uv_max: [f32; 2],
}

/// The blit pipeline for one egui target.
pub(crate) struct BlitPipeline {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
}

impl BlitPipeline {
    pub fn new(device: &wgpu::Device, target: EguiTarget) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("view3d blit.wgsl"),
            source: wgpu::ShaderSource::Wgsl(include_str!("blit.wgsl").into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("view3d blit"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::VERTEX,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: wgpu::BufferSize::new(size_of::<BlitUniform>() as u64),
                    },
                    count: None,
                },
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("view3d blit"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let fragment_entry = if target.format.is_srgb() {
            "fs_linear"
        } else {
            "fs_gamma"
        };
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("view3d blit"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_blit"),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState::default(),
            // egui's pass may carry a depth buffer; the image is drawn over whatever it holds.
            depth_stencil: target.depth_format.map(|format| wgpu::DepthStencilState {
                format,
                depth_write_enabled: Some(false),
                depth_compare: Some(wgpu::CompareFunction::Always),
                stencil: wgpu::StencilState::default(),
                bias: wgpu::DepthBiasState::default(),
            }),
            multisample: wgpu::MultisampleState {
                count: target.msaa_samples.max(1),
                ..wgpu::MultisampleState::default()
            },
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some(fragment_entry),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: target.format,
                    // The image is premultiplied, as egui's colours are.
                    blend: Some(wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING),
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        Self { pipeline, layout }
    }
}

/// One view's side of the blit: its uniform and a bind group for its current image.
pub(crate) struct BlitBinding {
    uniform: wgpu::Buffer,
    bind_group: Option<wgpu::BindGroup>,
    /// The image size the bind group was made for (a new size means a new texture).
    bound_size: [u32; 2],
}

impl BlitBinding {
    pub fn new(device: &wgpu::Device) -> Self {
        Self {
            uniform: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("view3d blit"),
                size: size_of::<BlitUniform>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            bind_group: None,
            bound_size: [0, 0],
        }
    }

    /// Points the binding at `image` (of `size` pixels) and queues the part to show.
    pub fn update(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        blit: &BlitPipeline,
        image: &wgpu::TextureView,
        size: [u32; 2],
        shown: BlitUniform,
    ) {
        if self.bind_group.is_none() || self.bound_size != size {
            self.bind_group = Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("view3d blit"),
                layout: &blit.layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(image),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: self.uniform.as_entire_binding(),
                    },
                ],
            }));
            self.bound_size = size;
        }
        queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&shown));
    }

    /// Draws the image into egui's pass (whose viewport egui has set to the view's rectangle).
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'static>, blit: &BlitPipeline) {
        if let Some(bind_group) = &self.bind_group {
            pass.set_pipeline(&blit.pipeline);
            pass.set_bind_group(0, bind_group, &[]);
            pass.draw(0..3, 0..1);
        }
    }
}
