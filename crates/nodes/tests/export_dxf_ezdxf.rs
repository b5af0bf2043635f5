//! DXF export: the file is read back by the independent Python reader `ezdxf` (scripts/read-dxf.py)
//! and by the `dxf` crate, and compared with what was written: version R2000, millimetres, one
//! layer per strip holding a closed LWPOLYLINE and its label.

mod fab_support;

use cnets_engine::{NodeContext, Value};
use cnets_geometry::Polyline;
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
    let names: Vec<String> = labels
        .as_list()
        .unwrap()
        .iter()
        .map(|l| match l {
            Value::Text(t) => t.to_string(),
            _ => panic!("text"),
        })
        .collect();

    let report = run_checker("python3", "scripts/read-dxf.py", &path);
    let r: serde_json::Value = serde_json::from_str(&report).expect("ezdxf report is JSON");
    assert_eq!(
        r["dxfversion"], "AC1015",
        "R2000 or later, or LWPOLYLINE is dropped"
    );
    assert_eq!(r["insunits"], 4, "millimetres");
    assert_eq!(r["audit_errors"], 0, "ezdxf audit found errors");
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
    let Value::Text(path) = get(&out, "path") else {
        panic!("path")
    };
    let report = run_checker(
        "python3",
        "scripts/read-dxf.py",
        std::path::Path::new(path.as_ref()),
    );
    let r: serde_json::Value = serde_json::from_str(&report).unwrap();
    assert_eq!(r["lwpolylines"][1]["layer"], "STRIP_1");
    assert!(r["texts"].as_array().unwrap().is_empty());
    let first = &polylines(&outlines)[0].points[2];
    assert!((r["lwpolylines"][0]["points"][2][0].as_f64().unwrap() - first.x * 10.0).abs() < 1e-9);
    std::fs::remove_dir_all(&dir).unwrap();
}
