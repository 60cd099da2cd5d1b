//! Rendering without a window (native only): a device of its own, pixels read back to the
//! CPU. The reference-image tests use it on Mesa's lavapipe; anyone can use it to save what
//! the 3D view shows.

use std::fmt;
use std::future::Future;
use std::sync::OnceLock;
use std::task::{Context, Poll, Waker};

use eframe::wgpu;

use super::frame::Frame3d;
use super::mesh_chunks::MeshUploadError;
use super::renderer::Renderer3d;

/// An 8-bit RGBA image, rows top to bottom without padding.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RgbaImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width × height × 4` bytes.
    pub pixels: Vec<u8>,
}

impl RgbaImage {
    /// The pixel at column `x`, row `y` (from the top).
    ///
    /// # Panics
    ///
    /// If the pixel lies outside the image.
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 4] {
        assert!(
            x < self.width && y < self.height,
            "pixel ({x}, {y}) outside the image"
        );
        let at = ((y * self.width + x) * 4) as usize;
        [
            self.pixels[at],
            self.pixels[at + 1],
            self.pixels[at + 2],
            self.pixels[at + 3],
        ]
    }
}

/// Why an offscreen image could not be made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum OffscreenError {
    /// No graphics adapter (no GPU, and no software driver such as lavapipe).
    NoAdapter,
    /// The mesh could not be drawn (the rest of the frame was).
    Mesh(MeshUploadError),
    /// The texture's format is not four bytes per pixel.
    UnsupportedFormat(wgpu::TextureFormat),
    /// Mapping the read-back buffer failed.
    ReadBack(String),
}

impl fmt::Display for OffscreenError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoAdapter => write!(f, "no graphics adapter found"),
            Self::Mesh(error) => write!(f, "the mesh was not drawn: {error}"),
            Self::UnsupportedFormat(format) => {
                write!(
                    f,
                    "cannot read back {format:?} (4 bytes per pixel expected)"
                )
            }
            Self::ReadBack(error) => write!(f, "reading the image back failed: {error}"),
        }
    }
}

impl std::error::Error for OffscreenError {}

/// Polls `future` on this thread until it is ready. wgpu's native adapter and device requests
/// are ready at once, so this needs no executor (and no dependency for one).
fn block_on<F: Future>(future: F) -> F::Output {
    let mut future = std::pin::pin!(future);
    let mut context = Context::from_waker(Waker::noop());
    loop {
        if let Poll::Ready(output) = future.as_mut().poll(&mut context) {
            return output;
        }
        std::thread::yield_now();
    }
}

/// A device with no window: the default adapter (on a machine without a GPU, Mesa's
/// lavapipe), with all of its limits, so the largest meshes fit. `WGPU_BACKEND` and the
/// other `WGPU_*` variables choose differently. `None` when no adapter exists.
pub fn headless_device() -> Option<(wgpu::Device, wgpu::Queue, wgpu::AdapterInfo)> {
    headless_device_with_limits(|adapter_limits| adapter_limits)
}

/// As [`headless_device`], with the limits `limits` makes of the adapter's (lower ones, say,
/// to see how the renderer copes with a small device).
pub fn headless_device_with_limits(
    limits: impl FnOnce(wgpu::Limits) -> wgpu::Limits,
) -> Option<(wgpu::Device, wgpu::Queue, wgpu::AdapterInfo)> {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter =
        block_on(instance.request_adapter(&wgpu::RequestAdapterOptions::default())).ok()?;
    let (device, queue) = block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("bvhlab headless"),
        required_limits: limits(adapter.limits()),
        ..wgpu::DeviceDescriptor::default()
    }))
    .ok()?;
    Some((device, queue, adapter.get_info()))
}

/// One headless device for the whole process, made on first use.
fn shared_device() -> Option<&'static (wgpu::Device, wgpu::Queue, wgpu::AdapterInfo)> {
    static DEVICE: OnceLock<Option<(wgpu::Device, wgpu::Queue, wgpu::AdapterInfo)>> =
        OnceLock::new();
    DEVICE.get_or_init(headless_device).as_ref()
}

