//! The editor, the preview and the optimizer read how a port is shown from the port's own
//! description (`PortDef::hint`, `choices`; issue 26, point 1), never from node ids or port
//! names. This test reads their sources (test modules and the scripted test binary left out) and
//! fails on the guesses that description replaced.

use std::path::{Path, PathBuf};

/// Comparisons that guess what a node is or how a port is shown from its id or name.
const GUESSES: &[&str] = &[
    "def.id == \"",
    "def.id.starts_with(",
    "def.id.contains(",
    "id.contains(\"support\")",
    "n.contains(\"support\")",
    "port.name == \"",
    "p.name == \"",
    "input_index(\"path\")",
    "\"mapper.graph\" &&",
    "== \"mapper.graph\"",
    "== \"param.number\"",
    "== \"param.integer\"",
    "POINT_PARAMS",
    "INTEGER_TYPE",
    "CHOICE_TYPE",
    "PANEL_TYPE",
    "output_index(\"configurations\")",
    "output_index(\"mesh\")",
    "Some(\"param.points\")",
    "PARAM_LIST",
    "name.as_ref() == \"",
    "input_index(\"options\")",
    "input_index(\"item_type\")",
    "input_index(\"values\")",
];

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            // The scripted window sessions pick nodes of known types on purpose.
            if path.file_name().is_some_and(|n| n == "bin") {
                continue;
            }
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn no_front_end_guesses_from_node_ids_or_port_names() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut files = Vec::new();
    for dir in [
        "crates/editor/src",
        "crates/preview/src",
        "crates/engine/src/optimize",
    ] {
        sources(&root.join(dir), &mut files);
    }
    assert!(files.len() > 40, "{} files", files.len());
    let mut found = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        // Test modules may build nodes of known types.
        let code = text.split("#[cfg(test)]").next().unwrap_or("");
        for (k, line) in code.lines().enumerate() {
            let code_part = line.split("//").next().unwrap_or("");
            for guess in GUESSES {
                if code_part.contains(guess) {
                    found.push(format!("{}:{}: {}", file.display(), k + 1, line.trim()));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "guesses from ids or names (use the port's hint or choices):\n{}",
        found.join("\n")
    );
}
