//! `cnets-editor [FILE] [--screenshot OUT.png] [--quit-after-frames N] [--size WxH]`
//!
//! The cnets desktop editor. With `--screenshot`, it waits for the first evaluation, takes an
//! in-app screenshot (egui `ViewportCommand::Screenshot`) after N frames (default 10), writes it
//! as PNG and quits: `scripts/editor-screenshot.sh` uses it under Xvfb.
//!
//! Started with a FILE while a window with the same settings folder is open, it hands the file
//! to that window (which asks about unsaved changes first) and exits.
//!
//! Test modes (the real window under Xvfb, `tests/window.rs`): `--drive-drag` drags the first
//! `param.number` slider with injected pointer events (press, moves, release), prints the values
//! shown once released and keeps running (the test kills it); `--restore-and-print` accepts the
//! recovery file's restore, prints the values and quits.

use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use anyhow::{Context as _, bail};
use cnets_editor::app::{AppOptions, EditorApp};
use cnets_editor::viewport::GpuTarget;

/// The process allocator: mimalloc keeps freed memory for reuse, where glibc's malloc hands large
/// freed blocks (a 1000 × 1000 construction's 49 MB) back to the kernel and page-faults them in again
/// on the next evaluation (docs/geometry.md, Performance).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

struct Args {
    file: Option<PathBuf>,
    bench_drag: Option<u32>,
    screenshot: Option<PathBuf>,
    quit_after: u32,
    size: [f32; 2],
    drive_drag: bool,
    restore_and_print: bool,
}

fn parse_args() -> anyhow::Result<Args> {
    let mut args = Args {
        file: None,
        bench_drag: None,
        screenshot: None,
        quit_after: 10,
        size: [1400.0, 860.0],
        drive_drag: false,
        restore_and_print: false,
    };
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--screenshot" => {
                args.screenshot = Some(it.next().context("--screenshot needs a path")?.into())
            }
            "--bench-drag" => {
                args.bench_drag = Some(
                    it.next()
                        .context("--bench-drag needs a frame count")?
                        .parse()?,
                )
            }
            "--quit-after-frames" => {
                args.quit_after = it
                    .next()
                    .context("--quit-after-frames needs a number")?
                    .parse()?
            }
            "--size" => {
                let s = it.next().context("--size needs WxH")?;
                let (w, h) = s.split_once('x').context("--size needs WxH")?;
                args.size = [w.parse()?, h.parse()?];
            }
            "--drive-drag" => args.drive_drag = true,
            "--restore-and-print" => args.restore_and_print = true,
            "-h" | "--help" => {
                println!(
                    "cnets-editor [FILE] [--screenshot OUT.png] [--quit-after-frames N] [--size WxH]"
                );
                std::process::exit(0);
            }
            s if s.starts_with('-') => bail!("unknown option {s}"),
            _ => args.file = Some(a.into()),
        }
    }
    Ok(args)
}

/// The window: the editor plus the screenshot mode.
struct Window {
    app: EditorApp,
    screenshot: Option<PathBuf>,
    quit_after: u32,
    frames: u32,
    requested: bool,
    result: Arc<Mutex<Option<anyhow::Result<()>>>>,
    bench: Option<Bench>,
    drive: Option<Drive>,
    restore_and_print: bool,
    config_dir: PathBuf,
}

/// The values of every `param.number` slider, one `node.value = x` a line (full precision).
fn slider_values(app: &EditorApp) -> String {
    let mut lines: Vec<String> = app
        .doc
        .graph
        .nodes()
        .filter(|(_, n)| n.def.id == "param.number")
        .map(|(_, n)| {
            let v = n.value_of("value").and_then(cnets_engine::Value::as_f64);
            format!("{}.value = {v:?}", n.id)
        })
        .collect();
    lines.sort();
    lines.join("\n")
}

/// `--drive-drag`: a slider drag made of real egui pointer events, injected into the window's
/// raw input (the same path a mouse takes after winit).
struct Drive {
    frames: u32,
    /// Where the press happens and how far the drag goes (screen points), once the slider is
    /// drawn.
    from: Option<egui::Pos2>,
    to: egui::Pos2,
    step: u32,
    node: String,
    /// The dragged slider's value before the drag.
    was: Option<f64>,
    reported: bool,
}

