//! How the 3D view's pipelines are made: one description per pipeline (shader entry points,
//! instance layout, culling, depth behaviour, blending), the formats they all share.

use eframe::wgpu;

/// The offscreen colour format: 8-bit channels holding sRGB-encoded values, as egui's are.
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// The depth format (exact float depth, supported by WebGPU and WebGL2 alike).
pub(crate) const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// How a pipeline uses the depth buffer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum DepthUse {
    /// Opaque geometry: test and write.
    Write,
    /// Translucent geometry: test against what is drawn, write nothing.
    Test,
    /// Drawn exactly over earlier geometry (highlights): test, pulled towards the eye.
    TestNudged,
    /// Overlays: no test, no write.
    Ignore,
}

/// One pipeline's description.
pub(crate) struct PipelineSpec<'a> {
    pub label: &'a str,
    pub module: &'a wgpu::ShaderModule,
    pub vertex_entry: &'a str,
    pub fragment_entry: &'a str,
    pub buffer: wgpu::VertexBufferLayout<'a>,
    pub cull: Option<wgpu::Face>,
    pub depth: DepthUse,
    /// Straight-alpha colours blended into the premultiplied target (alpha 1 replaces).
    pub blend: bool,
}

/// Straight-alpha sources over a premultiplied destination: colour `a·src + (1 − a)·dst`,
/// alpha `a + (1 − a)·dst_a`. Cleared with a premultiplied background, the image stays
/// premultiplied, which is what egui blends with.
const BLEND: wgpu::BlendState = wgpu::BlendState {
    color: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::SrcAlpha,
        dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
        operation: wgpu::BlendOperation::Add,
    },
    alpha: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
        operation: wgpu::BlendOperation::Add,
    },
};

/// Creates the pipeline `spec` describes, for targets with `samples` samples per pixel.
pub(crate) fn create_pipeline(
    device: &wgpu::Device,
    layout: &wgpu::PipelineLayout,
    spec: PipelineSpec<'_>,
    samples: u32,
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(spec.label),
        layout: Some(layout),
        vertex: wgpu::VertexState {
            module: spec.module,
            entry_point: Some(spec.vertex_entry),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            buffers: &[Some(spec.buffer)],
        },
        primitive: wgpu::PrimitiveState {
            topology: wgpu::PrimitiveTopology::TriangleList,
            front_face: wgpu::FrontFace::Ccw,
            cull_mode: spec.cull,
            ..wgpu::PrimitiveState::default()
        },
        depth_stencil: Some(depth_state(spec.depth)),
        multisample: wgpu::MultisampleState {
            count: samples,
            ..wgpu::MultisampleState::default()
        },
        fragment: Some(wgpu::FragmentState {
            module: spec.module,
            entry_point: Some(spec.fragment_entry),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format: COLOR_FORMAT,
                blend: spec.blend.then_some(BLEND),
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}

fn depth_state(depth: DepthUse) -> wgpu::DepthStencilState {
    let (write, compare) = match depth {
        DepthUse::Write => (true, wgpu::CompareFunction::Less),
        DepthUse::Test => (false, wgpu::CompareFunction::Less),
        DepthUse::TestNudged => (false, wgpu::CompareFunction::LessEqual),
        DepthUse::Ignore => (false, wgpu::CompareFunction::Always),
    };
    // The same triangle drawn twice gives (nearly) the same depths; the nudge, a few units of
    // depth precision plus one of the triangle's depth slope, settles the tie for the second.
    let bias = if depth == DepthUse::TestNudged {
        wgpu::DepthBiasState {
            constant: -4,
            slope_scale: -1.0,
            clamp: 0.0,
        }
    } else {
        wgpu::DepthBiasState::default()
    };
    wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(write),
        depth_compare: Some(compare),
        stencil: wgpu::StencilState::default(),
        bias,
    }
}
