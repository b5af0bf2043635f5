//! [`Blitter`]: draws a [`SceneRenderer`]'s texture into someone else's render pass (egui's).

use crate::renderer::SceneRenderer;

/// A full-screen-triangle pipeline that copies the scene texture into the current viewport of a
/// render pass.
///
/// It is created for the exact attachments of the pass it will draw into: colour format, MSAA
/// sample count and depth format (egui-wgpu passes have none in kittest and, by default, in eframe).
/// An `*Srgb` target format is handled (the texture's sRGB-encoded values are decoded first).
/// It does not blend: it replaces the viewport's pixels.
pub struct Blitter {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    target_format: wgpu::TextureFormat,
}

/// The bind group that lets a [`Blitter`] sample one renderer's colour texture.
///
/// Rebuild it when the renderer's texture was recreated (after a resize): see
/// [`BlitSource::is_current`] and [`Blitter::update_source`].
pub struct BlitSource {
    bind_group: wgpu::BindGroup,
    generation: u64,
}

impl BlitSource {
    /// Whether this source still refers to `renderer`'s current colour texture.
    pub fn is_current(&self, renderer: &SceneRenderer) -> bool {
        self.generation == renderer.generation()
    }
}

impl Blitter {
    /// A blit pipeline for a pass with this colour format, sample count and optional depth format.
    pub fn new(
        device: &wgpu::Device,
        target_format: wgpu::TextureFormat,
        sample_count: u32,
        depth_format: Option<wgpu::TextureFormat>,
    ) -> Self {
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("cnets blit shader"),
            source: wgpu::ShaderSource::Wgsl(include_str!("shaders/blit.wgsl").into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("cnets blit layout"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("cnets blit pipeline layout"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("cnets blit"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &shader,
                entry_point: Some("vs_blit"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: depth_format.map(|format| wgpu::DepthStencilState {
                format,
                depth_write_enabled: Some(false),
                depth_compare: Some(wgpu::CompareFunction::Always),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: wgpu::MultisampleState {
                count: sample_count.max(1),
                mask: !0,
                alpha_to_coverage_enabled: false,
            },
            fragment: Some(wgpu::FragmentState {
                module: &shader,
                entry_point: Some(if target_format.is_srgb() {
                    "fs_blit_srgb"
                } else {
                    "fs_blit"
                }),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: target_format,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("cnets blit sampler"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        Self {
            pipeline,
            layout,
            sampler,
            target_format,
        }
    }

    /// The colour format this blitter was made for.
    pub fn target_format(&self) -> wgpu::TextureFormat {
        self.target_format
    }

    /// A source for `renderer`'s current colour texture; `None` before the renderer first rendered.
    pub fn source(&self, device: &wgpu::Device, renderer: &SceneRenderer) -> Option<BlitSource> {
        let view = renderer.color_view()?;
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("cnets blit source"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Sampler(&self.sampler),
                },
            ],
        });
        Some(BlitSource {
            bind_group,
            generation: renderer.generation(),
        })
    }

    /// Rebuilds `source` when it is missing or refers to an outdated texture of `renderer`.
    pub fn update_source(
        &self,
        device: &wgpu::Device,
        renderer: &SceneRenderer,
        source: &mut Option<BlitSource>,
    ) {
        if source.as_ref().is_none_or(|s| !s.is_current(renderer)) {
            *source = self.source(device, renderer);
        }
    }

    /// Draws the source's texture over the pass's current viewport (one triangle, three vertices).
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>, source: &BlitSource) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &source.bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
}
