//! Off-screen rendering on whatever adapter exists (in CI: lavapipe, the software Vulkan driver).
//!
//! Without an adapter these tests fail with a clear message, unless `CNETS_SKIP_GPU_TESTS=1` is set.

use std::sync::{Mutex, OnceLock, PoisonError};

use cnets_geometry::{DVec3, QuadGrid};
use cnets_render::{
    Blitter, Camera, Color, FaceColors, Image, LineStyle, MeshStyle, Offscreen, PointShape,
    PointStyle, RenderError, RendererOptions, Scene, SceneRenderer, View, palette, read_texture,
    wgpu,
};
use glam::Vec3;

/// Runs `f` with the shared off-screen device; `None` when skipping is allowed and there is no GPU.
fn with_gpu(f: impl FnOnce(&mut Offscreen)) {
    static GPU: OnceLock<Mutex<Option<Offscreen>>> = OnceLock::new();
    let gpu = GPU.get_or_init(|| {
        Mutex::new(match Offscreen::new() {
            Ok(gpu) => {
                eprintln!("GPU tests on {}", gpu.adapter_summary());
                Some(gpu)
            }
            Err(e) if std::env::var("CNETS_SKIP_GPU_TESTS").as_deref() == Ok("1") => {
                eprintln!("skipping GPU tests (CNETS_SKIP_GPU_TESTS=1): {e}");
                None
            }
            Err(e) => panic!(
                "GPU tests need a graphics adapter and found none: {e}\n\
                 Install the software Vulkan driver (apt-get install mesa-vulkan-drivers libvulkan1) \
                 or set CNETS_SKIP_GPU_TESTS=1 to skip these tests."
            ),
        })
    });
    let mut guard = gpu.lock().unwrap_or_else(PoisonError::into_inner);
    if let Some(gpu) = guard.as_mut() {
        f(gpu);
    }
}

const W: u32 = 256;
const H: u32 = 192;
const CENTRE: Color = Color::hex(0xd62f2f);

/// A flat 6 × 6-quad grid in the XY plane over [-3, 3]², centre quads red, others the surface colour.
fn grid_scene(edges: Option<LineStyle>) -> (Scene, QuadGrid) {
    let n = 7;
    let v = (0..n)
        .flat_map(|i| (0..n).map(move |j| DVec3::new(j as f64 - 3.0, i as f64 - 3.0, 0.0)))
        .collect();
    let grid = QuadGrid::new(n, n, v).unwrap();
    let colors: Vec<Color> = grid
        .quads()
        .map(|((i, j), _)| {
            if (2..4).contains(&i) && (2..4).contains(&j) {
                CENTRE
            } else {
                palette::SURFACE
            }
        })
        .collect();
    let mut scene = Scene::new();
    scene
        .add_quad_grid(
            &grid,
            MeshStyle::new(FaceColors::PerFace(&colors)).edges(edges),
        )
        .unwrap();
    (scene, grid)
}

fn close(a: [u8; 4], b: [u8; 4], tol: i32) -> bool {
    (0..3).all(|k| (i32::from(a[k]) - i32::from(b[k])).abs() <= tol)
}

/// Pixel coordinates of a world point.
fn to_pixel(camera: &Camera, p: Vec3) -> (u32, u32) {
    let ndc = camera.project(p, W as f32 / H as f32).unwrap();
    (
        ((ndc.x + 1.0) * 0.5 * W as f32) as u32,
        ((1.0 - ndc.y) * 0.5 * H as f32) as u32,
    )
}

fn background_fraction(image: &Image, background: Color) -> f64 {
    image.count_color(background.0) as f64 / f64::from(image.width * image.height)
}

