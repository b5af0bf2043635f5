//! Document edits: what a gesture (on the canvas, in the parameter panel, from a menu) changes in
//! the graph, and their one [`apply`]. Every edit is validated by the engine and is one undo step
//! (continuous gestures merge by their [`EditKey`]); a refused edit leaves the graph unchanged.
//! What only changes the UI (open the palette, open a cluster, pick an optimization variable) is a
//! [`crate::request::UiRequest`] instead.

use std::sync::Arc;

use cnets_engine::cluster::{self, Cluster, ClusterSource, explode, make_cluster};
use cnets_engine::{Graph, Value};
use egui::Rect;

use crate::clipboard::Clipboard;
use crate::document::{GraphDocument, fresh_id};
pub use crate::edit_error::EditError;
use crate::history::EditKey;

/// One change to the document's graph.
#[derive(Clone, Debug, PartialEq)]
pub enum Edit {
    /// Wire `from.output` into `to.input`; `replace` removes the wires already in that input
    /// (a plain drag; Shift keeps them, as in Grasshopper).
    Connect {
        /// Source node.
        from: String,
        /// Source output.
        output: String,
        /// Target node.
        to: String,
        /// Target input.
        input: String,
        /// Replace existing wires into the input.
        replace: bool,
    },
    /// Remove one wire.
    Disconnect {
        /// Source node.
        from: String,
        /// Source output.
        output: String,
        /// Target node.
        to: String,
        /// Target input.
        input: String,
    },
    /// Remove every wire into an input.
    DropInputs {
        /// Node.
        node: String,
        /// Input.
        input: String,
    },
    /// Remove every wire out of an output.
    DropOutputs {
        /// Node.
        node: String,
        /// Output.
        output: String,
    },
    /// Set an input's literal value.
    SetValue {
        /// Node.
        node: String,
        /// Input.
        input: String,
        /// New value.
        value: Value,
    },
    /// Clear an input's literal value (back to the default).
    ClearValue {
        /// Node.
        node: String,
        /// Input.
        input: String,
    },
    /// Set several inputs at once (the graph mapper's handles and type), one undo step per drag.
    SetValues {
        /// Node.
        node: String,
        /// `(input, value)` pairs.
        values: Vec<(String, Value)>,
    },
    /// Set the points of point nodes moved in the 3D view: (node, input, value) — one undo step
    /// per drag.
    SetPoints(Vec<(String, String, Value)>),
    /// Set the inputs a drag of the net itself solved for: (node, input, value) — one undo step
    /// per drag (the Drag net tool, [`crate::net_drag`]).
    SetDragged(Vec<(String, String, Value)>),
    /// Turn the preview of a node on or off.
    SetPreview(String, bool),
    /// Set (or clear) the colour a node's geometry is previewed in.
    SetColor(String, Option<[u8; 3]>),
    /// Name a node for designers (`None` or blank: shown by its id again); saved with the graph.
    Rename(String, Option<String>),
    /// Enable or disable a node.
    SetEnabled(String, bool),
    /// Move nodes to new canvas positions.
    Move(Vec<(String, [f32; 2])>),
    /// Remove nodes.
    Remove(Vec<String>),
    /// Duplicate nodes (with the wires between them and wires coming in from outside).
    Duplicate(Vec<String>),
    /// Replace these nodes by one cluster node (wires crossing the selection become its ports).
    MakeCluster {
        /// The nodes to put in the cluster.
        nodes: Vec<String>,
        /// Their canvas rectangle, when known: the cluster's input nodes are laid out down its
        /// left side and its output nodes down its right side, so the opened cluster reads left
        /// to right.
        around: Option<Rect>,
    },
    /// Replace a cluster node by the nodes of its subgraph.
    ExplodeCluster(String),
    /// Add curves as editable points: per curve a `param.points` node holding its points wired
    /// into a `curve.spline` (or `curve.polyline`), the first pair at canvas position `at`, the
    /// next ones below it. Creates the nodes in that order.
    AddCurves {
        /// The curves.
        curves: Vec<crate::viewport::DrawnCurve>,
        /// Canvas position of the first `param.points` node.
        at: [f32; 2],
    },
    /// Keep a named construction plane with the graph (saved in its file; names are unique).
    AddCPlane(cnets_engine::file::NamedPlane),
}

