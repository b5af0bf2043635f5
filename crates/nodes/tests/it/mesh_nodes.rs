//! The mesh nodes through the registry: ports, cut/mirror/join results, face attributes.

use crate::fab_support;

use cnets_engine::{NodeContext, Value};
use cnets_geometry::{DVec3, Plane, PolygonMesh};
use fab_support::*;

fn mesh(v: &Value) -> &PolygonMesh {
    match v {
        Value::Mesh(m) => m,
        other => panic!("expected a mesh, got {}", other.type_name()),
    }
}

#[test]
fn ports_are_documented_contracts() {
    let table: &[(&str, &[&str], &[&str])] = &[
        ("mesh.to_polygons", &["mesh"], &["mesh"]),
        (
            "cnets.support_strips",
            &["mesh", "directrix", "layer", "direction"],
            &["strips"],
        ),
        (
            "fab.nest",
            &[
                "outlines",
                "sheet_width",
                "sheet_height",
                "spacing",
                "rotations",
                "labels",
                "folds",
                "marks",
            ],
            &[
                "outlines",
                "sheets",
                "utilization",
                "labels",
                "label_points",
                "folds",
                "marks",
            ],
        ),
        (
            "fab.schedule",
            &["mesh", "direction", "tolerance", "max_length"],
            &["table", "total_area"],
        ),
        ("cnets.subdivide_rows", &["mesh", "count"], &["mesh"]),
        (
            "mesh.cut_by_plane",
            &["mesh", "plane", "flip"],
            &["mesh", "section"],
        ),
        ("mesh.mirror", &["mesh", "plane", "tolerance"], &["mesh"]),
        ("mesh.join", &["meshes", "weld", "names"], &["mesh"]),
        (
            "analysis.face_planarity",
            &["mesh", "limit"],
            &["values", "max", "colours"],
        ),
        (
            "analysis.face_classes",
            &["mesh", "configurations"],
            &["classes", "labels", "colours", "convex", "convex_share"],
        ),
        (
            "io.export_gltf",
            &[
                "name",
                "meshes",
                "colours",
                "lines",
                "polylines",
                "planarity_limit",
                "names",
            ],
            &["path"],
        ),
        (
            "io.export_obj",
            &["name", "meshes", "lines", "polylines", "names"],
            &["path"],
        ),
        (
            "io.export_svg",
            &[
                "name",
                "outlines",
                "labels",
                "label_points",
                "scale",
                "sheets",
            ],
            &["path"],
        ),
        (
            "io.export_dxf",
            &[
                "name",
                "outlines",
                "labels",
                "label_points",
                "scale",
                "sheets",
                "folds",
                "fold_angles",
                "marks",
                "mark_labels",
            ],
            &["path"],
        ),
        ("io.export_json", &["name", "value"], &["path"]),
        ("io.export_csv", &["name", "value"], &["path"]),
    ];
    for (id, inputs, outputs) in table {
        let (i, o) = ports(id);
        assert_eq!(i, *inputs, "{id} inputs");
        assert_eq!(o, *outputs, "{id} outputs");
    }
    for id in [
        "io.export_gltf",
        "io.export_obj",
        "io.export_svg",
        "io.export_dxf",
        "io.export_json",
        "io.export_csv",
    ] {
        assert!(
            def(id).has_flag(cnets_engine::NodeFlag::Export),
            "{id} is an export"
        );
    }
}

