//! SVG export: the file is parsed as XML (roxmltree) and its paths and labels compared with the
//! outlines that were written (millimetres, y flipped, 5 mm margin).

mod fab_support;

use cnets_engine::{NodeContext, Value};
use cnets_geometry::{DVec3, Polyline};
use fab_support::*;

fn parse_path(d: &str) -> (Vec<(f64, f64)>, bool) {
    let mut pts = Vec::new();
    let tokens: Vec<&str> = d.split_whitespace().collect();
    let mut k = 0;
    let mut closed = false;
    while k < tokens.len() {
        let t = tokens[k];
        if t == "Z" {
            closed = true;
            k += 1;
            continue;
        }
        let x: f64 = t.trim_start_matches(['M', 'L']).parse().unwrap();
        let y: f64 = tokens[k + 1].parse().unwrap();
        pts.push((x, y));
        k += 2;
    }
    (pts, closed)
}

#[test]
fn paths_and_labels_read_back_in_millimetres() {
    let net = cone_net(4, 6, false);
    let out = run(
        &NodeContext::default(),
        "pq.unroll_strips",
        &[("mesh", net.mesh.into())],
    )
    .unwrap();
    let outlines: Vec<Polyline> = get(&out, "outlines")
        .as_list()
        .unwrap()
        .iter()
        .map(|p| match p {
            Value::Polyline(p) => (**p).clone(),
            _ => panic!("polyline"),
        })
        .collect();
    let dir = scratch("svg");
    let ctx = ctx_in(&dir);
    let labels = Value::list(vec![
        Value::text("D0 <&>"),
        Value::text("D1"),
        Value::text("D2"),
    ]);
    let out = run(
        &ctx,
        "io.export_svg",
        &[
            ("outlines", get(&out, "outlines").clone()),
            ("labels", labels),
            ("label_points", get(&out, "label_points").clone()),
        ],
    )
    .unwrap();
    let Value::Text(path) = get(&out, "path") else {
        panic!("path")
    };
    assert!(path.ends_with("strips.svg"));
    let text = std::fs::read_to_string(path.as_ref()).unwrap();
    let doc = roxmltree::Document::parse(&text).expect("well-formed XML");
    let svg = doc.root_element();
    assert_eq!(svg.tag_name().name(), "svg");
    assert_eq!(
        svg.tag_name().namespace(),
        Some("http://www.w3.org/2000/svg")
    );
    let width = svg.attribute("width").unwrap();
    assert!(width.ends_with("mm"));
    let view: Vec<f64> = svg
        .attribute("viewBox")
        .unwrap()
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    assert_eq!(
        format!("{}mm", view[2]),
        width,
        "one user unit is one millimetre"
    );
    // Bounds of all outlines in mm (the SVG maps x → x − min x + 5, y → max y − y + 5).
    let all: Vec<DVec3> = outlines.iter().flat_map(|o| o.points.clone()).collect();
    let (lo, hi) = cnets_geometry::quad_grid::bounds_of(&all).unwrap();
    let (lo, hi) = (lo * 1000.0, hi * 1000.0);
    assert!((view[2] - (hi.x - lo.x + 10.0)).abs() < 1e-3);
    let paths: Vec<_> = svg
        .descendants()
        .filter(|n| n.has_tag_name("path"))
        .collect();
    assert_eq!(paths.len(), outlines.len());
    for (node, outline) in paths.iter().zip(&outlines) {
        let (pts, closed) = parse_path(node.attribute("d").unwrap());
        assert!(closed);
        assert_eq!(pts.len(), outline.points.len());
        for ((x, y), p) in pts.iter().zip(&outline.points) {
            let (mx, my) = (x - 5.0 + lo.x, hi.y - (y - 5.0));
            assert!((mx - p.x * 1000.0).abs() < 1e-3 && (my - p.y * 1000.0).abs() < 1e-3);
        }
        assert_eq!(node.attribute("fill"), Some("none"));
    }
    let texts: Vec<String> = svg
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|n| n.text().unwrap().to_string())
        .collect();
    assert_eq!(texts, ["D0 <&>", "D1", "D2"]);
    std::fs::remove_dir_all(&dir).unwrap();
}
