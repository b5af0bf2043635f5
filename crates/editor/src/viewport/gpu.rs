//! The 3D view on the GPU: the preview [`Scene`] and the view's guides (grid, axes, highlights)
//! drawn with wgpu through an egui-wgpu paint callback (`cnets-render`'s [`SceneRenderer`] renders
//! into its own texture in `prepare` when the scene, guides, camera or size changed, the
//! [`Blitter`] copies it into egui's pass in `paint` every frame).

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use cnets_render::{
    BlitSource, Blitter, Camera, PointInstance, RendererOptions, Scene, SceneRenderer, Segment,
};
use eframe::egui_wgpu::{self, CallbackResources, CallbackTrait, ScreenDescriptor, wgpu};

/// What the viewport's render pipelines must match: egui's render pass and the adapter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GpuTarget {
    /// Colour format of egui's pass (eframe on X11: `Bgra8Unorm`, kittest: `Rgba8Unorm`).
    pub target_format: wgpu::TextureFormat,
    /// MSAA samples of egui's pass.
    pub msaa_samples: u32,
    /// Depth format of egui's pass, if it has one.
    pub depth_format: Option<wgpu::TextureFormat>,
    /// Renderer options for the adapter (no MSAA on software rasterizers).
    pub options: RendererOptions,
    /// The adapter is a software rasterizer (lavapipe, llvmpipe): while the picture changes
    /// (slider drags, orbiting) the view renders at half resolution, then once more at full
    /// resolution when it settles.
    pub software: bool,
}

impl GpuTarget {
    /// From an egui-wgpu render state; `msaa_samples` and `depth_format` as configured for the
    /// window (eframe's defaults: 1 and none).
    pub fn from_render_state(
        rs: &egui_wgpu::RenderState,
        msaa_samples: u32,
        depth_format: Option<wgpu::TextureFormat>,
    ) -> Self {
        Self {
            target_format: rs.target_format,
            msaa_samples: msaa_samples.max(1),
            depth_format,
            options: RendererOptions::for_adapter(&rs.adapter.get_info()),
            software: rs.adapter.get_info().device_type == wgpu::DeviceType::Cpu,
        }
    }
}

/// The guides of a frame: grid lines, axes and highlights, versioned (uploaded when it changes).
#[derive(Clone, Default)]
pub struct Guides {
    /// Segments (depth-tested with the scene, or on top by their flags).
    pub segments: Arc<Vec<Segment>>,
    /// Point markers.
    pub points: Arc<Vec<PointInstance>>,
    /// Bumped on every change.
    pub version: u64,
}

/// Per-viewport GPU state kept in egui's callback resources.
struct ViewportGpu {
    renderer: SceneRenderer,
    blitter: Blitter,
    source: Option<BlitSource>,
    version: u64,
    guides_version: u64,
    /// The camera and size of the picture in the view's texture: while they, the scene and the
    /// guides stay the same (panning the canvas, typing in a field) the texture is only blitted.
    rendered: Option<(Camera, [u32; 2])>,
}

/// The paint callback of one frame.
pub struct ViewportCallback {
    /// The scene.
    pub scene: Arc<Scene>,
    /// Its version (uploaded when it changes).
    pub version: u64,
    /// The guides.
    pub guides: Guides,
    /// The camera.
    pub camera: Camera,
    /// The texture size, in physical pixels.
    pub size_px: [u32; 2],
    /// The target formats.
    pub target: GpuTarget,
    /// Counts the pictures rendered into the view's texture (the blit of an unchanged one is not
    /// counted).
    pub pictures: Arc<AtomicU64>,
}

impl CallbackTrait for ViewportCallback {
    fn prepare(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        _screen: &ScreenDescriptor,
        encoder: &mut wgpu::CommandEncoder,
        resources: &mut CallbackResources,
    ) -> Vec<wgpu::CommandBuffer> {
        let t = self.target;
        let gpu = resources
            .entry::<ViewportGpu>()
            .or_insert_with(|| ViewportGpu {
                renderer: SceneRenderer::new(device, t.options),
                blitter: Blitter::new(device, t.target_format, t.msaa_samples, t.depth_format),
                source: None,
                version: u64::MAX,
                guides_version: u64::MAX,
                rendered: None,
            });
        if gpu.version != self.version {
            gpu.renderer.set_scene(device, queue, &self.scene);
            gpu.version = self.version;
            gpu.rendered = None;
        }
        if gpu.guides_version != self.guides.version {
            gpu.renderer
                .set_guides(device, queue, &self.guides.segments, &self.guides.points);
            gpu.guides_version = self.guides.version;
            gpu.rendered = None;
        }
        let picture = (self.camera, self.size_px);
        if gpu.source.is_some() && gpu.rendered == Some(picture) {
            return Vec::new();
        }
        let [w, h] = self.size_px;
        if gpu
            .renderer
            .render(device, queue, encoder, &self.camera, w, h)
            .is_ok()
        {
            gpu.blitter
                .update_source(device, &gpu.renderer, &mut gpu.source);
            gpu.rendered = Some(picture);
            self.pictures.fetch_add(1, Ordering::Relaxed);
        } else {
            gpu.rendered = None;
        }
        Vec::new()
    }

    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        pass: &mut wgpu::RenderPass<'static>,
        resources: &CallbackResources,
    ) {
        if let Some(gpu) = resources.get::<ViewportGpu>()
            && let Some(source) = &gpu.source
        {
            gpu.blitter.draw(pass, source);
        }
    }
}