/// Copies a 4-byte-per-pixel texture (such as [`Renderer3d::color_texture`]) to the CPU,
/// waiting for the GPU. The copy goes through a buffer in bands of rows, each within the
/// device's `max_buffer_size`.
///
/// # Errors
///
/// Another format, a row longer than the largest buffer, or a failed mapping.
pub fn read_back(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<RgbaImage, OffscreenError> {
    let format = texture.format();
    if format.block_copy_size(None) != Some(4) {
        return Err(OffscreenError::UnsupportedFormat(format));
    }
    let (width, height) = (texture.width(), texture.height());
    // Copies move whole rows whose byte counts are multiples of 256.
    let row_bytes = width * 4;
    let padded_row =
        row_bytes.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let band_rows =
        (device.limits().max_buffer_size / u64::from(padded_row)).min(u64::from(height));
    if band_rows == 0 {
        return Err(OffscreenError::ReadBack(format!(
            "a row of {padded_row} bytes exceeds the device's largest buffer"
        )));
    }
    let band_rows = band_rows as u32;
    let mut pixels = Vec::with_capacity((row_bytes * height) as usize);
    let mut top = 0;
    while top < height {
        let rows = band_rows.min(height - top);
        let band = read_band(device, queue, texture, top, rows, padded_row)?;
        for row in band.chunks(padded_row as usize) {
            pixels.extend_from_slice(&row[..row_bytes as usize]);
        }
        top += rows;
    }
    Ok(RgbaImage {
        width,
        height,
        pixels,
    })
}

/// Rows `top..top + rows` of `texture`, each padded to `padded_row` bytes.
fn read_band(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    top: u32,
    rows: u32,
    padded_row: u32,
) -> Result<Vec<u8>, OffscreenError> {
    let failed = |e: &dyn fmt::Display| OffscreenError::ReadBack(e.to_string());
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("view3d read-back"),
        size: u64::from(padded_row) * u64::from(rows),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("view3d read-back"),
    });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d { x: 0, y: top, z: 0 },
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded_row),
                rows_per_image: Some(rows),
            },
        },
        wgpu::Extent3d {
            width: texture.width(),
            height: rows,
            depth_or_array_layers: 1,
        },
    );
    queue.submit([encoder.finish()]);
    let (sender, receiver) = std::sync::mpsc::channel();
    buffer.map_async(wgpu::MapMode::Read, .., move |result| {
        // The receiver waits below; it is gone only if that wait already failed.
        let _ = sender.send(result);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| failed(&e))?;
    receiver
        .recv()
        .map_err(|e| failed(&e))?
        .map_err(|e| failed(&e))?;
    let bytes = buffer
        .get_mapped_range(..)
        .map_err(|e| failed(&e))?
        .to_vec();
    buffer.unmap();
    Ok(bytes)
}

/// Renders `frame` at `size` pixels on a headless device (shared by every call in the
/// process) with a fresh [`Renderer3d`], and reads the image back.
///
/// # Errors
///
/// No adapter, an undrawable mesh, or a failed read-back.
pub fn render_offscreen(frame: &Frame3d, size: [u32; 2]) -> Result<RgbaImage, OffscreenError> {
    let (device, queue, _) = shared_device().ok_or(OffscreenError::NoAdapter)?;
    let mut renderer = Renderer3d::new(device);
    render_and_read(device, queue, &mut renderer, frame, size)
}

/// Renders `frame` with `renderer` and reads the image back.
///
/// # Errors
///
/// As [`render_offscreen`], less the missing adapter.
pub fn render_and_read(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    renderer: &mut Renderer3d,
    frame: &Frame3d,
    size: [u32; 2],
) -> Result<RgbaImage, OffscreenError> {
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("view3d offscreen"),
    });
    let drawn = renderer.render(device, queue, &mut encoder, size, frame);
    queue.submit([encoder.finish()]);
    drawn.map_err(OffscreenError::Mesh)?;
    let texture = renderer
        .color_texture()
        .ok_or_else(|| OffscreenError::ReadBack("nothing was rendered".to_owned()))?;
    read_back(device, queue, texture)
}
