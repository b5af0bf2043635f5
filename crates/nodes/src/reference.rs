//! The Markdown node reference (`docs/nodes.md`), generated from the registry.

use std::fmt::Write as _;
use std::sync::Arc;

use cnets_engine::value::json::to_json;
use cnets_engine::{NodeDef, Registry};

/// The node types to list: the registry's, then the `cluster` type (documented, not registered:
/// each cluster node takes its ports from its subgraph).
pub fn listed(registry: &Registry) -> Vec<Arc<NodeDef>> {
    let mut defs: Vec<Arc<NodeDef>> = registry.iter().cloned().collect();
    if !defs
        .iter()
        .any(|d| d.id == cnets_engine::cluster::CLUSTER_TYPE)
    {
        defs.push(Arc::new(cnets_engine::cluster::cluster_type_description()));
    }
    defs
}

/// How an input is shown (its hint): the widget, a choice port's words, ranges and step; empty
/// for an input shown by its type.
fn shown_as(p: &cnets_engine::PortDef) -> String {
    let h = &p.hint;
    let mut parts = Vec::new();
    match &p.choices {
        Some(c) => parts.push(format!("choice: {}", c.options.join(", "))),
        None if p.widget() != cnets_engine::Widget::Auto => {
            parts.push(p.widget().as_str().replace('_', " "))
        }
        None => {}
    }
    if let Some((a, b)) = h.soft_range {
        parts.push(format!("range {a} … {b}"));
    }
    if let Some((a, b)) = h.hard_range {
        parts.push(if b == f64::MAX {
            format!("at least {a}")
        } else {
            format!("from {a} to {b}")
        });
    }
    if let Some(step) = h.step {
        parts.push(format!("step {step}"));
    }
    if let Some(name) = &h.display_name {
        parts.push(format!("named “{name}”"));
    }
    parts.join("; ")
}

/// The reference: every node type by category with its display name, doc, inputs (type, default,
/// how an editor shows it) and outputs (type, preview layer).
pub fn markdown(registry: &Registry) -> String {
    let mut out = String::from(
        "# Node reference\n\nGenerated from the node registry by `cargo run -p cnets -- nodes --markdown > docs/nodes.md`;\na test fails when this file is stale.\n",
    );
    let mut category = String::new();
    for def in &listed(registry) {
        if def.category != category {
            category = def.category.to_string();
            let _ = write!(out, "\n## {category}\n");
        }
        let _ = write!(
            out,
            "\n### `{}` — {}\n\n{}\n\n",
            def.id,
            def.name(),
            def.doc
        );
        if !def.inputs.is_empty() {
            out.push_str("| input | type | default | shown as | |\n|---|---|---|---|---|\n");
            for p in &def.inputs {
                let default = match &p.default {
                    Some(v) => format!("`{}`", to_json(v)),
                    None if p.optional => "optional".to_string(),
                    None => "required".to_string(),
                };
                let _ = writeln!(
                    out,
                    "| `{}` | {} | {} | {} | {} |",
                    p.name,
                    p.type_name(),
                    default,
                    shown_as(p),
                    p.doc.replace('|', "\\|")
                );
            }
            out.push('\n');
        }
        if !def.outputs.is_empty() {
            out.push_str("| output | type | layer | |\n|---|---|---|---|\n");
            for p in &def.outputs {
                let _ = writeln!(
                    out,
                    "| `{}` | {} | {} | {} |",
                    p.name,
                    p.type_name(),
                    match p.hint.layer {
                        None => String::new(),
                        Some(layer) => layer.hint_word().to_string(),
                    },
                    p.doc.replace('|', "\\|")
                );
            }
        }
    }
    out
}