/// Moves between the press and the release.
const DRIVE_MOVES: u32 = 12;

impl Drive {
    /// Finds the slider once the canvas has been framed (a few frames after the first results).
    fn locate(&mut self, app: &EditorApp) {
        if self.from.is_some() {
            return;
        }
        self.frames += 1;
        if self.frames < 30 {
            return;
        }
        let Some(id) = first_slider(app) else {
            return;
        };
        if let Some(r) = app.canvas.editor_screen_rect(&id, "value") {
            // On the rail: from a quarter of the way to 85 % (the rail is the left part of the
            // editor; the value box follows it).
            let rail = r.width().min(110.0 * app.canvas.zoom());
            let y = r.center().y;
            self.from = Some(egui::pos2(r.left() + rail * 0.25, y));
            self.to = egui::pos2(r.left() + rail * 0.85, y);
            self.was = app
                .doc
                .graph
                .node(&id)
                .and_then(|n| n.value_of("value"))
                .and_then(cnets_engine::Value::as_f64);
            self.node = id;
        }
    }

    fn inject(&mut self, raw: &mut egui::RawInput) {
        let Some(from) = self.from else {
            return;
        };
        let press = |pos, pressed| egui::Event::PointerButton {
            pos,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: egui::Modifiers::NONE,
        };
        let t = self.step as f32 / DRIVE_MOVES as f32;
        let at = from + (self.to - from) * t.min(1.0);
        match self.step {
            0 => {
                raw.events.push(egui::Event::PointerMoved(from));
                raw.events.push(press(from, true));
            }
            s if s <= DRIVE_MOVES => raw.events.push(egui::Event::PointerMoved(at)),
            s if s == DRIVE_MOVES + 1 => raw.events.push(press(self.to, false)),
            _ => return,
        }
        self.step += 1;
    }

    /// After the release frame: prints what the window shows (the test kills the process then).
    fn report(&mut self, app: &EditorApp) {
        if self.reported || self.step <= DRIVE_MOVES + 1 {
            return;
        }
        self.reported = true;
        println!(
            "drive-drag: released {} pid {}",
            self.node,
            std::process::id()
        );
        println!("{}.value was {:?}", self.node, self.was);
        println!("{}", slider_values(app));
        println!("drive-drag: end");
        use std::io::Write as _;
        let _ = std::io::stdout().flush();
    }
}

/// `--bench-drag N`: moves the first `param.number` slider every frame for N frames (as a drag
/// would, one undo step), then prints change-to-picture latency and frame intervals.
struct Bench {
    frames: u32,
    done: u32,
    last_frame: Option<std::time::Instant>,
    intervals: Vec<f64>,
    evals: Vec<f64>,
    scenes: Vec<f64>,
    uis: Vec<f64>,
    seen: usize,
    reported: bool,
}

fn stats(v: &mut [f64]) -> String {
    if v.is_empty() {
        return "n/a".into();
    }
    v.sort_by(f64::total_cmp);
    let q = |f: f64| v[((v.len() - 1) as f64 * f).round() as usize];
    format!(
        "median {:.1} ms, p90 {:.1} ms, max {:.1} ms (n = {})",
        q(0.5),
        q(0.9),
        q(1.0),
        v.len()
    )
}

