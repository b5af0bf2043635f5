//! `--bench-drag N`: the editor's latency benchmark — a slider moved every frame, then the
//! change-to-picture latency and frame times printed.

use cnets_editor::app::EditorApp;

use crate::drive::first_slider;

/// `--bench-drag N`: moves the first `param.number` slider every frame for N frames (as a drag
/// would, one undo step), then prints change-to-picture latency and frame intervals.
pub struct Bench {
    frames: u32,
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
    /// A benchmark of `frames` frames.
    pub fn new(frames: u32) -> Self {
        Bench {
            frames,
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

    pub fn step(&mut self, app: &mut EditorApp, ctx: &egui::Context) {
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
