//! `--bench-drag N`: the editor's latency benchmark — a slider moved every frame, then the
//! change-to-picture latency and frame times printed. `--bench-pan N`: the canvas panned and
//! zoomed every frame instead (a large graph's frame rate). Both print the time from launch to the
//! first frame showing the evaluated graph.

use cnets_editor::app::EditorApp;

use super::drive::first_slider;

/// What the benchmark changes every frame.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Motion {
    /// The first `param.number` slider (`--bench-drag`).
    Slider,
    /// The canvas's pan and zoom, around the graph's middle (`--bench-pan`).
    PanZoom,
}

/// `--bench-drag N`: moves the first `param.number` slider every frame for N frames (as a drag
/// would, one undo step), then prints change-to-picture latency and frame intervals;
/// `--bench-pan N` pans and zooms the canvas instead.
pub struct Bench {
    frames: u32,
    motion: Motion,
    /// When the process started (for the time to open).
    launched: std::time::Instant,
    /// Launch to the first benchmark frame (the evaluated graph shown), in milliseconds.
    opened_ms: Option<f64>,
    /// Frames done.
    pub done: u32,
    /// When the last frame started.
    pub last_frame: Option<std::time::Instant>,
    intervals: Vec<f64>,
    evals: Vec<f64>,
    scenes: Vec<f64>,
    /// UI thread time of each frame (ms).
    pub uis: Vec<f64>,
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
    /// A benchmark of `frames` frames changing `motion`, timed from `launched`.
    pub fn new(frames: u32, motion: Motion, launched: std::time::Instant) -> Self {
        Bench {
            frames,
            motion,
            launched,
            opened_ms: None,
            done: 0,
            last_frame: None,
            intervals: Vec::new(),
            evals: Vec::new(),
            scenes: Vec::new(),
            uis: Vec::new(),
            seen: 0,
            reported: false,
        }
    }

    /// Records the frame that just ran and makes the next frame's change (or prints the figures
    /// and quits after the last).
    pub fn step(&mut self, app: &mut EditorApp, ctx: &egui::Context) {
        let now = std::time::Instant::now();
        self.opened_ms
            .get_or_insert_with(|| (now - self.launched).as_secs_f64() * 1e3);
        if let Some(t) = self.last_frame {
            self.intervals.push((now - t).as_secs_f64() * 1e3);
        }
        self.last_frame = Some(now);
        if app.latency().samples.len() > self.seen {
            self.seen = app.latency().samples.len();
            self.evals.push(app.latency().eval_ms);
            self.scenes.push(app.latency().scene_ms);
        }
        if self.done >= self.frames {
            if std::mem::replace(&mut self.reported, true) {
                return;
            }
            let mut lat = app.latency().samples.clone();
            println!(
                "opened: {:.0} ms from launch to the first frame with the evaluated graph \
                 ({} nodes)",
                self.opened_ms.unwrap_or(0.0),
                app.doc().graph.node_count()
            );
            println!(
                "bench-{}: {} frames, {} pictures ({} before the rest of the graph finished)",
                match self.motion {
                    Motion::Slider => "drag",
                    Motion::PanZoom => "pan",
                },
                self.frames,
                lat.len(),
                app.latency().early_pictures
            );
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
            println!("  vertices: {}", app.viewport().stats().vertices);
            // Quit without the unsaved-changes question.
            app.quit_now();
            ctx.request_repaint();
            return;
        }
        self.done += 1;
        ctx.request_repaint();
        if std::env::var_os("CNETS_BENCH_IDLE").is_some() {
            // Baseline: frames without changes (nothing re-evaluated, the 3D view not re-rendered).
            return;
        }
        let t = f64::from(self.done - 1) / 60.0;
        if self.motion == Motion::PanZoom {
            pan_and_zoom(app, t);
            return;
        }
        let Some(id) = first_slider(app) else {
            return;
        };
        let node = app.doc().graph.node(&id).expect("the node");
        let k = node
            .def
            .inputs
            .iter()
            .position(|p| p.widget() == cnets_engine::Widget::Slider)
            .unwrap_or(0);
        let (min, max, _) = cnets_editor::widgets::slider_range(node, k);
        let value = min + (max - min) * (0.5 + 0.4 * (t * std::f64::consts::TAU).sin());
        app.edit(cnets_editor::edit::Edit::SetValue {
            node: id,
            input: "value".into(),
            value: cnets_engine::Value::Number(value),
        });
    }
}

/// Pans the canvas around the middle of the graph's nodes (a circle of a third of their extent,
/// once every two seconds) while zooming between 0.5 and 1, at time `t` seconds of 60 frames a
/// second.
fn pan_and_zoom(app: &mut EditorApp, t: f64) {
    let (mut lo, mut hi) = ([f32::MAX; 2], [f32::MIN; 2]);
    for (_, n) in app.doc().graph.nodes() {
        for k in 0..2 {
            lo[k] = lo[k].min(n.position[k]);
            hi[k] = hi[k].max(n.position[k]);
        }
    }
    if lo[0] > hi[0] {
        return;
    }
    let angle = (t * std::f64::consts::PI) as f32;
    let around = egui::pos2(
        0.5 * (lo[0] + hi[0]) + (hi[0] - lo[0]) / 3.0 * angle.cos(),
        0.5 * (lo[1] + hi[1]) + (hi[1] - lo[1]) / 3.0 * angle.sin(),
    );
    let zoom = 0.75 + 0.25 * (t * 1.3 * std::f64::consts::TAU).sin() as f32;
    app.zoom_canvas(zoom, Some(around));
}
