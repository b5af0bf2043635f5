//! Every loading problem is reported with file, line and column; loading never panics.

use crate::common;

use cnets_engine::file::load_str;

fn errors(text: &str) -> Vec<String> {
    match load_str(text, "g.ron", &common::registry()) {
        Ok(_) => Vec::new(),
        Err(e) => e.diagnostics.iter().map(|d| d.to_string()).collect(),
    }
}

#[test]
fn syntax_errors_have_a_location() {
    let e = errors("(\n    version: 1,\n    nodes: {\n        \"a\": (type: \"t.num\",\n    },\n)");
    assert_eq!(e.len(), 1);
    assert!(e[0].starts_with("g.ron:5:5: syntax error:"), "{e:?}");
}

#[test]
fn every_semantic_problem_is_reported_with_its_position() {
    let text = r#"(
    version: 1,
    nodes: {
        "a": (type: "t.nmu"),
        "b": (type: "t.add", inputs: {"c": 1.0, "a": "text"}),
        "c": (type: "t.text", colour: 3),
        "d": (type: "t.sign"),
    },
    edges: [
        "a.out -> b.a",
        "c.out -> d.x",
        "b.sum -> ghost.x",
        "nonsense",
        "d.out -> b.b",
        "b.sum -> d.x",
    ],
)"#;
    let e = errors(text);
    let expected = [
        "g.ron:4:21: node 'a': unknown node type 't.nmu' (did you mean 't.num'?)",
        "g.ron:5:39: node 'b' (t.add) has no input 'c'; its inputs are: a, b",
        "g.ron:5:54: input 'b.a' (number): expected a number, found a string",
        "g.ron:6:31: node 'c': unknown field 'colour'; expected type, name, position, inputs, preview, enabled, color",
        "g.ron:11:9: edge 'c.out -> d.x': type mismatch: c.out gives text but d.x takes number",
        "g.ron:12:9: dangling edge 'b.sum -> ghost.x': no node 'ghost'",
        "g.ron:13:9: malformed edge 'nonsense'; expected \"from.output -> to.input\"",
        "g.ron:15:9: edge 'b.sum -> d.x': connecting b.sum -> d.x would create a cycle: d -> b -> d",
    ];
    assert_eq!(e, expected, "{e:#?}");
}

#[test]
fn newer_versions_and_wrong_shapes_are_refused() {
    assert_eq!(
        errors("(version: 2, nodes: {}, edges: [])"),
        ["g.ron:1:11: file version 2 is newer than this cnets supports (1); upgrade cnets"]
    );
    assert_eq!(
        errors("(nodes: {}, edges: [])"),
        ["g.ron:1:1: missing field 'version' (this build writes version 1)"]
    );
    assert!(errors("[1, 2]")[0].contains("a graph file is a struct"));
    assert!(errors("(version: 1, nodes: [], edges: [])")[0].contains("'nodes' must be a map"));
    assert!(
        errors("(version: 1, nodes: {\"a b\": (type: \"t.num\")})")[0].contains("invalid node id")
    );
    assert!(
        errors("(version: 1, nodes: {\"a\": (type: \"t.num\"), \"a\": (type: \"t.num\")})")[0]
            .contains("already exists")
    );
    assert!(
        errors("(version: 1, nodes: {}, edges: [], extra: 1)")[0].contains("unknown field 'extra'")
    );
    assert!(errors("(version: 1, nodes: {}, edges: [])").is_empty());
}
