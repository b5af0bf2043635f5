//! Random mutations of valid graph files never make the loader panic. CI runs at least 10 000 cases
//! (set `PROPTEST_CASES` to run more).

use crate::common;

use cnets_engine::file::{load_str, to_ron};
use proptest::prelude::*;

const BASE: &str = r#"(
    version: 1,
    name: "fuzz",
    nodes: {
        "x": (type: "t.num", position: (1.0, 2.0), inputs: {"value": 2.5}),
        "s": (type: "t.series", inputs: {"n": 4}, preview: false),
        "sum": (type: "t.sum"),
        "add": (type: "t.add", inputs: {"b": [1.0, 2.0]}, enabled: false),
        "p": (type: "t.poly", inputs: {"curve": (points: [(0, 0, 0), (1, 0, 0)], closed: false)}),
        "m": (type: "t.maybe", inputs: {"p": Some((1.0, 2.0, 3.0))}),
        "t": (type: "t.text", inputs: {"value": "héllo \u{1F600} \"q\""}),
    },
    edges: ["x.out -> add.a", "s.out -> sum.xs", "sum.total -> add.b"],
)"#;

const TOKENS: &[&str] = &[
    "(",
    ")",
    "[",
    "]",
    "{",
    "}",
    ",",
    ":",
    "\"",
    "'",
    "->",
    ".",
    "-",
    "1e999",
    "NaN",
    "inf",
    "None",
    "Some(",
    "r#\"",
    "/*",
    "//",
    "\\u{",
    "0x",
    "version",
    "nodes",
    "edges",
    "type",
    "t.num",
    "\n",
    " ",
    "99999999999999999999",
    "é",
    "\u{0}",
];

#[derive(Debug, Clone)]
enum Mutation {
    Delete(usize, usize),
    Insert(usize, usize),
    Replace(usize, usize, usize),
    Duplicate(usize, usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), 1usize..8).prop_map(|(at, n)| Mutation::Delete(at, n)),
        (any::<usize>(), any::<usize>()).prop_map(|(at, t)| Mutation::Insert(at, t)),
        (any::<usize>(), 1usize..6, any::<usize>())
            .prop_map(|(at, n, t)| Mutation::Replace(at, n, t)),
        (any::<usize>(), 1usize..40).prop_map(|(at, n)| Mutation::Duplicate(at, n)),
    ]
}

fn apply(text: &str, mutations: &[Mutation]) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    for m in mutations {
        let len = chars.len().max(1);
        match *m {
            Mutation::Delete(at, n) => {
                let at = at % len;
                let end = (at + n).min(chars.len());
                chars.drain(at.min(chars.len())..end);
            }
            Mutation::Insert(at, t) => {
                let at = (at % (chars.len() + 1)).min(chars.len());
                let token: Vec<char> = TOKENS[t % TOKENS.len()].chars().collect();
                chars.splice(at..at, token);
            }
            Mutation::Replace(at, n, t) => {
                let at = (at % len).min(chars.len());
                let end = (at + n).min(chars.len());
                let token: Vec<char> = TOKENS[t % TOKENS.len()].chars().collect();
                chars.splice(at..end, token);
            }
            Mutation::Duplicate(at, n) => {
                let at = (at % len).min(chars.len());
                let end = (at + n).min(chars.len());
                let copy: Vec<char> = chars[at..end].to_vec();
                chars.splice(end..end, copy);
            }
        }
    }
    chars.into_iter().collect()
}

fn cases() -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(10_000)
        .max(10_000)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn mutated_graph_files_never_panic(mutations in proptest::collection::vec(mutation(), 1..6)) {
        let registry = common::registry();
        let text = apply(BASE, &mutations);
        match load_str(&text, "fuzz.ron", &registry) {
            Ok(doc) => {
                // Whatever loads must save and load again to the same text.
                let saved = to_ron(&doc.graph, &doc.meta);
                let again = load_str(&saved, "again.ron", &registry).expect("a saved graph loads");
                prop_assert_eq!(to_ron(&again.graph, &again.meta), saved);
            }
            Err(e) => {
                prop_assert!(!e.diagnostics.is_empty());
                for d in &e.diagnostics {
                    prop_assert!(d.file == "fuzz.ron");
                    prop_assert!(!d.message.is_empty());
                }
            }
        }
    }
}

#[test]
fn the_base_file_is_valid() {
    assert!(load_str(BASE, "base.ron", &common::registry()).is_ok());
}
