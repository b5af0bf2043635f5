//! [`Offscreen`]: renders scenes to RGBA8 images (and PNG files) without a window.

use std::io::Write;
use std::path::Path;
use std::sync::mpsc;

use crate::RenderError;
use crate::camera::{Camera, View};
use crate::renderer::{RendererOptions, SceneRenderer};
use crate::scene::Scene;

/// A rendered image: tightly packed, row-major RGBA8 pixels (sRGB), top row first.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height * 4` bytes.
    pub pixels: Vec<u8>,
}

impl Image {
    /// The pixel at `(x, y)`; `None` outside the image.
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 4]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let k = (y as usize * self.width as usize + x as usize) * 4;
        self.pixels.get(k..k + 4).map(|p| [p[0], p[1], p[2], p[3]])
    }

    /// Number of pixels equal to `color` (all four channels).
    pub fn count_color(&self, color: [u8; 4]) -> usize {
        self.pixels.chunks_exact(4).filter(|p| *p == color).count()
    }

    /// Encodes the image as PNG bytes.
    pub fn encode_png(&self) -> Result<Vec<u8>, png::EncodingError> {
        let mut out = Vec::new();
        {
            let mut encoder = png::Encoder::new(&mut out, self.width, self.height);
            encoder.set_color(png::ColorType::Rgba);
            encoder.set_depth(png::BitDepth::Eight);
            encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
            let mut writer = encoder.write_header()?;
            writer.write_image_data(&self.pixels)?;
            writer.finish()?;
        }
        Ok(out)
    }

    /// Writes the image as a PNG file, atomically: to a temporary file in the same directory,
    /// then renamed over `path`.
    pub fn save_png(&self, path: impl AsRef<Path>) -> Result<(), RenderError> {
        let path = path.as_ref();
        let fail = |message: String| RenderError::Png {
            path: path.to_path_buf(),
            message,
        };
        let bytes = self.encode_png().map_err(|e| fail(e.to_string()))?;
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let name = path
            .file_name()
            .ok_or_else(|| fail("not a file path".into()))?;
        let tmp = dir.join(format!(
            ".{}.{}.tmp",
            name.to_string_lossy(),
            std::process::id()
        ));
        let write = || -> std::io::Result<()> {
            let mut f = std::fs::File::create(&tmp)?;
            f.write_all(&bytes)?;
            f.sync_all()?;
            std::fs::rename(&tmp, path)
        };
        write().map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            fail(e.to_string())
        })
    }
}

/// A device of its own plus a [`SceneRenderer`], for rendering scenes to images without a window
/// (the runner's `cnets render`, tests, previews).
///
/// The adapter is chosen from the environment like the rest of the wgpu ecosystem does:
/// `WGPU_BACKEND` (e.g. `vulkan`, `gl`), `WGPU_ADAPTER_NAME`, `WGPU_POWER_PREF`; without them, the
/// default adapter (on a machine without GPU: the software Vulkan driver, lavapipe, if installed).
pub struct Offscreen {
    // Kept alive for the lifetime of the device.
    _instance: wgpu::Instance,
    adapter_info: wgpu::AdapterInfo,
    device: wgpu::Device,
    queue: wgpu::Queue,
    renderer: SceneRenderer,
}

impl Offscreen {
    /// Opens an adapter and device chosen from the environment, with default renderer options.
    pub fn new() -> Result<Self, RenderError> {
        Self::with_options(RendererOptions::default())
    }