#[test]
fn quad_grid_is_drawn_with_faces_and_edges() {
    with_gpu(|gpu| {
        let edge = LineStyle::new(Color::BLACK, 2.0);
        let (scene, _) = grid_scene(Some(edge));
        let camera = Camera::framing(View::Top, scene.bounds(), W as f32 / H as f32);
        let image = gpu.render(&scene, &camera, W, H).unwrap();
        assert_eq!(
            (image.width, image.height, image.pixels.len()),
            (W, H, (W * H * 4) as usize)
        );

        let bg = background_fraction(&image, scene.background());
        assert!(bg < 0.5, "image is mostly background ({:.0}%)", bg * 100.0);
        assert!(
            bg > 0.05,
            "the framing leaves a margin ({:.0}% background)",
            bg * 100.0
        );

        // The centre quads are red, lit nearly head-on; a corner quad is the surface colour.
        let centre = to_pixel(&camera, Vec3::new(0.5, 0.5, 0.0));
        let p = image.pixel(centre.0, centre.1).unwrap();
        assert!(
            p[0] > 150 && p[1] < 80 && p[2] < 80,
            "centre pixel {p:?} is not the red face colour"
        );
        let corner = to_pixel(&camera, Vec3::new(-2.5, -2.5, 0.0));
        let q = image.pixel(corner.0, corner.1).unwrap();
        assert!(
            close(q, palette::SURFACE.0, 30),
            "corner face pixel {q:?} is not the surface colour"
        );
        assert!(q[2] > q[0], "surface colour is bluish: {q:?}");

        // Edges: the pixel on every grid line midpoint is (nearly) black.
        let mut dark = 0;
        let mut total = 0;
        for i in 0..7 {
            for j in 0..6 {
                for p in [
                    Vec3::new(j as f32 - 2.5, i as f32 - 3.0, 0.0),
                    Vec3::new(i as f32 - 3.0, j as f32 - 2.5, 0.0),
                ] {
                    let (x, y) = to_pixel(&camera, p);
                    total += 1;
                    // Allow a pixel of rounding: darkest of the 3 × 3 neighbourhood.
                    let darkest = (x.saturating_sub(1)..=x + 1)
                        .flat_map(|x| (y.saturating_sub(1)..=y + 1).map(move |y| (x, y)))
                        .filter_map(|(x, y)| image.pixel(x, y))
                        .map(|p| p[0].max(p[1]).max(p[2]))
                        .min()
                        .unwrap();
                    if darkest < 60 {
                        dark += 1;
                    }
                }
            }
        }
        assert_eq!(
            dark, total,
            "only {dark} of {total} edge midpoints are drawn dark"
        );
    });
}

#[test]
fn edges_win_over_faces_at_grazing_angles() {
    with_gpu(|gpu| {
        let (scene, _) = grid_scene(Some(LineStyle::new(Color::BLACK, 1.0)));
        let mut camera = Camera::new(View::Iso);
        camera.pitch = 0.15; // low, grazing view
        camera.fit(scene.bounds(), W as f32 / H as f32);
        let image = gpu.render(&scene, &camera, W, H).unwrap();
        // Along a grid line in the middle of the image, the edge must show (no z-fighting gaps).
        let mut dark = 0;
        let samples = 40;
        for k in 0..samples {
            let t = -2.8 + 5.6 * k as f32 / (samples - 1) as f32;
            let (x, y) = to_pixel(&camera, Vec3::new(t, 0.0, 0.0));
            let darkest = (y.saturating_sub(1)..=y + 1)
                .filter_map(|y| image.pixel(x, y))
                .map(|p| p[0].max(p[1]).max(p[2]))
                .min()
                .unwrap();
            if darkest < 110 {
                dark += 1;
            }
        }
        assert!(
            dark >= samples - 1,
            "edge visible at only {dark} of {samples} samples"
        );
    });
}

#[test]
fn rendering_twice_gives_identical_pixels() {
    with_gpu(|gpu| {
        let (mut scene, grid) = grid_scene(Some(MeshStyle::default_edges()));
        scene.add_points(&[DVec3::new(0.0, 0.0, 2.0)], PointStyle::default());
        scene.add_polyline(&grid.row(0), LineStyle::new(palette::LINE, 3.0));
        let a = gpu.render_view(&scene, View::Iso, W, H).unwrap();
        let b = gpu.render_view(&scene, View::Iso, W, H).unwrap();
        assert!(a == b, "two renders of the same scene differ");
        // A different view gives a different picture (the camera is honoured).
        let c = gpu.render_view(&scene, View::Front, W, H).unwrap();
        assert!(a != c);
    });
}

