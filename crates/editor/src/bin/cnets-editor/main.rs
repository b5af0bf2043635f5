//! `cnets-editor [FILE] [--screenshot OUT.png] [--quit-after-frames N] [--size WxH]`
//!
//! The cnets desktop editor. With `--screenshot`, it waits for the first evaluation, takes an
//! in-app screenshot (egui `ViewportCommand::Screenshot`) after N frames (default 10), writes it
//! as PNG and quits: `scripts/editor-screenshot.sh` uses it under Xvfb.
//!
//! Started with a FILE while a window with the same settings folder is open, it hands the file
//! to that window (which asks about unsaved changes first) and exits.
//!
//! The test kit (the benchmarks and the scripted sessions the window tests play) is in
//! `drivers/`, built only with the feature `drivers` (`cargo test` in `scripts/test.sh` enables
//! it; the release build does not); without it `no_drivers.rs` stands in.

use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use anyhow::{Context as _, bail};
use cnets_editor::app::{AppOptions, EditorApp};
use cnets_editor::viewport::GpuTarget;

#[cfg(feature = "drivers")]
mod drivers;
#[cfg(not(feature = "drivers"))]
#[path = "no_drivers.rs"]
mod drivers;

use drivers::{DriverArgs, Drivers};

/// The process allocator: mimalloc keeps freed memory for reuse, where glibc's malloc hands large
/// freed blocks (a 1000 × 1000 construction's 49 MB) back to the kernel and page-faults them in again
/// on the next evaluation (docs/geometry.md, Performance).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

struct Args {
    file: Option<PathBuf>,
    screenshot: Option<PathBuf>,
    quit_after: u32,
    size: [f32; 2],
    drivers: DriverArgs,
}

fn parse_args() -> anyhow::Result<Args> {
    let mut args = Args {
        file: None,
        screenshot: None,
        quit_after: 10,
        size: [1400.0, 860.0],
        drivers: DriverArgs::default(),
    };
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--screenshot" => {
                args.screenshot = Some(it.next().context("--screenshot needs a path")?.into())
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
            "-h" | "--help" => {
                println!(
                    "cnets-editor [FILE] [--screenshot OUT.png] [--quit-after-frames N] [--size WxH] {}",
                    drivers::HELP
                );
                std::process::exit(0);
            }
            s if args.drivers.take(s, &mut it)? => {}
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
    drivers: Drivers,
    config_dir: PathBuf,
    /// When the window was made.
    opened: std::time::Instant,
}

/// How long the screenshot mode waits for the evaluation to end and its picture to be drawn.
const SCREENSHOT_PATIENCE: Duration = Duration::from_secs(300);

impl Window {
    /// The evaluation is done and its picture drawn.
    fn settled(&self) -> bool {
        !self.app.busy()
            && self.app.viewport().handed_version() >= self.app.viewport().scene_version()
    }
}

impl eframe::App for Window {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        if self.screenshot.is_some() && self.frames == 0 {
            // Show the evaluated graph in the picture, not the first empty frame.
            self.app.wait_for_worker(Duration::from_secs(60));
        }
        self.drivers.before_frame(&mut self.app);
        let started = std::time::Instant::now();
        self.app.ui(ui);
        let ctx = ui.ctx().clone();
        let ui_ms = started.elapsed().as_secs_f64() * 1e3;
        self.drivers.after_frame(&mut self.app, &ctx, ui_ms);
        if self.app.wants_to_quit() {
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
            self.app.quit_now();
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        } else if self.frames >= self.quit_after
            && !self.requested
            && self.app.viewport().framing().render_scale >= 1.0
            && (self.settled() || self.opened.elapsed() > SCREENSHOT_PATIENCE)
        {
            // (On a software rasterizer the view renders at full resolution once it settles; a
            // heavy graph on a busy machine may still be evaluating after the first wait.)
            ctx.send_viewport_cmd(egui::ViewportCommand::Screenshot(egui::UserData::default()));
            self.requested = true;
        }
        ctx.request_repaint();
    }

    fn raw_input_hook(&mut self, ctx: &egui::Context, raw_input: &mut egui::RawInput) {
        self.drivers.filter_input(raw_input);
        self.app.raw_input(raw_input);
        self.drivers.inject(&self.app, ctx, raw_input);
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
    let launched = std::time::Instant::now();
    let mut args = parse_args()?;
    let config_dir = cnets_editor::settings::config_dir();
    let test_mode = args.screenshot.is_some() || args.drivers.any();
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
    let injects_pointer = args.drivers.injects_pointer();
    let drivers = std::mem::take(&mut args.drivers);
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
            if test_mode {
                // The screenshot, benchmark and scripted modes start on the file given, read.
                app.wait_for_loading(Duration::from_secs(600));
            }
            if injects_pointer {
                // A scripted click is a click however long its frame took on a busy machine
                // (egui's real-window clock would call a press held over 0.8 s a long press).
                cc.egui_ctx
                    .options_mut(|o| o.input_options.max_click_duration = f64::INFINITY);
            }
            Ok(Box::new(Window {
                app,
                screenshot: args.screenshot.clone(),
                quit_after: args.quit_after.max(1),
                frames: 0,
                requested: false,
                result: result2,
                drivers: drivers.start(launched),
                config_dir: config_dir.clone(),
                opened: std::time::Instant::now(),
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
