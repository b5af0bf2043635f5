//! `fab.schedule`: the panel schedule measured against independent computations on the 3D net
//! (areas, edge lengths, dihedral angles), named as `pq.unroll_strips` names the parts, and written
//! by `io.export_csv` as a table that Python's `csv` module reads back exactly.

use crate::fab_support;

use std::path::Path;
use std::sync::Arc;

use cnets_engine::{NodeContext, Record, Value};
use cnets_geometry::fabrication::cut_by_plane;
use cnets_geometry::{DVec3, Plane, PolygonMesh, QuadGrid};
use fab_support::*;

/// The schedule's columns, in order.
const COLUMNS: [&str; 10] = [
    "strip",
    "piece",
    "panel",
    "face",
    "corners",
    "area",
    "edges",
    "fold_previous_deg",
    "fold_next_deg",
    "planarity",
];

fn records(v: &Value) -> Vec<Arc<Record>> {
    v.as_list()
        .expect("a list")
        .iter()
        .map(|r| match r {
            Value::Record(r) => r.clone(),
            other => panic!("a record, got {}", other.type_name()),
        })
        .collect()
}

fn text(r: &Record, name: &str) -> String {
    match r.get(name) {
        Some(Value::Text(t)) => t.to_string(),
        other => panic!("{name}: a text, got {other:?}"),
    }
}

fn number(r: &Record, name: &str) -> Option<f64> {
    match r.get(name) {
        Some(Value::Null) => None,
        Some(v) => Some(v.as_f64().unwrap_or_else(|| panic!("{name}: a number"))),
        None => panic!("no field {name}"),
    }
}

fn points(r: &Record, name: &str) -> Vec<DVec3> {
    r.get(name)
        .and_then(Value::as_list)
        .unwrap_or_else(|| panic!("{name}: a list"))
        .iter()
        .map(|p| p.as_vec3().expect("a point"))
        .collect()
}

fn numbers(r: &Record, name: &str) -> Vec<f64> {
    r.get(name)
        .and_then(Value::as_list)
        .unwrap_or_else(|| panic!("{name}: a list"))
        .iter()
        .map(|p| p.as_f64().expect("a number"))
        .collect()
}

fn labels(v: &Value) -> Vec<String> {
    v.as_list()
        .unwrap()
        .iter()
        .map(|t| match t {
            Value::Text(t) => t.to_string(),
            other => panic!("a text, got {}", other.type_name()),
        })
        .collect()
}

/// The distinct values of a column, in order of first appearance.
fn distinct(rows: &[Arc<Record>], name: &str) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for r in rows {
        let t = text(r, name);
        if out.last() != Some(&t) {
            out.push(t);
        }
    }
    out
}

/// The area of a planar polygon by a fan of triangles from its first corner.
fn fan_area(c: &[DVec3]) -> f64 {
    let mut sum = DVec3::ZERO;
    for k in 1..c.len() - 1 {
        sum += (c[k] - c[0]).cross(c[k + 1] - c[0]);
    }
    0.5 * sum.length()
}

