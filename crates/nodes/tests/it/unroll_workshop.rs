//! `pq.unroll_strips` for the workshop (issue 43): fold lines and signed fold angles that match the
//! 3D net, and collapsed edges named by strip and panel.

use crate::fab_support;

use cnets_engine::{NodeContext, Value};
use cnets_geometry::{DVec3, QuadGrid};
use fab_support::*;

fn polylines(v: &Value) -> Vec<Vec<DVec3>> {
    v.as_list()
        .expect("a list")
        .iter()
        .map(|p| match p {
            Value::Polyline(p) => p.points.clone(),
            other => panic!("a polyline, got {}", other.type_name()),
        })
        .collect()
}

fn texts(v: &Value) -> Vec<String> {
    v.as_list()
        .expect("a list")
        .iter()
        .map(|t| match t {
            Value::Text(t) => t.to_string(),
            other => panic!("a text, got {}", other.type_name()),
        })
        .collect()
}

/// The signed dihedral angle (radians) between quads (i, k−1) and (i, k) of a grid across their
/// shared column edge, mountain positive seen from the side of the quads' normals (the cross product
/// of the diagonals in the mesh's corner order).
fn dihedral(g: &QuadGrid, i: usize, k: usize) -> f64 {
    let (a, b) = (g.quad(i, k - 1), g.quad(i, k));
    let (p, q) = (a[1], a[2]);
    let t = (q - p).normalize();
    let across = |x: DVec3| {
        let d = x - p;
        d - t * d.dot(t)
    };
    let (ua, ub) = (across(a[0]), across(b[1]));
    let magnitude = std::f64::consts::PI - ua.cross(ub).length().atan2(ua.dot(ub));
    let na = (a[2] - a[0]).cross(a[3] - a[1]);
    if ub.dot(na) < 0.0 {
        magnitude
    } else {
        -magnitude
    }
}

#[test]
fn fold_angles_through_the_node_are_the_nets_dihedral_angles() {
    let net = cone_net(5, 8, false);
    let g = &net.mesh;
    let ctx = NodeContext::default();
    let out = run(&ctx, "pq.unroll_strips", &[("mesh", g.clone().into())]).unwrap();
    let folds = polylines(get(&out, "folds"));
    let angles: Vec<f64> = get(&out, "fold_angles")
        .as_list()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    // Directrix strips: one fold per inner column of every strip, strip after strip.
    let (strips, per) = (g.rows - 1, g.cols - 2);
    assert_eq!(folds.len(), strips * per);
    assert_eq!(angles.len(), folds.len());
    let mut worst = 0.0f64;
    for i in 0..strips {
        for k in 1..=per {
            let n = i * per + (k - 1);
            let line = &folds[n];
            assert_eq!(line.len(), 2);
            assert!(line.iter().all(|p| p.z == 0.0));
            // The fold line is the rung between the two quads, at its 3D length.
            let rung = g.at(i, k).distance(g.at(i + 1, k));
            assert!((line[0].distance(line[1]) - rung).abs() <= 1e-9 * rung);
            worst = worst.max((angles[n].to_radians() - dihedral(g, i, k)).abs());
        }
    }
    eprintln!(
        "node: largest fold-angle error {worst:e} rad over {} folds",
        folds.len()
    );
    assert!(worst <= 1e-9, "{worst}");
    assert!(get(&out, "degenerate").as_list().unwrap().is_empty());
}

#[test]
fn collapsed_edges_are_reported_by_strip_and_panel() {
    // A folded plate (a profile swept along y: every quad planar) whose profile points 1 and 2 are
    // 2.5e-12 apart, as a correction can leave them.
    let profile = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.4),
        DVec3::new(1.0 + 2.5e-12, 0.0, 0.4 - 1e-12),
        DVec3::new(2.1, 0.0, -0.2),
    ];
    let plate = QuadGrid {
        classes: Vec::new(),
        rows: 3,
        cols: 4,
        wrap_rows: false,
        wrap_cols: false,
        vertices: (0..3)
            .flat_map(|i| profile.iter().map(move |p| *p + DVec3::Y * i as f64))
            .collect(),
    };
    let ctx = NodeContext::default();
    let out = run(&ctx, "pq.unroll_strips", &[("mesh", plate.into())]).unwrap();
    let err = get(&out, "max_length_error").as_f64().unwrap();
    assert!(err <= 1e-9, "{err}");
    let degenerate = texts(get(&out, "degenerate"));
    assert_eq!(degenerate.len(), 4, "{degenerate:?}");
    for (n, line) in degenerate.iter().enumerate() {
        let strip = format!("D{} panel 1 (mesh quad row {}, column 1)", n / 2, n / 2);
        assert!(line.starts_with(&strip), "{line}");
        assert!(line.contains("collapsed to 2.69"), "{line}");
    }
}

