//! The everyday toolbox of issue 16: ids, ports (names, order, types and defaults) are contracts
//! that outside checks call through `cnets eval` and graph files; and the nested-list rule that
//! makes Grasshopper's grid idiom work (a grafted list times a flat list).

use cnets_engine::eval::evaluate_node;
use cnets_engine::{NodeContext, Value};

type Port<'a> = (&'a str, &'a str, Option<&'a str>);

fn check(id: &str, inputs: &[Port<'_>], outputs: &[(&str, &str)]) {
    let registry = cnets_nodes::registry();
    let def = registry
        .get(id)
        .unwrap_or_else(|| panic!("{id} is registered"));
    let got: Vec<(String, String)> = def
        .inputs
        .iter()
        .map(|p| (p.name.to_string(), p.type_name()))
        .collect();
    let want: Vec<(String, String)> = inputs
        .iter()
        .map(|(n, t, _)| (n.to_string(), t.to_string()))
        .collect();
    assert_eq!(got, want, "{id} inputs");
    for ((name, _, default), port) in inputs.iter().zip(&def.inputs) {
        if let Some(d) = default {
            let shown = port
                .default
                .as_ref()
                .map(cnets_engine::value::json::to_json)
                .map(|j| j.to_string());
            assert_eq!(shown.as_deref(), Some(*d), "{id}.{name} default");
        }
    }
    let got: Vec<(String, String)> = def
        .outputs
        .iter()
        .map(|p| (p.name.to_string(), p.type_name()))
        .collect();
    let want: Vec<(String, String)> = outputs
        .iter()
        .map(|(n, t)| (n.to_string(), t.to_string()))
        .collect();
    assert_eq!(got, want, "{id} outputs");
}

#[test]
fn toolbox_nodes_have_their_contract_ports() {
    check(
        "math.expression",
        &[
            ("expression", "text", None),
            ("x", "number", Some("0.0")),
            ("y", "number", Some("0.0")),
            ("z", "number", Some("0.0")),
        ],
        &[("result", "number")],
    );
    check(
        "math.random",
        &[
            ("count", "integer", Some("10")),
            ("min", "number", Some("0.0")),
            ("max", "number", Some("1.0")),
            ("seed", "integer", Some("0")),
        ],
        &[("values", "list<number>")],
    );
    check(
        "list.sort",
        &[("list", "list<any>", None), ("keys", "list<number>", None)],
        &[("list", "list<any>"), ("indices", "list<integer>")],
    );
    check(
        "list.shift",
        &[
            ("list", "list<any>", None),
            ("offset", "integer", Some("1")),
            ("wrap", "boolean", Some("true")),
        ],
        &[("list", "list<any>")],
    );
    check(
        "list.cull",
        &[
            ("list", "list<any>", None),
            ("pattern", "list<boolean>", None),
        ],
        &[("list", "list<any>")],
    );
    check(
        "list.dispatch",
        &[
            ("list", "list<any>", None),
            ("pattern", "list<boolean>", None),
        ],
        &[("a", "list<any>"), ("b", "list<any>")],
    );
    check(
        "list.weave",
        &[
            ("lists", "tree<any>", None),
            ("pattern", "list<integer>", None),
        ],
        &[("list", "list<any>")],
    );
    check(
        "list.cross_reference",
        &[("a", "list<any>", None), ("b", "list<any>", None)],
        &[("a", "list<any>"), ("b", "list<any>")],
    );
    check(
        "vector.length",
        &[("vector", "vector", None)],
        &[("length", "number")],
    );
    check(
        "vector.unit",
        &[("vector", "vector", None)],
        &[("vector", "vector")],
    );
    check(
        "vector.dot",
        &[("a", "vector", None), ("b", "vector", None)],
        &[("value", "number")],
    );
    check(
        "vector.cross",
        &[("a", "vector", None), ("b", "vector", None)],
        &[("vector", "vector")],
    );
    check(
        "vector.distance",
        &[("a", "point", None), ("b", "point", None)],
        &[("distance", "number")],
    );
    check(
        "vector.add",
        &[("a", "vector", None), ("b", "vector", None)],
        &[("vector", "vector")],
    );
    check(
        "vector.scale",
        &[("vector", "vector", None), ("factor", "number", None)],
        &[("vector", "vector")],
    );
    check(
        "vector.angle",
        &[("a", "vector", None), ("b", "vector", None)],
        &[("degrees", "number")],
    );
    check(
        "curve.evaluate",
        &[("curve", "polyline", None), ("t", "number", None)],
        &[("point", "point"), ("tangent", "vector")],
    );
    check(
        "curve.closest_point",
        &[("curve", "polyline", None), ("point", "point", None)],
        &[("point", "point"), ("t", "number"), ("distance", "number")],
    );
    check(
        "curve.offset",
        &[
            ("curve", "polyline", None),
            ("distance", "number", None),
            ("plane", "plane", None),
        ],
        &[("curve", "polyline")],
    );
    check(
        "io.read_mesh",
        &[
            ("path", "text", None),
            ("format", "text", Some("\"auto\"")),
            ("weld", "number", None),
        ],
        &[("mesh", "mesh"), ("meshes", "list<mesh>")],
    );
    check(
        "mesh.closest_point",
        &[("mesh", "mesh", None), ("points", "list<point>", None)],
        &[
            ("points", "list<point>"),
            ("distances", "list<number>"),
            ("faces", "list<integer>"),
        ],
    );
    // Issue 32 added `samples` and the two-way outputs after `value` and `max`, which keep their
    // meaning (mesh vertices → reference).
    check(
        "measure.surface_distance",
        &[
            ("mesh", "mesh", None),
            ("reference", "mesh", None),
            ("samples", "integer", Some("2")),
        ],
        &[
            ("value", "number"),
            ("max", "number"),
            ("symmetric", "number"),
            ("hausdorff", "number"),
            ("to_reference", "number"),
            ("to_reference_max", "number"),
            ("from_reference", "number"),
            ("from_reference_max", "number"),
        ],
    );
    check(
        "mesh.deconstruct",
        &[("mesh", "mesh", None)],
        &[("vertices", "list<point>"), ("faces", "tree<integer>")],
    );
    check(
        "mesh.construct",
        &[
            ("vertices", "list<point>", None),
            ("faces", "tree<integer>", None),
        ],
        &[("mesh", "mesh")],
    );
    check(
        "view.panel",
        &[("value", "tree<any>", None)],
        &[("text", "text")],
    );
    check(
        "param.choice",
        &[
            ("options", "list<text>", None),
            ("index", "integer", Some("0")),
        ],
        &[("value", "text"), ("index", "integer")],
    );
    check(
        "io.read_polylines",
        &[
            ("path", "text", None),
            ("format", "text", None),
            ("segments", "integer", None),
        ],
        &[("curves", "list<polyline>")],
    );
}

#[test]
fn the_contract_examples_hold() {
    let registry = cnets_nodes::registry();
    let run = |id: &str, inputs: Vec<Value>| {
        let def = registry.get(id).unwrap();
        evaluate_node(def, &NodeContext::default(), &inputs).map(|o| o.values)
    };
    let n = |x: f64| Value::Number(x);
    let nums = |xs: &[f64]| Value::list(xs.iter().map(|&x| n(x)).collect());
    let v = run(
        "math.expression",
        vec![Value::text("sin(pi*x)^2 + y/4"), n(0.5), n(2.0), n(0.0)],
    )
    .unwrap();
    assert!((v[0].as_f64().unwrap() - 1.5).abs() < 1e-15);
    let v = run(
        "list.shift",
        vec![
            nums(&[1.0, 2.0, 3.0, 4.0]),
            Value::Integer(1),
            Value::Boolean(true),
        ],
    )
    .unwrap();
    assert_eq!(v[0], nums(&[2.0, 3.0, 4.0, 1.0]));
    let v = run(
        "list.shift",
        vec![
            nums(&[1.0, 2.0, 3.0, 4.0]),
            Value::Integer(1),
            Value::Boolean(false),
        ],
    )
    .unwrap();
    assert_eq!(v[0], nums(&[2.0, 3.0, 4.0]));
    let pattern = Value::list(vec![Value::Boolean(true), Value::Boolean(false)]);
    let v = run(
        "list.cull",
        vec![nums(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]), pattern],
    )
    .unwrap();
    assert_eq!(v[0], nums(&[1.0, 3.0, 5.0]));
    let lists = Value::list(vec![nums(&[1.0, 2.0, 3.0]), nums(&[10.0, 20.0, 30.0])]);
    let v = run(
        "list.weave",
        vec![
            lists,
            Value::list(vec![Value::Integer(0), Value::Integer(1)]),
        ],
    )
    .unwrap();
    assert_eq!(v[0], nums(&[1.0, 10.0, 2.0, 20.0, 3.0, 30.0]));
    let v = run(
        "list.cross_reference",
        vec![nums(&[1.0, 2.0]), nums(&[10.0, 20.0, 30.0])],
    )
    .unwrap();
    assert_eq!(
        v,
        vec![
            nums(&[1.0, 1.0, 1.0, 2.0, 2.0, 2.0]),
            nums(&[10.0, 20.0, 30.0, 10.0, 20.0, 30.0])
        ]
    );
}

