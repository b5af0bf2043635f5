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
