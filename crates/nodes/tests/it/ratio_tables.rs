//! Ratio tables for a cone-net come from two mappers: `list.table` builds N × (M−1) from a per-row
//! and a per-column mapper, and `list.transpose` turns it into (M−1) × N and back.

use std::sync::Arc;

use cnets_engine::file::load_str;
use cnets_engine::{Evaluator, NodeContext, Value};

const GRAPH: &str = r#"(
    version: 1,
    nodes: {
        "per_row": (type: "mapper.graph", position: (0.0, 0.0),
            inputs: {"kind": "linear", "handles": [(0.0, 0.4, 0.0), (1.0, 0.6, 0.0)], "count": 4}),
        "per_column": (type: "mapper.graph", position: (0.0, 100.0),
            inputs: {"kind": "sine", "count": 6}),
        "table": (type: "list.table", position: (200.0, 0.0)),
        "flip": (type: "list.transpose", position: (400.0, 0.0)),
        "back": (type: "list.transpose", position: (600.0, 0.0)),
    },
    edges: [
        "per_row.y -> table.rows",
        "per_column.y -> table.columns",
        "table.table -> flip.table",
        "flip.table -> back.table",
    ],
)"#;

fn numbers(v: &Value) -> Vec<f64> {
    v.as_list()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn a_table_from_two_mappers_has_the_right_shape_and_values() {
    let registry = Arc::new(cnets_nodes::registry());
    let doc = load_str(GRAPH, "tables.ron", &registry).unwrap_or_else(|e| panic!("{e:?}"));
    let mut ev = Evaluator::new();
    ev.evaluate_all(&doc.graph, &NodeContext::default());
    let g = &doc.graph;
    let rows = numbers(ev.output(g, "per_row", "y").unwrap());
    let cols = numbers(ev.output(g, "per_column", "y").unwrap());
    let table = ev.output(g, "table", "table").unwrap().as_list().unwrap();
    assert_eq!(table.len(), 4);
    for (i, row) in table.iter().enumerate() {
        let row = numbers(row);
        assert_eq!(row.len(), 6);
        for (j, t) in row.iter().enumerate() {
            assert!((t - (rows[i] + cols[j] - 0.5)).abs() < 1e-15);
        }
    }
    let flipped = ev.output(g, "flip", "table").unwrap().as_list().unwrap();
    assert_eq!(flipped.len(), 6);
    assert_eq!(numbers(&flipped[2]).len(), 4);
    assert_eq!(
        ev.output(g, "back", "table").unwrap(),
        ev.output(g, "table", "table").unwrap()
    );
}
