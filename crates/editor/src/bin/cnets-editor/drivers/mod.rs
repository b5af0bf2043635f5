//! The test kit of the window (feature `drivers`, which the release build does not enable): the
//! latency benchmarks (`--bench-drag N`, `--bench-pan N`), the slider drag the recovery test kills
//! (`--drive-drag`), the restore it checks (`--restore-and-print`) and the scripted design
//! sessions (`--drive-script NAME [--drive-out DIR]`, `scenarios.rs`) the window tests play under
//! Xvfb (`tests/it/window.rs`) with injected pointer events and keys.

mod bench;
mod canopy;
mod cplane;
mod drag_net;
mod drive;
mod scenarios;
mod script;
mod tutorial;

use std::path::PathBuf;
use std::time::{Duration, Instant};

use anyhow::{Context as _, bail};
use cnets_editor::app::EditorApp;

use bench::{Bench, Motion};
use drive::{Drive, slider_values};
use script::Script;

/// The drivers' options, for `--help`.
pub const HELP: &str = "[--bench-drag N] [--bench-pan N] [--drive-drag] [--restore-and-print] \
                        [--drive-script NAME [--drive-out DIR]]";

/// The drivers asked for on the command line.
#[derive(Default)]
pub struct DriverArgs {
    bench_drag: Option<u32>,
    bench_pan: Option<u32>,
    drive_drag: bool,
    restore_and_print: bool,
    drive_script: Option<String>,
    drive_out: Option<PathBuf>,
}

/// The next argument's value, parsed.
fn value<T: std::str::FromStr>(
    it: &mut dyn Iterator<Item = String>,
    what: &str,
) -> anyhow::Result<T>
where
    T::Err: std::error::Error + Send + Sync + 'static,
{
    Ok(it
        .next()
        .with_context(|| format!("needs {what}"))?
        .parse()?)
}

impl DriverArgs {
    /// Takes `arg` (and its value from `rest`) when it is a driver's option; `false` otherwise.
    pub fn take(
        &mut self,
        arg: &str,
        rest: &mut dyn Iterator<Item = String>,
    ) -> anyhow::Result<bool> {
        match arg {
            "--bench-drag" => {
                self.bench_drag = Some(value(rest, "a frame count").context("--bench-drag")?)
            }
            "--bench-pan" => {
                self.bench_pan = Some(value(rest, "a frame count").context("--bench-pan")?)
            }
            "--drive-drag" => self.drive_drag = true,
            "--restore-and-print" => self.restore_and_print = true,
            "--drive-script" => {
                let name = rest.next().context("--drive-script needs a name")?;
                if scenarios::script(&name).is_none() {
                    bail!("unknown script {name} (known: {})", scenarios::NAMES);
                }
                self.drive_script = Some(name);
            }
            "--drive-out" => {
                self.drive_out = Some(rest.next().context("--drive-out needs a folder")?.into())
            }
            _ => return Ok(false),
        }
        Ok(true)
    }

    /// Whether any driver runs (the window then starts on the file given, read, and never hands
    /// it to an open window).
    pub fn any(&self) -> bool {
        self.bench_drag.is_some()
            || self.bench_pan.is_some()
            || self.drive_drag
            || self.restore_and_print
            || self.drive_script.is_some()
    }

    /// Whether a driver injects pointer events (a scripted click is a click however long its
    /// frame took on a busy machine).
    pub fn injects_pointer(&self) -> bool {
        self.drive_drag || self.drive_script.is_some()
    }

    /// The drivers, started (`launched`: when the process started, for the time to open).
    pub fn start(self, launched: Instant) -> Drivers {
        Drivers {
            bench: match (self.bench_drag, self.bench_pan) {
                (Some(frames), _) => Some(Bench::new(frames, Motion::Slider, launched)),
                (None, Some(frames)) => Some(Bench::new(frames, Motion::PanZoom, launched)),
                (None, None) => None,
            },
            drive: self.drive_drag.then(Drive::new),
            script: self
                .drive_script
                .as_deref()
                .and_then(scenarios::script)
                .map(|steps| Script::new(steps, self.drive_out.unwrap_or_else(|| ".".into()))),
            restore_and_print: self.restore_and_print,
        }
    }
}

/// The drivers running in the window.
pub struct Drivers {
    bench: Option<Bench>,
    drive: Option<Drive>,
    script: Option<Script>,
    restore_and_print: bool,
}

impl Drivers {
    /// Before the editor's frame: the benchmark waits for the first evaluation; the restore mode
    /// restores, prints the values and quits.
    pub fn before_frame(&mut self, app: &mut EditorApp) {
        if self
            .bench
            .as_ref()
            .is_some_and(|b| b.done == 0 && b.last_frame.is_none())
        {
            app.wait_for_worker(Duration::from_secs(60));
        }
        if std::mem::take(&mut self.restore_and_print) {
            if app.restore_offered() {
                app.restore();
                app.wait_for_worker(Duration::from_secs(60));
                println!("restored: {}", app.message());
                println!("{}", slider_values(app));
            } else {
                println!("restored: nothing to restore");
            }
            println!("restored: end");
            // Quit without the unsaved-changes question, keeping the recovery file.
            std::process::exit(0);
        }
    }

    /// After the editor's frame (`ui_ms`: the UI thread's time for it).
    pub fn after_frame(&mut self, app: &mut EditorApp, ctx: &egui::Context, ui_ms: f64) {
        if let Some(d) = &mut self.drive {
            d.locate(app);
            d.report(app);
            if d.needs_frames() {
                ctx.request_repaint();
            }
        }
        if let Some(b) = &mut self.bench {
            b.uis.push(ui_ms);
            b.step(app, ctx);
        }
        if let Some(s) = &mut self.script {
            s.after_frame(app, ctx);
        }
    }

    /// Before the editor sees the frame's input: a driver that injects the pointer drops the X
    /// server's own (moved over the window as it maps, it would break a scripted click or drag).
    pub fn filter_input(&self, raw_input: &mut egui::RawInput) {
        if self.drive.is_some() || self.script.is_some() {
            raw_input.events.retain(|e| {
                !matches!(
                    e,
                    egui::Event::PointerMoved(_)
                        | egui::Event::PointerButton { .. }
                        | egui::Event::PointerGone
                )
            });
        }
    }

    /// After the editor saw the frame's input: the drivers' events for the frame.
    pub fn inject(&mut self, app: &EditorApp, ctx: &egui::Context, raw_input: &mut egui::RawInput) {
        if let Some(d) = &mut self.drive {
            d.inject(raw_input);
        }
        if let Some(s) = &mut self.script {
            s.inject(app, ctx, raw_input);
        }
    }
}
