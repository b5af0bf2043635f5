//! `cnets nodes [--json | --markdown]`.

use std::process::ExitCode;

use cnets_engine::value::json::to_json;
use std::path::PathBuf;
use std::sync::Arc;

use cnets_engine::{NodeDef, PortDef, Registry};

use crate::library;
use serde_json::{Value as Json, json};

use crate::failure::CommandResult;

/// Arguments of `cnets nodes`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Print a JSON array of node types.
    #[arg(long, conflicts_with = "markdown")]
    json: bool,
    /// Print the Markdown reference (docs/nodes.md).
    #[arg(long)]
    markdown: bool,
    /// List the graphs of this folder as node types (clusters) instead of the built-in nodes.
    #[arg(long, value_name = "DIR")]
    library: Option<PathBuf>,
}

/// How a port is shown: its display name, widget, ranges, step and preview layer (only what is
/// set), and for a choice port its words.
fn hint_json(p: &PortDef) -> Json {
    let h = &p.hint;
    let mut o = json!({ "display_name": p.display_name(), "widget": p.widget().as_str() });
    let range = |r: Option<(f64, f64)>| r.map(|(a, b)| json!([a, b]));
    if let Some(r) = range(h.soft_range) {
        o["range"] = r;
    }
    if let Some(r) = range(h.hard_range) {
        o["hard_range"] = r;
    }
    if let Some(step) = h.step {
        o["step"] = json!(step);
    }
    if let Some(layer) = h.layer {
        o["layer"] = json!(layer.hint_word());
    }
    o
}

fn port_json(p: &PortDef, with_default: bool) -> Json {
    let mut o = json!({ "name": p.name, "type": p.type_name(), "doc": p.doc });
    o["hint"] = hint_json(p);
    if let Some(c) = &p.choices {
        o["choices"] = json!(c.options);
    }
    if with_default {
        o["default"] = p.default.as_ref().map_or(Json::Null, to_json);
        o["optional"] = json!(p.optional);
        o["required"] = json!(p.required());
    }
    o
}

/// The JSON description of a node type.
pub fn node_json(def: &NodeDef) -> Json {
    json!({
        "id": def.id,
        "name": def.name(),
        "category": def.category,
        "doc": def.doc,
        "flags": def.flags.iter().map(|f| format!("{f:?}").to_lowercase()).collect::<Vec<_>>(),
        "inputs": def.inputs.iter().map(|p| port_json(p, true)).collect::<Vec<_>>(),
        "outputs": def.outputs.iter().map(|p| port_json(p, false)).collect::<Vec<_>>(),
    })
}

/// Runs the command.
pub fn run(args: Args) -> CommandResult {
    let shared = Arc::new(cnets_nodes::registry());
    let registry = match &args.library {
        Some(dir) => {
            let mut r = Registry::new();
            for def in library::folder_defs(dir, &shared)? {
                r.register(def);
            }
            r
        }
        None => (*shared).clone(),
    };
    let defs = match &args.library {
        Some(_) => registry.iter().cloned().collect(),
        None => cnets_nodes::reference::listed(&registry),
    };
    if args.json {
        let all: Vec<Json> = defs.iter().map(|d| node_json(d)).collect();
        crate::outln!("{}", serde_json::to_string_pretty(&all).unwrap_or_default());
    } else if args.markdown {
        crate::out!("{}", cnets_nodes::reference::markdown(&registry));
    } else {
        let mut category = String::new();
        for def in &defs {
            if def.category != category {
                category = def.category.to_string();
                crate::outln!("\n{category}");
            }
            crate::outln!("  {:<28} {}", def.id, def.summary());
            for p in &def.inputs {
                let default = p
                    .default
                    .as_ref()
                    .map(|d| format!(" = {}", to_json(d)))
                    .unwrap_or_default();
                let optional = if p.optional { " (optional)" } else { "" };
                crate::outln!("      in  {}: {}{default}{optional}", p.name, p.type_name());
            }
            for p in &def.outputs {
                crate::outln!("      out {}: {}", p.name, p.type_name());
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}
