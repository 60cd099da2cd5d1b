//! The offscreen images the 3D view draws into: colour (multisampled, then resolved to a
//! single-sample texture others read) and depth, made again whenever the size changes.

use eframe::wgpu;

use super::pipeline::{COLOR_FORMAT, DEPTH_FORMAT};

/// The textures for one size.
pub(crate) struct Targets {
    pub size: [u32; 2],
    /// The multisampled colour drawn into, when drawing with more than one sample.
    multisampled: Option<wgpu::TextureView>,
    /// The finished image: drawn into directly at one sample, else the resolve target.
    pub color: wgpu::Texture,
    pub color_view: wgpu::TextureView,
    pub depth_view: wgpu::TextureView,
}

impl Targets {
    pub fn new(device: &wgpu::Device, size: [u32; 2], samples: u32) -> Self {
        let extent = wgpu::Extent3d {
            width: size[0],
            height: size[1],
            depth_or_array_layers: 1,
        };
        let texture = |label, format, sample_count, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: extent,
                mip_level_count: 1,
                sample_count,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let color = texture(
            "view3d colour",
            COLOR_FORMAT,
            1,
            wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
        );
        let multisampled = (samples > 1).then(|| {
            texture(
                "view3d colour (multisampled)",
                COLOR_FORMAT,
                samples,
                wgpu::TextureUsages::RENDER_ATTACHMENT,
            )
            .create_view(&wgpu::TextureViewDescriptor::default())
        });
        let depth = texture(
            "view3d depth",
            DEPTH_FORMAT,
            samples,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        Self {
            size,
            multisampled,
            color_view: color.create_view(&wgpu::TextureViewDescriptor::default()),
            color,
            depth_view: depth.create_view(&wgpu::TextureViewDescriptor::default()),
        }
    }

    /// The colour attachment of a pass that clears to `clear` and leaves the finished image
    /// in [`Self::color`].
    pub fn color_attachment(&self, clear: wgpu::Color) -> wgpu::RenderPassColorAttachment<'_> {
        let (view, resolve_target, store) = match &self.multisampled {
            Some(samples) => (samples, Some(&self.color_view), wgpu::StoreOp::Discard),
            None => (&self.color_view, None, wgpu::StoreOp::Store),
        };
        wgpu::RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(clear),
                store,
            },
        }
    }

    /// The depth attachment of a pass: cleared to the far plane, not kept afterwards.
    pub fn depth_attachment(&self) -> wgpu::RenderPassDepthStencilAttachment<'_> {
        wgpu::RenderPassDepthStencilAttachment {
            view: &self.depth_view,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(1.0),
                store: wgpu::StoreOp::Discard,
            }),
            stencil_ops: None,
        }
    }
}
