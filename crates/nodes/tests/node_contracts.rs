//! The node ids and port names of issue 4 are contracts used from outside (`cnets eval`, graph
//! files): every one is registered with exactly these inputs and outputs, in this order.

fn ports(id: &str) -> (Vec<String>, Vec<String>) {
    let registry = cnets_nodes::registry();
    let def = registry
        .get(id)
        .unwrap_or_else(|| panic!("{id} is registered"));
    (
        def.inputs.iter().map(|p| p.name.to_string()).collect(),
        def.outputs.iter().map(|p| p.name.to_string()).collect(),
    )
}

#[test]
fn every_input_node_has_its_documented_ports() {
    let table: &[(&str, &[&str], &[&str])] = &[
        ("param.number", &["value", "min", "max", "step"], &["value"]),
        ("param.integer", &["value", "min", "max"], &["value"]),
        ("param.boolean", &["value"], &["value"]),
        ("param.point", &["value"], &["value"]),
        ("param.vector", &["value"], &["value"]),
        ("param.text", &["value"], &["value"]),
        ("param.series", &["start", "step", "count"], &["values"]),
        ("param.range", &["start", "end", "count"], &["values"]),
        ("param.list", &["values", "item_type"], &["values"]),
        ("vector.point", &["x", "y", "z"], &["point"]),
        ("vector.vector", &["x", "y", "z"], &["vector"]),
        ("vector.deconstruct", &["point"], &["x", "y", "z"]),
        ("vector.plane", &["origin", "normal", "x_axis"], &["plane"]),
        ("math.add", &["a", "b"], &["result"]),
        ("math.subtract", &["a", "b"], &["result"]),
        ("math.multiply", &["a", "b"], &["result"]),
        ("math.divide", &["a", "b"], &["result"]),
        ("math.power", &["base", "exponent"], &["result"]),
        (
            "math.remap",
            &[
                "value",
                "from_start",
                "from_end",
                "to_start",
                "to_end",
                "clamp",
            ],
            &["result"],
        ),
        ("math.min", &["a", "b"], &["result"]),
        ("math.max", &["a", "b"], &["result"]),
        ("math.bounds", &["values"], &["min", "max"]),
        ("math.clamp", &["value", "min", "max"], &["result"]),
        ("curve.polyline", &["points", "closed"], &["curve"]),
        ("curve.line", &["start", "end", "count"], &["curve"]),
        (
            "curve.arc",
            &["centre", "radius", "start", "end", "plane", "count"],
            &["curve"],
        ),
        (
            "curve.circle",
            &["centre", "radius", "plane", "count"],
            &["curve"],
        ),
        (
            "curve.polygon",
            &["centre", "radius", "sides", "plane", "rotation"],
            &["curve"],
        ),
        (
            "curve.helix",
            &[
                "centre",
                "plane",
                "radius",
                "end_radius",
                "pitch",
                "turns",
                "count",
            ],
            &["curve"],
        ),
        (
            "curve.spline",
            &["points", "closed", "count", "method"],
            &["curve"],
        ),
        (
            "curve.resample",
            &["curve", "count", "length", "chords"],
            &["curve"],
        ),
        (
            "curve.subdivide",
            &["curve", "levels", "scheme"],
            &["curve"],
        ),
        (
            "curve.transform",
            &[
                "curve",
                "translation",
                "angle",
                "axis",
                "centre",
                "scale",
                "mirror",
            ],
            &["curve"],
        ),
        ("curve.reverse", &["curve"], &["curve"]),
        ("curve.join", &["curves", "tolerance"], &["curves"]),
        ("curve.length", &["curve"], &["length"]),
        ("curve.points", &["curve"], &["points", "closed", "count"]),
        (
            "io.read_polylines",
            &["path", "format", "segments"],
            &["curves"],
        ),
        (
            "mapper.graph",
            &[
                "kind", "handles", "x_start", "x_end", "y_start", "y_end", "count", "values",
            ],
            &["y", "x"],
        ),
        ("list.item", &["list", "index", "wrap"], &["item"]),
        ("list.length", &["list"], &["length"]),
        ("list.reverse", &["list"], &["list"]),
        ("list.repeat", &["value", "count"], &["list"]),
        ("list.slice", &["list", "start", "end"], &["list"]),
        ("list.flatten", &["tree"], &["list"]),
        ("list.graft", &["list"], &["tree"]),
        ("list.transpose", &["table"], &["table"]),
        (
            "list.table",
            &["rows", "columns", "rule", "centre"],
            &["table"],
        ),
    ];
    for (id, inputs, outputs) in table {
        let (i, o) = ports(id);
        assert_eq!(i, *inputs, "{id} inputs");
        assert_eq!(o, *outputs, "{id} outputs");
    }
}
