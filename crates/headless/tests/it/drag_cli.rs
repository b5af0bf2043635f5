//! `cnets drag`: a vertex of the default graph's net dragged to where other slider values put it
//! comes back to those values; pins, bad requests and `--out`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value as Json;

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap()
}

fn cnets(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_cnets"))
        .args(args)
        .current_dir(workspace())
        .output()
        .unwrap()
}

fn json_of(out: &Output) -> Json {
    assert!(
        out.status.success(),
        "{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// Vertex (i, j) of the default net with the sliders at `apex` and `ratio`, from `cnets run`.
fn vertex_at(apex: f64, ratio: f64, i: usize, j: usize) -> [f64; 3] {
    let apex = format!("apex.value={apex}");
    let ratio = format!("ratio.value={ratio}");
    let out = cnets(&[
        "run",
        "graphs/editor-default.ron",
        "--set",
        &apex,
        "--set",
        &ratio,
        "--json",
    ]);
    let run = json_of(&out);
    let mesh = &run["nodes"]["construct"]["outputs"]["mesh"];
    let cols = mesh["cols"].as_u64().unwrap() as usize;
    let k = i * cols + j;
    let v = &mesh["vertices"];
    std::array::from_fn(|c| v[k][c].as_f64().unwrap())
}

#[test]
fn a_reachable_target_is_reached_and_the_sliders_come_back() {
    let target = vertex_at(0.9, 0.42, 5, 9);
    let to = format!("{},{},{}", target[0], target[1], target[2]);
    let report = json_of(&cnets(&[
        "drag",
        "graphs/editor-default.ron",
        "--node",
        "construct",
        "--vertex",
        "5,9",
        "--to",
        &to,
        "--json",
    ]));
    let left = report["distance_left"].as_f64().unwrap();
    assert!(left < 1e-9, "distance left {left}");
    assert_eq!(report["not_convex"]["construct"], 0);
    let changes = report["changes"].as_array().unwrap();
    let new = |input: &str| {
        changes
            .iter()
            .find(|c| c["input"] == input)
            .unwrap_or_else(|| panic!("{input} did not change: {changes:?}"))["new"]
            .as_f64()
            .unwrap()
    };
    assert!((new("apex.value") - 0.9).abs() < 1e-9);
    assert!((new("ratio.value") - 0.42).abs() < 1e-9);
}

#[test]
fn free_inputs_limit_the_drag_and_an_unreachable_target_says_how_far_it_stayed() {
    // Only the ratio may move: the vertex goes as near as the ratio takes it.
    let target = vertex_at(0.9, 0.42, 5, 9);
    let to = format!("{},{},{}", target[0], target[1], target[2]);
    let report = json_of(&cnets(&[
        "drag",
        "graphs/editor-default.ron",
        "--node",
        "construct",
        "--vertex",
        "5,9",
        "--to",
        &to,
        "--free",
        "ratio.value",
        "--json",
    ]));
    let changes = report["changes"].as_array().unwrap();
    assert!(
        changes.iter().all(|c| c["input"] == "ratio.value"),
        "{changes:?}"
    );
    let left = report["distance_left"].as_f64().unwrap();
    let reached: Vec<f64> = report["reached"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let measured = ((reached[0] - target[0]).powi(2)
        + (reached[1] - target[1]).powi(2)
        + (reached[2] - target[2]).powi(2))
    .sqrt();
    assert!(
        left > 1e-3,
        "the apex alone moves the vertex that far: {left}"
    );
    assert!((measured - left).abs() < 1e-12, "{measured} vs {left}");
}

#[test]
fn the_out_file_holds_the_new_values() {
    let target = vertex_at(0.95, 0.55, 3, 12);
    let to = format!("{},{},{}", target[0], target[1], target[2]);
    let dir = std::env::temp_dir().join(format!("cnets-drag-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("dragged.ron");
    let out_s = out.to_str().unwrap();
    let report = json_of(&cnets(&[
        "drag",
        "graphs/editor-default.ron",
        "--node",
        "construct",
        "--vertex",
        "3,12",
        "--to",
        &to,
        "--out",
        out_s,
        "--json",
    ]));
    assert!(report["distance_left"].as_f64().unwrap() < 1e-9);
    let text = std::fs::read_to_string(&out).unwrap();
    let run = json_of(&cnets(&["run", out_s, "--json"]));
    let apex = run["nodes"]["apex"]["outputs"]["value"].as_f64().unwrap();
    assert!((apex - 0.95).abs() < 1e-9, "{apex}\n{text}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_requests_exit_2_naming_what_is_wrong() {
    for (args, says) in [
        (
            vec!["--node", "nope", "--vertex", "1,1", "--to", "0,0,0"],
            "no node 'nope'",
        ),
        (
            vec!["--node", "apex", "--vertex", "1,1", "--to", "0,0,0"],
            "no quad mesh output",
        ),
        (
            vec!["--node", "construct", "--vertex", "11,0", "--to", "0,0,0"],
            "out of range",
        ),
        (
            vec!["--node", "construct", "--vertex", "1,1", "--to", "0,inf,0"],
            "not finite",
        ),
        (
            vec!["--node", "construct", "--vertex", "1,1", "--to", "0,NaN,0"],
            "not finite",
        ),
        (
            vec!["--node", "construct", "--vertex", "a,1", "--to", "0,0,0"],
            "not a vertex",
        ),
        (
            vec!["--node", "construct", "--vertex", "1,1", "--to", "0,0"],
            "not a point",
        ),
    ] {
        let mut all = vec!["drag", "graphs/editor-default.ron"];
        all.extend(args.iter().copied());
        let out = cnets(&all);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
}
