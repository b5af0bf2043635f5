//! `cnets-editor [FILE] [--screenshot OUT.png] [--quit-after-frames N] [--size WxH]`
//!
//! The cnets desktop editor. With `--screenshot`, it waits for the first evaluation, takes an
//! in-app screenshot (egui `ViewportCommand::Screenshot`) after N frames (default 10), writes it
//! as PNG and quits: `scripts/editor-screenshot.sh` uses it under Xvfb.

use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use anyhow::{Context as _, bail};
use cnets_editor::app::{AppOptions, EditorApp};
use cnets_editor::viewport::GpuTarget;

struct Args {
    file: Option<PathBuf>,
    screenshot: Option<PathBuf>,
    quit_after: u32,
    size: [f32; 2],
}

fn parse_args() -> anyhow::Result<Args> {
    let mut args = Args {
        file: None,
        screenshot: None,
        quit_after: 10,
        size: [1400.0, 860.0],
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
}

impl eframe::App for Window {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        if self.screenshot.is_some() && self.frames == 0 {
            // Show the evaluated graph in the picture, not the first empty frame.
            self.app.wait_for_worker(Duration::from_secs(60));
        }
        self.app.ui(ui);
        let ctx = ui.ctx().clone();
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
            let saved = png.save_png(&out).map_err(anyhow::Error::from);
            if saved.is_ok() {
                eprintln!(
                    "cnets-editor: screenshot {w}x{h} written to {}",
                    out.display()
                );
            }
            *self.result.lock().unwrap_or_else(|p| p.into_inner()) = Some(saved);
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        } else if self.frames >= self.quit_after && !self.requested {
            ctx.send_viewport_cmd(egui::ViewportCommand::Screenshot(egui::UserData::default()));
            self.requested = true;
        }
        ctx.request_repaint();
    }

    fn on_exit(&mut self) {
        self.app.on_exit();
    }
}

/// Fails when the screenshot is (nearly) blank: too few colours, or the right half (the 3D view)
/// one flat colour.
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
    if colours.len() < 64 || covered < 0.05 {
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
            let app = EditorApp::new(AppOptions {
                gpu,
                config_dir: cnets_editor::settings::config_dir(),
                file: args.file.clone(),
                examples_dir,
                wake: Arc::new(move || ctx.request_repaint()),
            });
            Ok(Box::new(Window {
                app,
                screenshot: args.screenshot.clone(),
                quit_after: args.quit_after.max(1),
                frames: 0,
                requested: false,
                result: result2,
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