#[test]
fn empty_scene_is_uniform_background() {
    with_gpu(|gpu| {
        let scene = Scene::new().with_background(Color::hex(0x204060));
        let image = gpu.render_view(&scene, View::Iso, 64, 48).unwrap();
        assert_eq!(image.count_color(Color::hex(0x204060).0), 64 * 48);
        // Odd sizes need row padding on readback; still uniform and the right size.
        let image = gpu.render_view(&scene, View::Top, 37, 5).unwrap();
        assert_eq!(image.pixels.len(), 37 * 5 * 4);
        assert_eq!(image.count_color(Color::hex(0x204060).0), 37 * 5);
    });
}

#[test]
fn zero_and_huge_sizes_are_errors_not_panics() {
    with_gpu(|gpu| {
        let (scene, _) = grid_scene(None);
        let camera = Camera::default();
        assert!(matches!(
            gpu.render(&scene, &camera, 0, 10),
            Err(RenderError::InvalidSize { .. })
        ));
        assert!(matches!(
            gpu.render(&scene, &camera, 10, 0),
            Err(RenderError::InvalidSize { .. })
        ));
        assert!(matches!(
            gpu.render(&scene, &camera, 1 << 20, 4),
            Err(RenderError::InvalidSize { .. })
        ));
        // Still usable afterwards.
        assert!(gpu.render(&scene, &camera, 8, 8).is_ok());
    });
}

#[test]
fn nan_geometry_renders_without_error() {
    with_gpu(|gpu| {
        let (mut scene, mut grid) = grid_scene(None);
        *grid.at_mut(3, 3) = DVec3::new(f64::NAN, 0.0, 0.0);
        scene.add_quad_grid(&grid, FaceColors::default()).unwrap();
        scene.add_points(&[DVec3::splat(f64::NAN)], PointStyle::default());
        let image = gpu.render_view(&scene, View::Iso, W, H).unwrap();
        assert!(background_fraction(&image, scene.background()) < 0.9);
    });
}

#[test]
fn depth_tested_and_on_top_points_behind_a_surface() {
    with_gpu(|gpu| {
        let (mut scene, _) = grid_scene(None);
        // Both below the grid, seen from the top: the depth-tested one is hidden, the default
        // (on top) one shows.
        let below = [DVec3::new(-1.5, 0.5, -1.0)];
        let above = [DVec3::new(1.5, 0.5, -1.0)];
        let green = Color::hex(0x00ff00);
        scene.add_points(
            &below,
            PointStyle::new(green, 12.0)
                .shape(PointShape::Square)
                .depth_tested(),
        );
        scene.add_points(
            &above,
            PointStyle::new(green, 12.0)
                .shape(PointShape::Square)
                .on_top(),
        );
        let camera = Camera::framing(View::Top, scene.bounds(), W as f32 / H as f32);
        let image = gpu.render(&scene, &camera, W, H).unwrap();
        let (x, y) = to_pixel(&camera, Vec3::new(-1.5, 0.5, -1.0));
        assert!(
            !close(image.pixel(x, y).unwrap(), green.0, 40),
            "hidden point shows through"
        );
        let (x, y) = to_pixel(&camera, Vec3::new(1.5, 0.5, -1.0));
        assert!(
            close(image.pixel(x, y).unwrap(), green.0, 10),
            "on-top point is hidden"
        );
        // Squares are 12 px: about 144 green pixels for the visible one.
        let n = image.count_color(green.0);
        assert!((100..=200).contains(&n), "{n} green pixels");
    });
}