#[test]
fn marks_name_the_neighbours_and_the_stations() {
    use cnets_geometry::Plane;
    let net = cone_net(5, 8, false);
    let ctx = NodeContext::default();
    let station = Plane::from_normal(DVec3::new(3.5, 0.0, 0.0), DVec3::X).unwrap();
    let out = run(
        &ctx,
        "pq.unroll_strips",
        &[
            ("mesh", net.mesh.clone().into()),
            ("stations", Value::list(vec![Value::Plane(station.into())])),
        ],
    )
    .unwrap();
    let marks = polylines(get(&out, "marks"));
    let labels = texts(get(&out, "mark_labels"));
    assert_eq!(marks.len(), labels.len());
    // Four directrix strips: 2 × 2 inner neighbours + 2 outer ones, and the station on each strip.
    let neighbours: Vec<&str> = labels
        .iter()
        .map(String::as_str)
        .filter(|l| l.starts_with('D'))
        .collect();
    assert_eq!(neighbours, ["D1", "D0", "D2", "D1", "D3", "D2"]);
    assert_eq!(labels.iter().filter(|l| *l == "S0").count(), 4);
    assert!(marks.iter().flatten().all(|p| p.z == 0.0));
    // Without stations: only the neighbours.
    let out = run(
        &ctx,
        "pq.unroll_strips",
        &[("mesh", net.mesh.clone().into())],
    )
    .unwrap();
    assert_eq!(texts(get(&out, "mark_labels")).len(), 6);
}

#[test]
fn max_length_splits_strips_into_labelled_pieces_with_joint_marks() {
    let net = cone_net(3, 25, false);
    let ctx = NodeContext::default();
    let out = run(
        &ctx,
        "pq.unroll_strips",
        &[
            ("mesh", net.mesh.clone().into()),
            ("max_length", Value::Number(6.0)),
        ],
    )
    .unwrap();
    let outlines = polylines(get(&out, "outlines"));
    let labels = texts(get(&out, "labels"));
    assert_eq!(outlines.len(), labels.len());
    assert_eq!(
        get(&out, "label_points").as_list().unwrap().len(),
        labels.len()
    );
    assert!(labels.len() >= 6, "{labels:?}");
    assert_eq!(labels[0], "D0.1");
    assert_eq!(labels[1], "D0.2");
    for (o, l) in outlines.iter().zip(&labels) {
        let (lo, hi) = o
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p.x), b.max(p.x))
            });
        assert!(hi - lo <= 6.0 + 1e-9, "{l}: {}", hi - lo);
    }
    // Each joint is marked on both pieces with both names, at the same length.
    let marks = polylines(get(&out, "marks"));
    let mark_labels = texts(get(&out, "mark_labels"));
    let joint: Vec<&Vec<DVec3>> = marks
        .iter()
        .zip(&mark_labels)
        .filter(|(_, l)| *l == "D0.1 | D0.2")
        .map(|(m, _)| m)
        .collect();
    assert_eq!(joint.len(), 2);
    let len = |l: &[DVec3]| l[0].distance(l[1]);
    assert!((len(joint[0]) - len(joint[1])).abs() <= 1e-9);
    // One fold fewer per joint.
    let folds = get(&out, "folds").as_list().unwrap().len();
    let whole = run(
        &ctx,
        "pq.unroll_strips",
        &[("mesh", net.mesh.clone().into())],
    )
    .unwrap();
    let all = get(&whole, "folds").as_list().unwrap().len();
    assert_eq!(folds + (labels.len() - 2), all);
    // A panel longer than max_length is named.
    let err = run(
        &ctx,
        "pq.unroll_strips",
        &[
            ("mesh", net.mesh.clone().into()),
            ("max_length", Value::Number(0.5)),
        ],
    )
    .unwrap_err();
    assert!(
        err.contains("D0 panel 0") && err.contains("max_length"),
        "{err}"
    );
}