/// Canvas spacing of the nodes [`Edit::AddCurves`] places: a curve node clear of its
/// `param.points` (about 460 wide with its output summary's slot) and the next curve below.
pub const CURVE_NODE_STEP: [f32; 2] = [500.0, 150.0];

/// Sets several nodes' input values as one step of the gesture `key` (a drag's edits merge).
fn set_inputs(
    doc: &mut GraphDocument,
    key: EditKey,
    values: Vec<(String, String, Value)>,
) -> Result<(), EditError> {
    doc.edit(Some(key), |g, _| {
        for (node, input, value) in values {
            g.set_value(&node, &input, value)?;
        }
        Ok(())
    })
}

/// Applies an edit to a document as one undoable step. Returns the ids of the nodes the edit
/// created (the cluster node, the duplicates). Errors are messages for the status bar; the graph
/// is unchanged then.
pub fn apply(doc: &mut GraphDocument, edit: Edit) -> Result<Vec<String>, EditError> {
    let err = EditError::from;
    let none = |r: Result<(), EditError>| r.map(|()| Vec::new());
    match edit {
        Edit::Connect {
            from,
            output,
            to,
            input,
            replace,
        } => none(doc.edit(None, |g, _| {
            if replace {
                g.disconnect_input(&to, &input).map_err(err)?;
            }
            g.connect(&from, &output, &to, &input)
                .map(|_| ())
                .map_err(err)
        })),
        Edit::Disconnect {
            from,
            output,
            to,
            input,
        } => none(doc.edit(None, |g, _| {
            g.disconnect(&from, &output, &to, &input).map_err(err)
        })),
        Edit::DropInputs { node, input } => none(doc.edit(None, |g, _| {
            g.disconnect_input(&node, &input).map(|_| ()).map_err(err)
        })),
        Edit::DropOutputs { node, output } => none(doc.edit(None, |g, _| {
            g.disconnect_output(&node, &output).map(|_| ()).map_err(err)
        })),
        Edit::SetValue { node, input, value } => {
            let key = EditKey::Value(node.clone(), input.clone());
            none(doc.edit(Some(key), |g, _| {
                g.set_value(&node, &input, value).map(|_| ()).map_err(err)
            }))
        }
        Edit::ClearValue { node, input } => none(doc.edit(None, |g, _| {
            g.clear_value(&node, &input).map(|_| ()).map_err(err)
        })),
        Edit::SetValues { node, values } => {
            none(doc.edit(Some(EditKey::Mapper(node.clone())), |g, _| {
                for (input, value) in values {
                    g.set_value(&node, &input, value).map_err(err)?;
                }
                Ok(())
            }))
        }
        Edit::SetPoints(values) => none(set_inputs(doc, EditKey::Points, values)),
        Edit::SetDragged(values) => none(set_inputs(doc, EditKey::NetDrag, values)),
        Edit::SetPreview(node, on) => {
            none(doc.edit(None, |g, _| g.set_preview(&node, on).map_err(err)))
        }
        Edit::SetColor(node, color) => {
            none(doc.edit(None, |g, _| g.set_color(&node, color).map_err(err)))
        }
        Edit::Rename(node, name) => {
            none(doc.edit(None, |g, _| g.set_name(&node, name).map_err(err)))
        }
        Edit::SetEnabled(node, on) => {
            none(doc.edit(None, |g, _| g.set_enabled(&node, on).map_err(err)))
        }
        Edit::Move(moves) => none(doc.edit(Some(EditKey::Move), |g, _| {
            for (id, pos) in moves {
                g.set_position(&id, pos).map_err(err)?;
            }
            Ok(())
        })),
        Edit::Remove(ids) => none(doc.edit(None, |g, _| {
            for id in ids {
                g.remove_node(&id).map_err(err)?;
            }
            Ok(())
        })),
        Edit::Duplicate(ids) => {
            let clip = Clipboard::copy(&doc.graph, &ids);
            let mut created = Vec::new();
            doc.edit(None, |g, _| {
                created = clip
                    .paste(g, [30.0, 30.0], true)
                    .map_err(EditError::Paste)?;
                Ok::<_, EditError>(())
            })?;
            Ok(created)
        }
        Edit::MakeCluster { nodes, around } => {
            let id = fresh_id(&doc.graph, "cluster");
            doc.edit(None, |g, _| cluster_nodes(g, &nodes, &id, around))?;
            Ok(vec![id])
        }
        Edit::ExplodeCluster(id) => none(doc.edit(None, |g, _| {
            explode(g, &id).map(|_| ()).map_err(EditError::from)
        })),
        Edit::AddCurves { curves, at } => {
            let mut created = Vec::new();
            doc.edit(None, |g, _| {
                for (k, curve) in curves.into_iter().enumerate() {
                    let y = at[1] + k as f32 * CURVE_NODE_STEP[1];
                    let points = fresh_id(g, "points");
                    g.add_node(&points, "param.points").map_err(err)?;
                    g.set_position(&points, [at[0], y]).map_err(err)?;
                    let list = curve
                        .points
                        .iter()
                        .map(|p| Value::Point(*p))
                        .collect::<Vec<_>>();
                    g.set_value(&points, "points", Value::list(list))
                        .map_err(err)?;
                    let (kind, stem) = if curve.spline {
                        ("curve.spline", "spline")
                    } else {
                        ("curve.polyline", "polyline")
                    };
                    let id = fresh_id(g, stem);
                    g.add_node(&id, kind).map_err(err)?;
                    g.set_position(&id, [at[0] + CURVE_NODE_STEP[0], y])
                        .map_err(err)?;
                    g.set_value(&id, "closed", Value::Boolean(curve.closed))
                        .map_err(err)?;
                    g.connect(&points, "points", &id, "points").map_err(err)?;
                    g.set_preview(&id, true).map_err(err)?;
                    created.push(points);
                    created.push(id);
                }
                Ok::<_, EditError>(())
            })?;
            Ok(created)
        }
        Edit::AddCPlane(plane) => none(doc.edit(None, |_, meta| {
            if meta.cplanes.iter().any(|p| p.name == plane.name) {
                return Err(EditError::CPlaneNameTaken(plane.name));
            }
            meta.cplanes.push(plane);
            Ok(())
        })),
    }
}

