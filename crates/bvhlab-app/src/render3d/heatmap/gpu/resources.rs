//! The heat map's GPU resources: buffers checked against the device's limits, the
//! per-image buffer and texture, pipelines and bind groups.

use eframe::wgpu;

use super::{HeatMapError, TRACE_BYTES, Target};

pub(super) fn check_buffer(
    device: &wgpu::Device,
    what: &'static str,
    size: u64,
) -> Result<(), HeatMapError> {
    let limits = device.limits();
    let limit = limits
        .max_storage_buffer_binding_size
        .min(limits.max_buffer_size);
    if size > limit {
        return Err(HeatMapError::TooBig { what, size, limit });
    }
    Ok(())
}

pub(super) fn make_target(device: &wgpu::Device, size: [u32; 2]) -> Result<Target, HeatMapError> {
    let side = device.limits().max_texture_dimension_2d;
    let largest = size[0].max(size[1]);
    if largest > side {
        return Err(HeatMapError::TooBig {
            what: "image",
            size: u64::from(largest),
            limit: u64::from(side),
        });
    }
    let trace_bytes = u64::from(size[0]) * u64::from(size[1]) * TRACE_BYTES;
    check_buffer(device, "pixel traces", trace_bytes)?;
    let traces = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("heat map traces"),
        size: trace_bytes,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("heat map image"),
        size: wgpu::Extent3d {
            width: size[0],
            height: size[1],
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let storage_view = texture.create_view(&wgpu::TextureViewDescriptor::default());
    // egui-wgpu 0.37 keeps its own textures as `Rgba8Unorm` and samples the sRGB-encoded
    // bytes as they are (it blends in gamma space), so the image is shown the same way: an
    // `Rgba8UnormSrgb` view would decode it and show it darker than the CPU's image.
    let display_view = texture.create_view(&wgpu::TextureViewDescriptor {
        format: Some(wgpu::TextureFormat::Rgba8Unorm),
        usage: Some(wgpu::TextureUsages::TEXTURE_BINDING),
        ..wgpu::TextureViewDescriptor::default()
    });
    Ok(Target {
        size,
        traces,
        texture,
        storage_view,
        display_view,
    })
}

pub(super) fn pipeline(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    entry: &str,
) -> wgpu::ComputePipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: None,
        module: &module,
        entry_point: Some(entry),
        compilation_options: wgpu::PipelineCompilationOptions::default(),
        cache: None,
    })
}

/// A bind group for group 0 of a pipeline, bindings numbered in order.
pub(super) fn bind_group(
    device: &wgpu::Device,
    pipeline: &wgpu::ComputePipeline,
    resources: &[wgpu::BindingResource<'_>],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry<'_>> = resources
        .iter()
        .enumerate()
        .map(|(i, resource)| wgpu::BindGroupEntry {
            binding: i as u32,
            resource: resource.clone(),
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("heat map"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &entries,
    })
}
