//! Renders a demo scene (a wavy 100 × 100 quad grid with edges, a boundary polyline and a few
//! points) from each preset view into PNG files and prints timings.
//!
//! `cargo run --release -p cnets-render --example preview -- [OUT_DIR] [N]` (default: `target/preview`, 100).

use std::time::Instant;

use cnets_geometry::{DVec3, Polyline, QuadGrid};
use cnets_render::{
    Camera, FaceColors, LineStyle, MeshStyle, Offscreen, PointStyle, RendererOptions, Scene,
    SceneRenderer, SequentialMap, View, palette, wgpu,
};

fn wavy_grid(n: usize) -> QuadGrid {
    let vertices = (0..n)
        .flat_map(|i| {
            (0..n).map(move |j| {
                let (u, v) = (i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64);
                let (x, y) = (v * 10.0 - 5.0, u * 8.0 - 4.0);
                DVec3::new(x, y, 1.2 * (0.6 * x).sin() * (0.5 * y).cos() + 0.05 * x * y)
            })
        })
        .collect();
    QuadGrid::new(n, n, vertices).expect("grid")
}

fn build(scene: &mut Scene, grid: &QuadGrid, colors: &[cnets_render::Color]) {
    scene.clear();
    scene
        .add_quad_grid(grid, MeshStyle::new(FaceColors::PerFace(colors)))
        .expect("mesh");
    let boundary = Polyline::open(grid.row(0).points);
    scene.add_polyline(&boundary, LineStyle::new(palette::LINE, 3.0));
    let apices: Vec<DVec3> = (0..grid.cols)
        .step_by(grid.cols.div_ceil(8))
        .map(|j| grid.at(0, j) + DVec3::Z)
        .collect();
    scene.add_points(&apices, PointStyle::new(palette::POINT, 10.0));
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let out = std::path::PathBuf::from(args.next().unwrap_or_else(|| "target/preview".into()));
    let n: usize = args.next().map_or(Ok(100), |s| s.parse())?;
    std::fs::create_dir_all(&out)?;

    let grid = wavy_grid(n);
    // Per-face colours: classes in four bands, to show the class palette.
    let qc = grid.quad_cols();
    let colors: Vec<_> = (0..grid.quad_count())
        .map(|k| {
            let j = k % qc;
            if j < qc / 2 {
                palette::SURFACE
            } else {
                palette::viridis(((k / qc) * 4 / grid.quad_rows()) as f32 / 3.0)
            }
        })
        .collect();

    let mut scene = Scene::new();
    let reps = 50;
    build(&mut scene, &grid, &colors);
    let t = Instant::now();
    for _ in 0..reps {
        build(&mut scene, &grid, &colors);
    }
    let build_ms = t.elapsed().as_secs_f64() * 1e3 / f64::from(reps);
    println!(
        "scene build {n}×{n} vertices ({} quads): {build_ms:.3} ms ({} triangles, {} segments)",
        grid.quad_count(),
        scene.triangle_count(),
        scene.segments().len()
    );

    let t = Instant::now();
    let mut gpu = Offscreen::new()?;
    println!(
        "adapter: {} (start {:.0} ms)",
        gpu.adapter_summary(),
        t.elapsed().as_secs_f64() * 1e3
    );

    for view in View::ALL {
        let image = gpu.render_view(&scene, view, 1280, 720)?;
        let path = out.join(format!("demo-{view}.png"));
        image.save_png(&path)?;
        println!("wrote {}", path.display());
    }
    // Frame timing: re-render (camera changes each frame, so a full pass plus readback).
    let mut camera = Camera::framing(View::Iso, scene.bounds(), 1280.0 / 720.0);
    let frames = 10;
    let t = Instant::now();
    for _ in 0..frames {
        camera.orbit(0.01, 0.0);
        gpu.render(&scene, &camera, 1280, 720)?;
    }
    println!(
        "frame 1280×720 incl. upload + readback: {:.1} ms",
        t.elapsed().as_secs_f64() * 1e3 / f64::from(frames)
    );

    // The pass alone (as in the editor: no readback), with and without MSAA.
    for samples in [4, 1] {
        let device = gpu.device().clone();
        let queue = gpu.queue().clone();
        let mut renderer = SceneRenderer::new(
            &device,
            RendererOptions {
                sample_count: samples,
            },
        );
        renderer.set_scene(&device, &queue, &scene);
        let t = Instant::now();
        for _ in 0..frames {
            camera.orbit(0.01, 0.0);
            let mut encoder = device.create_command_encoder(&Default::default());
            renderer.render(&device, &queue, &mut encoder, &camera, 1280, 720)?;
            queue.submit([encoder.finish()]);
            device.poll(wgpu::PollType::wait_indefinitely())?;
        }
        println!(
            "scene pass only 1280×720, {samples}× MSAA: {:.1} ms",
            t.elapsed().as_secs_f64() * 1e3 / f64::from(frames)
        );
    }

    // Planarity-style colouring.
    let values: Vec<f64> = grid
        .quads()
        .map(|(_, q)| (q[0] - q[2]).length() * 1e-3)
        .collect();
    let map = SequentialMap::fit(&values);
    let pc = map.colors(&values);
    scene.clear();
    scene.add_quad_grid(&grid, FaceColors::PerFace(&pc))?;
    gpu.render_view(&scene, View::Iso, 1280, 720)?
        .save_png(out.join("demo-planarity.png"))?;
    println!("legend: {:?}", map.legend("planarity", 3));

    // A closed surface (both directions wrap): a torus, classes in bands, with a polyline and apices.
    let (rows, cols) = (24, 48);
    let torus: Vec<DVec3> = (0..rows)
        .flat_map(|i| {
            (0..cols).map(move |j| {
                let (u, v) = (
                    i as f64 / rows as f64 * std::f64::consts::TAU,
                    j as f64 / cols as f64 * std::f64::consts::TAU,
                );
                let r = 3.0 + 1.2 * u.cos();
                DVec3::new(r * v.cos(), r * v.sin(), 1.2 * u.sin())
            })
        })
        .collect();
    let torus = QuadGrid::new(rows, cols, torus)?.with_wrap(true, true);
    let tc: Vec<_> = torus
        .quads()
        .map(|((i, _), _)| palette::viridis((i * 4 / rows) as f32 / 3.0))
        .collect();
    scene.clear();
    scene.add_quad_grid(&torus, FaceColors::PerFace(&tc))?;
    scene.add_polyline(&torus.row(0), LineStyle::new(palette::LINE, 3.0));
    scene.add_points(
        &[DVec3::new(0.0, 0.0, 2.5)],
        PointStyle::new(palette::POINT, 12.0).on_top(),
    );
    for view in [View::Iso, View::Top] {
        gpu.render_view(&scene, view, 960, 640)?
            .save_png(out.join(format!("torus-{view}.png")))?;
    }
    println!("wrote torus-*.png");
    Ok(())
}