    /// Opens an adapter and device chosen from the environment.
    pub fn with_options(options: RendererOptions) -> Result<Self, RenderError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let adapter = pollster::block_on(wgpu::util::initialize_adapter_from_env_or_default(
            &instance, None,
        ))
        .map_err(|e| RenderError::NoAdapter(e.to_string()))?;
        let adapter_info = adapter.get_info();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("cnets offscreen device"),
            required_limits: wgpu::Limits::downlevel_defaults().using_resolution(adapter.limits()),
            ..Default::default()
        }))
        .map_err(|e| RenderError::RequestDevice(e.to_string()))?;
        let renderer = SceneRenderer::new(&device, options);
        Ok(Self {
            _instance: instance,
            adapter_info,
            device,
            queue,
            renderer,
        })
    }

    /// The adapter in use (name, backend, device type).
    pub fn adapter_info(&self) -> &wgpu::AdapterInfo {
        &self.adapter_info
    }

    /// A one-line description of the adapter, e.g. `llvmpipe (LLVM 19.1.7, 256 bits) (Vulkan, Cpu)`.
    pub fn adapter_summary(&self) -> String {
        let i = &self.adapter_info;
        format!("{} ({:?}, {:?})", i.name, i.backend, i.device_type)
    }

    /// The device (e.g. to create more resources on it).
    pub fn device(&self) -> &wgpu::Device {
        &self.device
    }

    /// The queue.
    pub fn queue(&self) -> &wgpu::Queue {
        &self.queue
    }

    /// Renders `scene` from `camera` at `width × height` pixels and reads the image back.
    pub fn render(
        &mut self,
        scene: &Scene,
        camera: &Camera,
        width: u32,
        height: u32,
    ) -> Result<Image, RenderError> {
        let max = self.device.limits().max_texture_dimension_2d;
        if width == 0 || height == 0 || width > max || height > max {
            return Err(RenderError::InvalidSize { width, height, max });
        }
        let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let oom = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let result = self.render_inner(scene, camera, width, height);
        let oom_error = pollster::block_on(oom.pop());
        let validation_error = pollster::block_on(validation.pop());
        if let Some(e) = oom_error.or(validation_error) {
            // The renderer may hold half-made state: start over on the next call.
            self.renderer.invalidate();
            return Err(RenderError::Gpu(e.to_string()));
        }
        result
    }

    /// Renders `scene` framed from a preset view (the camera is fitted tightly to the scene).
    pub fn render_view(
        &mut self,
        scene: &Scene,
        view: View,
        width: u32,
        height: u32,
    ) -> Result<Image, RenderError> {
        let camera = Camera::framing_scene(view, scene, width as f32 / height.max(1) as f32);
        self.render(scene, &camera, width, height)
    }

    fn render_inner(
        &mut self,
        scene: &Scene,
        camera: &Camera,
        width: u32,
        height: u32,
    ) -> Result<Image, RenderError> {
        let device = &self.device;
        self.renderer.set_scene(device, &self.queue, scene);
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("cnets offscreen"),
        });
        self.renderer
            .render(device, &self.queue, &mut encoder, camera, width, height)?;
        self.queue.submit([encoder.finish()]);
        let texture = self
            .renderer
            .color_texture()
            .ok_or_else(|| RenderError::Readback("no colour texture".into()))?;
        read_texture(device, &self.queue, texture)
    }
}

/// Copies a 2D `Rgba8Unorm(Srgb)` or `Bgra8Unorm(Srgb)` texture (with `COPY_SRC` usage) back to the
/// CPU as an RGBA [`Image`] (BGRA is swizzled), waiting for the GPU. Useful to check what was drawn
/// into any texture, e.g. an egui target in tests.
pub fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Image, RenderError> {
    use wgpu::TextureFormat as F;
    let bgra = match texture.format() {
        F::Rgba8Unorm | F::Rgba8UnormSrgb => false,
        F::Bgra8Unorm | F::Bgra8UnormSrgb => true,
        other => {
            return Err(RenderError::Readback(format!(
                "unsupported texture format {other:?}"
            )));
        }
    };
    let (width, height) = (texture.width(), texture.height());
    let unpadded = width * 4;
    let align = wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let padded = unpadded.div_ceil(align) * align;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("cnets readback"),
        size: u64::from(padded) * u64::from(height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("cnets readback"),
    });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    let index = queue.submit([encoder.finish()]);

    let slice = buffer.slice(..);
    let (tx, rx) = mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device
        .poll(wgpu::PollType::Wait {
            submission_index: Some(index),
            timeout: None,
        })
        .map_err(|e| RenderError::Readback(e.to_string()))?;
    rx.recv()
        .map_err(|e| RenderError::Readback(e.to_string()))?
        .map_err(|e| RenderError::Readback(e.to_string()))?;
    let mut pixels = Vec::with_capacity((unpadded * height) as usize);
    {
        let data = slice
            .get_mapped_range()
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        for row in data.chunks_exact(padded as usize).take(height as usize) {
            pixels.extend_from_slice(&row[..unpadded as usize]);
        }
    }
    buffer.unmap();
    if bgra {
        for p in pixels.chunks_exact_mut(4) {
            p.swap(0, 2);
        }
    }
    Ok(Image {
        width,
        height,
        pixels,
    })
}
