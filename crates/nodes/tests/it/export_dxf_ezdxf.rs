//! DXF export: the file is read back by the independent Python reader `ezdxf` (scripts/read-dxf.py)
//! and by the `dxf` crate, and compared with what was written: version R2000, millimetres, one
//! layer per strip holding a closed LWPOLYLINE and its label.

use crate::fab_support;

use cnets_engine::{NodeContext, Value};
use cnets_geometry::{DVec3, Polyline};
use fab_support::*;

/// Unrolled strips of a test cone-net: (outlines, labels, label points) as node values.
fn unrolled() -> (Value, Value, Value) {
    let net = cone_net(4, 6, false);
    let out = run(
        &NodeContext::default(),
        "pq.unroll_strips",
        &[
            ("mesh", net.mesh.into()),
            ("direction", Value::text("generatrix")),
        ],
    )
    .unwrap();
    (
        get(&out, "outlines").clone(),
        get(&out, "labels").clone(),
        get(&out, "label_points").clone(),
    )
}

fn polylines(v: &Value) -> Vec<Polyline> {
    v.as_list()
        .unwrap()
        .iter()
        .map(|p| match p {
            Value::Polyline(p) => (**p).clone(),
            _ => panic!("polyline"),
        })
        .collect()
}

/// What ezdxf (scripts/read-dxf.py) reads from the file an `io.export_dxf` run wrote.
fn ezdxf_report(out: &[(String, Value)]) -> serde_json::Value {
    let Value::Text(path) = get(out, "path") else {
        panic!("path")
    };
    let report = run_checker(
        "python3",
        "scripts/read-dxf.py",
        std::path::Path::new(path.as_ref()),
    );
    serde_json::from_str(&report).expect("ezdxf report is JSON")
}

/// The texts of a list of texts (the strips' labels).
fn texts(v: &Value) -> Vec<String> {
    v.as_list()
        .unwrap()
        .iter()
        .map(|l| match l {
            Value::Text(t) => t.to_string(),
            _ => panic!("text"),
        })
        .collect()
}

