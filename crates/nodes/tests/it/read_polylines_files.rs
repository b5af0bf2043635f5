//! `io.read_polylines` reads real files in all four formats, resolves relative paths against the
//! graph's folder, and names the file when it cannot read it.

use std::path::PathBuf;

use cnets_engine::eval::evaluate_node;
use cnets_engine::{NodeContext, Value};
use cnets_geometry::{DVec3, Polyline};

/// A fresh folder of this test's own: tests run in parallel threads of one process, so each names
/// its folder (one test removing a shared folder took the other's files away in CI).
fn scratch_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "cnets-read-polylines-{test}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn read(ctx: &NodeContext, path: &str, format: &str) -> Result<Vec<Polyline>, String> {
    let def = cnets_nodes::io_read::read_polylines();
    let out = evaluate_node(
        &def,
        ctx,
        &[Value::text(path), Value::text(format), Value::Integer(16)],
    )
    .map_err(|e| e.to_string())?;
    Ok(out.values[0]
        .as_list()
        .unwrap()
        .iter()
        .map(|v| match v {
            Value::Polyline(p) => (**p).clone(),
            other => panic!("expected polylines, got {}", other.type_name()),
        })
        .collect())
}

#[test]
fn the_same_square_reads_the_same_from_every_format() {
    let dir = scratch_dir("formats");
    let files = [
        ("square.csv", "x,y,z\n0,0,0\n2,0,0\n2,2,0\n0,2,0\n0,0,0\n"),
        (
            "square.json",
            r#"[{"points": [[0,0,0],[2,0,0],[2,2,0],[0,2,0]], "closed": true}]"#,
        ),
        (
            "square.obj",
            "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nl 1 2 3 4 1\n",
        ),
        (
            "square.svg",
            r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0 h2 v-2 h-2 z"/></svg>"#,
        ),
    ];
    let ctx = NodeContext::new(None, Some(dir.clone()));
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
        // Relative to the graph's folder (the context's base directory).
        let curves = read(&ctx, name, "auto").unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(curves.len(), 1, "{name}");
        let c = &curves[0];
        assert!(c.closed, "{name}");
        assert_eq!(c.points.len(), 4, "{name}");
        assert_eq!(c.points[2], DVec3::new(2.0, 2.0, 0.0), "{name}");
        assert!((c.length() - 8.0).abs() < 1e-12, "{name}");
    }
    // An absolute path is read only under an allowed folder; the format can be forced.
    let copy = dir.join("square.data");
    std::fs::copy(dir.join("square.obj"), &copy).unwrap();
    let e = read(&NodeContext::default(), copy.to_str().unwrap(), "obj").unwrap_err();
    assert!(
        e.contains("outside the folders reads are allowed in"),
        "{e}"
    );
    let mut allowed = NodeContext::default();
    allowed.allow_read.push(dir.clone());
    let curves = read(&allowed, copy.to_str().unwrap(), "obj").unwrap();
    assert_eq!(curves[0].points.len(), 4);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn unreadable_or_empty_files_are_errors_naming_the_file() {
    let dir = scratch_dir("errors");
    let ctx = NodeContext::new(None, Some(dir.clone()));
    let e = read(&ctx, "missing.csv", "auto").unwrap_err();
    assert!(
        e.contains("cannot read") && e.contains("missing.csv"),
        "{e}"
    );
    std::fs::write(dir.join("empty.svg"), "<svg></svg>").unwrap();
    let e = read(&ctx, "empty.svg", "auto").unwrap_err();
    assert!(e.contains("empty.svg") && e.contains("no polylines"), "{e}");
    std::fs::write(dir.join("bad.csv"), "0,0\n1,x\n").unwrap();
    let e = read(&ctx, "bad.csv", "auto").unwrap_err();
    assert!(e.contains("bad.csv") && e.contains("line 2"), "{e}");
    assert!(read(&ctx, "", "auto").unwrap_err().contains("path"));
    std::fs::remove_dir_all(&dir).ok();
}
