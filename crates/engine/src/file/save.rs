//! Saving a graph: canonical RON text (nodes in creation order, inputs in port order, shortest
//! round-trip floats) written atomically.

use std::path::Path;

use super::FORMAT_VERSION;
use super::literal::{self, push_indent, quote};
use super::load::GraphMeta;
use crate::atomic::write_atomic;
use crate::cluster::{Cluster, ClusterSource};
use crate::graph::Graph;

/// Writes a graph as canonical RON text (nodes in creation order, inputs in port order).
pub fn to_ron(graph: &Graph, meta: &GraphMeta) -> String {
    let mut out = String::from("(\n");
    push_indent(&mut out, 1);
    out.push_str(&format!("version: {FORMAT_VERSION},\n"));
    for (name, value) in [("name", &meta.name), ("description", &meta.description)] {
        if let Some(v) = value {
            push_indent(&mut out, 1);
            out.push_str(name);
            out.push_str(": ");
            quote(&mut out, v);
            out.push_str(",\n");
        }
    }
    super::cplanes::write(&mut out, &meta.cplanes, 1);
    if let Some(setup) = &meta.optimization {
        push_indent(&mut out, 1);
        out.push_str("optimization: ");
        out.push_str(&setup.to_ron(1));
        out.push_str(",\n");
    }
    push_indent(&mut out, 1);
    out.push_str("nodes: {\n");
    let mut nodes: Vec<_> = graph.nodes().map(|(_, n)| n).collect();
    nodes.sort_by_key(|n| n.uid());
    for node in nodes {
        push_indent(&mut out, 2);
        quote(&mut out, &node.id);
        out.push_str(": (\n");
        push_indent(&mut out, 3);
        out.push_str("type: ");
        quote(&mut out, &node.def.id);
        out.push_str(",\n");
        if let Some(cluster) = Cluster::of(&node.def) {
            push_indent(&mut out, 3);
            match &cluster.source {
                ClusterSource::File { written, .. } => {
                    out.push_str("source: ");
                    quote(&mut out, written);
                    out.push_str(",\n");
                }
                ClusterSource::Inline => {
                    out.push_str("graph: ");
                    let inner = to_ron(&cluster.template, &cluster.meta);
                    for (k, line) in inner.trim_end().lines().enumerate() {
                        if k > 0 {
                            out.push('\n');
                            if !line.is_empty() {
                                push_indent(&mut out, 3);
                            }
                        }
                        out.push_str(line);
                    }
                    out.push_str(",\n");
                }
            }
        }
        if let Some(name) = &node.name {
            push_indent(&mut out, 3);
            out.push_str("name: ");
            quote(&mut out, name);
            out.push_str(",\n");
        }
        push_indent(&mut out, 3);
        out.push_str(&format!(
            "position: ({:?}, {:?}),\n",
            node.position[0], node.position[1]
        ));
        if !node.preview {
            push_indent(&mut out, 3);
            out.push_str("preview: false,\n");
        }
        if !node.enabled {
            push_indent(&mut out, 3);
            out.push_str("enabled: false,\n");
        }
        if let Some(rgb) = node.color {
            push_indent(&mut out, 3);
            out.push_str(&format!("color: \"{}\",\n", super::load::format_color(rgb)));
        }
        let values: Vec<_> = node
            .def
            .inputs
            .iter()
            .enumerate()
            .filter_map(|(k, p)| Some((p, node.value(k)?)))
            .collect();
        if !values.is_empty() {
            push_indent(&mut out, 3);
            out.push_str("inputs: {\n");
            for (port, value) in values {
                push_indent(&mut out, 4);
                quote(&mut out, &port.name);
                out.push_str(": ");
                out.push_str(&literal::encode(value, &port.ty, 4));
                out.push_str(",\n");
            }
            push_indent(&mut out, 3);
            out.push_str("},\n");
        }
        push_indent(&mut out, 2);
        out.push_str("),\n");
    }
    push_indent(&mut out, 1);
    out.push_str("},\n");
    push_indent(&mut out, 1);
    out.push_str("edges: [\n");
    for wire in graph.wires() {
        push_indent(&mut out, 2);
        quote(&mut out, &wire.to_string());
        out.push_str(",\n");
    }
    push_indent(&mut out, 1);
    out.push_str("],\n)\n");
    out
}

/// Saves a graph file atomically (temporary file, then rename).
pub fn save_file(path: &Path, graph: &Graph, meta: &GraphMeta) -> std::io::Result<()> {
    write_atomic(path, to_ron(graph, meta).as_bytes())
}