impl Bench {
    fn step(&mut self, app: &mut EditorApp, ctx: &egui::Context) {
        let now = std::time::Instant::now();
        if let Some(t) = self.last_frame {
            self.intervals.push((now - t).as_secs_f64() * 1e3);
        }
        self.last_frame = Some(now);
        if app.latency.samples.len() > self.seen {
            self.seen = app.latency.samples.len();
            self.evals.push(app.latency.eval_ms);
            self.scenes.push(app.latency.scene_ms);
        }
        if self.done >= self.frames {
            if std::mem::replace(&mut self.reported, true) {
                return;
            }
            let mut lat = app.latency.samples.clone();
            println!("bench-drag: {} frames, {} pictures", self.frames, lat.len());
            println!(
                "  change-to-picture (CPU side, up to the frame handing the scene to wgpu): {}",
                stats(&mut lat)
            );
            println!(
                "  frame interval (UI + GPU render + present): {}",
                stats(&mut self.intervals)
            );
            println!(
                "  UI thread per frame (egui + canvas + edit + submit): {}",
                stats(&mut self.uis)
            );
            println!("  evaluation (worker): {}", stats(&mut self.evals));
            println!("  scene build (worker): {}", stats(&mut self.scenes));
            println!("  vertices: {}", app.viewport.stats.vertices);
            // Quit without the unsaved-changes question.
            app.quit = true;
            ctx.request_repaint();
            return;
        }
        self.done += 1;
        ctx.request_repaint();
        if std::env::var_os("CNETS_BENCH_IDLE").is_some() {
            // Baseline: frames without changes (nothing re-evaluated, the 3D view not re-rendered).
            return;
        }
        let Some(id) = first_slider(app) else {
            return;
        };
        let node = app.doc.graph.node(&id).expect("the node");
        let (min, max, _) = cnets_editor::widgets::slider_range(node);
        let t = f64::from(self.done - 1) / 60.0;
        let value = min + (max - min) * (0.5 + 0.4 * (t * std::f64::consts::TAU).sin());
        let _ = cnets_editor::edit::apply(
            &mut app.doc,
            cnets_editor::edit::Edit::SetValue {
                node: id,
                input: "value".into(),
                value: cnets_engine::Value::Number(value),
            },
        );
    }
}

impl eframe::App for Window {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        if self.screenshot.is_some() && self.frames == 0 {
            // Show the evaluated graph in the picture, not the first empty frame.
            self.app.wait_for_worker(Duration::from_secs(60));
        }
        if self
            .bench
            .as_ref()
            .is_some_and(|b| b.done == 0 && b.last_frame.is_none())
        {
            self.app.wait_for_worker(Duration::from_secs(60));
        }
        if std::mem::take(&mut self.restore_and_print) {
            if self.app.restore_offered() {
                self.app.restore();
                self.app.wait_for_worker(Duration::from_secs(60));
                println!("restored: {}", self.app.message);
                println!("{}", slider_values(&self.app));
            } else {
                println!("restored: nothing to restore");
            }
            println!("restored: end");
            // Quit without the unsaved-changes question, keeping the recovery file.
            std::process::exit(0);
        }
        let started = std::time::Instant::now();
        self.app.ui(ui);
        let ctx = ui.ctx().clone();
        if let Some(d) = &mut self.drive {
            d.locate(&self.app);
            d.report(&self.app);
            if !d.reported {
                ctx.request_repaint();
            }
        }
        if let Some(b) = &mut self.bench {
            b.uis.push(started.elapsed().as_secs_f64() * 1e3);
            b.step(&mut self.app, &ctx);
        }
        if self.app.quit {
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        }
        let Some(out) = self.screenshot.clone() else {
            return;
        };
        self.frames += 1;
        let image = ctx.input(|i| {
            i.events.iter().find_map(|e| match e {
                egui::Event::Screenshot { image, .. } => Some(image.clone()),
                _ => None,
            })
        });
        if let Some(image) = image {
            let [w, h] = image.size;
            let pixels: Vec<u8> = image.pixels.iter().flat_map(|c| c.to_array()).collect();
            let png = cnets_render::Image {
                width: w as u32,
                height: h as u32,
                pixels,
            };
            let saved = png
                .save_png(&out)
                .map_err(anyhow::Error::from)
                .and_then(|()| {
                    eprintln!(
                        "cnets-editor: screenshot {w}x{h} written to {}",
                        out.display()
                    );
                    check_not_blank(&png)
                });
            *self.result.lock().unwrap_or_else(|p| p.into_inner()) = Some(saved);
            self.app.quit = true;
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        } else if self.frames >= self.quit_after
            && !self.requested
            && self.app.viewport.render_scale >= 1.0
        {
            // (On a software rasterizer the view renders at full resolution once it settles.)
            ctx.send_viewport_cmd(egui::ViewportCommand::Screenshot(egui::UserData::default()));
            self.requested = true;
        }
        ctx.request_repaint();
    }

    fn raw_input_hook(&mut self, _ctx: &egui::Context, raw_input: &mut egui::RawInput) {
        self.app.raw_input(raw_input);
        if let Some(d) = &mut self.drive {
            d.inject(raw_input);
        }
    }

    fn on_exit(&mut self) {
        self.app.on_exit();
        cnets_editor::instance::release(&self.config_dir);
    }
}

