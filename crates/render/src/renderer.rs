//! [`SceneRenderer`]: draws a [`Scene`] into its own colour + depth textures on a caller's device.

use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

use crate::RenderError;
use crate::camera::Camera;
use crate::palette::Color;
use crate::scene::{FaceVertex, PointInstance, Scene, Segment};

/// Format of the renderer's colour texture (sRGB-encoded values in a linear-unorm texture).
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
/// Format of the renderer's depth texture.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// Relative depth bias of edges and lines (towards the eye), so they win over the faces they lie on.
const LINE_DEPTH_BIAS: f32 = 2e-3;
/// Relative depth bias of points.
const POINT_DEPTH_BIAS: f32 = 4e-3;
/// Ambient share of the lighting (the rest is the headlight's diffuse term).
const AMBIENT: f32 = 0.32;

/// Options of a [`SceneRenderer`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RendererOptions {
    /// MSAA sample count: 1 (off) or 4 (WebGPU guarantees 4× for the formats used).
    pub sample_count: u32,
}

impl RendererOptions {
    /// Options suited to an adapter: 4× MSAA on GPUs, none on software rasterizers (lavapipe,
    /// llvmpipe), where 4× costs about twice the frame time (≈ 42 vs 24 ms at 1280 × 720).
    pub fn for_adapter(info: &wgpu::AdapterInfo) -> Self {
        let software = info.device_type == wgpu::DeviceType::Cpu;
        Self {
            sample_count: if software { 1 } else { 4 },
        }
    }
}

impl Default for RendererOptions {
    fn default() -> Self {
        Self { sample_count: 4 }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct Globals {
    view_proj: [[f32; 4]; 4],
    eye: [f32; 4],
    light: [f32; 4],
    viewport: [f32; 4],
}

/// A GPU buffer that grows (never shrinks) to hold the data written into it.
struct GrowBuffer {
    label: &'static str,
    usage: wgpu::BufferUsages,
    buffer: Option<wgpu::Buffer>,
}

impl GrowBuffer {
    fn new(label: &'static str, usage: wgpu::BufferUsages) -> Self {
        Self {
            label,
            usage: usage | wgpu::BufferUsages::COPY_DST,
            buffer: None,
        }
    }

    fn write(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, data: &[u8]) {
        if data.is_empty() {
            return;
        }
        let len = data.len() as u64;
        if self.buffer.as_ref().is_none_or(|b| b.size() < len) {
            let size = len.next_power_of_two().max(4096);
            self.buffer = Some(device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(self.label),
                size,
                usage: self.usage,
                mapped_at_creation: false,
            }));
        }
        if let Some(b) = &self.buffer {
            queue.write_buffer(b, 0, data);
        }
    }

    fn slice(&self, len: u64) -> Option<wgpu::BufferSlice<'_>> {
        self.buffer.as_ref().map(|b| b.slice(..len))
    }
}

/// The render targets at one size.
struct Targets {
    width: u32,
    height: u32,
    color: wgpu::Texture,
    color_view: wgpu::TextureView,
    msaa_view: Option<wgpu::TextureView>,
    depth_view: wgpu::TextureView,
}

/// Renders a [`Scene`] with a [`Camera`] into its own textures, on a device it is given.
///
/// The result is [`SceneRenderer::color_texture`]: [`COLOR_FORMAT`] with `RENDER_ATTACHMENT |
/// TEXTURE_BINDING | COPY_SRC`, sized in physical pixels, holding sRGB-encoded colours. Draw it into
/// another pass with a [`crate::Blitter`] or copy it out (as [`crate::Offscreen`] does).
///
/// Geometry is uploaded by [`SceneRenderer::set_scene`] (once per scene change);
/// [`SceneRenderer::render`] records a pass only when the scene, the camera or the size changed.
pub struct SceneRenderer {
    options: RendererOptions,
    globals: wgpu::Buffer,
    globals_bind_group: wgpu::BindGroup,
    face_pipeline: wgpu::RenderPipeline,
    line_pipeline: wgpu::RenderPipeline,
    point_pipeline: wgpu::RenderPipeline,
    face_vertices: GrowBuffer,
    face_indices: GrowBuffer,
    segments: GrowBuffer,
    points: GrowBuffer,
    counts: Counts,
    guide_segments: GrowBuffer,
    guide_points: GrowBuffer,
    guide_counts: (usize, usize),
    background: Color,
    targets: Option<Targets>,
    /// Incremented whenever the colour texture is recreated.
    generation: u64,
    /// The camera and size of the last recorded frame; `None` forces a redraw.
    last: Option<(Camera, u32, u32)>,
}