#[test]
fn cut_mirror_join_through_nodes() {
    let net = cone_net(4, 6, false);
    let ctx = NodeContext::default();
    let polys = run(
        &ctx,
        "mesh.to_polygons",
        &[("mesh", net.mesh.clone().into())],
    )
    .unwrap();
    let whole = mesh(get(&polys, "mesh")).clone();
    assert_eq!(whole.face_count(), 3 * 5);
    assert_eq!(whole.face(0), &[0, 1, 7, 6]);
    // Cut at x = 2.5 (a YZ plane moved along x), keep x ≥ 2.5, then mirror back in the same plane.
    let plane = Plane::from_normal(DVec3::new(2.5, 0.0, 0.0), DVec3::X).unwrap();
    let cut = run(
        &ctx,
        "mesh.cut_by_plane",
        &[("mesh", net.mesh.clone().into()), ("plane", plane.into())],
    )
    .unwrap();
    let right = mesh(get(&cut, "mesh")).clone();
    assert!(right.vertices.iter().all(|p| p.x >= 2.5 - 1e-12));
    let Value::Lines(section) = get(&cut, "section") else {
        panic!("lines")
    };
    assert_eq!(section.len(), 3, "one segment per quad row");
    let flipped = run(
        &ctx,
        "mesh.cut_by_plane",
        &[
            ("mesh", net.mesh.clone().into()),
            ("plane", plane.into()),
            ("flip", Value::Boolean(true)),
        ],
    )
    .unwrap();
    assert!(
        mesh(get(&flipped, "mesh"))
            .vertices
            .iter()
            .all(|p| p.x <= 2.5 + 1e-12)
    );
    let mirrored = run(
        &ctx,
        "mesh.mirror",
        &[("mesh", right.clone().into()), ("plane", plane.into())],
    )
    .unwrap();
    let sym = mesh(get(&mirrored, "mesh"));
    assert_eq!(sym.face_count(), 2 * right.face_count());
    // The four section points on the plane are shared.
    let on = right
        .vertices
        .iter()
        .filter(|p| (p.x - 2.5).abs() < 1e-9)
        .count();
    assert_eq!(on, 4);
    assert_eq!(sym.vertices.len(), 2 * right.vertices.len() - on);
    // Join the two halves of the cut and weld: the original vertex count plus the 4 section points.
    let joined = run(
        &ctx,
        "mesh.join",
        &[
            (
                "meshes",
                Value::list(vec![right.clone().into(), get(&flipped, "mesh").clone()]),
            ),
            ("weld", Value::Number(1e-9)),
        ],
    )
    .unwrap();
    let j = mesh(get(&joined, "mesh"));
    assert_eq!(j.vertices.len(), 24 + 4);
    let err = run(
        &ctx,
        "mesh.join",
        &[("meshes", Value::list(vec![PolygonMesh::new().into()]))],
    )
    .unwrap_err();
    assert!(err.contains("empty"), "{err}");
    let err = run(&ctx, "mesh.mirror", &[("mesh", PolygonMesh::new().into())]).unwrap_err();
    assert!(err.contains("empty"), "{err}");
}

#[test]
fn face_attribute_nodes() {
    let net = cone_net(4, 5, false);
    let ctx = NodeContext::default();
    let out = run(
        &ctx,
        "analysis.face_planarity",
        &[("mesh", net.mesh.clone().into())],
    )
    .unwrap();
    assert_eq!(get(&out, "values").as_list().unwrap().len(), 12);
    assert!(get(&out, "max").as_f64().unwrap() < 1e-12);
    let colours = get(&out, "colours").as_list().unwrap();
    assert!((colours[0].as_vec3().unwrap() - DVec3::new(0.15, 0.60, 0.25)).length() < 1e-9);

    let labels = net.configurations.to_strings();
    let table = Value::list(
        labels
            .iter()
            .map(|row| Value::list(row.iter().map(|l| Value::text(*l)).collect()))
            .collect(),
    );
    let out = run(
        &ctx,
        "analysis.face_classes",
        &[("mesh", net.mesh.clone().into()), ("configurations", table)],
    )
    .unwrap();
    let classes: Vec<i64> = get(&out, "classes")
        .as_list()
        .unwrap()
        .iter()
        .map(|c| match c {
            Value::Integer(i) => *i,
            _ => panic!("integer"),
        })
        .collect();
    assert_eq!(classes.len(), 12);
    for i in 0..3 {
        // Every face column is classified, column 0 included (c_{i,0}, issue 17).
        for j in 0..4 {
            let both_good = labels[i][j] == "++" && labels[i + 1][j] == "++";
            assert_eq!(classes[i * 4 + j] == 0, both_good);
            assert_ne!(classes[i * 4 + j], 4);
        }
    }
    // The convex faces counted, and their share of all faces.
    let convex = classes.iter().filter(|c| **c == 0).count();
    assert_eq!(get(&out, "convex"), &Value::Integer(convex as i64));
    assert_eq!(
        get(&out, "convex_share"),
        &Value::Number(convex as f64 / 12.0)
    );
    let err = run(
        &ctx,
        "analysis.face_classes",
        &[
            ("mesh", net.mesh.clone().into()),
            ("configurations", Value::list(vec![Value::text("++")])),
        ],
    )
    .unwrap_err();
    assert!(err.contains("configurations"), "{err}");
    let err = run(
        &ctx,
        "analysis.face_planarity",
        &[("mesh", net.mesh.into()), ("limit", Value::Number(0.0))],
    )
    .unwrap_err();
    assert!(err.contains("limit"), "{err}");
}
