//! Issue 27 §3 through the command line: long inputs are quoted as short excerpts, the "did you
//! mean" search is bounded, and a long flat expression evaluates (no stack overflow).

use crate::common;

use std::process::{Command, Output, Stdio};

fn cnets_in(dir: &std::path::Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_cnets"))
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .output()
        .unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn long_names_edges_and_expressions_are_quoted_short() {
    let d = common::Folder::new("messages");
    // A node type of 10⁷ characters and an edge of 10 MB in a graph file.
    let name = "t".repeat(10_000_000);
    let edge = "e".repeat(10_000_000);
    std::fs::write(
        d.join("g.ron"),
        format!(r#"(version: 1, nodes: {{ "n": (type: "{name}") }}, edges: ["{edge}"])"#),
    )
    .unwrap();
    let o = cnets_in(&d, &["check", "g.ron"]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        &stderr(&o)[..200.min(stderr(&o).len())]
    );
    let err = stderr(&o);
    assert!(
        err.contains("unknown node type 'tttt"),
        "{}",
        &err[..200.min(err.len())]
    );
    assert!(
        err.contains("malformed edge 'eeee"),
        "{}",
        &err[..200.min(err.len())]
    );
    assert!(err.len() < 2_000, "{} bytes of errors", err.len());
    // The same name given to `cnets eval`.
    std::fs::write(d.join("in.json"), "{}").unwrap();
    let o = cnets_in(&d, &["eval", &name[..100_000], "--inputs", "in.json"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).len() < 500, "{}", stderr(&o).len());
    // A 1 MB expression with a mistake at its end.
    let text = format!("{}+", "x+".repeat(500_000));
    std::fs::write(d.join("in.json"), format!(r#"{{"expression": "{text}"}}"#)).unwrap();
    let o = cnets_in(&d, &["eval", "math.expression", "--inputs", "in.json"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).len() < 500, "{}", stderr(&o).len());
    assert!(stderr(&o).contains("(column 1000002)"), "{}", stderr(&o));
}

#[test]
fn a_flat_sum_of_150000_terms_evaluates() {
    let d = common::Folder::new("messages-sum");
    let text = vec!["x"; 150_000].join("+");
    std::fs::write(
        d.join("in.json"),
        format!(r#"{{"expression": "{text}", "x": 0.5}}"#),
    )
    .unwrap();
    let o = cnets_in(&d, &["eval", "math.expression", "--inputs", "in.json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        String::from_utf8_lossy(&o.stdout).trim(),
        r#"{"result":75000.0}"#
    );
}

/// Every error line of the command quotes long inputs as excerpts: a 1 MB input name, format or
/// path, a 100 kB output name or `--set` target (issue 27 §3: "every error line that quotes
/// input").
#[test]
fn long_inputs_in_any_error_line_are_quoted_short() {
    let d = common::Folder::new("messages-lines");
    let long = "k".repeat(1_000_000);
    let inputs = [
        ("param.number", format!(r#"{{"{long}": 1}}"#)),
        (
            "io.read_polylines",
            format!(r#"{{"path": "a.csv", "format": "{long}"}}"#),
        ),
        ("io.read_polylines", format!(r#"{{"path": "{long}.csv"}}"#)),
        ("io.read_polylines", format!(r#"{{"path": "{long}"}}"#)),
    ];
    for (node, json) in inputs {
        std::fs::write(d.join("in.json"), json).unwrap();
        let o = cnets_in(&d, &["eval", node, "--inputs", "in.json"]);
        assert!(matches!(o.status.code(), Some(1 | 2)), "{node}");
        let err = stderr(&o);
        assert!(
            err.contains("kkkk"),
            "{node}: {}",
            &err[..200.min(err.len())]
        );
        assert!(err.len() < 5_000, "{node}: {} bytes of errors", err.len());
    }
    std::fs::write(d.join("in.json"), "{}").unwrap();
    let name = "o".repeat(100_000);
    let o = cnets_in(
        &d,
        &[
            "eval",
            "math.add",
            "--inputs",
            "in.json",
            "--outputs",
            &name,
        ],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).len() < 5_000, "{} bytes", stderr(&o).len());
    std::fs::write(
        d.join("g.ron"),
        r#"(version: 1, nodes: { "n": (type: "param.number") }, edges: [])"#,
    )
    .unwrap();
    for set in [format!("{name}.value=1"), format!("n.value={name}")] {
        let o = cnets_in(&d, &["run", "g.ron", "--set", &set]);
        assert_eq!(o.status.code(), Some(2), "{}", &stderr(&o)[..200]);
        assert!(stderr(&o).len() < 5_000, "{} bytes", stderr(&o).len());
    }
}
