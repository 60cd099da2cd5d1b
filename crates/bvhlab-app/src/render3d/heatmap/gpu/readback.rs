//! Read-backs that wait for the GPU, natively: the traces, counts and image of the last
//! dispatch, for tests and measurements (a web page cannot block on the GPU).

use eframe::wgpu;

use super::GpuHeatMap;

impl GpuHeatMap {
    /// Every pixel's `[nodes visited, primitive tests, hit index (u32::MAX for none), hit t
    /// (f32 bits)]` from the last dispatch (submitted), row-major from the top left.
    ///
    /// # Errors
    /// When nothing was dispatched, or the read-back fails.
    pub fn read_traces(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<Vec<[u32; 4]>, String> {
        let target = self.target.as_ref().ok_or("nothing dispatched")?;
        let bytes = read_buffer(device, queue, &target.traces)?;
        Ok(bytemuck::cast_slice(&bytes).to_vec())
    }

    /// The last dispatch's counts of its metric, row-major from the top left.
    ///
    /// # Errors
    /// As [`read_traces`](Self::read_traces).
    pub fn read_counts(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<Vec<u32>, String> {
        let metric = self.metric.index() as usize;
        Ok(self
            .read_traces(device, queue)?
            .iter()
            .map(|t| t[metric])
            .collect())
    }

    /// The coloured image as RGBA bytes, row-major from the top left.
    ///
    /// # Errors
    /// As [`read_traces`](Self::read_traces).
    pub fn read_image(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<Vec<[u8; 4]>, String> {
        let target = self.target.as_ref().ok_or("nothing dispatched")?;
        let [w, h] = target.size;
        let row = (w * 4).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT)
            * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("heat map image read-back"),
            size: u64::from(row) * u64::from(h),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        encoder.copy_texture_to_buffer(
            target.texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(row),
                    rows_per_image: Some(h),
                },
            },
            wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
        );
        queue.submit([encoder.finish()]);
        let bytes = read_buffer(device, queue, &buffer)?;
        Ok(bytes
            .chunks(row as usize)
            .flat_map(|r| {
                r[..w as usize * 4]
                    .chunks(4)
                    .map(|p| [p[0], p[1], p[2], p[3]])
            })
            .collect())
    }
}

/// Copies a buffer into a mappable one and reads it, waiting for the GPU.
fn read_buffer(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    source: &wgpu::Buffer,
) -> Result<Vec<u8>, String> {
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("heat map read-back"),
        size: source.size(),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    encoder.copy_buffer_to_buffer(source, 0, &staging, 0, source.size());
    queue.submit([encoder.finish()]);
    staging.map_async(wgpu::MapMode::Read, .., |_| {});
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| e.to_string())?;
    let bytes = staging
        .get_mapped_range(..)
        .map_err(|e| e.to_string())?
        .to_vec();
    staging.unmap();
    Ok(bytes)
}
