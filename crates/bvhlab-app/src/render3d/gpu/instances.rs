//! Per-frame instance data (lines, translucent triangles, markers, highlights) in GPU vertex
//! buffers that grow as needed and never shrink, so a steady scene allocates nothing.
//!
//! A single buffer may not exceed the device's `max_buffer_size`; more instances than fit go
//! to further buffers, drawn with further draw calls.

use bytemuck::Pod;
use eframe::wgpu;

/// Instances of one `#[repr(C)]` type, in as many buffers as their bytes need.
pub(crate) struct InstanceBuffers {
    label: &'static str,
    stride: u64,
    buffers: Vec<wgpu::Buffer>,
    /// How many instances the last upload put in each buffer (a prefix of `buffers`).
    counts: Vec<u32>,
}

impl InstanceBuffers {
    /// Empty, for instances of `stride` bytes.
    pub fn new(label: &'static str, stride: usize) -> Self {
        Self {
            label,
            stride: stride as u64,
            buffers: Vec::new(),
            counts: Vec::new(),
        }
    }

    /// Queues `items` for the next submission, replacing the last upload.
    pub fn upload<T: Pod>(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, items: &[T]) {
        debug_assert_eq!(size_of::<T>() as u64, self.stride);
        self.counts.clear();
        let max_bytes = device.limits().max_buffer_size;
        let per_buffer = usize::try_from((max_bytes / self.stride).max(1)).unwrap_or(usize::MAX);
        for (i, part) in items.chunks(per_buffer).enumerate() {
            let bytes: &[u8] = bytemuck::cast_slice(part);
            let needed = bytes.len() as u64;
            if self.buffers.get(i).is_none_or(|b| b.size() < needed) {
                // Grow to the next power of two, so a slowly growing scene reallocates rarely.
                let size = needed
                    .next_power_of_two()
                    .min(max_bytes / wgpu::COPY_BUFFER_ALIGNMENT * wgpu::COPY_BUFFER_ALIGNMENT)
                    .max(needed);
                let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(self.label),
                    size,
                    usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                if i < self.buffers.len() {
                    self.buffers[i] = buffer;
                } else {
                    self.buffers.push(buffer);
                }
            }
            queue.write_buffer(&self.buffers[i], 0, bytes);
            self.counts.push(part.len() as u32);
        }
    }

    /// Whether the last upload was empty.
    pub fn is_empty(&self) -> bool {
        self.counts.is_empty()
    }

    /// Draws every instance of the last upload, `vertices` vertices each, from vertex buffer
    /// slot 0 (the pipeline and bind group must be set).
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>, vertices: u32) {
        for (buffer, &count) in self.buffers.iter().zip(&self.counts) {
            pass.set_vertex_buffer(0, buffer.slice(..u64::from(count) * self.stride));
            pass.draw(0..vertices, 0..count);
        }
    }

    /// Bytes of GPU memory the buffers take.
    pub fn gpu_bytes(&self) -> u64 {
        self.buffers.iter().map(wgpu::Buffer::size).sum()
    }
}
