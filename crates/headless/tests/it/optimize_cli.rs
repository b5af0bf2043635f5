//! `cnets optimize --check-gradient`: the exact gradient against finite differences, as printed.

use std::path::{Path, PathBuf};
use std::process::Command;

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap()
}

#[test]
fn check_gradient_prints_the_largest_relative_difference() {
    let out = Command::new(env!("CARGO_BIN_EXE_cnets"))
        .args(["optimize", "graphs/tube-closure.ron", "--check-gradient"])
        .current_dir(workspace())
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let line = text
        .lines()
        .find(|l| l.starts_with("largest relative difference: "))
        .unwrap_or_else(|| panic!("no difference line in:\n{text}"));
    let value: f64 = line["largest relative difference: ".len()..]
        .parse()
        .unwrap();
    // The tube's ratios start at ½ on level mapper handles (kinks of the ratio map and the
    // monotone spline): exact and central differences still agree to 1e-5 there.
    assert!(value < 1e-5, "{value}");
    // The mapper has no exact derivative and says so.
    assert!(
        text.contains("note: node 'ratios': finite differences for its part"),
        "{text}"
    );
    assert!(!text.contains("node 'tube'"), "{text}");
}

#[test]
fn check_gradient_json_has_both_gradients() {
    let out = Command::new(env!("CARGO_BIN_EXE_cnets"))
        .args([
            "optimize",
            "graphs/tube-closure.ron",
            "--check-gradient",
            "--json",
        ])
        .current_dir(workspace())
        .output()
        .unwrap();
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["exact"].as_array().unwrap().len(), 40);
    assert_eq!(v["finite_differences"].as_array().unwrap().len(), 40);
    assert!(v["largest_relative_difference"].as_f64().unwrap() < 1e-5);
}

#[test]
fn check_gradient_through_cut_and_mirror_is_exact() {
    // The catamaran hull is cut by its symmetry plane and mirrored before it is measured against
    // the reference (issue 32: before, the cut and the mirror took finite differences over all of
    // their input coordinates).
    let out = Command::new(env!("CARGO_BIN_EXE_cnets"))
        .args(["optimize", "graphs/catamaran-hull.ron", "--check-gradient"])
        .current_dir(workspace())
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let line = text
        .lines()
        .find(|l| l.starts_with("largest relative difference: "))
        .unwrap_or_else(|| panic!("no difference line in:\n{text}"));
    let value: f64 = line["largest relative difference: ".len()..]
        .parse()
        .unwrap();
    assert!(value <= 1e-6, "{value}");
    for node in ["half", "whole", "fit", "hull"] {
        assert!(!text.contains(&format!("node '{node}'")), "{text}");
    }
}

/// A temporary folder with the catamaran hull graph and its reference.
fn catamaran_copy(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cnets-{name}-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("reference")).unwrap();
    let graphs = workspace().join("graphs");
    std::fs::copy(
        graphs.join("catamaran-hull.ron"),
        dir.join("catamaran-hull.ron"),
    )
    .unwrap();
    std::fs::copy(
        graphs.join("reference/catamaran-hull.obj"),
        dir.join("reference/catamaran-hull.obj"),
    )
    .unwrap();
    dir
}