#[test]
fn ezdxf_reads_layers_polylines_and_labels() {
    let (outlines, labels, points) = unrolled();
    let dir = scratch("dxf");
    let ctx = ctx_in(&dir);
    let out = run(
        &ctx,
        "io.export_dxf",
        &[
            ("name", Value::text("strips")),
            ("outlines", outlines.clone()),
            ("labels", labels.clone()),
            ("label_points", points.clone()),
        ],
    )
    .unwrap();
    let Value::Text(path) = get(&out, "path") else {
        panic!("path")
    };
    assert!(path.ends_with("strips.dxf"));
    let path = std::path::PathBuf::from(path.as_ref());
    let written = polylines(&outlines);
    let names = texts(&labels);

    let report = run_checker("python3", "scripts/read-dxf.py", &path);
    let r: serde_json::Value = serde_json::from_str(&report).expect("ezdxf report is JSON");
    assert_eq!(
        r["dxfversion"], "AC1015",
        "R2000 or later, or LWPOLYLINE is dropped"
    );
    assert_eq!(r["insunits"], 4, "millimetres");
    assert_eq!(r["audit_errors"], 0, "ezdxf audit found errors");
    assert_eq!(
        r["audit_fixes"], 0,
        "ezdxf audit repaired something: {}",
        r["audit_messages"]
    );
    assert_eq!(r["measurement"], 1, "metric");
    // Extents: the bounds of the outlines in mm.
    let all: Vec<_> = written.iter().flat_map(|o| o.points.clone()).collect();
    let (lo, hi) = cnets_geometry::quad_grid::bounds_of(&all).unwrap();
    for (key, p) in [("extmin", lo), ("extmax", hi)] {
        let e = &r[key];
        assert!(
            (e[0].as_f64().unwrap() - p.x * 1000.0).abs() < 1e-6
                && (e[1].as_f64().unwrap() - p.y * 1000.0).abs() < 1e-6,
            "{key}: {e}"
        );
    }
    let polys = r["lwpolylines"].as_array().unwrap();
    assert_eq!(polys.len(), written.len());
    for (k, (poly, outline)) in polys.iter().zip(&written).enumerate() {
        let layer = format!("STRIP_{}", names[k]);
        assert_eq!(poly["layer"], layer.as_str());
        assert!(
            r["layers"]
                .as_array()
                .unwrap()
                .iter()
                .any(|l| l == layer.as_str())
        );
        assert_eq!(poly["closed"], true);
        let pts = poly["points"].as_array().unwrap();
        assert_eq!(pts.len(), outline.points.len());
        for (p, q) in pts.iter().zip(&outline.points) {
            let (x, y) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
            assert!((x - q.x * 1000.0).abs() < 1e-6 && (y - q.y * 1000.0).abs() < 1e-6);
        }
    }
    let texts = r["texts"].as_array().unwrap();
    assert_eq!(texts.len(), written.len());
    let anchors: Vec<_> = points
        .as_list()
        .unwrap()
        .iter()
        .map(|p| p.as_vec3().unwrap())
        .collect();
    for (k, t) in texts.iter().enumerate() {
        assert_eq!(t["text"], names[k].as_str());
        assert_eq!(t["layer"], format!("STRIP_{}", names[k]).as_str());
        assert!((t["insert"][0].as_f64().unwrap() - anchors[k].x * 1000.0).abs() < 1e-6);
    }

    // The dxf crate reads the same entities back.
    let drawing = dxf::Drawing::load_file(&path).expect("the dxf crate reads the file");
    let count = drawing
        .entities()
        .filter(|e| matches!(e.specific, dxf::entities::EntityType::LwPolyline(_)))
        .count();
    assert_eq!(count, written.len());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn without_labels_layers_are_numbered_and_scale_applies() {
    let (outlines, _, _) = unrolled();
    let dir = scratch("dxf-plain");
    let out = run(
        &ctx_in(&dir),
        "io.export_dxf",
        &[
            ("outlines", outlines.clone()),
            ("scale", Value::Number(10.0)),
        ],
    )
    .unwrap();
    let r = ezdxf_report(&out);
    assert_eq!(r["lwpolylines"][1]["layer"], "STRIP_1");
    assert!(r["texts"].as_array().unwrap().is_empty());
    let first = &polylines(&outlines)[0].points[2];
    assert!((r["lwpolylines"][0]["points"][2][0].as_f64().unwrap() - first.x * 10.0).abs() < 1e-9);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_same_input_gives_the_same_bytes_and_nested_sheets_are_blocks() {
    let (outlines, labels, points) = unrolled();
    let n = outlines.as_list().unwrap().len();
    let sheets = Value::list((0..n).map(|k| Value::Integer((k % 2) as i64)).collect());
    let mut files = Vec::new();
    for run_index in 0..2 {
        let dir = scratch(&format!("dxf-same-{run_index}"));
        let out = run(
            &ctx_in(&dir),
            "io.export_dxf",
            &[
                ("outlines", outlines.clone()),
                ("labels", labels.clone()),
                ("label_points", points.clone()),
                ("sheets", sheets.clone()),
            ],
        )
        .unwrap();
        let Value::Text(path) = get(&out, "path") else {
            panic!("path")
        };
        files.push(std::fs::read(path.as_ref()).unwrap());
        if run_index == 1 {
            let report = run_checker(
                "python3",
                "scripts/read-dxf.py",
                std::path::Path::new(path.as_ref()),
            );
            let r: serde_json::Value = serde_json::from_str(&report).unwrap();
            assert_eq!(r["audit_errors"], 0);
            assert_eq!(r["audit_fixes"], 0, "{}", r["audit_messages"]);
            // Model space holds one INSERT per sheet; each sheet's outlines are in its block,
            // on the sheet's layers, inserted at the block's base point.
            assert!(r["lwpolylines"].as_array().unwrap().is_empty());
            let blocks = r["blocks"].as_array().unwrap();
            let names: Vec<&str> = blocks.iter().map(|b| b["name"].as_str().unwrap()).collect();
            assert_eq!(names, ["SHEET_1", "SHEET_2"]);
            for (s, block) in blocks.iter().enumerate() {
                let polys = block["lwpolylines"].as_array().unwrap();
                assert_eq!(polys.len(), (n + 1 - s) / 2, "{}", block["name"]);
                for poly in polys {
                    let layer = poly["layer"].as_str().unwrap();
                    assert!(
                        layer.starts_with(&format!("SHEET{}_STRIP_", s + 1)),
                        "{layer}"
                    );
                }
                assert_eq!(block["texts"].as_array().unwrap().len(), polys.len());
            }
            let inserts = r["inserts"].as_array().unwrap();
            assert_eq!(inserts.len(), 2);
            for (i, b) in inserts.iter().zip(blocks) {
                assert_eq!(i["name"], b["name"]);
                assert_eq!(i["insert"], b["base"]);
            }
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
    assert!(files[0] == files[1], "two runs wrote different bytes");
}

#[test]
fn writing_is_linear_in_the_outlines() {
    // 80 000 small outlines: the old writer took about 50 s (quadratic); this one is linear. The
    // bound is the issue's, met by the test build (opt-level 1, 0.56 s measured).
    let outlines: Vec<Value> = (0..80_000)
        .map(|k| {
            let (x, y) = ((k % 300) as f64, (k / 300) as f64);
            Value::from(Polyline::closed(vec![
                cnets_geometry::DVec3::new(x, y, 0.0),
                cnets_geometry::DVec3::new(x + 0.8, y, 0.0),
                cnets_geometry::DVec3::new(x + 0.8, y + 0.5, 0.0),
                cnets_geometry::DVec3::new(x, y + 0.5, 0.0),
            ]))
        })
        .collect();
    let labels: Vec<Value> = (0..80_000).map(|k| Value::text(format!("P{k}"))).collect();
    let dir = scratch("dxf-big");
    let started = std::time::Instant::now();
    let out = run(
        &ctx_in(&dir),
        "io.export_dxf",
        &[
            ("outlines", Value::list(outlines)),
            ("labels", Value::list(labels)),
        ],
    )
    .unwrap();
    let took = started.elapsed();
    eprintln!("80 000 outlines written in {took:?}");
    let Value::Text(path) = get(&out, "path") else {
        panic!("path")
    };
    let text = std::fs::read_to_string(path.as_ref()).unwrap();
    assert_eq!(text.matches("\nLWPOLYLINE\n").count(), 80_000);
    // 0.71 s idle and 0.6–0.95 s under load (6–9) in the test build on the 2-core machine, but
    // 15.8 s once at `nice 5` beside three clean-clone builds (load 14); a writer copying its
    // output per outline would take minutes (80 000² bytes moved). The bound is 60 s: 63× the
    // loaded figure and 3.8× the starved one (issue 30).
    assert!(took.as_secs_f64() < 60.0, "80 000 outlines took {took:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The whole hull to the cutter (issue 32): a cone-net cut by an oblique plane (trimmed panels,
/// pentagons, triangles) and mirrored in it, its strips unrolled by `pq.unroll_strips` and written
/// by `io.export_dxf`; ezdxf audits the file clean and reads every strip of both halves, the
/// mirrored copies marked in their labels and layers.
#[test]
fn the_strips_of_a_cut_and_mirrored_net_pass_the_ezdxf_audit() {
    use cnets_geometry::{DVec3, Plane};
    let ctx = NodeContext::default();
    let net = cone_net(9, 12, false);
    let plane = Plane::from_normal(DVec3::new(6.3, 0.0, 0.0), DVec3::new(1.0, 0.45, 0.2)).unwrap();
    let plane = Value::from(plane);
    let cut = run(
        &ctx,
        "mesh.cut_by_plane",
        &[("mesh", net.mesh.into()), ("plane", plane.clone())],
    )
    .unwrap();
    let whole = run(
        &ctx,
        "mesh.mirror",
        &[
            ("mesh", get(&cut, "mesh").clone()),
            ("plane", plane),
            ("tolerance", Value::Number(1e-9)),
        ],
    )
    .unwrap();
    let strips = run(
        &ctx,
        "pq.unroll_strips",
        &[
            ("mesh", get(&whole, "mesh").clone()),
            ("direction", Value::text("directrix")),
        ],
    )
    .unwrap();
    let error = get(&strips, "max_length_error").as_f64().unwrap();
    assert!(error <= 1e-9, "unroll error {error:e}");
    let labels = texts(get(&strips, "labels"));
    let mirrored = labels.iter().filter(|l| l.contains("(mirror of ")).count();
    assert_eq!((labels.len(), mirrored), (16, 8), "{labels:?}");

    let dir = scratch("dxf-mirrored");
    let out = run(
        &ctx_in(&dir),
        "io.export_dxf",
        &[
            ("name", Value::text("hull-strips")),
            ("outlines", get(&strips, "outlines").clone()),
            ("labels", get(&strips, "labels").clone()),
            ("label_points", get(&strips, "label_points").clone()),
        ],
    )
    .unwrap();
    let r = ezdxf_report(&out);
    assert_eq!(r["audit_errors"], 0, "ezdxf audit found errors");
    assert_eq!(
        r["audit_fixes"], 0,
        "ezdxf audit repaired something: {}",
        r["audit_messages"]
    );
    let written = polylines(get(&strips, "outlines"));
    let polys = r["lwpolylines"].as_array().unwrap();
    assert_eq!(polys.len(), written.len());
    for (poly, outline) in polys.iter().zip(&written) {
        assert_eq!(poly["closed"], true);
        assert_eq!(
            poly["points"].as_array().unwrap().len(),
            outline.points.len()
        );
    }
    let texts: Vec<&str> = r["texts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["text"].as_str().unwrap())
        .collect();
    assert_eq!(
        texts, labels,
        "every strip labelled, the mirror images marked"
    );
    // One layer a strip, distinct for the mirrored copies.
    let layers: std::collections::HashSet<&str> =
        polys.iter().map(|p| p["layer"].as_str().unwrap()).collect();
    assert_eq!(layers.len(), 16, "{layers:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The full workshop export (issue 43): a net cut and mirrored, unrolled with stations and split at
/// `max_length`, written with outlines, labels, folds with their angles and marks. ezdxf audits it
/// clean and finds every entity on its layer: `CUT`, `FOLDS`, `MARKS`, `TEXT`.
#[test]
fn the_full_workshop_export_passes_the_ezdxf_audit_on_its_layers() {
    use cnets_geometry::fabrication::{cut_by_plane, mirror};
    use cnets_geometry::{Plane, PolygonMesh};
    let net = cone_net(6, 12, false);
    let plane = Plane::from_normal(DVec3::new(6.3, 0.0, 0.0), DVec3::new(1.0, 0.3, 0.1)).unwrap();
    let half = cut_by_plane(&PolygonMesh::from(&net.mesh), &plane, false)
        .unwrap()
        .mesh;
    let whole = mirror(&half, &plane, 1e-9).unwrap();
    let station = Plane::from_normal(DVec3::new(3.0, 0.0, 0.0), DVec3::X).unwrap();
    let unrolled = run(
        &NodeContext::default(),
        "pq.unroll_strips",
        &[
            ("mesh", Value::Mesh(std::sync::Arc::new(whole))),
            ("stations", Value::list(vec![Value::Plane(station.into())])),
            ("max_length", Value::Number(4.0)),
        ],
    )
    .unwrap();
    let dir = scratch("dxf-workshop");
    let ctx = ctx_in(&dir);
    let mut inputs = vec![("name", Value::text("workshop"))];
    for (port, output) in [
        ("outlines", "outlines"),
        ("labels", "labels"),
        ("label_points", "label_points"),
        ("folds", "folds"),
        ("fold_angles", "fold_angles"),
        ("marks", "marks"),
        ("mark_labels", "mark_labels"),
    ] {
        inputs.push((port, get(&unrolled, output).clone()));
    }
    let out = run(&ctx, "io.export_dxf", &inputs).unwrap();
    let r = ezdxf_report(&out);
    assert_eq!(r["audit_errors"], 0, "ezdxf audit found errors");
    assert_eq!(
        r["audit_fixes"], 0,
        "ezdxf audit repaired something: {}",
        r["audit_messages"]
    );
    let layers: Vec<&str> = r["layers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l.as_str().unwrap())
        .collect();
    for layer in ["CUT", "FOLDS", "MARKS", "TEXT"] {
        assert!(layers.contains(&layer), "no layer {layer}: {layers:?}");
    }
    let on = |kind: &str, layer: &str| -> Vec<serde_json::Value> {
        r[kind]
            .as_array()
            .unwrap()
            .iter()
            .filter(|e| e["layer"] == layer)
            .cloned()
            .collect()
    };
    let outlines = polylines(get(&unrolled, "outlines"));
    let folds = polylines(get(&unrolled, "folds"));
    let marks = polylines(get(&unrolled, "marks"));
    assert!(!folds.is_empty() && !marks.is_empty());
    let cut = on("lwpolylines", "CUT");
    assert_eq!(cut.len(), outlines.len());
    assert!(cut.iter().all(|c| c["closed"] == true));
    assert_eq!(on("lwpolylines", "FOLDS").len(), folds.len());
    assert_eq!(on("lwpolylines", "MARKS").len(), marks.len());
    // Every fold's angle as text on FOLDS, in order; the labels on TEXT; the mark labels on MARKS.
    let angles: Vec<String> = get(&unrolled, "fold_angles")
        .as_list()
        .unwrap()
        .iter()
        .map(|a| format!("{:+.2}", a.as_f64().unwrap()))
        .collect();
    let written: Vec<String> = on("texts", "FOLDS")
        .iter()
        .map(|t| t["text"].as_str().unwrap().to_string())
        .collect();
    assert_eq!(written, angles);
    let labels = texts(get(&unrolled, "labels"));
    assert!(
        labels
            .iter()
            .any(|l| l.ends_with(".2") || l.contains(".2 "))
    );
    let on_text: Vec<String> = on("texts", "TEXT")
        .iter()
        .map(|t| t["text"].as_str().unwrap().to_string())
        .collect();
    assert_eq!(on_text, labels);
    let mark_texts: Vec<String> = on("texts", "MARKS")
        .iter()
        .map(|t| t["text"].as_str().unwrap().to_string())
        .collect();
    assert_eq!(mark_texts, texts(get(&unrolled, "mark_labels")));
    // Coordinates in mm: the first fold line at 1000 × its model coordinates.
    let f0 = &on("lwpolylines", "FOLDS")[0]["points"];
    assert!((f0[0][0].as_f64().unwrap() - 1000.0 * folds[0].points[0].x).abs() < 1e-6);
}

/// Whether `p` is inside the closed polygon `poly` (even–odd rule).
fn inside(p: [f64; 2], poly: &[[f64; 2]]) -> bool {
    let mut odd = false;
    for k in 0..poly.len() {
        let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
        if (a[1] > p[1]) != (b[1] > p[1])
            && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
        {
            odd = !odd;
        }
    }
    odd
}

fn points_of(poly: &serde_json::Value) -> Vec<[f64; 2]> {
    poly["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| [p[0].as_f64().unwrap(), p[1].as_f64().unwrap()])
        .collect()
}

#[test]
fn nested_workshop_sheets_are_one_block_each_with_their_folds_and_marks() {
    let net = cone_net(4, 14, false);
    let station = cnets_geometry::Plane::from_normal(DVec3::new(5.0, 0.0, 0.0), DVec3::X).unwrap();
    let ctx = NodeContext::default();
    let unrolled = run(
        &ctx,
        "pq.unroll_strips",
        &[
            ("mesh", net.mesh.clone().into()),
            ("stations", Value::list(vec![Value::Plane(station.into())])),
        ],
    )
    .unwrap();
    // Sheets a little longer than the longest strip and too low for two strips: one strip a sheet.
    let (mut long, mut high) = (0.0f64, 0.0f64);
    for o in polylines(get(&unrolled, "outlines")) {
        let (lo, hi) = cnets_geometry::quad_grid::bounds_of(&o.points).unwrap();
        long = long.max(hi.x - lo.x);
        high = high.max(hi.y - lo.y);
    }
    let nested = run(
        &ctx,
        "fab.nest",
        &[
            ("outlines", get(&unrolled, "outlines").clone()),
            ("labels", get(&unrolled, "labels").clone()),
            ("sheet_width", Value::Number(1.05 * long)),
            ("sheet_height", Value::Number(1.3 * high)),
            ("folds", get(&unrolled, "folds").clone()),
            ("marks", get(&unrolled, "marks").clone()),
        ],
    )
    .unwrap();
    let sheets: Vec<i64> = get(&nested, "sheets")
        .as_list()
        .unwrap()
        .iter()
        .map(|s| match s {
            Value::Integer(s) => *s,
            other => panic!("a sheet index, got {other:?}"),
        })
        .collect();
    let sheet_count = *sheets.iter().max().unwrap() as usize + 1;
    assert!(sheet_count >= 2, "{sheets:?}");
    // The folds and marks moved with their strips: same lengths, each inside a placed outline.
    let (before, after) = (
        polylines(get(&unrolled, "folds")),
        polylines(get(&nested, "folds")),
    );
    assert_eq!(before.len(), after.len());
    for (a, b) in before.iter().zip(&after) {
        let (la, lb) = (a.length(), b.length());
        assert!((la - lb).abs() <= 1e-12 * la, "{la} vs {lb}");
    }
    let dir = scratch("dxf-nested-workshop");
    let mut inputs = vec![
        ("name", Value::text("sheets")),
        ("sheets", get(&nested, "sheets").clone()),
        ("fold_angles", get(&unrolled, "fold_angles").clone()),
        ("mark_labels", get(&unrolled, "mark_labels").clone()),
    ];
    for port in ["outlines", "labels", "label_points", "folds", "marks"] {
        inputs.push((port, get(&nested, port).clone()));
    }
    let out = run(&ctx_in(&dir), "io.export_dxf", &inputs).unwrap();
    let r = ezdxf_report(&out);
    assert_eq!(r["audit_errors"], 0, "ezdxf audit found errors");
    assert_eq!(
        r["audit_fixes"], 0,
        "ezdxf repaired: {}",
        r["audit_messages"]
    );
    let blocks = r["blocks"].as_array().unwrap();
    let names: Vec<String> = blocks
        .iter()
        .map(|b| b["name"].as_str().unwrap().to_string())
        .collect();
    let expected: Vec<String> = (1..=sheet_count).map(|s| format!("SHEET_{s}")).collect();
    assert_eq!(names, expected);
    let inserts = r["inserts"].as_array().unwrap();
    assert_eq!(inserts.len(), sheet_count);
    let labels = texts(get(&nested, "labels"));
    let (mut folds_seen, mut marks_seen) = (0, 0);
    for (s, (block, insert)) in blocks.iter().zip(inserts).enumerate() {
        assert_eq!(insert["name"], block["name"]);
        assert_eq!(insert["insert"], block["base"], "inserted at its own place");
        let on = |kind: &str, layer: &str| -> Vec<serde_json::Value> {
            block[kind]
                .as_array()
                .unwrap()
                .iter()
                .filter(|e| e["layer"] == layer)
                .cloned()
                .collect()
        };
        // This sheet's outlines, closed on CUT, with their labels on TEXT.
        let here: Vec<String> = labels
            .iter()
            .zip(&sheets)
            .filter(|(_, sh)| **sh == s as i64)
            .map(|(l, _)| l.clone())
            .collect();
        let cut = on("lwpolylines", "CUT");
        assert_eq!(cut.len(), here.len(), "SHEET_{}", s + 1);
        assert!(cut.iter().all(|c| c["closed"] == true));
        let text: Vec<String> = on("texts", "TEXT")
            .iter()
            .map(|t| t["text"].as_str().unwrap().to_string())
            .collect();
        assert_eq!(text, here);
        // Every fold and mark of the block lies on one of the block's outlines, with its text.
        let outlines: Vec<Vec<[f64; 2]>> = cut.iter().map(points_of).collect();
        for (layer, seen) in [("FOLDS", &mut folds_seen), ("MARKS", &mut marks_seen)] {
            let lines = on("lwpolylines", layer);
            assert_eq!(on("texts", layer).len(), lines.len(), "{layer}");
            for line in &lines {
                let p = points_of(line);
                let m = p.len().saturating_sub(1) / 2;
                let mid = [(p[m][0] + p[m + 1][0]) / 2.0, (p[m][1] + p[m + 1][1]) / 2.0];
                // Folds are rungs inside their strip, marks ticks and station lines inside it.
                assert!(
                    outlines.iter().any(|o| inside(mid, o)),
                    "{layer} line at {mid:?} on no outline of SHEET_{}",
                    s + 1
                );
            }
            *seen += lines.len();
        }
    }
    assert_eq!(folds_seen, after.len());
    assert_eq!(marks_seen, polylines(get(&nested, "marks")).len());
    std::fs::remove_dir_all(&dir).unwrap();
}