/// The signed dihedral angle (radians) between quads (i, k−1) and (i, k) of a grid across their
/// shared column edge, mountain positive seen from the side of the quads' normals (the cross
/// product of the diagonals in the mesh's corner order): the angle between the two faces' in-plane
/// directions away from the edge.
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
fn rows_measure_every_panel_of_the_net() {
    let net = cone_net(5, 8, false);
    let g = &net.mesh;
    let ctx = NodeContext::default();
    let out = run(&ctx, "fab.schedule", &[("mesh", g.clone().into())]).unwrap();
    let rows = records(get(&out, "table"));
    let (strips, per) = (g.rows - 1, g.cols - 1);
    assert_eq!(rows.len(), strips * per);
    let mut total = 0.0;
    let (mut worst_area, mut worst_edge, mut worst_fold) = (0.0f64, 0.0f64, 0.0f64);
    for (n, r) in rows.iter().enumerate() {
        let names: Vec<&str> = r.fields().iter().map(|(f, _)| f.as_str()).collect();
        assert_eq!(names, COLUMNS);
        let (i, k) = (n / per, n % per);
        assert_eq!(text(r, "strip"), format!("D{i}"));
        assert_eq!(text(r, "piece"), format!("D{i}"));
        assert_eq!(r.get("panel"), Some(&Value::Integer(k as i64)));
        assert_eq!(text(r, "face"), format!("mesh quad row {i}, column {k}"));
        let quad = g.quad(i, k);
        assert_eq!(points(r, "corners"), quad.to_vec());
        // Area: half the cross product of the diagonals (a planar quad's area).
        let area = number(r, "area").unwrap();
        let by_diagonals = 0.5 * (quad[2] - quad[0]).cross(quad[3] - quad[1]).length();
        worst_area = worst_area.max((area - by_diagonals).abs() / by_diagonals);
        total += area;
        let edges = numbers(r, "edges");
        assert_eq!(edges.len(), 4);
        for (e, l) in edges.iter().enumerate() {
            let d = quad[(e + 1) % 4] - quad[e];
            let independent = (d.x * d.x + d.y * d.y + d.z * d.z).sqrt();
            worst_edge = worst_edge.max((l - independent).abs() / independent);
        }
        // Folds to the neighbours in the strip: none before the first panel, none after the last.
        let previous = number(r, "fold_previous_deg");
        let next = number(r, "fold_next_deg");
        assert_eq!(previous.is_none(), k == 0, "row {n}");
        assert_eq!(next.is_none(), k + 1 == per, "row {n}");
        if let Some(p) = previous {
            worst_fold = worst_fold.max((p.to_radians() - dihedral(g, i, k)).abs());
        }
        if let Some(x) = next {
            worst_fold = worst_fold.max((x.to_radians() - dihedral(g, i, k + 1)).abs());
        }
        assert!(number(r, "planarity").unwrap() <= 1e-9);
    }
    assert!(worst_area <= 1e-12, "area {worst_area}");
    assert!(worst_edge <= 1e-15, "edge {worst_edge}");
    assert!(worst_fold <= 1e-9, "fold {worst_fold} rad");
    let sum = get(&out, "total_area").as_f64().unwrap();
    assert!((sum - total).abs() <= 1e-12 * total, "{sum} vs {total}");
    // The folds equal those `pq.unroll_strips` writes on the cutting sheets, in the same order.
    let unrolled = run(&ctx, "pq.unroll_strips", &[("mesh", g.clone().into())]).unwrap();
    let angles: Vec<f64> = get(&unrolled, "fold_angles")
        .as_list()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let from_rows: Vec<f64> = rows
        .iter()
        .filter_map(|r| number(r, "fold_previous_deg"))
        .collect();
    assert_eq!(from_rows, angles);
}

#[test]
fn names_follow_the_unrolled_parts_of_a_cut_net_and_of_pieces() {
    let net = cone_net(6, 9, false);
    let plane = Plane::from_normal(DVec3::new(4.3, 0.0, 0.0), DVec3::new(1.0, 0.3, 0.1)).unwrap();
    let cut = cut_by_plane(&PolygonMesh::from(&net.mesh), &plane, false)
        .unwrap()
        .mesh;
    let ctx = NodeContext::default();
    for direction in ["directrix", "generatrix"] {
        let given = [
            ("mesh", Value::Mesh(Arc::new(cut.clone()))),
            ("direction", Value::text(direction)),
        ];
        let out = run(&ctx, "fab.schedule", &given).unwrap();
        let rows = records(get(&out, "table"));
        // Every face of the cut net once, trimmed panels (triangles, pentagons) included.
        assert_eq!(rows.len(), cut.face_count());
        let mut faces: Vec<String> = rows.iter().map(|r| text(r, "face")).collect();
        faces.sort();
        faces.dedup();
        assert_eq!(faces.len(), cut.face_count());
        assert!(rows.iter().any(|r| points(r, "corners").len() != 4));
        for r in &rows {
            let c = points(r, "corners");
            let area = number(r, "area").unwrap();
            let fan = fan_area(&c);
            assert!((area - fan).abs() <= 1e-12 * fan, "{area} vs {fan}");
        }
        let unrolled = run(&ctx, "pq.unroll_strips", &given).unwrap();
        assert_eq!(distinct(&rows, "strip"), labels(get(&unrolled, "labels")));
    }
    // With max_length the pieces are named as on the sheets; the joints keep their fold.
    let long = cone_net(3, 25, false);
    let given = [
        ("mesh", long.mesh.clone().into()),
        ("max_length", Value::Number(6.0)),
    ];
    let rows = records(get(&run(&ctx, "fab.schedule", &given).unwrap(), "table"));
    let unrolled = run(&ctx, "pq.unroll_strips", &given).unwrap();
    let pieces = labels(get(&unrolled, "labels"));
    assert_eq!(distinct(&rows, "piece"), pieces);
    assert_eq!(distinct(&rows, "strip"), ["D0", "D1"]);
    let joint = rows
        .windows(2)
        .find(|w| text(&w[0], "piece") == "D0.1" && text(&w[1], "piece") == "D0.2")
        .expect("the joint between D0.1 and D0.2");
    assert!(number(&joint[0], "fold_next_deg").is_some());
    assert_eq!(
        number(&joint[0], "fold_next_deg"),
        number(&joint[1], "fold_previous_deg")
    );
}

