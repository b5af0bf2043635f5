//! Export failures are clear errors, never panics, and never leave a file (or a temporary file)
//! behind: names with `..` or a root, no output directory, a read-only directory, a target that
//! cannot be replaced, nothing to export, non-finite geometry.

use crate::fab_support;

use std::path::Path;

use cnets_engine::{NodeContext, Value};
use cnets_geometry::{DVec3, PolygonMesh, Polyline, QuadGrid};
use fab_support::*;

fn quad() -> Value {
    PolygonMesh::from_faces(
        vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
        &[vec![0, 1, 2, 3]],
    )
    .unwrap()
    .into()
}

fn square() -> Value {
    Polyline::closed(vec![
        DVec3::ZERO,
        DVec3::X,
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::Y,
    ])
    .into()
}

/// A valid input set for every export node.
fn inputs(id: &str) -> Vec<(&'static str, Value)> {
    match id {
        "io.export_gltf" | "io.export_obj" => vec![("meshes", quad())],
        "io.export_svg" | "io.export_dxf" => vec![("outlines", square())],
        _ => vec![("value", quad())],
    }
}

const EXPORTS: [&str; 6] = [
    "io.export_gltf",
    "io.export_obj",
    "io.export_svg",
    "io.export_dxf",
    "io.export_json",
    "io.export_csv",
];

fn assert_clear(err: &str) {
    assert!(!err.contains("panicked"), "a panic: {err}");
    assert!(!err.is_empty());
}

#[test]
fn names_outside_the_output_directory_are_refused() {
    let parent = scratch("escape");
    let dir = parent.join("out");
    std::fs::create_dir_all(&dir).unwrap();
    for id in EXPORTS {
        for name in ["../escape.out", "a/../../escape.out", "/tmp/escape.out"] {
            let mut given = inputs(id);
            given.push(("name", Value::text(name)));
            let err = run(&ctx_in(&dir), id, &given).unwrap_err();
            assert_clear(&err);
            assert!(
                err.contains("inside the output directory"),
                "{id} {name}: {err}"
            );
        }
        let err = run(&NodeContext::default(), id, &inputs(id)).unwrap_err();
        assert!(err.contains("no output directory"), "{id}: {err}");
    }
    assert!(entries(&dir).is_empty());
    assert_eq!(entries(&parent), ["out"]);
    std::fs::remove_dir_all(&parent).unwrap();
}

/// Whether this process can create files in `dir` (root ignores permissions).
fn writable(dir: &Path) -> bool {
    let probe = dir.join(".probe");
    let ok = std::fs::write(&probe, b"x").is_ok();
    let _ = std::fs::remove_file(&probe);
    ok
}

#[test]
fn unwritable_targets_give_an_error_and_leave_nothing() {
    use std::os::unix::fs::PermissionsExt;
    for id in EXPORTS {
        // A read-only output directory. Root ignores directory permissions: then the test uses
        // /sys, where nobody may create files.
        let dir = scratch("readonly");
        std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o555)).unwrap();
        let readonly = if writable(&dir) {
            std::path::PathBuf::from("/sys")
        } else {
            dir.clone()
        };
        if !writable(&readonly) {
            let before = entries(&readonly);
            let err = run(&ctx_in(&readonly), id, &inputs(id)).unwrap_err();
            assert_clear(&err);
            assert!(
                err.contains("cannot write") && err.contains("denied"),
                "{id}: {err}"
            );
            assert_eq!(entries(&readonly), before, "{id} left a file");
        }
        std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o755)).unwrap();

        // The target name is taken by a directory: the rename fails after the temporary file was
        // written; the temporary file is removed again.
        let target = [
            "model.glb",
            "model.obj",
            "strips.svg",
            "strips.dxf",
            "data.json",
            "vertices.csv",
        ][EXPORTS.iter().position(|e| *e == id).unwrap()];
        std::fs::create_dir(dir.join(target)).unwrap();
        let err = run(&ctx_in(&dir), id, &inputs(id)).unwrap_err();
        assert_clear(&err);
        assert!(err.contains("cannot write"), "{id}: {err}");
        assert_eq!(entries(&dir), [target], "{id} left a temporary file");

        // A sub-folder whose parent is a file cannot be created.
        std::fs::write(dir.join("plain"), b"x").unwrap();
        let mut given = inputs(id);
        given.push(("name", Value::text("plain/x.out")));
        let err = run(&ctx_in(&dir), id, &given).unwrap_err();
        assert!(
            err.contains("cannot create the output folder"),
            "{id}: {err}"
        );
        let mut expected = vec!["plain".to_string(), target.to_string()];
        expected.sort();
        assert_eq!(entries(&dir), expected);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

/// (node id, inputs, expected part of the error).
type Case = (&'static str, Vec<(&'static str, Value)>, &'static str);

#[test]
fn empty_and_invalid_inputs_are_errors_without_files() {
    let dir = scratch("empty");
    let ctx = ctx_in(&dir);
    let empty_mesh: Value = PolygonMesh::new().into();
    let nan_mesh: Value = PolygonMesh::from_faces(
        vec![DVec3::ZERO, DVec3::X, DVec3::new(f64::NAN, 1.0, 0.0)],
        &[vec![0, 1, 2]],
    )
    .unwrap()
    .into();
    let cases: Vec<Case> = vec![
        ("io.export_gltf", vec![], "nothing to export"),
        (
            "io.export_gltf",
            vec![("meshes", empty_mesh.clone())],
            "nothing to export",
        ),
        (
            "io.export_gltf",
            vec![("meshes", nan_mesh.clone())],
            "not finite",
        ),
        (
            "io.export_gltf",
            vec![
                ("meshes", quad()),
                ("colours", Value::list(vec![Value::Vector(DVec3::X); 2])),
            ],
            "colours has 2 entries",
        ),
        ("io.export_obj", vec![], "nothing to export"),
        (
            "io.export_obj",
            vec![("meshes", empty_mesh)],
            "nothing to export",
        ),
        ("io.export_obj", vec![("meshes", nan_mesh)], "not finite"),
        (
            "io.export_svg",
            vec![("outlines", Value::list(vec![]))],
            "no outline",
        ),
        (
            "io.export_svg",
            vec![("outlines", square()), ("scale", Value::Number(0.0))],
            "scale",
        ),
        (
            "io.export_dxf",
            vec![
                ("outlines", square()),
                (
                    "labels",
                    Value::list(vec![Value::text("a"), Value::text("b")]),
                ),
            ],
            "labels has 2 entries",
        ),
        (
            "io.export_dxf",
            vec![(
                "outlines",
                Polyline::open(vec![DVec3::ZERO, DVec3::splat(f64::INFINITY)]).into(),
            )],
            "not finite",
        ),
        ("io.export_json", vec![("value", Value::Null)], "value"),
        (
            "io.export_csv",
            vec![("value", Value::Number(3.0))],
            "vertex table",
        ),
        (
            "io.export_csv",
            vec![("value", QuadGrid::default().into())],
            "no vertices",
        ),
    ];
    for (id, given, needle) in cases {
        let err = run(&ctx, id, &given).unwrap_err();
        assert_clear(&err);
        assert!(err.contains(needle), "{id}: expected '{needle}' in: {err}");
    }
    assert!(entries(&dir).is_empty(), "left {:?}", entries(&dir));
    std::fs::remove_dir_all(&dir).unwrap();
}