#[derive(Clone, Copy, Default)]
struct Counts {
    vertices: usize,
    indices: usize,
    segments: usize,
    points: usize,
}

impl SceneRenderer {
    /// Creates the pipelines on `device`. Cheap enough to do once per viewport.
    pub fn new(device: &wgpu::Device, options: RendererOptions) -> Self {
        let options = RendererOptions {
            sample_count: if options.sample_count >= 4 { 4 } else { 1 },
        };
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("cnets scene shader"),
            source: wgpu::ShaderSource::Wgsl(include_str!("shaders/scene.wgsl").into()),
        });
        let globals = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("cnets scene globals"),
            contents: bytemuck::bytes_of(&Globals::zeroed()),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("cnets scene globals layout"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: wgpu::BufferSize::new(std::mem::size_of::<Globals>() as u64),
                },
                count: None,
            }],
        });
        let globals_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("cnets scene globals"),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: globals.as_entire_binding(),
            }],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("cnets scene pipeline layout"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });

        let face_attrs =
            wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Unorm8x4, 3 => Uint32];
        let face_layout = wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<FaceVertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &face_attrs,
        };
        let seg_attrs = wgpu::vertex_attr_array![
            0 => Float32x3, 1 => Float32x3, 2 => Unorm8x4, 3 => Float32, 4 => Uint32
        ];
        let seg_layout = wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<Segment>() as u64,
            step_mode: wgpu::VertexStepMode::Instance,
            attributes: &seg_attrs,
        };
        let point_attrs =
            wgpu::vertex_attr_array![0 => Float32x3, 1 => Unorm8x4, 2 => Float32, 3 => Uint32];
        let point_layout = wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<PointInstance>() as u64,
            step_mode: wgpu::VertexStepMode::Instance,
            attributes: &point_attrs,
        };

        let make = |label: &str, vs: &str, fs: &str, layout: wgpu::VertexBufferLayout<'_>| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &shader,
                    entry_point: Some(vs),
                    compilation_options: Default::default(),
                    buffers: &[Some(layout)],
                },
                primitive: wgpu::PrimitiveState {
                    topology: wgpu::PrimitiveTopology::TriangleList,
                    cull_mode: None,
                    ..Default::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(true),
                    // Reverse-Z: nearer is larger.
                    depth_compare: Some(wgpu::CompareFunction::GreaterEqual),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: wgpu::MultisampleState {
                    count: options.sample_count,
                    mask: !0,
                    alpha_to_coverage_enabled: false,
                },
                fragment: Some(wgpu::FragmentState {
                    module: &shader,
                    entry_point: Some(fs),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::ColorTargetState {
                        format: COLOR_FORMAT,
                        blend: Some(wgpu::BlendState::ALPHA_BLENDING),
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let face_pipeline = make("cnets faces", "vs_face", "fs_face", face_layout);
        let line_pipeline = make("cnets lines", "vs_line", "fs_flat", seg_layout);
        let point_pipeline = make("cnets points", "vs_point", "fs_flat", point_layout);

        Self {
            options,
            globals,
            globals_bind_group,
            face_pipeline,
            line_pipeline,
            point_pipeline,
            face_vertices: GrowBuffer::new("cnets face vertices", wgpu::BufferUsages::VERTEX),
            face_indices: GrowBuffer::new("cnets face indices", wgpu::BufferUsages::INDEX),
            segments: GrowBuffer::new("cnets segments", wgpu::BufferUsages::VERTEX),
            points: GrowBuffer::new("cnets points", wgpu::BufferUsages::VERTEX),
            counts: Counts::default(),
            guide_segments: GrowBuffer::new("cnets guide segments", wgpu::BufferUsages::VERTEX),
            guide_points: GrowBuffer::new("cnets guide points", wgpu::BufferUsages::VERTEX),
            guide_counts: (0, 0),
            background: crate::palette::BACKGROUND,
            targets: None,
            generation: 0,
            last: None,
        }
    }

    /// The options in effect (sample count normalised to 1 or 4).
    pub fn options(&self) -> RendererOptions {
        self.options
    }

    /// Uploads the scene's buffers (growing them when needed) and marks the image stale.
    pub fn set_scene(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, scene: &Scene) {
        self.face_vertices
            .write(device, queue, bytemuck::cast_slice(scene.face_vertices()));
        self.face_indices
            .write(device, queue, bytemuck::cast_slice(scene.face_indices()));
        self.segments
            .write(device, queue, bytemuck::cast_slice(scene.segments()));
        self.points
            .write(device, queue, bytemuck::cast_slice(scene.points()));
        self.counts = Counts {
            vertices: scene.face_vertices().len(),
            indices: scene.face_indices().len(),
            segments: scene.segments().len(),
            points: scene.points().len(),
        };
        self.background = scene.background();
        self.last = None;
    }

    /// Uploads guides drawn with the scene (depth-tested like it): an editor's grid, axes and
    /// highlights. They change with the camera, the scene does not; empty slices draw none.
    pub fn set_guides(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        segments: &[Segment],
        points: &[PointInstance],
    ) {
        self.guide_segments
            .write(device, queue, bytemuck::cast_slice(segments));
        self.guide_points
            .write(device, queue, bytemuck::cast_slice(points));
        self.guide_counts = (segments.len(), points.len());
        self.last = None;
    }

    /// Forces the next [`SceneRenderer::render`] to draw.
    pub fn invalidate(&mut self) {
        self.last = None;
    }

    /// Whether [`SceneRenderer::render`] with this camera and size would draw.
    pub fn needs_render(&self, camera: &Camera, width: u32, height: u32) -> bool {
        self.last != Some((*camera, width, height))
    }

    /// Records the scene pass into `encoder` if the scene, camera or size changed since the last
    /// call (returns whether it drew). The textures are (re)created at `width × height` physical
    /// pixels as needed; zero or too large a size is an error.
    pub fn render(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        camera: &Camera,
        width: u32,
        height: u32,
    ) -> Result<bool, RenderError> {
        self.ensure_targets(device, width, height)?;
        if !self.needs_render(camera, width, height) {
            return Ok(false);
        }
        let aspect = width as f32 / height as f32;
        let (right, up, back) = (camera.right(), camera.up(), camera.back());
        // A headlight a little above and to the left of the eye, so facing planes still differ.
        let light = (back + 0.35 * up - 0.25 * right).normalize();
        let globals = Globals {
            view_proj: camera.view_projection(aspect).to_cols_array_2d(),
            eye: camera.eye().extend(camera.ortho_bias_scale()).to_array(),
            light: light.extend(AMBIENT).to_array(),
            viewport: [
                width as f32,
                height as f32,
                LINE_DEPTH_BIAS,
                POINT_DEPTH_BIAS,
            ],
        };
        queue.write_buffer(&self.globals, 0, bytemuck::bytes_of(&globals));

        let Some(t) = &self.targets else {
            return Ok(false);
        };
        let (view, resolve_target) = match &t.msaa_view {
            Some(msaa) => (msaa, Some(&t.color_view)),
            None => (&t.color_view, None),
        };
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("cnets scene pass"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(self.background.to_wgpu()),
                        store: if resolve_target.is_some() {
                            wgpu::StoreOp::Discard
                        } else {
                            wgpu::StoreOp::Store
                        },
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &t.depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(0.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_bind_group(0, &self.globals_bind_group, &[]);
            let c = self.counts;
            if c.indices > 0
                && let (Some(vb), Some(ib)) = (
                    self.face_vertices
                        .slice((c.vertices * std::mem::size_of::<FaceVertex>()) as u64),
                    self.face_indices.slice((c.indices * 4) as u64),
                )
            {
                pass.set_pipeline(&self.face_pipeline);
                pass.set_vertex_buffer(0, vb);
                pass.set_index_buffer(ib, wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..c.indices as u32, 0, 0..1);
            }
            let (guide_segments, guide_points) = self.guide_counts;
            for (buffer, count) in [
                (&self.guide_segments, guide_segments),
                (&self.segments, c.segments),
            ] {
                if count > 0
                    && let Some(sb) = buffer.slice((count * std::mem::size_of::<Segment>()) as u64)
                {
                    pass.set_pipeline(&self.line_pipeline);
                    pass.set_vertex_buffer(0, sb);
                    pass.draw(0..6, 0..count as u32);
                }
            }
            for (buffer, count) in [(&self.points, c.points), (&self.guide_points, guide_points)] {
                if count > 0
                    && let Some(pb) =
                        buffer.slice((count * std::mem::size_of::<PointInstance>()) as u64)
                {
                    pass.set_pipeline(&self.point_pipeline);
                    pass.set_vertex_buffer(0, pb);
                    pass.draw(0..6, 0..count as u32);
                }
            }
        }
        self.last = Some((*camera, width, height));
        Ok(true)
    }

    fn ensure_targets(
        &mut self,
        device: &wgpu::Device,
        width: u32,
        height: u32,
    ) -> Result<(), RenderError> {
        let max = device.limits().max_texture_dimension_2d;
        if width == 0 || height == 0 || width > max || height > max {
            return Err(RenderError::InvalidSize { width, height, max });
        }
        if self
            .targets
            .as_ref()
            .is_some_and(|t| t.width == width && t.height == height)
        {
            return Ok(());
        }
        let size = wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        };
        let texture = |label: &str, format, samples, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size,
                mip_level_count: 1,
                sample_count: samples,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let color = texture(
            "cnets scene colour",
            COLOR_FORMAT,
            1,
            wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
        );
        let samples = self.options.sample_count;
        let msaa_view = (samples > 1).then(|| {
            texture(
                "cnets scene colour (msaa)",
                COLOR_FORMAT,
                samples,
                wgpu::TextureUsages::RENDER_ATTACHMENT,
            )
            .create_view(&Default::default())
        });
        let depth = texture(
            "cnets scene depth",
            DEPTH_FORMAT,
            samples,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        self.targets = Some(Targets {
            width,
            height,
            color_view: color.create_view(&Default::default()),
            color,
            msaa_view,
            depth_view: depth.create_view(&Default::default()),
        });
        self.generation += 1;
        self.last = None;
        Ok(())
    }

    /// The colour texture of the last size rendered at; `None` before the first render.
    pub fn color_texture(&self) -> Option<&wgpu::Texture> {
        self.targets.as_ref().map(|t| &t.color)
    }

    /// A view of [`SceneRenderer::color_texture`].
    pub fn color_view(&self) -> Option<&wgpu::TextureView> {
        self.targets.as_ref().map(|t| &t.color_view)
    }

    /// Current texture size in pixels, `(0, 0)` before the first render.
    pub fn size(&self) -> (u32, u32) {
        self.targets
            .as_ref()
            .map_or((0, 0), |t| (t.width, t.height))
    }

    /// Counter that changes whenever the colour texture is recreated (bind groups that sample it
    /// must then be rebuilt; see [`crate::BlitSource::is_current`]).
    pub fn generation(&self) -> u64 {
        self.generation
    }
}
