//! The editor's named construction planes in a graph file: optional, round-tripped exactly,
//! checked with positions.

use crate::common;

use cnets_engine::file::{NamedPlane, load_str, to_ron};

const PLAIN: &str = r#"(
    version: 1,
    nodes: {
        "x": (
            type: "t.num",
            position: (0.0, 0.0),
        ),
    },
    edges: [
    ],
)
"#;

const WITH_PLANES: &str = r#"(
    version: 1,
    cplanes: [
        (name: "CPlane 1", origin: (1.0, 0.0, 2.0), u: (0.6, 0.0, 0.8), v: (0.0, 1.0, 0.0)),
        (name: "a \"tilted\" one", origin: (0.1, 0.2, 0.30000000000000004), u: (0.7071067811865475, 0.7071067811865476, 0.0), v: (-0.0, 0.0, 1.0)),
    ],
    nodes: {
        "x": (
            type: "t.num",
            position: (0.0, 0.0),
        ),
    },
    edges: [
    ],
)
"#;

#[test]
fn files_without_cplanes_load_as_before_and_write_none() {
    let doc = load_str(PLAIN, "plain.ron", &common::registry()).unwrap();
    assert!(doc.meta.cplanes.is_empty());
    assert_eq!(to_ron(&doc.graph, &doc.meta), PLAIN);
}

#[test]
fn cplanes_round_trip_bit_for_bit() {
    let doc = load_str(WITH_PLANES, "planes.ron", &common::registry()).unwrap();
    assert_eq!(
        doc.meta.cplanes[0],
        NamedPlane {
            name: "CPlane 1".into(),
            origin: [1.0, 0.0, 2.0],
            u: [0.6, 0.0, 0.8],
            v: [0.0, 1.0, 0.0],
        }
    );
    assert_eq!(doc.meta.cplanes[1].name, "a \"tilted\" one");
    assert_eq!(doc.meta.cplanes[1].origin[2], 0.1 + 0.2);
    let text = to_ron(&doc.graph, &doc.meta);
    assert_eq!(text, WITH_PLANES);
    let again = load_str(&text, "again.ron", &common::registry()).unwrap();
    assert_eq!(again.meta.cplanes, doc.meta.cplanes);
    // Standard RON too.
    let parsed: Result<ron::Value, _> = ron::from_str(&text);
    assert!(parsed.is_ok(), "{parsed:?}");
    // Integers are numbers.
    let ints = WITH_PLANES.replace("origin: (1.0, 0.0, 2.0)", "origin: (1, 0, 2)");
    let doc = load_str(&ints, "ints.ron", &common::registry()).unwrap();
    assert_eq!(doc.meta.cplanes[0].origin, [1.0, 0.0, 2.0]);
}

#[test]
fn a_bad_cplane_is_a_diagnostic_at_its_place() {
    for (from, to, says) in [
        ("u: (0.6, 0.0, 0.8)", "u: (0.0, 1.0, 0.0)", "not parallel"),
        (
            "u: (0.6, 0.0, 0.8)",
            "u: (0.6, 0.0)",
            "three finite numbers",
        ),
        ("name: \"CPlane 1\", ", "", "missing field 'name'"),
        (
            "name: \"CPlane 1\"",
            "title: \"CPlane 1\"",
            "unknown field 'title'",
        ),
    ] {
        let bad = WITH_PLANES.replace(from, to);
        let text = load_str(&bad, "bad.ron", &common::registry())
            .unwrap_err()
            .to_string();
        assert!(text.contains(says) && text.contains("bad.ron:4:"), "{text}");
    }
    let bad = WITH_PLANES.replace("cplanes: [", "cplanes: 3, x: [");
    assert!(load_str(&bad, "bad.ron", &common::registry()).is_err());
}