fn cnets(dir: &Path, args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_cnets"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn a_rerun_at_the_optimum_stops_there_and_says_why() {
    let dir = catamaran_copy("rerun");
    let (ok, text, err) = cnets(
        &dir,
        &["optimize", "catamaran-hull.ron", "--out", "fitted.ron"],
    );
    assert!(ok, "{text}\n{err}");
    // Again from the optimum: before issue 32 `auto` fell back to Nelder–Mead there without a
    // word and spent its 40 iterations changing nothing.
    let (ok, text, err) = cnets(&dir, &["optimize", "fitted.ron"]);
    assert!(ok, "{text}\n{err}");
    let summary = text.lines().next().unwrap_or_default();
    // It converges where it is (no descent step, or only steps that decrease nothing more).
    assert!(
        summary.contains("converged (at a minimum")
            || summary.contains("converged (no further decrease)"),
        "{text}"
    );
    assert!(!text.contains("Nelder–Mead"), "{text}");
    let iterations: usize = summary
        .split(" in ")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{summary}"));
    assert!(iterations < 10, "{summary}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_failed_upstream_node_is_named_with_its_own_message() {
    let dir = catamaran_copy("failed");
    let graph = std::fs::read_to_string(dir.join("catamaran-hull.ron"))
        .unwrap()
        .replace("reference/catamaran-hull.obj", "reference/missing.obj");
    std::fs::write(dir.join("broken.ron"), graph).unwrap();
    let (ok, text, err) = cnets(&dir, &["optimize", "broken.ron"]);
    assert!(!ok, "{text}");
    assert!(
        err.contains("comes from 'reference_hull', which failed; 'reference_hull' failed: cannot read 'reference/missing.obj'"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A gallery graph copied to a temporary folder with an optimization setup whose variables are
/// the directrix's points (`variables`, RON) and objective `objective`, plus `nodes` and `edges`
/// (RON, may be empty) added.
fn with_free_directrix(
    graph: &str,
    variables: &[String],
    objective: &str,
    nodes: &str,
    edges: &str,
) -> PathBuf {
    let text = std::fs::read_to_string(workspace().join("graphs").join(graph)).unwrap();
    // Without the file's own setup (if any): ours goes before the nodes.
    let text = match (text.find("    optimization: ("), text.find("    nodes: {")) {
        (Some(start), Some(end)) if start < end => format!("{}{}", &text[..start], &text[end..]),
        _ => text,
    };
    let setup = format!(
        "    optimization: (\n        objective: \"{objective}\",\n        variables: [\n{}        ],\n        method: \"lbfgsb\",\n        max_iter: 2,\n    ),\n",
        variables
            .iter()
            .map(|v| format!("            (input: \"{v}\", min: -100.0, max: 100.0),\n"))
            .collect::<String>()
    );
    let text = text
        .replacen(
            "    nodes: {\n",
            &format!("{setup}    nodes: {{\n{nodes}"),
            1,
        )
        .replacen("    edges: [\n", &format!("    edges: [\n{edges}"), 1);
    let dir = std::env::temp_dir().join(format!(
        "cnets-free-directrix-{}-{}",
        graph.trim_end_matches(".ron"),
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(graph);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn check_gradient_with_the_directrix_points_free_is_exact() {
    // The pedestrian bridge (CNets Construct Coplanar) draws its directrix as a spline through
    // points (x, y · bulge, −1) from two lists; its area is the objective. The closing tube (CNets
    // Construct) draws its directrix as a closed spline through four literal points; the gap of
    // its end is the objective. Every node from the points to the objective has an exact product.
    let bridge_points: Vec<String> = (0..5)
        .flat_map(|k| [format!("plan_x.values[{k}]"), format!("plan_y.values[{k}]")])
        .collect();
    let tube_points: Vec<String> = (0..4)
        .flat_map(|k| (0..3).map(move |d| format!("directrix.points[{k}][{d}]")))
        .collect();
    let bridge = with_free_directrix(
        "pedestrian-bridge.ron",
        &bridge_points,
        "area.total",
        "        \"area\": (\n            type: \"measure.area\",\n            position: (2208.0, 700.0),\n        ),\n",
        "        \"bridge.mesh -> area.mesh\",\n",
    );
    let tube = with_free_directrix("tube-closure.ron", &tube_points, "gap.value", "", "");
    for (path, count) in [(&bridge, 10), (&tube, 12)] {
        let dir = path.parent().unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_cnets"))
            .args(["optimize"])
            .arg(path)
            .args(["--check-gradient", "--json"])
            .current_dir(dir)
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{}: {text}\n{}",
            path.display(),
            String::from_utf8_lossy(&out.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["variables"].as_u64(), Some(count), "{v}");
        let rel = v["largest_relative_difference"].as_f64().unwrap();
        println!("{}: largest relative difference {rel:.3e}", path.display());
        assert!(rel < 1e-5, "{}: {rel:e}\n{v}", path.display());
        assert!(
            v["exact"]
                .as_array()
                .unwrap()
                .iter()
                .any(|g| g.as_f64().unwrap().abs() > 1e-6),
            "{v}"
        );
        // No node on the path is differenced.
        assert_eq!(v["notes"].as_array().map(Vec::len), Some(0), "{v}");
        // The same in an optimization's report.
        let out = Command::new(env!("CARGO_BIN_EXE_cnets"))
            .args(["optimize"])
            .arg(path)
            .args(["--json", "--max-iter", "1"])
            .current_dir(dir)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}: {}",
            path.display(),
            String::from_utf8_lossy(&out.stderr)
        );
        let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(
            report["finite_difference_nodes"].as_array().map(Vec::len),
            Some(0),
            "{}: {report}",
            path.display()
        );
        assert_eq!(report["gradients"], report["exact_gradients"], "{report}");
    }
    for path in [bridge, tube] {
        std::fs::remove_dir_all(path.parent().unwrap()).ok();
    }
}
