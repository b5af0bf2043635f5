//! The parameter panel (Grasshopper's Remote Control Panel): every slider, toggle, value list and
//! graph mapper of the graph in one docked list, editable there — the same edits as on the canvas
//! (undo, autosave). Grouped by where they sit: the graph being edited first, then one group per
//! cluster node holding parameters (listed, with a button that opens the cluster to edit them).

use cnets_engine::cluster::Cluster;
use cnets_engine::{Graph, NodeDef};

use crate::canvas::CanvasAction;
use crate::edit::Edit;
use crate::request::UiRequest;

/// The input the panel edits on a node of this type: its first input whose declared widget is a
/// designer-facing parameter's — a slider, a toggle, a value list, a graph mapper's handles
/// ([`cnets_engine::Widget::is_parameter`]); `None`: the panel does not list the node.
pub fn edited_input(def: &NodeDef) -> Option<usize> {
    def.inputs.iter().position(|p| p.hint.widget.is_parameter())
}

/// The parameter nodes of `graph` in file order: (id, type id).
pub fn parameters(graph: &Graph) -> Vec<(String, String)> {
    graph
        .nodes()
        .filter(|(_, n)| edited_input(&n.def).is_some())
        .map(|(_, n)| (n.id.clone(), n.def.id.to_string()))
        .collect()
}

/// Cluster nodes of `graph` with parameters inside: (cluster node id, their ids).
pub fn cluster_groups(graph: &Graph) -> Vec<(String, Vec<String>)> {
    graph
        .nodes()
        .filter_map(|(_, n)| {
            let c = Cluster::of(&n.def)?;
            let inner: Vec<String> = parameters(&c.template)
                .into_iter()
                .map(|(id, _)| id)
                .collect();
            (!inner.is_empty()).then(|| (n.id.clone(), inner))
        })
        .collect()
}

/// Shows the panel's contents; returns the edits (and cluster openings) asked for.
pub fn show(
    ui: &mut egui::Ui,
    graph: &Graph,
    statuses: &std::collections::HashMap<String, crate::worker::NodeStatus>,
) -> Vec<CanvasAction> {
    show_with_rects(ui, graph, statuses).0
}

/// [`show`], and where each parameter's value editor (slider, toggle, value list) was drawn:
/// (node id, rectangle in points), for scripts and tests that drive the panel.
pub fn show_with_rects(
    ui: &mut egui::Ui,
    graph: &Graph,
    statuses: &std::collections::HashMap<String, crate::worker::NodeStatus>,
) -> (Vec<CanvasAction>, Vec<(String, egui::Rect)>) {
    let mut actions = Vec::new();
    let mut rects = Vec::new();
    let params = parameters(graph);
    let groups = cluster_groups(graph);
    egui::ScrollArea::vertical()
        .id_salt("cnets-parameters-scroll")
        .show(ui, |ui| {
            if params.is_empty() && groups.is_empty() {
                ui.weak("no sliders, toggles, value lists or graph mappers in this graph");
            }
            if !params.is_empty() {
                egui::CollapsingHeader::new("this graph")
                    .id_salt("cnets-parameters-main")
                    .default_open(true)
                    .show(ui, |ui| {
                        for (id, type_id) in &params {
                            let Some(node) = graph.node(id) else { continue };
                            ui.push_id(("cnets-parameter", id), |ui| {
                                // The node's name when it was given one (its id in the hover).
                                let what = format!(
                                    "{type_id} — {}",
                                    crate::palette::display_name(&node.def)
                                );
                                ui.strong(node.label()).on_hover_text(match &node.name {
                                    Some(_) => format!("id: {id}\n{what}"),
                                    None => what,
                                });
                                if crate::mapper::is_mapper(node) {
                                    let ran_on = statuses.get(id).and_then(|s| s.ran_on());
                                    let r = crate::mapper::show(ui, graph, node, ran_on);
                                    if let Some(values) = r.changes {
                                        actions.push(CanvasAction::Edit(Edit::SetValues {
                                            node: id.clone(),
                                            values,
                                        }));
                                    }
                                } else if let Some(k) = edited_input(&node.def) {
                                    ui.spacing_mut().slider_width = 160.0;
                                    let (changed, rect) =
                                        crate::widgets::input_editor_with_rect(ui, node, k);
                                    rects.push((id.clone(), rect));
                                    if let Some(value) = changed {
                                        actions.push(CanvasAction::Edit(Edit::SetValue {
                                            node: id.clone(),
                                            input: node.def.inputs[k].name.to_string(),
                                            value,
                                        }));
                                    }
                                }
                            });
                            ui.add_space(4.0);
                        }
                    });
            }
            for (cluster, inner) in &groups {
                let cluster_node = graph.node(cluster);
                let template = cluster_node
                    .and_then(|n| Cluster::of(&n.def))
                    .map(|c| &c.template);
                let title = cluster_node.map_or(cluster.as_str(), |n| n.label());
                egui::CollapsingHeader::new(format!("cluster {title}"))
                    .id_salt(("cnets-parameters-cluster", cluster))
                    .default_open(false)
                    .show(ui, |ui| {
                        for id in inner {
                            let inner_node = template.and_then(|t| t.node(id));
                            ui.label(inner_node.map_or(id.as_str(), |n| n.label()));
                        }
                        if ui
                            .button("Open the cluster to edit them")
                            .on_hover_text("double-click its title on the canvas does the same")
                            .clicked()
                        {
                            actions.push(CanvasAction::Request(UiRequest::OpenCluster(
                                cluster.clone(),
                            )));
                        }
                    });
            }
        });
    (actions, rects)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    #[test]
    fn the_panel_lists_parameters_in_file_order_and_clusters_holding_some() {
        let registry = Arc::new(cnets_nodes::registry());
        let d = cnets_engine::file::load_str(crate::app::DEFAULT_GRAPH, "d", &registry).unwrap();
        let mut g = d.graph;
        let ids: Vec<String> = parameters(&g).into_iter().map(|(id, _)| id).collect();
        assert_eq!(ids, vec!["apex".to_string(), "ratio".to_string()]);
        cnets_engine::cluster::make_cluster(&mut g, &["ratio"], "c").unwrap();
        let groups = cluster_groups(&g);
        assert_eq!(groups, vec![("c".to_string(), vec!["ratio".to_string()])]);
        let edited = |id: &str| {
            let def = registry.get(id).unwrap();
            edited_input(def).map(|k| def.inputs[k].name.to_string())
        };
        assert_eq!(edited("param.choice").as_deref(), Some("index"));
        assert_eq!(edited("param.number").as_deref(), Some("value"));
        assert_eq!(edited("param.integer").as_deref(), Some("value"));
        assert_eq!(edited("param.boolean").as_deref(), Some("value"));
        assert_eq!(edited("mapper.graph").as_deref(), Some("handles"));
        // A construction's choice port (end_planes) is a drop-down on the node, not a parameter.
        assert_eq!(edited("cnets.construct"), None);
        assert_eq!(edited("curve.arc"), None);
    }
}