/// Four distinct face colours (the editor's class colours are of this kind).
const FACE_COLORS: [Color; 4] = [
    Color::hex(0x8fb4d9),
    Color::hex(0xd62f2f),
    Color::hex(0xf28e1c),
    Color::hex(0x7b3fa8),
];

#[test]
fn per_face_colours_render_in_their_colours() {
    with_gpu(|gpu| {
        // Four quads side by side in four colours, no edges.
        let v = (0..2)
            .flat_map(|i| (0..5).map(move |j| DVec3::new(j as f64, i as f64, 0.0)))
            .collect();
        let grid = QuadGrid::new(2, 5, v).unwrap();
        let colors = FACE_COLORS;
        let mut scene = Scene::new();
        scene
            .add_quad_grid(
                &grid,
                MeshStyle::new(FaceColors::PerFace(&colors)).edges(None),
            )
            .unwrap();
        let camera = Camera::framing(View::Top, scene.bounds(), W as f32 / H as f32);
        let image = gpu.render(&scene, &camera, W, H).unwrap();
        let pixels: Vec<[u8; 4]> = (0..4)
            .map(|k| {
                let (x, y) = to_pixel(&camera, Vec3::new(k as f32 + 0.5, 0.5, 0.0));
                image.pixel(x, y).unwrap()
            })
            .collect();
        for (k, p) in pixels.iter().enumerate() {
            // Lit at ~95 %: within a few levels of the class colour.
            assert!(
                close(*p, colors[k].0, 20),
                "face {k}: {p:?} vs {:?}",
                colors[k]
            );
        }
    });
}

#[test]
fn png_round_trip_and_atomic_save() {
    with_gpu(|gpu| {
        let (scene, _) = grid_scene(Some(MeshStyle::default_edges()));
        let image = gpu.render_view(&scene, View::Iso, W, H).unwrap();
        let dir = std::env::temp_dir().join(format!("cnets-render-png-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("grid.png");
        image.save_png(&path).unwrap();
        // Overwriting works too (rename over an existing file).
        image.save_png(&path).unwrap();
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(
            names,
            vec![std::ffi::OsString::from("grid.png")],
            "temporary file left behind"
        );

        let decoder =
            png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&path).unwrap()));
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        assert_eq!((info.width, info.height), (W, H));
        assert_eq!(info.color_type, png::ColorType::Rgba);
        assert_eq!(&buf[..info.buffer_size()], &image.pixels[..]);

        // A path in a missing directory is a typed error.
        let err = image.save_png(dir.join("missing/dir/x.png")).unwrap_err();
        assert!(matches!(err, RenderError::Png { .. }), "{err}");
        std::fs::remove_dir_all(&dir).unwrap();
    });
}

