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

/// Runs the editor binary under Xvfb with `args`, its settings in `home`; stdout piped.
fn spawn_window(home: &std::path::Path, args: &[&str]) -> std::process::Child {
    Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1600x1000x24"])
        .arg(env!("CARGO_BIN_EXE_cnets-editor"))
        .args(args)
        .args(["--size", "1200x760"])
        .env("CNETS_EDITOR_HOME", home)
        .stdout(std::process::Stdio::piped())
        .spawn()
        .expect("xvfb-run runs")
}

/// Reads `child`'s stdout up to the line starting with `end`; returns the lines before it.
fn read_until(child: &mut std::process::Child, end: &str) -> Vec<String> {
    use std::io::BufRead;
    let out = child.stdout.take().expect("piped stdout");
    let mut lines = Vec::new();
    for line in std::io::BufReader::new(out).lines() {
        let line = line.expect("stdout");
        if line.starts_with(end) {
            return lines;
        }
        lines.push(line);
    }
    panic!("the editor ended before printing '{end}'; it printed {lines:?}");
}

/// `node.value = Some(x)` lines → (node, x).
fn values(lines: &[String]) -> Vec<(String, String)> {
    lines
        .iter()
        .filter_map(|l| l.split_once(" = "))
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect()
}

/// The `NODE.value was X` lines.
fn lines_was(lines: &[String]) -> Vec<(String, String)> {
    lines
        .iter()
        .filter_map(|l| l.split_once(".value was "))
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect()
}

fn shown_lines_was(was: &[(String, String)], node: &str) -> String {
    was.iter()
        .find(|(n, _)| n == node)
        .map(|(_, v)| v.clone())
        .unwrap_or_else(|| panic!("no 'was' line for {node}: {was:?}"))
}

#[test]
fn a_window_killed_right_after_a_slider_drag_restores_the_values_it_showed() {
    if std::env::var_os("CNETS_SKIP_WINDOW_TEST").is_some() {
        eprintln!("skipped: CNETS_SKIP_WINDOW_TEST is set");
        return;
    }
    let dir = std::env::temp_dir().join(format!("cnets-editor-kill-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let home = dir.join("home");
    std::fs::create_dir_all(&home).unwrap();
    let graph = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../graphs/editor-default.ron"
    );
    // A real drag (pointer press, moves, release through egui's input) in the real window.
    let mut child = spawn_window(&home, &[graph, "--drive-drag"]);
    let shown_raw = read_until(&mut child, "drive-drag: end");
    let released = shown_raw
        .iter()
        .find(|l| l.starts_with("drive-drag: released"))
        .expect("the drag was released");
    let pid = released.rsplit(' ').next().unwrap().to_string();
    let shown = values(&shown_raw);
    assert!(!shown.is_empty(), "slider values were printed");
    let node = released.split(' ').nth(2).unwrap();
    let was = shown_lines_was(&lines_was(&shown_raw), node);
    let now = &shown
        .iter()
        .find(|(n, _)| n == &format!("{node}.value"))
        .unwrap()
        .1;
    assert_ne!(&was, now, "the drag changed {node}'s value");
    // SIGKILL within a second of the release: no exit handler, no last autosave chance.
    std::thread::sleep(std::time::Duration::from_millis(900));
    let killed = Command::new("kill")
        .args(["-KILL", &pid])
        .status()
        .expect("kill runs");
    assert!(killed.success(), "killed the editor (pid {pid})");
    let _ = child.wait();
    assert!(
        home.join("recovery.ron").is_file(),
        "a recovery file is left"
    );
    // Restart: the recovery is offered and restored.
    let mut again = spawn_window(&home, &["--restore-and-print"]);
    let lines = read_until(&mut again, "restored: end");
    let _ = again.wait();
    assert!(
        lines.iter().any(|l| l.contains("restored unsaved work")),
        "restored: {lines:?}"
    );
    assert_eq!(
        values(&lines),
        shown,
        "the restored values are the ones shown"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn every_shipped_graph_opens_with_its_design_drawn_in_the_real_window() {
    if std::env::var_os("CNETS_SKIP_WINDOW_TEST").is_some() {
        eprintln!("skipped: CNETS_SKIP_WINDOW_TEST is set");
        return;
    }
    let graphs = std::path::PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../graphs"));
    let dir = std::env::temp_dir().join(format!("cnets-editor-gallery-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut files: Vec<_> = std::fs::read_dir(&graphs)
        .unwrap()
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    files.sort();
    let mut failed = Vec::new();
    for file in &files {
        let name = file.file_stem().unwrap().to_string_lossy().into_owned();
        let out = dir.join(format!("{name}.png"));
        // The editor checks the picture itself (enough colours, the 3D view drawn).
        let run = Command::new("xvfb-run")
            .args(["-a", "-s", "-screen 0 1600x1000x24"])
            .arg(env!("CARGO_BIN_EXE_cnets-editor"))
            .arg(file)
            .arg("--screenshot")
            .arg(&out)
            .args(["--quit-after-frames", "10", "--size", "1400x860"])
            .env("CNETS_EDITOR_HOME", dir.join(format!("home-{name}")))
            .output()
            .expect("xvfb-run runs");
        if !run.status.success() {
            failed.push(format!(
                "{name}: {}",
                String::from_utf8_lossy(&run.stderr)
                    .lines()
                    .filter(|l| l.starts_with("cnets-editor") || l.starts_with("Error"))
                    .collect::<Vec<_>>()
                    .join(" / ")
            ));
        }
    }
    assert!(failed.is_empty(), "blank or failed:\n{}", failed.join("\n"));
    std::fs::remove_dir_all(&dir).ok();
}
