//! JSON and CSV exports: vertex tables in the runner's JSON encoding, read back and compared exactly.

use crate::fab_support;

use cnets_engine::value::json::{from_json, to_json};
use cnets_engine::{Value, ValueType};
use cnets_geometry::{DVec3, Polyline};
use fab_support::*;

#[test]
fn json_holds_the_runner_encoding_and_decodes_to_the_same_value() {
    let net = cone_net(3, 4, false);
    let dir = scratch("json");
    let value: Value = net.mesh.clone().into();
    let out = run(&ctx_in(&dir), "io.export_json", &[("value", value.clone())]).unwrap();
    let Value::Text(path) = get(&out, "path") else {
        panic!("path")
    };
    assert!(path.ends_with("data.json"));
    let text = std::fs::read_to_string(path.as_ref()).unwrap();
    // The file is the runner's encoding, byte for byte.
    assert_eq!(
        text,
        serde_json::to_string_pretty(&to_json(&value)).unwrap() + "\n"
    );
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(json["rows"], 3);
    assert_eq!(json["vertices"].as_array().unwrap().len(), 12);
    let back = from_json(&json, &ValueType::QuadMesh).unwrap();
    let Value::QuadMesh(g) = back else {
        panic!("quad mesh")
    };
    assert_eq!((g.rows, g.cols), (3, 4));
    // serde_json's default float parser may be off by an ulp, so the coordinates are read with
    // Rust's correctly rounded parser: they round-trip exactly.
    let tail = &text[text.find("\"vertices\"").unwrap() + 10..];
    let numbers: Vec<f64> = tail
        .split(|c: char| !(c.is_ascii_digit() || matches!(c, '-' | '.' | 'e' | 'E' | '+')))
        .filter(|t| !t.is_empty())
        .map(|t| t.parse().unwrap())
        .collect();
    let expected: Vec<f64> = net
        .mesh
        .vertices
        .iter()
        .flat_map(|p| p.to_array())
        .collect();
    assert_eq!(numbers, expected, "coordinates round-trip exactly");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn csv_lists_every_vertex_with_exact_numbers() {
    let net = cone_net(3, 4, false);
    let curve = Polyline::open(vec![
        DVec3::new(0.1, 0.2, 0.3),
        DVec3::new(1.0 / 3.0, -2.5e-9, 7.0),
    ]);
    let dir = scratch("csv");
    let value = Value::list(vec![net.mesh.clone().into(), curve.clone().into()]);
    let out = run(
        &ctx_in(&dir),
        "io.export_csv",
        &[("name", Value::text("tables/v")), ("value", value)],
    )
    .unwrap();
    let Value::Text(path) = get(&out, "path") else {
        panic!("path")
    };
    assert!(path.ends_with("tables/v.csv"));
    let text = std::fs::read_to_string(path.as_ref()).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("item,index,row,col,x,y,z"));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 12 + 2);
    for (k, r) in rows[..12].iter().enumerate() {
        assert_eq!(r[0], "0");
        assert_eq!(r[1], k.to_string());
        assert_eq!(
            (r[2], r[3]),
            ((k / 4).to_string().as_str(), (k % 4).to_string().as_str())
        );
        let p = DVec3::new(
            r[4].parse().unwrap(),
            r[5].parse().unwrap(),
            r[6].parse().unwrap(),
        );
        assert_eq!(p, net.mesh.vertices[k]);
    }
    let last = &rows[13];
    assert_eq!((last[0], last[1], last[2], last[3]), ("1", "1", "", ""));
    let p = DVec3::new(
        last[4].parse().unwrap(),
        last[5].parse().unwrap(),
        last[6].parse().unwrap(),
    );
    assert_eq!(p, curve.points[1]);
    std::fs::remove_dir_all(&dir).unwrap();
}