/// Draws the renderer's texture through a [`Blitter`] into a target like egui's and reads it back.
fn blit_into(
    gpu: &Offscreen,
    renderer: &SceneRenderer,
    format: wgpu::TextureFormat,
    samples: u32,
    depth: Option<wgpu::TextureFormat>,
) -> Image {
    let device = gpu.device();
    let (w, h) = renderer.size();
    let size = wgpu::Extent3d {
        width: w,
        height: h,
        depth_or_array_layers: 1,
    };
    let make = |format, samples, usage| {
        device.create_texture(&wgpu::TextureDescriptor {
            label: None,
            size,
            mip_level_count: 1,
            sample_count: samples,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        })
    };
    let target = make(
        format,
        1,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
    );
    let target_view = target.create_view(&Default::default());
    let msaa = (samples > 1).then(|| {
        make(format, samples, wgpu::TextureUsages::RENDER_ATTACHMENT)
            .create_view(&Default::default())
    });
    let depth_view = depth.map(|f| {
        make(f, samples, wgpu::TextureUsages::RENDER_ATTACHMENT).create_view(&Default::default())
    });

    let blitter = Blitter::new(device, format, samples, depth);
    assert_eq!(blitter.target_format(), format);
    let mut source = None;
    blitter.update_source(device, renderer, &mut source);
    let source = source.expect("renderer has a texture");
    assert!(source.is_current(renderer));

    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: None,
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: msaa.as_ref().unwrap_or(&target_view),
                depth_slice: None,
                resolve_target: msaa.as_ref().map(|_| &target_view),
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: depth_view.as_ref().map(|view| {
                wgpu::RenderPassDepthStencilAttachment {
                    view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        // Like egui: the viewport is the callback rect (here the whole target).
        pass.set_viewport(0.0, 0.0, w as f32, h as f32, 0.0, 1.0);
        blitter.draw(&mut pass, &source);
    }
    gpu.queue().submit([encoder.finish()]);
    let error = pollster::block_on(scope.pop());
    assert!(
        error.is_none(),
        "blit into {format:?}×{samples} {depth:?}: {error:?}"
    );
    read_texture(device, gpu.queue(), &target).unwrap()
}

#[test]
fn blitter_copies_the_scene_into_egui_like_passes() {
    with_gpu(|gpu| {
        let (scene, _) = grid_scene(Some(MeshStyle::default_edges()));
        let camera = Camera::framing(View::Iso, scene.bounds(), W as f32 / H as f32);
        let device = gpu.device().clone();
        let queue = gpu.queue().clone();
        let mut renderer = SceneRenderer::new(&device, RendererOptions::default());
        renderer.set_scene(&device, &queue, &scene);
        let mut encoder = device.create_command_encoder(&Default::default());
        assert!(
            renderer
                .render(&device, &queue, &mut encoder, &camera, W, H)
                .unwrap()
        );
        // Nothing changed: no second pass.
        assert!(
            !renderer
                .render(&device, &queue, &mut encoder, &camera, W, H)
                .unwrap()
        );
        queue.submit([encoder.finish()]);
        let reference = read_texture(&device, &queue, renderer.color_texture().unwrap()).unwrap();
        assert!(background_fraction(&reference, scene.background()) < 0.9);
        // Same as the Offscreen path.
        assert!(reference == gpu.render(&scene, &camera, W, H).unwrap());

        // kittest: Rgba8Unorm, no MSAA, no depth. eframe on X11: Bgra8Unorm; also with MSAA + depth.
        let cases = [
            (wgpu::TextureFormat::Rgba8Unorm, 1, None),
            (wgpu::TextureFormat::Bgra8Unorm, 1, None),
            (
                wgpu::TextureFormat::Bgra8Unorm,
                4,
                Some(wgpu::TextureFormat::Depth32Float),
            ),
            (
                wgpu::TextureFormat::Rgba8UnormSrgb,
                1,
                Some(wgpu::TextureFormat::Depth24Plus),
            ),
        ];
        for (format, samples, depth) in cases {
            let out = blit_into(gpu, &renderer, format, samples, depth);
            let max_diff = out
                .pixels
                .iter()
                .zip(&reference.pixels)
                .map(|(a, b)| (i32::from(*a) - i32::from(*b)).abs())
                .max()
                .unwrap();
            assert!(
                max_diff <= 1,
                "{format:?}×{samples}: blit differs from the scene by {max_diff}"
            );
        }

        // A resize recreates the texture: the old source is stale.
        let blitter = Blitter::new(&device, wgpu::TextureFormat::Rgba8Unorm, 1, None);
        let source = blitter.source(&device, &renderer).unwrap();
        let mut encoder = device.create_command_encoder(&Default::default());
        assert!(
            renderer
                .render(&device, &queue, &mut encoder, &camera, W / 2, H / 2)
                .unwrap()
        );
        queue.submit([encoder.finish()]);
        assert!(!source.is_current(&renderer));
        assert_eq!(renderer.size(), (W / 2, H / 2));
    });
}

#[test]
fn scene_changes_are_uploaded_and_buffers_grow_and_shrink_correctly() {
    with_gpu(|gpu| {
        let (small, _) = grid_scene(Some(MeshStyle::default_edges()));
        let camera = Camera::framing(View::Iso, small.bounds(), W as f32 / H as f32);
        let first = gpu.render(&small, &camera, W, H).unwrap();
        // A much larger scene in the same place (the buffers must grow).
        let n = 60;
        let v = (0..n)
            .flat_map(|i| {
                (0..n).map(move |j| {
                    let (x, y) = (j as f64 / 10.0 - 3.0, i as f64 / 10.0 - 3.0);
                    DVec3::new(x, y, 0.3 * (x * y).sin())
                })
            })
            .collect();
        let mut large = Scene::new();
        large
            .add_quad_grid(&QuadGrid::new(n, n, v).unwrap(), FaceColors::default())
            .unwrap();
        let big = gpu.render(&large, &camera, W, H).unwrap();
        assert!(big != first);
        // Back to the small scene: stale data past the new counts must not be drawn.
        let again = gpu.render(&small, &camera, W, H).unwrap();
        assert!(
            again == first,
            "re-rendering the small scene after a large one differs"
        );
    });
}

/// A tilted plane as a 7 × 7 grid and the same surface as a polygon mesh whose faces start one
/// corner later (the other diagonal): coincident surfaces whose depths differ by rounding, which
/// z-fight.
fn coincident_surfaces() -> (QuadGrid, cnets_geometry::PolygonMesh) {
    let n = 7;
    let v = (0..n)
        .flat_map(|i| {
            (0..n).map(move |j| {
                let (x, y) = (j as f64 - 3.0, i as f64 - 3.0);
                DVec3::new(x, y, 0.3 * x + 0.2 * y)
            })
        })
        .collect();
    let grid = QuadGrid::new(n, n, v).unwrap();
    let mut mesh = cnets_geometry::PolygonMesh::from(&grid);
    for f in 0..mesh.face_count() {
        let start = mesh.face_starts[f] as usize;
        mesh.indices[start..start + 4].rotate_left(1);
    }
    (grid, mesh)
}

/// Pixels of the image whose red (`red`) or blue channel clearly dominates, however lit.
fn count_dominant(image: &Image, red: bool) -> usize {
    image
        .pixels
        .chunks_exact(4)
        .filter(|p| {
            let (r, b) = (i32::from(p[0]), i32::from(p[2]));
            if red { r > b + 40 } else { b > r + 40 }
        })
        .count()
}

#[test]
fn coincident_surfaces_on_depth_layers_do_not_z_fight() {
    with_gpu(|gpu| {
        let (blue, red) = (Color::hex(0x1f4fd8), Color::hex(0xd62f2f));
        let (grid, mesh) = coincident_surfaces();
        let render = |layers: (u32, u32), gpu: &mut Offscreen| {
            let mut scene = Scene::new();
            // The upper layer first: drawing order alone would let the later surface win.
            scene
                .add_quad_grid(
                    &grid,
                    MeshStyle::new(FaceColors::Uniform(blue))
                        .edges(None)
                        .depth_layer(layers.0),
                )
                .unwrap();
            scene
                .add_polygon_mesh(
                    &mesh,
                    MeshStyle::new(FaceColors::Uniform(red))
                        .edges(None)
                        .depth_layer(layers.1),
                )
                .unwrap();
            let mut camera = Camera::new(View::Iso);
            camera.pitch = 0.35;
            camera.fit(scene.bounds(), W as f32 / H as f32);
            gpu.render(&scene, &camera, W, H).unwrap()
        };
        let layered = render((1, 0), gpu);
        let (b, r) = (
            count_dominant(&layered, false),
            count_dominant(&layered, true),
        );
        assert!(b > 2000, "the surface covers the picture: {b} blue pixels");
        assert_eq!(r, 0, "{r} red pixels through the upper layer ({b} blue)");
        // The control: on one layer the same surfaces fight (the red one shows through).
        let flat = render((0, 0), gpu);
        let r0 = count_dominant(&flat, true);
        eprintln!("layered: {b} blue, {r} red; one layer: {r0} red");
        assert!(
            r0 > 100,
            "without layers {r0} red pixels: the test would not see z-fighting"
        );
    });
}
