//! The 3D scene renderer of cnets, shared by the editor's viewport and the runner's `cnets render`.
//!
//! - [`Scene`]: a plain, GPU-ready description of what is shown: meshes ([`QuadGrid`] or
//!   [`PolygonMesh`], flat-shaded, coloured per face, polygon outlines as edges), line sets, point
//!   markers and a background colour. Cheap to rebuild (a 100 × 100 grid well below a millisecond).
//! - [`palette`]: the default look, viridis for planarity (with a [`palette::Legend`]) and the four
//!   configuration-class colours.
//! - [`Camera`]: a Z-up orbit camera with [`View`] presets, fit-to-bounds, orbit / pan / zoom.
//! - [`SceneRenderer`]: renders a scene on a caller's `wgpu::Device` into its own
//!   [`COLOR_FORMAT`] texture (+ `Depth32Float`, 4× MSAA by default).
//! - [`Blitter`]: copies that texture into any render pass (egui's), matching its formats.
//! - [`Offscreen`]: its own device, renders to an [`Image`] (RGBA8) and PNG, for headless use.
//!
//! The crate depends on `wgpu` 30, the version egui-wgpu 0.36 uses, so the editor hands its own
//! device and queue to [`SceneRenderer`] and [`Blitter`]. It does not depend on egui.
//!
//! Colours are sRGB-encoded bytes everywhere. The renderer lights in linear space and stores
//! sRGB-encoded values in a `*Unorm` texture, which is what egui's `*Unorm` targets expect; the
//! blitter decodes for `*Srgb` targets.
//!
//! # Off-screen
//!
//! ```no_run
//! use cnets_render::{Offscreen, Scene, View, FaceColors, palette};
//! # fn demo(grid: &cnets_geometry::QuadGrid) -> Result<(), cnets_render::RenderError> {
//! let mut scene = Scene::new();
//! scene.add_quad_grid(grid, FaceColors::Uniform(palette::SURFACE))?;
//! let mut gpu = Offscreen::new()?; // a typed error, not a panic, when there is no adapter
//! gpu.render_view(&scene, View::Iso, 1280, 720)?.save_png("preview.png")?;
//! # Ok(()) }
//! ```
//!
//! # In the editor: inside an egui-wgpu paint callback
//!
//! egui's render pass has no depth attachment (in egui_kittest, and in eframe unless
//! `NativeOptions::depth_buffer` is set), so the scene is rendered into the renderer's own textures
//! in `prepare` (with egui's encoder) and copied into egui's pass in `paint`:
//!
//! ```ignore
//! use cnets_render::{Blitter, BlitSource, Camera, RendererOptions, Scene, SceneRenderer};
//! use eframe::egui_wgpu::{self, wgpu, CallbackResources, CallbackTrait, ScreenDescriptor};
//!
//! /// Per-viewport GPU state, kept in egui's `CallbackResources` (a type map: key several
//! /// viewports by an id inside one map if there are several).
//! struct ViewportGpu { renderer: SceneRenderer, blitter: Blitter, source: Option<BlitSource> }
//!
//! /// Built every frame by the viewport widget.
//! struct ViewportCallback {
//!     /// `Some` when the scene changed since the last frame (shared, e.g. `Arc<Scene>`).
//!     new_scene: Option<std::sync::Arc<Scene>>,
//!     camera: Camera,
//!     /// `rect.size() * pixels_per_point`, rounded: `prepare` only sees the whole screen.
//!     size_px: [u32; 2],
//!     /// From the render state: `target_format`, MSAA samples, depth format of egui's pass
//!     /// (kittest: Rgba8Unorm, eframe on X11: Bgra8Unorm; never hard-code one).
//!     target_format: wgpu::TextureFormat,
//!     msaa_samples: u32,
//!     depth_format: Option<wgpu::TextureFormat>,
//!     /// `RendererOptions::for_adapter(&render_state.adapter.get_info())`: no MSAA on software
//!     /// rasterizers, where it doubles the frame time.
//!     options: RendererOptions,
//! }
//!
//! impl CallbackTrait for ViewportCallback {
//!     fn prepare(
//!         &self,
//!         device: &wgpu::Device,
//!         queue: &wgpu::Queue,
//!         _screen: &ScreenDescriptor,
//!         encoder: &mut wgpu::CommandEncoder,
//!         resources: &mut CallbackResources,
//!     ) -> Vec<wgpu::CommandBuffer> {
//!         let gpu = resources.entry::<ViewportGpu>().or_insert_with(|| ViewportGpu {
//!             renderer: SceneRenderer::new(device, self.options),
//!             blitter: Blitter::new(device, self.target_format, self.msaa_samples, self.depth_format),
//!             source: None,
//!         });
//!         if let Some(scene) = &self.new_scene {
//!             gpu.renderer.set_scene(device, queue, scene); // upload once per scene change
//!         }
//!         let [w, h] = self.size_px;
//!         // Draws only when scene, camera or size changed; errors only for a zero/oversized rect.
//!         if gpu.renderer.render(device, queue, encoder, &self.camera, w, h).is_ok() {
//!             gpu.blitter.update_source(device, &gpu.renderer, &mut gpu.source);
//!         }
//!         Vec::new()
//!     }
//!
//!     fn paint(
//!         &self,
//!         _info: egui::PaintCallbackInfo,
//!         pass: &mut wgpu::RenderPass<'static>,
//!         resources: &CallbackResources,
//!     ) {
//!         // egui has set viewport and scissor to the callback rect already.
//!         if let Some(gpu) = resources.get::<ViewportGpu>()
//!             && let Some(source) = &gpu.source
//!         {
//!             gpu.blitter.draw(pass, source);
//!         }
//!     }
//! }
//! // In the widget: ui.painter().add(egui_wgpu::Callback::new_paint_callback(rect, ViewportCallback { .. }));
//! ```
//!
//! The editor's mouse handling maps to [`Camera::orbit`] (drag, radians per pixel),
//! [`Camera::pan`] (pixels), [`Camera::zoom`] (scroll factor) and [`Camera::fit`] (the F key).

pub mod blit;
pub mod camera;
pub mod error;
pub mod offscreen;
pub mod overlay;
pub mod palette;
pub mod renderer;
pub mod scene;
mod scene_bytes;

pub use blit::{BlitSource, Blitter};
pub use camera::{Camera, ORTHO_DEPTH, ParseViewError, Projection, Ray, View};
pub use cnets_geometry::{Line, PolygonMesh, Polyline, QuadGrid};
pub use error::RenderError;
pub use offscreen::{Image, Offscreen, read_texture};
pub use overlay::{LegendBlock, PanelRect, draw_legend};
pub use palette::{Color, Legend, SequentialMap, ToleranceMap};
pub use renderer::{COLOR_FORMAT, DEPTH_FORMAT, RendererOptions, SceneRenderer};
pub use scene::{
    Bounds, FACE_LAYER_BIAS, FLAG_BESIDE, FaceColors, FaceVertex, LineStyle, MAX_DEPTH_LAYER,
    MeshInfo, MeshStyle, PointInstance, PointShape, PointStyle, Scene, SceneParts, SceneStats,
    Segment,
};
/// The wgpu this crate is built against (30, the one egui-wgpu 0.36 uses).
pub use wgpu;
