//! Runs the real `cnets-editor` window once under Xvfb (a virtual X server), takes an in-app
//! screenshot and checks it is not blank (the binary checks the picture itself and fails
//! otherwise). Needs `xvfb-run` (apt: xvfb), which `scripts/install-test-deps.sh` installs; set
//! `CNETS_SKIP_WINDOW_TEST=1` to skip where there is none.

use std::process::Command;

#[test]
fn the_real_window_renders_the_default_graph_under_xvfb() {
    if std::env::var_os("CNETS_SKIP_WINDOW_TEST").is_some() {
        eprintln!("skipped: CNETS_SKIP_WINDOW_TEST is set");
        return;
    }
    let have_xvfb = Command::new("xvfb-run").arg("--help").output().is_ok();
    assert!(
        have_xvfb,
        "xvfb-run is missing: run scripts/install-test-deps.sh (or set CNETS_SKIP_WINDOW_TEST=1)"
    );
    let dir = std::env::temp_dir().join(format!("cnets-editor-window-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("editor.png");
    let status = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1600x1000x24"])
        .arg(env!("CARGO_BIN_EXE_cnets-editor"))
        // The bundled default graph, whatever else graphs/ holds.
        .arg(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../graphs/editor-default.ron"
        ))
        .arg("--screenshot")
        .arg(&out)
        .args(["--quit-after-frames", "10", "--size", "1200x760"])
        .env("CNETS_EDITOR_HOME", dir.join("home"))
        .status()
        .expect("xvfb-run runs");
    assert!(
        status.success(),
        "cnets-editor --screenshot failed: {status}"
    );
    let bytes = std::fs::read(&out).expect("the screenshot was written");
    assert!(bytes.starts_with(b"\x89PNG"), "a PNG file");
    std::fs::remove_dir_all(&dir).ok();
}