/// Fails when the screenshot is (nearly) blank: too few colours, or the right part (the 3D view)
/// one flat colour (less than 0.2 % of it drawn).
fn check_not_blank(image: &cnets_render::Image) -> anyhow::Result<()> {
    let mut colours = std::collections::HashSet::new();
    let mut right = std::collections::HashMap::<[u8; 4], usize>::new();
    for y in 0..image.height {
        for x in 0..image.width {
            let p = image.pixel(x, y).unwrap_or_default();
            colours.insert(p);
            if x > image.width * 6 / 10 && y > image.height / 10 && y < image.height * 9 / 10 {
                *right.entry(p).or_default() += 1;
            }
        }
    }
    let total: usize = right.values().sum();
    let background = right.values().copied().max().unwrap_or(0);
    let covered = 1.0 - background as f64 / total.max(1) as f64;
    eprintln!(
        "cnets-editor: {} colours; {:.0}% of the 3D view differs from its background",
        colours.len(),
        covered * 100.0
    );
    // A design of curves only (curves-demo) draws thin lines: half a percent of the view.
    if colours.len() < 64 || covered < 0.002 {
        bail!(
            "the screenshot looks blank ({} colours, {:.1}% of the 3D view drawn)",
            colours.len(),
            covered * 100.0
        );
    }
    Ok(())
}

fn main() -> anyhow::Result<()> {
    let args = parse_args()?;
    let config_dir = cnets_editor::settings::config_dir();
    let test_mode = args.screenshot.is_some()
        || args.bench_drag.is_some()
        || args.drive_drag
        || args.restore_and_print;
    if !test_mode
        && let Some(file) = &args.file
        && cnets_editor::instance::hand_over(&config_dir, file)
    {
        println!("cnets-editor: {} sent to the open window", file.display());
        return Ok(());
    }
    let examples_dir = std::env::var_os("CNETS_GRAPHS")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../graphs")));
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_inner_size(args.size)
            .with_title("cnets editor"),
        renderer: eframe::Renderer::Wgpu,
        ..Default::default()
    };
    let result = Arc::new(Mutex::new(None));
    let result2 = result.clone();
    let screenshot = args.screenshot.clone();
    eframe::run_native(
        "cnets editor",
        options,
        Box::new(move |cc| {
            let gpu = cc
                .wgpu_render_state
                .as_ref()
                .map(|rs| GpuTarget::from_render_state(rs, 1, None));
            let ctx = cc.egui_ctx.clone();
            let wake: Arc<dyn Fn() + Send + Sync> = Arc::new(move || ctx.request_repaint());
            let mut app = EditorApp::new(AppOptions {
                gpu,
                config_dir: config_dir.clone(),
                file: args.file.clone(),
                examples_dir,
                wake: wake.clone(),
            });
            if !test_mode && let Some(inbox) = cnets_editor::instance::listen(&config_dir, wake) {
                app.set_inbox(inbox);
            }
            Ok(Box::new(Window {
                app,
                screenshot: args.screenshot.clone(),
                quit_after: args.quit_after.max(1),
                frames: 0,
                requested: false,
                result: result2,
                bench: args.bench_drag.map(|frames| Bench {
                    frames,
                    done: 0,
                    last_frame: None,
                    intervals: Vec::new(),
                    evals: Vec::new(),
                    scenes: Vec::new(),
                    uis: Vec::new(),
                    seen: 0,
                    reported: false,
                }),
                drive: args.drive_drag.then(|| Drive {
                    frames: 0,
                    from: None,
                    to: egui::Pos2::ZERO,
                    step: 0,
                    node: String::new(),
                    was: None,
                    reported: false,
                }),
                restore_and_print: args.restore_and_print,
                config_dir: config_dir.clone(),
            }))
        }),
    )
    .map_err(|e| anyhow::anyhow!("cannot start the window: {e}"))?;
    if screenshot.is_some() {
        match result.lock().unwrap_or_else(|p| p.into_inner()).take() {
            Some(r) => r?,
            None => bail!("the window closed before the screenshot was taken"),
        }
    }
    Ok(())
}

/// The id of the graph's first number slider (what the drag measurements move).
fn first_slider(app: &EditorApp) -> Option<String> {
    app.doc
        .graph
        .nodes()
        .find(|(_, n)| n.def.id == "param.number")
        .map(|(_, n)| n.id.clone())
}
