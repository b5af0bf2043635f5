//! The fabrication nodes through the registry: port contracts, results that match the geometry,
//! and clear errors (never panics) on bad input.

use crate::fab_support;

use cnets_engine::{NodeContext, Value};
use cnets_geometry::{DVec3, QuadGrid};
use fab_support::*;

fn quad(v: &Value) -> &QuadGrid {
    match v {
        Value::QuadMesh(g) => g,
        other => panic!("expected a quad mesh, got {}", other.type_name()),
    }
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_list()
        .expect("a list")
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn ports_are_the_contract() {
    let table: &[(&str, &[&str], &[&str])] = &[
        (
            "cnets.graph_to_apex",
            &["widths", "normalized", "directrix", "scale"],
            &["apex"],
        ),
        ("cnets.torsion_free_axes", &["directrix", "mesh"], &["axes"]),
        (
            "cnets.conical_support",
            &["directrix", "mesh", "apex", "factor"],
            &["mesh"],
        ),
        (
            "pq.parallel_support",
            &["directrix", "mesh", "distance"],
            &["mesh"],
        ),
        ("pq.parallel_transform", &["mesh", "mu", "nu"], &["mesh"]),
        ("pq.extract_strips", &["mesh", "direction"], &["strips"]),
        (
            "pq.unroll_strips",
            &[
                "mesh",
                "direction",
                "tolerance",
                "spacing",
                "stations",
                "max_length",
            ],
            &[
                "outlines",
                "max_length_error",
                "labels",
                "label_points",
                "folds",
                "fold_angles",
                "degenerate",
                "marks",
                "mark_labels",
            ],
        ),
    ];
    for (id, inputs, outputs) in table {
        let (i, o) = ports(id);
        assert_eq!(i, *inputs, "{id} inputs");
        assert_eq!(o, *outputs, "{id} outputs");
    }
    let d = def("cnets.conical_support");
    assert_eq!(
        d.inputs[3].default.as_ref().and_then(Value::as_f64),
        Some(0.8)
    );
    let u = def("pq.unroll_strips");
    assert_eq!(u.inputs[1].default, Some(Value::text("directrix")));
}

#[test]
fn conical_support_node_puts_vertices_on_axes() {
    let net = cone_net(5, 7, false);
    let ctx = NodeContext::default();
    let apex = Value::list(net.apex.iter().map(|a| Value::Number(*a)).collect());
    let out = run(
        &ctx,
        "cnets.conical_support",
        &[
            ("directrix", directrix(7).into()),
            ("mesh", net.mesh.clone().into()),
            ("apex", apex.clone()),
        ],
    )
    .unwrap();
    let support = quad(get(&out, "mesh"));
    for i in 0..5 {
        for j in 0..7 {
            let (x, g, s) = (net.directrix[j], net.mesh.at(i, j), support.at(i, j));
            let dist = (s - x).cross(g - x).length() / (g - x).length();
            assert!(dist <= 1e-12 * net.mesh.size());
            // Default factor 0.8 on the first column.
            if j == 0 {
                assert!(s.distance(x + (g - x) * 0.8) < 1e-14);
            }
        }
    }
    // The axes node gives the same lines.
    let axes = run(
        &ctx,
        "cnets.torsion_free_axes",
        &[
            ("directrix", directrix(7).into()),
            ("mesh", net.mesh.clone().into()),
        ],
    )
    .unwrap();
    let Value::Lines(lines) = get(&axes, "axes") else {
        panic!("lines")
    };
    assert_eq!(lines.len(), 35);
    assert_eq!(lines[7 + 3].start, net.directrix[3]);
    assert_eq!(lines[7 + 3].end, net.mesh.at(1, 3));
    // Wrong apex length: a clear error, no panic.
    let err = run(
        &ctx,
        "cnets.conical_support",
        &[
            ("directrix", directrix(7).into()),
            ("mesh", net.mesh.clone().into()),
            ("apex", Value::list(vec![Value::Number(1.0)])),
        ],
    )
    .unwrap_err();
    assert!(err.contains("apex has 1 entries, expected 6"), "{err}");
}

#[test]
fn parallel_nodes_keep_edges_parallel() {
    let net = cone_net(5, 6, false);
    let ctx = NodeContext::default();
    let support = run(
        &ctx,
        "pq.parallel_support",
        &[
            ("directrix", directrix(6).into()),
            ("mesh", net.mesh.clone().into()),
            ("distance", Value::Number(0.25)),
        ],
    )
    .unwrap();
    let h = quad(get(&support, "mesh")).clone();
    let mu = Value::list([1.2, 0.8, 1.0, 1.1].map(Value::Number).to_vec());
    let transform = run(
        &ctx,
        "pq.parallel_transform",
        &[
            ("mesh", net.mesh.clone().into()),
            ("mu", mu),
            ("nu", Value::Number(0.9)),
        ],
    )
    .unwrap();
    let t = quad(get(&transform, "mesh")).clone();
    for other in [&h, &t] {
        for i in 0..5 {
            for j in 0..6 {
                for (di, dj) in [(0, 1), (1, 0)] {
                    if i + di >= 5 || j + dj >= 6 {
                        continue;
                    }
                    let a = net.mesh.at(i + di, j + dj) - net.mesh.at(i, j);
                    let b = other.at(i + di, j + dj) - other.at(i, j);
                    assert!(a.cross(b).length() <= 1e-9 * a.length() * b.length());
                }
            }
        }
    }
    assert!((h.at(0, 0).distance(net.mesh.at(0, 0)) - 0.25).abs() < 1e-14);
    // A zero factor is refused with its index.
    let err = run(
        &ctx,
        "pq.parallel_transform",
        &[
            ("mesh", net.mesh.clone().into()),
            (
                "nu",
                Value::list(vec![
                    Value::Number(1.0),
                    Value::Number(0.0),
                    Value::Number(1.0),
                    Value::Number(1.0),
                    Value::Number(1.0),
                ]),
            ),
        ],
    )
    .unwrap_err();
    assert!(err.contains("nu[1]"), "{err}");
}

#[test]
fn strips_and_unrolling_nodes() {
    let net = cone_net(5, 7, false);
    let ctx = NodeContext::default();
    for (direction, count) in [("directrix", 4), ("generatrix", 6)] {
        let strips = run(
            &ctx,
            "pq.extract_strips",
            &[
                ("mesh", net.mesh.clone().into()),
                ("direction", Value::text(direction)),
            ],
        )
        .unwrap();
        assert_eq!(get(&strips, "strips").as_list().unwrap().len(), count);
        let out = run(
            &ctx,
            "pq.unroll_strips",
            &[
                ("mesh", net.mesh.clone().into()),
                ("direction", Value::text(direction)),
            ],
        )
        .unwrap();
        let outlines = get(&out, "outlines").as_list().unwrap();
        assert_eq!(outlines.len(), count);
        for o in outlines {
            let Value::Polyline(p) = o else {
                panic!("polyline")
            };
            assert!(p.closed);
            assert!(p.points.iter().all(|q| q.z == 0.0));
        }
        let err = get(&out, "max_length_error").as_f64().unwrap();
        assert!(err <= 1e-9, "{err}");
        let labels = get(&out, "labels").as_list().unwrap();
        assert_eq!(
            labels[0],
            Value::text(if direction == "directrix" { "D0" } else { "G0" })
        );
        assert_eq!(get(&out, "label_points").as_list().unwrap().len(), count);
    }
    // A non-planar face: the error names the strip and the quad.
    let mut bent = net.mesh.clone();
    *bent.at_mut(1, 1) += DVec3::new(0.0, 0.0, 0.1);
    let err = run(&ctx, "pq.unroll_strips", &[("mesh", bent.into())]).unwrap_err();
    assert!(
        err.contains("strip 0, quad 0") && err.contains("not planar"),
        "{err}"
    );
    let err = run(
        &ctx,
        "pq.unroll_strips",
        &[
            ("mesh", net.mesh.clone().into()),
            ("direction", Value::text("diagonal")),
        ],
    )
    .unwrap_err();
    assert!(
        err.contains("directrix") && err.contains("generatrix"),
        "{err}"
    );
    let err = run(
        &ctx,
        "pq.unroll_strips",
        &[("mesh", QuadGrid::default().into())],
    )
    .unwrap_err();
    assert!(err.contains("empty"), "{err}");
}

#[test]
fn a_cut_and_mirrored_net_unrolls_through_the_node_with_mirror_marks() {
    use cnets_geometry::fabrication::{cut_by_plane, mirror};
    use cnets_geometry::{Plane, PolygonMesh};
    let net = cone_net(6, 9, false);
    let plane = Plane::from_normal(DVec3::new(4.3, 0.0, 0.0), DVec3::new(1.0, 0.3, 0.1)).unwrap();
    let half = cut_by_plane(&PolygonMesh::from(&net.mesh), &plane, false)
        .unwrap()
        .mesh;
    let whole = mirror(&half, &plane, 1e-9).unwrap();
    let ctx = NodeContext::default();
    for (mesh, mirrored) in [(half, false), (whole, true)] {
        let faces = mesh.face_count();
        let out = run(
            &ctx,
            "pq.unroll_strips",
            &[("mesh", Value::Mesh(std::sync::Arc::new(mesh)))],
        )
        .unwrap();
        let err = get(&out, "max_length_error").as_f64().unwrap();
        assert!(err <= 1e-9, "{err}");
        let labels: Vec<String> = get(&out, "labels")
            .as_list()
            .unwrap()
            .iter()
            .map(|l| match l {
                Value::Text(t) => t.to_string(),
                other => panic!("a label, got {}", other.type_name()),
            })
            .collect();
        assert!(faces > 0 && labels[0] == "D0", "{labels:?}");
        let marks = labels.iter().filter(|l| l.contains("(mirror of D")).count();
        if mirrored {
            assert_eq!(2 * marks, labels.len(), "{labels:?}");
        } else {
            assert_eq!(marks, 0, "{labels:?}");
        }
        assert_eq!(get(&out, "outlines").as_list().unwrap().len(), labels.len());
    }
}

#[test]
fn graph_to_apex_node() {
    let ctx = NodeContext::default();
    let widths = Value::list([2.0, 1.0, 1.5, 1.5].map(Value::Number).to_vec());
    let out = run(&ctx, "cnets.graph_to_apex", &[("widths", widths.clone())]).unwrap();
    assert_eq!(numbers(get(&out, "apex")), vec![0.5, 1.5, 1.0]);
    let out = run(
        &ctx,
        "cnets.graph_to_apex",
        &[
            ("widths", widths.clone()),
            ("normalized", Value::Boolean(true)),
            ("directrix", directrix(4).into()),
            ("scale", Value::Number(2.0)),
        ],
    )
    .unwrap();
    let abar = numbers(get(&out, "apex"));
    let d = directrix(4);
    let l1 = d.points[1].distance(d.points[0]);
    assert!((abar[0] - (1.0 - 0.5 * 2.0 / l1)).abs() < 1e-14);
    assert_eq!(abar[2], 1.0);
    let err = run(
        &ctx,
        "cnets.graph_to_apex",
        &[("widths", widths), ("normalized", Value::Boolean(true))],
    )
    .unwrap_err();
    assert!(err.contains("directrix"), "{err}");
    let err = run(
        &ctx,
        "cnets.graph_to_apex",
        &[(
            "widths",
            Value::list(vec![Value::Number(1.0), Value::Number(-1.0)]),
        )],
    )
    .unwrap_err();
    assert!(err.contains("y_1"), "{err}");
}
