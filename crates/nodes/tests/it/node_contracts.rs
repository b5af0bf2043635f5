//! Node ids and ports are contracts used from outside (`cnets eval`, graph files, Python, Hops):
//! the frozen contract is `crates/nodes/signatures.txt`, one line per node type — its id, then its
//! inputs (name, type, default) and outputs (name, type) in order. The registry must match it
//! line for line; `docs/nodes.md` is generated from the registry and checked against it
//! (`docs_nodes_md_is_up_to_date` in `src/lib.rs`), so all three agree.
//!
//! A new node type, or a new port (added at the end, an input with a default), is a new or longer
//! line in the contract, written by hand from what this test prints. A renamed or removed id or
//! port is a changed line: never make one.

use std::collections::BTreeMap;

use cnets_engine::NodeDef;
use cnets_engine::value::json::to_json;

/// The contract, beside this crate's manifest.
const CONTRACT: &str = include_str!("../../signatures.txt");

/// One node type's line: `id(input: type = default, …) -> (output: type, …)`. A required input
/// has no `= …`, an optional one without a default ends in `?`; defaults are written in JSON.
fn signature(def: &NodeDef) -> String {
    let inputs: Vec<String> = def
        .inputs
        .iter()
        .map(|p| match &p.default {
            Some(v) => format!("{}: {} = {}", p.name, p.type_name(), to_json(v)),
            None if p.optional => format!("{}: {}?", p.name, p.type_name()),
            None => format!("{}: {}", p.name, p.type_name()),
        })
        .collect();
    let outputs: Vec<String> = def
        .outputs
        .iter()
        .map(|p| format!("{}: {}", p.name, p.type_name()))
        .collect();
    format!(
        "{}({}) -> ({})",
        def.id,
        inputs.join(", "),
        outputs.join(", ")
    )
}

/// The node type id a contract line is about (the text before its first `(`).
fn id_of(line: &str) -> &str {
    line.split_once('(').map_or(line, |(id, _)| id)
}

/// The contract's lines by id (comments `#` and blank lines left out), checked sorted and unique.
fn contract() -> BTreeMap<&'static str, &'static str> {
    let lines: Vec<&str> = CONTRACT
        .lines()
        .map(str::trim_end)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .collect();
    let ids: Vec<&str> = lines.iter().map(|l| id_of(l)).collect();
    let mut sorted = ids.clone();
    sorted.sort_unstable();
    sorted.dedup();
    assert_eq!(
        ids, sorted,
        "signatures.txt: one line per node type, sorted by id"
    );
    lines.into_iter().map(|l| (id_of(l), l)).collect()
}

/// What differs between the contract and the registry's signatures, in words (empty: nothing).
fn differences(contract: &BTreeMap<&str, &str>, registry: &BTreeMap<String, String>) -> String {
    let mut out = String::new();
    for (id, line) in contract {
        match registry.get(*id) {
            None => out.push_str(&format!(
                "`{id}` is in the contract but not registered (an id is a contract: never remove or rename one)\n  contract: {line}\n"
            )),
            Some(now) if now != line => out.push_str(&format!(
                "`{id}` does not match its contract (port names are contracts: never rename one; a new port goes at the end, an input with a default, and lengthens the line)\n  contract: {line}\n  registry: {now}\n"
            )),
            Some(_) => {}
        }
    }
    let new: Vec<&String> = registry
        .iter()
        .filter(|(id, _)| !contract.contains_key(id.as_str()))
        .map(|(_, line)| line)
        .collect();
    if !new.is_empty() {
        out.push_str(
            "new node types: add their lines to crates/nodes/signatures.txt (sorted by id):\n",
        );
        for line in new {
            out.push_str(&format!("{line}\n"));
        }
    }
    out
}

#[test]
fn every_node_type_matches_its_frozen_signature() {
    let registry: BTreeMap<String, String> = cnets_nodes::registry()
        .iter()
        .map(|def| (def.id.to_string(), signature(def)))
        .collect();
    let found = differences(&contract(), &registry);
    assert!(found.is_empty(), "{found}");
}

#[test]
fn a_renamed_port_or_a_missing_node_is_reported() {
    let registry = cnets_nodes::registry();
    let number = registry.get("param.number").expect("registered");
    let line = signature(number);
    assert_eq!(
        line,
        "param.number(value: number = 0.5, min: number = 0.0, max: number = 1.0, step: number = 0.0) -> (value: number)"
    );
    let contract = BTreeMap::from([
        ("param.number", line.as_str()),
        ("param.gone", "param.gone() -> ()"),
    ]);
    let renamed = BTreeMap::from([
        (
            "param.number".to_string(),
            line.replace("step:", "increment:"),
        ),
        ("param.new".to_string(), "param.new() -> ()".to_string()),
    ]);
    let found = differences(&contract, &renamed);
    assert!(
        found.contains("`param.gone` is in the contract but not registered"),
        "{found}"
    );
    assert!(
        found.contains("`param.number` does not match its contract"),
        "{found}"
    );
    assert!(found.contains("registry: param.number(value: number = 0.5, min: number = 0.0, max: number = 1.0, increment:"), "{found}");
    assert!(found.contains("new node types: add their lines"), "{found}");
    assert!(found.ends_with("param.new() -> ()\n"), "{found}");
    let same = BTreeMap::from([("param.number".to_string(), line.clone())]);
    assert_eq!(
        differences(&BTreeMap::from([("param.number", line.as_str())]), &same),
        ""
    );
}