#[test]
fn the_csv_table_round_trips_through_pythons_csv_reader() {
    let net = cone_net(4, 6, false);
    let ctx_plain = NodeContext::default();
    let out = run(
        &ctx_plain,
        "fab.schedule",
        &[("mesh", net.mesh.clone().into())],
    )
    .unwrap();
    let table = get(&out, "table").clone();
    let rows = records(&table);
    let dir = scratch("schedule-csv");
    let written = run(
        &ctx_in(&dir),
        "io.export_csv",
        &[("name", Value::text("schedule")), ("value", table)],
    )
    .unwrap();
    let Value::Text(path) = get(&written, "path") else {
        panic!("path")
    };
    assert!(path.ends_with("schedule.csv"));
    let report = run_checker("python3", "scripts/read-csv.py", Path::new(path.as_ref()));
    let read: Vec<Vec<String>> = serde_json::from_str(&report).unwrap();
    assert_eq!(read[0], COLUMNS);
    assert_eq!(read.len(), rows.len() + 1);
    let parse = |s: &str| -> f64 { s.parse().unwrap_or_else(|_| panic!("a number: {s:?}")) };
    for (r, line) in rows.iter().zip(&read[1..]) {
        assert_eq!(line.len(), COLUMNS.len());
        assert_eq!(line[0], text(r, "strip"));
        assert_eq!(line[1], text(r, "piece"));
        let panel = Value::Integer(line[2].parse().unwrap());
        assert_eq!(r.get("panel"), Some(&panel));
        // `mesh quad row 1, column 2` holds a comma: quoted, and read back whole.
        assert_eq!(line[3], text(r, "face"));
        let corners: Vec<DVec3> = line[4]
            .split("; ")
            .map(|p| {
                let x: Vec<f64> = p.split(' ').map(parse).collect();
                DVec3::new(x[0], x[1], x[2])
            })
            .collect();
        assert_eq!(corners, points(r, "corners"), "corners bit for bit");
        assert_eq!(parse(&line[5]), number(r, "area").unwrap());
        let edges: Vec<f64> = line[6].split("; ").map(parse).collect();
        assert_eq!(edges, numbers(r, "edges"));
        for (cell, name) in [(&line[7], COLUMNS[7]), (&line[8], COLUMNS[8])] {
            match number(r, name) {
                None => assert_eq!(cell, "", "{name}: no fold, an empty cell"),
                Some(a) => assert_eq!(parse(cell), a),
            }
        }
        assert_eq!(parse(&line[9]), number(r, "planarity").unwrap());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn table_cells_are_quoted_and_missing_fields_left_empty() {
    let a = Record::new()
        .with("name", Value::text("say \"6,5\"\nthen"))
        .with("n", Value::Integer(3));
    let b = Record::new()
        .with("n", Value::Number(0.1))
        .with("ok", Value::Boolean(true));
    let dir = scratch("record-csv");
    let value = Value::list(vec![a.into(), b.into()]);
    let out = run(
        &ctx_in(&dir),
        "io.export_csv",
        &[("name", Value::text("t.csv")), ("value", value)],
    )
    .unwrap();
    let Value::Text(path) = get(&out, "path") else {
        panic!("path")
    };
    let report = run_checker("python3", "scripts/read-csv.py", Path::new(path.as_ref()));
    let read: Vec<Vec<String>> = serde_json::from_str(&report).unwrap();
    assert_eq!(
        read,
        [
            vec!["name", "n", "ok"],
            vec!["say \"6,5\"\nthen", "3", ""],
            vec!["", "0.1", "true"],
        ]
    );
    // A cell that cannot be written names its record and field; no file is left.
    let bad = Record::new().with("mesh", Value::from(PolygonMesh::default()));
    let err = run(
        &ctx_in(&dir),
        "io.export_csv",
        &[("name", Value::text("bad.csv")), ("value", bad.into())],
    )
    .unwrap_err();
    assert!(err.contains("record 0, field 'mesh'"), "{err}");
    assert!(!dir.join("bad.csv").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
