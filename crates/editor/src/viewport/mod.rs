//! The 3D viewport: the preview [`Scene`] drawn with wgpu through an egui-wgpu paint callback
//! (`cnets-render`'s [`SceneRenderer`] renders into its own texture in `prepare`, the [`Blitter`]
//! copies it into egui's pass in `paint`), an orbit camera driven by the mouse, and an overlay
//! with the legend, vertex count and max planarity.
//!
//! Mouse: left-drag orbits, right- or middle-drag (or Shift + left-drag) pans, the wheel zooms;
//! F (or the Fit button) frames everything.

use std::sync::Arc;

use cnets_render::{BlitSource, Blitter, Camera, RendererOptions, Scene, SceneRenderer, View};
use eframe::egui_wgpu::{self, CallbackResources, CallbackTrait, ScreenDescriptor, wgpu};
use egui::{Color32, Rect, Sense, Ui};

use crate::preview::{LegendInfo, PreviewOptions, PreviewStats};
use crate::worker::format_number;

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

/// The viewport's state.
pub struct Viewport {
    /// The camera.
    pub camera: Camera,
    /// Display options (colour mode, layers).
    pub options: PreviewOptions,
    scene: Arc<Scene>,
    scene_version: u64,
    /// Figures of the current scene.
    pub stats: PreviewStats,
    fit_pending: bool,
    fitted_once: bool,
    aspect: f32,
    /// Scene versions handed to the GPU (one per frame at most): the app reads it to know when a
    /// change reached the picture.
    pub drawn_version: u64,
    /// egui time of the last change of scene or camera.
    last_change: f64,
    /// Resolution factor of the last frame (1 or [`INTERACTIVE_SCALE`]).
    pub render_scale: f32,
    /// Where the view was drawn in the last frame (screen points).
    pub rect: egui::Rect,
}

/// Resolution factor while the picture changes on a software rasterizer.
pub const INTERACTIVE_SCALE: f32 = 0.5;
/// Seconds without changes after which the view is rendered at full resolution again.
const SETTLE_SECONDS: f64 = 0.3;

impl Default for Viewport {
    fn default() -> Self {
        Self {
            camera: Camera::new(View::Iso),
            options: PreviewOptions::default(),
            scene: Arc::new(Scene::new()),
            scene_version: 0,
            stats: PreviewStats::default(),
            fit_pending: false,
            fitted_once: false,
            aspect: 1.0,
            drawn_version: 0,
            last_change: f64::NEG_INFINITY,
            render_scale: 1.0,
            rect: egui::Rect::NOTHING,
        }
    }
}

/// Per-viewport GPU state kept in egui's callback resources.
struct ViewportGpu {
    renderer: SceneRenderer,
    blitter: Blitter,
    source: Option<BlitSource>,
    version: u64,
}

