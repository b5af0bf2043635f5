//! SVG export: the file is parsed as XML (roxmltree) and its paths and labels compared with the
//! outlines that were written (millimetres, y flipped, 5 mm margin).

use crate::fab_support;

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

/// Writes `outlines` (squares of side `side` metres) to SVG, optionally with sheets; returns the text.
fn squares_svg(side: f64, count: usize, sheets: Option<Vec<i64>>) -> String {
    let outlines: Vec<Value> = (0..count)
        .map(|k| {
            let x = k as f64 * side * 2.0;
            Value::from(Polyline::closed(vec![
                DVec3::new(x, 0.0, 0.0),
                DVec3::new(x + side, 0.0, 0.0),
                DVec3::new(x + side, side, 0.0),
                DVec3::new(x, side, 0.0),
            ]))
        })
        .collect();
    let labels = Value::list((0..count).map(|k| Value::text(format!("S{k}"))).collect());
    let dir = scratch("svg-scaled");
    let mut named = vec![("outlines", Value::list(outlines)), ("labels", labels)];
    if let Some(s) = sheets {
        named.push((
            "sheets",
            Value::list(s.into_iter().map(Value::Integer).collect()),
        ));
    }
    let out = run(&ctx_in(&dir), "io.export_svg", &named).unwrap();
    let Value::Text(path) = get(&out, "path") else {
        panic!("path")
    };
    let text = std::fs::read_to_string(path.as_ref()).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    text
}

#[test]
fn strokes_and_labels_scale_with_the_drawing_and_sheets_are_layers() {
    let attr = |text: &str, tag: &str, name: &str| -> f64 {
        let doc = roxmltree::Document::parse(text).unwrap();
        doc.descendants()
            .find(|n| n.has_tag_name(tag))
            .and_then(|n| n.attribute(name))
            .unwrap()
            .parse()
            .unwrap()
    };
    // 1 cm squares: a small drawing keeps the 0.1 mm hairline; 10 m squares: far larger strokes and
    // labels, still 1:1 in mm (the viewBox width equals the width in mm).
    let small = squares_svg(0.01, 3, None);
    let large = squares_svg(10.0, 3, None);
    assert_eq!(attr(&small, "path", "stroke-width"), 0.1);
    let (s_stroke, l_stroke) = (
        attr(&small, "path", "stroke-width"),
        attr(&large, "path", "stroke-width"),
    );
    assert!(l_stroke > 10.0 * s_stroke, "{s_stroke} → {l_stroke}");
    let (s_font, l_font) = (
        attr(&small, "text", "font-size"),
        attr(&large, "text", "font-size"),
    );
    assert!(l_font > 10.0 * s_font, "{s_font} → {l_font}");
    let doc = roxmltree::Document::parse(&large).unwrap();
    let svg = doc.root_element();
    let width = svg.attribute("width").unwrap();
    let view: Vec<&str> = svg
        .attribute("viewBox")
        .unwrap()
        .split_whitespace()
        .collect();
    assert_eq!(format!("{}mm", view[2]), width);
    // Sheets: one Inkscape layer per sheet, each holding its outlines.
    let nested = squares_svg(1.0, 4, Some(vec![1, 0, 1, 0]));
    let doc = roxmltree::Document::parse(&nested).unwrap();
    let layers: Vec<_> = doc
        .descendants()
        .filter(|n| {
            n.attribute(("http://www.inkscape.org/namespaces/inkscape", "groupmode"))
                == Some("layer")
        })
        .collect();
    assert_eq!(layers.len(), 2);
    for (s, layer) in layers.iter().enumerate() {
        assert_eq!(layer.attribute("id"), Some(format!("sheet-{s}").as_str()));
        let strips: Vec<_> = layer
            .children()
            .filter(|n| n.has_tag_name("g"))
            .filter_map(|n| n.attribute("id"))
            .collect();
        let expected: Vec<String> = (0..4)
            .filter(|k| (k + 1) % 2 == s)
            .map(|k| format!("strip-{k}"))
            .collect();
        assert_eq!(strips, expected);
    }
}
