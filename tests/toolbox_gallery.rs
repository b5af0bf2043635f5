//! The gallery graph built as a Grasshopper user builds it (graphs/grasshopper-style.ron): what its
//! description claims, measured.

use cnets_engine::{NodeContext, Value};
use cnets_tests::{Evaluated, load};

fn text(v: &Value) -> String {
    match v {
        Value::Text(t) => t.to_string(),
        other => panic!("text, got {}", other.type_name()),
    }
}

#[test]
fn ratios_come_from_an_expression_over_a_cross_reference() {
    let e = Evaluated::new(load("grasshopper-style"));
    let rows = e.number("rows", "value") as usize;
    let columns = e.number("columns", "value") as usize;
    let amplitude = e.number("amplitude", "value");
    let table = e.output("ratio_table", "chunks").as_list().unwrap();
    assert_eq!(table.len(), rows, "one row of ratios per generatrix point");
    for (i, row) in table.iter().enumerate() {
        let row = row.as_list().unwrap();
        assert_eq!(row.len(), columns - 1, "one ratio per directrix edge");
        for (j, r) in row.iter().enumerate() {
            let (x, y) = (i as f64, j as f64);
            let expected = 0.5
                + amplitude
                    * (std::f64::consts::PI * x / 8.0).sin()
                    * (std::f64::consts::PI * y / 6.0).cos();
            assert!(
                (r.as_f64().unwrap() - expected).abs() < 1e-15,
                "ratio ({i}, {j})"
            );
        }
    }
    let Value::QuadMesh(net) = e.output("net", "mesh") else {
        panic!("a cone-net")
    };
    assert_eq!((net.rows, net.cols), (rows, columns));
    // The panels read what they are wired to.
    let quality = text(e.output("quality_panel", "text"));
    assert!(quality.starts_with("max_planarity: "), "{quality}");
    let planarity: f64 = quality.lines().next().unwrap()["max_planarity: ".len()..]
        .parse()
        .unwrap();
    assert!(planarity < 1e-12 * net.size(), "{planarity}");
    let ratios = text(e.output("ratio_panel", "text"));
    assert_eq!(
        ratios.lines().filter(|l| l.starts_with('{')).count(),
        rows,
        "one branch per row"
    );
}

#[test]
fn the_value_list_switches_the_mapper_kind() {
    let mut doc = load("grasshopper-style");
    let ctx = NodeContext::default();
    let mut ev = cnets_engine::Evaluator::new();
    ev.evaluate_all(&doc.graph, &ctx);
    let before = ev.output(&doc.graph, "apex", "apex").unwrap().clone();
    assert_eq!(
        ev.output(&doc.graph, "widths", "y")
            .unwrap()
            .as_list()
            .unwrap()
            .len(),
        13
    );
    doc.graph
        .set_value("mapper_kind", "index", Value::Integer(2))
        .unwrap();
    ev.evaluate_all(&doc.graph, &ctx);
    assert_eq!(
        ev.output(&doc.graph, "mapper_kind", "value"),
        Some(&Value::text("sine"))
    );
    let after = ev.output(&doc.graph, "apex", "apex").unwrap();
    assert_ne!(
        &before, after,
        "another mapper kind gives another apex function"
    );
    assert!(
        ev.output(&doc.graph, "net", "mesh").is_some(),
        "and the net still builds"
    );
}