/// Puts `nodes` into a new cluster node `id`; with their rectangle `around`, lays the cluster's
/// input nodes out down its left side and its output nodes down its right side (in port order).
fn cluster_nodes(
    g: &mut Graph,
    nodes: &[String],
    id: &str,
    around: Option<Rect>,
) -> Result<(), EditError> {
    let selection: Vec<&str> = nodes.iter().map(String::as_str).collect();
    let made = make_cluster(g, &selection, id)?;
    let Some(b) = around else { return Ok(()) };
    let mut sub = made.template.clone();
    let mut order: Vec<(u64, String, bool)> = sub
        .nodes()
        .filter_map(|(_, n)| {
            let input = n.def.id == cluster::INPUT_TYPE;
            (input || n.def.id == cluster::OUTPUT_TYPE).then(|| (n.uid(), n.id.clone(), input))
        })
        .collect();
    order.sort();
    let (mut k_in, mut k_out) = (0.0, 0.0);
    for (_, n, input) in order {
        let at = if input {
            k_in += 1.0;
            [b.left() - 380.0, b.top() + 190.0 * (k_in - 1.0)]
        } else {
            k_out += 1.0;
            [b.right() + 100.0, b.top() + 190.0 * (k_out - 1.0)]
        };
        sub.set_position(&n, at)?;
    }
    let laid_out = Cluster::new(
        ClusterSource::Inline,
        sub,
        made.meta.clone(),
        made.base_dir.clone(),
    )
    .map_err(EditError::Interface)?;
    g.replace_def(id, Arc::new(laid_out.node_def()))?;
    Ok(())
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// `n` (a number) → `arc.radius`, `arc.curve` → `len.curve`.
    pub(crate) fn doc() -> GraphDocument {
        let mut d = GraphDocument::new(Arc::new(cnets_nodes::registry()));
        d.edit(None, |g, _| {
            g.add_node("n", "param.number").map_err(|e| e.to_string())?;
            g.add_node("arc", "curve.arc").map_err(|e| e.to_string())?;
            g.add_node("len", "curve.length")
                .map_err(|e| e.to_string())?;
            g.connect("n", "value", "arc", "radius")
                .map_err(|e| e.to_string())?;
            g.connect("arc", "curve", "len", "curve")
                .map(|_| ())
                .map_err(|e| e.to_string())
        })
        .unwrap();
        d
    }

    #[test]
    fn incompatible_and_cyclic_wires_are_refused() {
        let mut d = doc();
        let before = d.to_ron();
        // A polyline into a number input.
        let e = apply(
            &mut d,
            Edit::Connect {
                from: "arc".into(),
                output: "curve".into(),
                to: "n".into(),
                input: "value".into(),
                replace: true,
            },
        )
        .unwrap_err();
        assert!(matches!(e, EditError::Graph(_)), "{e}");
        assert!(e.to_string().contains("type mismatch"), "{e}");
        // len.length (number) into arc.radius would close arc -> len -> arc.
        let e = apply(
            &mut d,
            Edit::Connect {
                from: "len".into(),
                output: "length".into(),
                to: "arc".into(),
                input: "radius".into(),
                replace: false,
            },
        )
        .unwrap_err();
        assert!(e.to_string().contains("cycle"), "{e}");
        assert_eq!(d.to_ron(), before);
    }

    #[test]
    fn plain_connect_replaces_shift_connect_adds() {
        let mut d = doc();
        d.edit(None, |g, _| {
            g.add_node("m", "param.number")
                .map(|_| ())
                .map_err(|e| e.to_string())
        })
        .unwrap();
        let connect = |replace| Edit::Connect {
            from: "m".into(),
            output: "value".into(),
            to: "arc".into(),
            input: "radius".into(),
            replace,
        };
        apply(&mut d, connect(false)).unwrap();
        assert_eq!(d.graph.wires().iter().filter(|w| w.to == "arc").count(), 2);
        apply(
            &mut d,
            Edit::DropInputs {
                node: "arc".into(),
                input: "radius".into(),
            },
        )
        .unwrap();
        apply(&mut d, connect(true)).unwrap();
        let into: Vec<_> = d
            .graph
            .wires()
            .into_iter()
            .filter(|w| w.to == "arc")
            .collect();
        assert_eq!(into.len(), 1);
        assert_eq!(into[0].from, "m");
    }
    #[test]
    fn every_edit_is_one_undo_step() {
        let mut d = doc();
        let edits = [
            Edit::SetValue {
                node: "n".into(),
                input: "value".into(),
                value: Value::Number(2.5),
            },
            Edit::DropOutputs {
                node: "arc".into(),
                output: "curve".into(),
            },
            Edit::SetPreview("arc".into(), false),
            Edit::Rename("arc".into(), Some("Directrix".into())),
            Edit::SetEnabled("len".into(), false),
            Edit::Duplicate(vec!["n".into()]),
            Edit::MakeCluster {
                nodes: vec!["n".into(), "arc".into()],
                around: Some(Rect::from_min_max([0.0, 0.0].into(), [200.0, 100.0].into())),
            },
            Edit::Remove(vec!["len".into()]),
        ];
        let mut texts = vec![d.to_ron()];
        for e in edits {
            let kind = format!("{e:?}");
            apply(&mut d, e).unwrap_or_else(|m| panic!("{kind}: {m}"));
            texts.push(d.to_ron());
            d.history.end_gesture();
        }
        for k in (0..texts.len() - 1).rev() {
            assert!(d.undo());
            assert_eq!(d.to_ron(), texts[k], "undo step {k}");
        }
    }

    #[test]
    fn a_cluster_lays_its_ports_out_around_its_nodes() {
        let mut d = doc();
        let around = Rect::from_min_max([100.0, 50.0].into(), [400.0, 300.0].into());
        let created = apply(
            &mut d,
            Edit::MakeCluster {
                nodes: vec!["arc".into()],
                around: Some(around),
            },
        )
        .unwrap();
        assert_eq!(created, ["cluster"]);
        let c = Cluster::shared(&d.graph.node("cluster").unwrap().def).unwrap();
        for (_, n) in c.template.nodes() {
            if n.def.id == cluster::INPUT_TYPE {
                assert_eq!(n.position[0], around.left() - 380.0, "{}", n.id);
            } else if n.def.id == cluster::OUTPUT_TYPE {
                assert_eq!(n.position[0], around.right() + 100.0, "{}", n.id);
            }
        }
    }
}
