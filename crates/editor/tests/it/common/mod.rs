//! Shared test setup: the editor in a kittest harness rendered with wgpu.

#![allow(dead_code)]

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

use cnets_editor::app::{AppOptions, EditorApp};
use cnets_editor::viewport::GpuTarget;
use egui_kittest::Harness;
use egui_kittest::wgpu::{WgpuTestRenderer, create_render_state, default_wgpu_setup};

/// A fresh, empty settings folder for one test (numbered: two modules' tests may share a name,
/// and they run in one process).
pub fn temp_config(name: &str) -> PathBuf {
    static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let k = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!(
        "cnets-editor-test-{}-{name}-{k}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The repository's `graphs/` folder.
pub fn graphs_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../graphs"))
}

/// The editor on the default graph (the built-in one: the examples folder given has no
/// torus-monge.ron), in a 1280 × 800 harness rendered with wgpu, first evaluation done.
pub fn harness(name: &str) -> Harness<'static, EditorApp> {
    harness_with(name, None, temp_config(name))
}

/// Like [`harness`] with a file and settings folder.
pub fn harness_with(
    name: &str,
    file: Option<PathBuf>,
    config: PathBuf,
) -> Harness<'static, EditorApp> {
    let _ = name;
    // An empty examples folder of the test's own: the built-in default graph is used, and no
    // other file (of another test, another process) is listed as an example or library entry.
    let examples = examples_of(&config);
    build(config, file, examples)
}

/// The (empty, created) examples folder [`harness_with`] gives the editor of settings `config`.
pub fn examples_of(config: &std::path::Path) -> PathBuf {
    let dir = config.join("examples");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn build(
    config: PathBuf,
    file: Option<PathBuf>,
    examples_dir: PathBuf,
) -> Harness<'static, EditorApp> {
    let rs = create_render_state(
        default_wgpu_setup(),
        egui_wgpu::RendererOptions::PREDICTABLE,
    );
    let gpu = GpuTarget::from_render_state(&rs, 1, None);
    let mut app = EditorApp::new(AppOptions {
        gpu: Some(gpu),
        config_dir: config,
        file,
        examples_dir,
        wake: Arc::new(|| {}),
    });
    app.set_show_timings(false);
    app.wait_for_worker(Duration::from_secs(60));
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .with_step_dt(1.0 / 60.0)
        .renderer(WgpuTestRenderer::from_render_state(rs))
        .build_ui_state(|ui, app: &mut EditorApp| app.ui(ui), app);
    settle(&mut h);
    h
}

/// The editor on an examples folder of the test's own (start-up graph: its torus-monge.ron, when
/// present), with an optional file.
pub fn harness_on(
    config: PathBuf,
    file: Option<PathBuf>,
    examples_dir: PathBuf,
) -> Harness<'static, EditorApp> {
    build(config, file, examples_dir)
}

/// The node the canvas focused (the one a palette pick just added).
pub fn focused_node(h: &Harness<'static, EditorApp>) -> String {
    h.state()
        .canvas()
        .focused
        .clone()
        .expect("a node was added")
}

/// Runs frames until the worker has answered and the UI is idle.
pub fn settle(h: &mut Harness<'static, EditorApp>) {
    for _ in 0..5 {
        h.state_mut().wait_for_worker(Duration::from_secs(60));
        h.run_steps(3);
        if !h.state().busy() {
            break;
        }
    }
    // Past the viewport's settle time (0.3 s of egui time at 1/60 s a step), so the 3D view is
    // rendered at full resolution.
    h.run_steps(30);
}