/// `math.multiply` with `a` = graft of [r0 … r8] and `b` = [c0 … c12] gives 9 lists of 13 values
/// r_i · c_j — through a real graph with `list.graft`.
#[test]
fn a_grafted_list_times_a_flat_list_is_a_table() {
    use std::sync::Arc;
    let mut g = cnets_engine::Graph::new(Arc::new(cnets_nodes::registry()));
    let rows: Vec<f64> = (0..9).map(|i| 0.4 + 0.01 * i as f64).collect();
    let cols: Vec<f64> = (0..13).map(|j| 1.0 + 0.02 * j as f64).collect();
    let list = |xs: &[f64]| Value::list(xs.iter().map(|&x| Value::Number(x)).collect());
    g.add_node("rows", "param.list").unwrap();
    g.set_value("rows", "values", list(&rows)).unwrap();
    g.add_node("graft", "list.graft").unwrap();
    g.connect("rows", "values", "graft", "list").unwrap();
    g.add_node("cols", "param.list").unwrap();
    g.set_value("cols", "values", list(&cols)).unwrap();
    g.add_node("mul", "math.multiply").unwrap();
    g.connect("graft", "tree", "mul", "a").unwrap();
    g.connect("cols", "values", "mul", "b").unwrap();
    let mut ev = cnets_engine::Evaluator::new();
    ev.evaluate_all(&g, &NodeContext::default());
    let table = ev.output(&g, "mul", "result").expect("evaluated");
    let outer = table.as_list().unwrap();
    assert_eq!(outer.len(), 9);
    for (i, row) in outer.iter().enumerate() {
        let row = row.as_list().unwrap();
        assert_eq!(row.len(), 13);
        for (j, x) in row.iter().enumerate() {
            assert_eq!(x.as_f64().unwrap(), rows[i] * cols[j]);
        }
    }
    // The panel shows it branch by branch with paths.
    g.add_node("panel", "view.panel").unwrap();
    g.connect("mul", "result", "panel", "value").unwrap();
    ev.evaluate_all(&g, &NodeContext::default());
    let Some(Value::Text(text)) = ev.output(&g, "panel", "text") else {
        panic!("panel text")
    };
    assert!(text.starts_with("{0}\n0  0.4\n"), "{text}");
    assert!(text.contains("\n{8}\n"), "{text}");
}