/// The paint callback of one frame.
struct ViewportCallback {
    scene: Arc<Scene>,
    version: u64,
    camera: Camera,
    size_px: [u32; 2],
    target: GpuTarget,
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
            });
        if gpu.version != self.version {
            gpu.renderer.set_scene(device, queue, &self.scene);
            gpu.version = self.version;
        }
        let [w, h] = self.size_px;
        if gpu
            .renderer
            .render(device, queue, encoder, &self.camera, w, h)
            .is_ok()
        {
            gpu.blitter
                .update_source(device, &gpu.renderer, &mut gpu.source);
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

impl Viewport {
    /// Replaces the scene (from a finished evaluation).
    pub fn set_scene(&mut self, scene: Arc<Scene>, stats: PreviewStats) {
        self.scene = scene;
        self.stats = stats;
        self.scene_version += 1;
        self.last_change = f64::NAN; // stamped with egui's time in the next `show`
        if !self.fitted_once && !self.scene.is_empty() {
            self.fit_pending = true;
        }
    }

    /// Clears the scene for a new document (the next geometry is framed again).
    pub fn reset(&mut self) {
        self.set_scene(Arc::new(Scene::new()), PreviewStats::default());
        self.fitted_once = false;
    }

    /// The scene shown.
    pub fn scene(&self) -> &Arc<Scene> {
        &self.scene
    }

    /// The figures and legend of the scene shown.
    pub fn stats(&self) -> &PreviewStats {
        &self.stats
    }

    /// Version of the scene (bumped by [`Viewport::set_scene`]).
    pub fn scene_version(&self) -> u64 {
        self.scene_version
    }

    /// Frames everything on the next frame (the F key).
    pub fn fit(&mut self) {
        self.fit_pending = true;
    }

    /// Points the camera at the surfaces (apices and other markers can lie far away, even near
    /// infinity, and would shrink the mesh to a dot), or at everything when there are none.
    fn frame_geometry(&mut self) {
        self.camera.fit_surfaces(&self.scene, self.aspect);
    }

    /// Shows the viewport in the rest of `ui`.
    pub fn show(&mut self, ui: &mut Ui, gpu: Option<&GpuTarget>) {
        let rect = ui.available_rect_before_wrap();
        let response = ui.allocate_rect(rect, Sense::click_and_drag());
        self.rect = rect;
        self.aspect = rect.width().max(1.0) / rect.height().max(1.0);
        if self.fit_pending && !self.scene.is_empty() {
            self.frame_geometry();
            self.fit_pending = false;
            self.fitted_once = true;
        }
        let camera_before = self.camera;
        self.handle_input(ui, &response, rect);
        let now = ui.input(|i| i.time);
        if self.camera != camera_before || self.last_change.is_nan() {
            self.last_change = now;
        }
        let changing = now - self.last_change < SETTLE_SECONDS;
        self.render_scale = if changing && gpu.is_some_and(|g| g.software) {
            // Come back for the full-resolution picture once things settle.
            ui.ctx()
                .request_repaint_after(std::time::Duration::from_secs_f64(SETTLE_SECONDS));
            INTERACTIVE_SCALE
        } else {
            1.0
        };
        let ppp = ui.ctx().pixels_per_point() * self.render_scale;
        let size_px = [
            (rect.width() * ppp).round().max(1.0) as u32,
            (rect.height() * ppp).round().max(1.0) as u32,
        ];
        match gpu {
            Some(target) => {
                ui.painter().add(egui_wgpu::Callback::new_paint_callback(
                    rect,
                    ViewportCallback {
                        scene: self.scene.clone(),
                        version: self.scene_version,
                        camera: self.camera,
                        size_px,
                        target: *target,
                    },
                ));
                self.drawn_version = self.scene_version;
            }
            None => {
                ui.painter().rect_filled(rect, 0.0, Color32::from_gray(60));
                ui.painter().text(
                    rect.center(),
                    egui::Align2::CENTER_CENTER,
                    "no wgpu renderer: the 3D view needs the wgpu backend",
                    egui::FontId::proportional(14.0),
                    Color32::WHITE,
                );
            }
        }
        self.overlay(ui, rect);
    }

    fn handle_input(&mut self, ui: &Ui, response: &egui::Response, rect: Rect) {
        let (shift, scroll) = ui.input(|i| (i.modifiers.shift, i.smooth_scroll_delta.y));
        let delta = response.drag_delta();
        if response.dragged_by(egui::PointerButton::Primary) && !shift {
            self.camera.orbit(-delta.x * 0.008, delta.y * 0.008);
        } else if response.dragged_by(egui::PointerButton::Secondary)
            || response.dragged_by(egui::PointerButton::Middle)
            || (response.dragged_by(egui::PointerButton::Primary) && shift)
        {
            self.camera.pan(delta.x, delta.y, rect.height());
        }
        if response.hovered() && scroll != 0.0 {
            self.camera.zoom((-scroll * 0.002).exp());
        }
        if response.double_clicked() {
            self.fit();
        }
    }

    fn overlay(&self, ui: &mut Ui, rect: Rect) {
        let painter = ui.painter_at(rect);
        let font = egui::FontId::proportional(12.0);
        let ink = Color32::from_gray(30);
        let s = &self.stats;
        let mut lines = vec![format!("{} vertices · {} faces", s.vertices, s.faces)];
        if let Some(p) = s.max_planarity {
            // Below 1e-12 the digits are rounding noise (and differ between machines).
            let shown = if p < 1e-12 {
                "< 1e-12".to_string()
            } else {
                format_number(p)
            };
            lines.push(format!("max planarity {shown}"));
        }
        for (k, line) in lines.iter().enumerate() {
            painter.text(
                rect.left_top() + egui::vec2(8.0, 6.0 + 16.0 * k as f32),
                egui::Align2::LEFT_TOP,
                line,
                font.clone(),
                ink,
            );
        }
        let swatch =
            |painter: &egui::Painter, y: f32, color: cnets_render::Color, label: String| {
                let [r, g, b, _] = color.0;
                let x = rect.right() - 170.0;
                painter.rect_filled(
                    Rect::from_min_size(egui::pos2(x, y), egui::vec2(14.0, 12.0)),
                    2.0,
                    Color32::from_rgb(r, g, b),
                );
                painter.text(
                    egui::pos2(x + 20.0, y),
                    egui::Align2::LEFT_TOP,
                    label,
                    font.clone(),
                    ink,
                );
            };
        let top = rect.top() + 8.0;
        match &s.legend {
            LegendInfo::None => {}
            LegendInfo::Classes(classes) => {
                painter.text(
                    egui::pos2(rect.right() - 170.0, top),
                    egui::Align2::LEFT_TOP,
                    "configuration",
                    font.clone(),
                    ink,
                );
                for (k, (class, count)) in classes.iter().enumerate() {
                    swatch(
                        &painter,
                        top + 18.0 + 16.0 * k as f32,
                        crate::preview::class_color(*class),
                        format!("{}  {}  {count}", paper_class(*class), class.name()),
                    );
                }
            }
            LegendInfo::Planarity(legend) => {
                painter.text(
                    egui::pos2(rect.right() - 170.0, top),
                    egui::Align2::LEFT_TOP,
                    &legend.title,
                    font.clone(),
                    ink,
                );
                for (k, (value, color)) in legend.stops.iter().enumerate().rev() {
                    let row = legend.stops.len() - 1 - k;
                    let label = legend
                        .labels
                        .get(k)
                        .cloned()
                        .unwrap_or_else(|| format_number(*value));
                    swatch(&painter, top + 18.0 + 16.0 * row as f32, *color, label);
                }
            }
        }
    }
}

/// The configuration class of a face in the paper's notation: the (±±) configurations of its two
/// construction planes (CNets, Fig. 4).
pub fn paper_class(class: cnets_geometry::fabrication::FaceClass) -> &'static str {
    use cnets_geometry::fabrication::FaceClass;
    match class {
        FaceClass::Convex => "(++)(++)",
        FaceClass::NonConvex => "(++)(−−)",
        FaceClass::MinusMinus => "(−−)(−−)",
        FaceClass::NegativeApex => "(+−)/(−+)",
        FaceClass::Unclassified => "—",
    }
}
