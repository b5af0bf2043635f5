//! The snarl viewer: draws the graph's nodes (headers, input and output rows with their value
//! editors, bodies, menus) and turns the designer's gestures into [`CanvasAction`]s.

use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

use cnets_engine::cluster::Cluster;
use cnets_engine::optimize::ValuePath;
use cnets_engine::{Graph, NodeFlag, Value, ValueType};
use egui::emath::TSTransform;
use egui::{Color32, Pos2, Rect, Stroke, Ui};
use egui_snarl::ui::{PinInfo, SnarlViewer};
use egui_snarl::{InPin, NodeId, OutPin, Snarl};
use rustc_hash::FxHashMap;

use crate::edit::Edit;
use crate::request::UiRequest;
use crate::worker::{NodeStatus, readout_output};
use crate::{list_editor, mapper, widgets};

use super::action::{CanvasAction, CanvasNode};
use super::pins::{PinKey, RecordingPin, fitted_port_name, pin_info, summary_slot};

/// The readout of a `view.panel` node: its text (selectable, monospace, every line) in a
/// scrolling box the designer resizes by its bottom-right corner (the size is kept per node for
/// the session). Returns the box's rectangle.
fn panel_readout(ui: &mut Ui, id: &str, text: Option<&str>) -> Rect {
    let frame = egui::Frame::new()
        .fill(ui.visuals().extreme_bg_color)
        .inner_margin(egui::Margin::same(4));
    ui.scope(|ui| {
        egui::Resize::default()
            .id_salt(("cnets-panel", id))
            .default_size([220.0, 110.0])
            .min_size([90.0, 40.0])
            .max_size([1200.0, 1600.0])
            .show(ui, |ui| {
                frame.show(ui, |ui| {
                    egui::ScrollArea::both()
                        .id_salt(("cnets-panel-scroll", id))
                        .auto_shrink(false)
                        .show(ui, |ui| match text {
                            Some(t) => {
                                ui.add(
                                    egui::Label::new(egui::RichText::new(t).monospace())
                                        .selectable(true)
                                        .extend(),
                                );
                            }
                            None => {
                                ui.weak("(no value yet)");
                            }
                        });
                });
            });
    })
    .response
    .rect
}

/// The snarl viewer: draws nodes from the graph and collects actions.
pub(super) struct Viewer<'a> {
    pub(super) graph: &'a Graph,
    pub(super) statuses: &'a HashMap<String, NodeStatus>,
    /// The canvas's, lent for the frame.
    pub(super) list_views: list_editor::OnNodeCache,
    pub(super) actions: Vec<CanvasAction>,
    pub(super) shift: bool,
    pub(super) pins: Rc<RefCell<FxHashMap<PinKey, Pos2>>>,
    pub(super) to_global: TSTransform,
    pub(super) rects: HashMap<String, Rect>,
    pub(super) focused: Option<String>,
    pub(super) pressed_node: Option<String>,
    pub(super) fit: Option<TSTransform>,
    pub(super) plots: HashMap<String, Rect>,
    pub(super) mapper_views: HashMap<String, (mapper::Shown, usize)>,
    pub(super) editors: HashMap<(String, String), Rect>,
    pub(super) panels: HashMap<String, Rect>,
    pub(super) selected: Vec<String>,
    /// Nodes selected from outside the canvas (outlined here: the snarl does not know them).
    pub(super) chosen: Vec<String>,
    /// Nodes locked for dragging the net (marked with a lock; their menu unlocks them).
    pub(super) drag_locked: std::collections::BTreeSet<String>,
}

/// The graph node id a snarl node shows, if the snarl has that node.
fn node_id(snarl: &Snarl<CanvasNode>, node: NodeId) -> Option<String> {
    snarl.get_node(node).map(|n| n.id.clone())
}

impl Viewer<'_> {
    /// A pin that records where it is drawn, under `key`.
    fn pin(&self, key: PinKey, info: PinInfo) -> RecordingPin {
        RecordingPin {
            info,
            key,
            sink: self.pins.clone(),
        }
    }

    /// The graph node id and port name of a snarl pin (an input pin when `input`), if both
    /// still exist.
    fn pin_port(
        &self,
        snarl: &Snarl<CanvasNode>,
        node: NodeId,
        input: bool,
        index: usize,
    ) -> Option<(String, String)> {
        let id = node_id(snarl, node)?;
        let def = &self.graph.node(&id)?.def;
        let ports = if input { &def.inputs } else { &def.outputs };
        let name = ports.get(index)?.name.to_string();
        Some((id, name))
    }

    fn names(
        &self,
        snarl: &Snarl<CanvasNode>,
        from: &OutPin,
        to: &InPin,
    ) -> Option<(String, String, String, String)> {
        let a = snarl.get_node(from.id.node)?;
        let b = snarl.get_node(to.id.node)?;
        let na = self.graph.node(&a.id)?;
        let nb = self.graph.node(&b.id)?;
        Some((
            a.id.clone(),
            na.def.outputs.get(from.id.output)?.name.to_string(),
            b.id.clone(),
            nb.def.inputs.get(to.id.input)?.name.to_string(),
        ))
    }

    /// "Rename port" in the context menu of a `graph.input` / `graph.output` node: a field with
    /// the port's name and a Rename button, which sets the node's `name` (one undo step; the
    /// cluster node keeps its wires on the renamed port, see [`crate::cluster_ports`]).
    fn rename_port_menu(&mut self, ui: &mut Ui, id: &str) {
        let current = match self.graph.node(id).and_then(|n| n.value_of("name")) {
            Some(Value::Text(t)) => t.to_string(),
            _ => String::new(),
        };
        let key = egui::Id::new(("rename-port", id));
        let mut name: String = ui.data_mut(|d| d.get_temp(key)).unwrap_or(current.clone());
        ui.label("Rename port");
        let field = ui.add(
            egui::TextEdit::singleline(&mut name)
                .desired_width(140.0)
                .id(key.with("field")),
        );
        let valid = crate::cluster_ports::valid_port_name(&name);
        if !valid {
            ui.weak("letters, digits and _ only");
        }
        let enter = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        let clicked = ui
            .add_enabled(valid && name != current, egui::Button::new("Rename"))
            .clicked();
        if valid && name != current && (clicked || enter) {
            self.actions.push(CanvasAction::Edit(Edit::SetValue {
                node: id.to_string(),
                input: "name".into(),
                value: Value::text(name.clone()),
            }));
            ui.data_mut(|d| d.remove::<String>(key));
            ui.close();
        } else {
            ui.data_mut(|d| d.insert_temp(key, name));
        }
    }

    /// "Name" in a node's context menu: a field with the node's name (its id when it has none)
    /// and a "Rename node" button (Enter too): one undo step, saved with the graph; an empty name shows
    /// the id again. The id itself never changes (wires, `--set` and scripts use it).
    fn rename_node_menu(&mut self, ui: &mut Ui, id: &str) {
        let Some(node) = self.graph.node(id) else {
            return;
        };
        let current = node.label().to_string();
        let key = egui::Id::new(("rename-node", id));
        let mut name: String = ui.data_mut(|d| d.get_temp(key)).unwrap_or(current.clone());
        ui.horizontal(|ui| {
            ui.label("Name");
            let field = ui.add(
                egui::TextEdit::singleline(&mut name)
                    .desired_width(140.0)
                    .hint_text(id)
                    .id(key.with("field")),
            );
            let enter = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            let changed = name.trim() != current;
            let clicked = ui
                .add_enabled(changed, egui::Button::new("Rename node"))
                .on_hover_text(
                    "the name shown on the canvas, in the parameter panel and the 3D view (the \
                     id stays: wires and --set use it)",
                )
                .clicked();
            if changed && (clicked || enter) {
                let name = name.trim();
                let name = (!name.is_empty() && name != id).then(|| name.to_string());
                self.actions
                    .push(CanvasAction::Edit(Edit::Rename(id.to_string(), name)));
                ui.data_mut(|d| d.remove::<String>(key));
                ui.close();
            } else {
                ui.data_mut(|d| d.insert_temp(key, name));
            }
        });
    }
}

const ERROR_COLOR: Color32 = Color32::from_rgb(0xd6, 0x2f, 0x2f);
const WARNING_COLOR: Color32 = Color32::from_rgb(0xe0, 0x9a, 0x2b);

impl SnarlViewer<CanvasNode> for Viewer<'_> {
    fn title(&mut self, node: &CanvasNode) -> String {
        self.graph
            .node(&node.id)
            .map_or_else(|| node.id.clone(), |n| n.label().to_string())
    }

    fn node_frame(
        &mut self,
        default: egui::Frame,
        node: NodeId,
        _inputs: &[InPin],
        _outputs: &[OutPin],
        snarl: &Snarl<CanvasNode>,
    ) -> egui::Frame {
        let Some(n) = snarl.get_node(node) else {
            return default;
        };
        let mut frame = default;
        if self
            .statuses
            .get(&n.id)
            .and_then(NodeStatus::error)
            .is_some()
        {
            frame.stroke = Stroke::new(2.0, ERROR_COLOR);
        }
        if self.focused.as_deref() == Some(n.id.as_str()) {
            frame.stroke = Stroke::new(2.0, Color32::from_rgb(0x3a, 0x8e, 0xe6));
        }
        if self.graph.node(&n.id).is_some_and(|g| !g.enabled) {
            frame.fill = frame.fill.gamma_multiply(0.6);
        }
        frame
    }

    fn show_header(
        &mut self,
        node: NodeId,
        _inputs: &[InPin],
        _outputs: &[OutPin],
        ui: &mut Ui,
        snarl: &mut Snarl<CanvasNode>,
    ) {
        let Some(id) = node_id(snarl, node) else {
            return;
        };
        let Some(instance) = self.graph.node(&id) else {
            return;
        };
        let cluster = Cluster::of(&instance.def);
        ui.horizontal(|ui| {
            // The header's texts are not selectable and take no clicks: a click (Shift+click:
            // select, Ctrl+click: deselect) or a drag on the title goes to the node itself.
            ui.style_mut().interaction.selectable_labels = false;
            let title = ui
                .add(
                    egui::Label::new(egui::RichText::new(instance.label()).strong())
                        .sense(egui::Sense::hover()),
                )
                .on_hover_ui(|ui| {
                    ui.set_max_width(360.0);
                    if instance.name.is_some() {
                        // A named node: its id is what wires, `--set` and scripts use.
                        ui.label(format!("id: {id}"));
                    }
                    ui.strong(instance.def.id.as_ref());
                    ui.label(instance.def.doc.as_ref());
                    if cluster.is_some() {
                        ui.weak("double-click to open it");
                    }
                });
            let double_clicked = title.contains_pointer()
                && ui.input(|i| {
                    i.pointer
                        .button_double_clicked(egui::PointerButton::Primary)
                });
            if cluster.is_some() && double_clicked {
                self.actions
                    .push(CanvasAction::Request(UiRequest::OpenCluster(id.clone())));
            }
            match cluster {
                Some(c) => {
                    ui.weak(format!("cluster · {}", c.label()))
                        .on_hover_text(instance.def.doc.as_ref());
                }
                None => {
                    ui.weak(instance.def.id.as_ref());
                }
            }
            if self.drag_locked.contains(&id) {
                ui.label("🔒").on_hover_text(
                    "locked for dragging: the Drag net tool leaves its inputs alone",
                );
            }
            let mut preview = instance.preview;
            // The eye takes the node's preview colour; right-click it to pick one.
            let eye = match instance.color {
                Some([r, g, b]) => egui::RichText::new("👁").color(Color32::from_rgb(r, g, b)),
                None => egui::RichText::new("👁"),
            };
            let toggle = ui.toggle_value(&mut preview, eye).on_hover_text(
                "preview this node's geometry in the viewport (right-click: its colour)",
            );
            if toggle.changed() {
                self.actions
                    .push(CanvasAction::Edit(Edit::SetPreview(id.clone(), preview)));
            }
            toggle.context_menu(|ui| {
                if let Some(color) = crate::viewport::colors::pick(ui, instance.color) {
                    self.actions
                        .push(CanvasAction::Edit(Edit::SetColor(id.clone(), color)));
                }
            });
            let mut enabled = instance.enabled;
            if ui
                .toggle_value(&mut enabled, "✔")
                .on_hover_text("enable / disable this node (disabled nodes do not run)")
                .changed()
            {
                self.actions
                    .push(CanvasAction::Edit(Edit::SetEnabled(id.clone(), enabled)));
            }
            match self.statuses.get(&id) {
                Some(NodeStatus::Error(m)) => {
                    ui.colored_label(ERROR_COLOR, "⛔").on_hover_text(m);
                }
                Some(NodeStatus::Blocked(m)) => {
                    ui.colored_label(Color32::GRAY, "⏸").on_hover_text(m);
                }
                Some(s @ NodeStatus::Ok { .. }) if !s.warnings().is_empty() => {
                    ui.colored_label(WARNING_COLOR, "⚠")
                        .on_hover_text(s.warnings().join("\n"));
                }
                Some(NodeStatus::Running { last_ms }) => {
                    ui.spinner().on_hover_text(if *last_ms > 0.0 {
                        format!(
                            "running after the 3D view was updated (last run {})",
                            crate::worker::format_ms(*last_ms)
                        )
                    } else {
                        "running after the 3D view was updated".to_string()
                    });
                }
                _ => {}
            }
        });
    }

    fn inputs(&mut self, node: &CanvasNode) -> usize {
        self.graph.node(&node.id).map_or(0, |n| n.def.inputs.len())
    }

    fn outputs(&mut self, node: &CanvasNode) -> usize {
        self.graph.node(&node.id).map_or(0, |n| n.def.outputs.len())
    }

    #[allow(refining_impl_trait)]
    fn show_input(
        &mut self,
        pin: &InPin,
        ui: &mut Ui,
        snarl: &mut Snarl<CanvasNode>,
    ) -> RecordingPin {
        let id = node_id(snarl, pin.id.node).unwrap_or_default();
        let key = (id.clone(), true, pin.id.input);
        let Some((instance, port)) = self
            .graph
            .node(&id)
            .and_then(|n| Some((n, n.def.inputs.get(pin.id.input)?)))
        else {
            return self.pin(key, PinInfo::circle());
        };
        let wired = !pin.remotes.is_empty();
        let missing = !wired && port.required() && instance.value(pin.id.input).is_none();
        ui.horizontal(|ui| {
            let (shown, full) = fitted_port_name(ui, &port.name);
            let mut text = egui::RichText::new(shown);
            if missing {
                text = text.color(ERROR_COLOR);
            }
            let k = pin.id.input;
            let label = ui
                .add(egui::Label::new(text).sense(egui::Sense::click()))
                .on_hover_text(format!(
                    "{full}{} — {}{}",
                    port.type_name(),
                    port.doc,
                    if missing {
                        "\n(required: connect it or set a value)"
                    } else {
                        ""
                    }
                ));
            if !wired {
                let candidates = crate::optimization::variable_candidates(instance, k);
                if !candidates.is_empty() {
                    label.context_menu(|ui| {
                        if let Some(c) = crate::optimization::variable_menu(ui, &candidates) {
                            self.actions.push(c.into());
                        }
                    });
                }
            }
            let unset_optional =
                port.optional && port.default.is_none() && instance.value(k).is_none();
            if !wired && unset_optional && widgets::has_editor(instance, k) {
                // An optional input left empty: the node sees "none", which differs from any value
                // an editor would show. Offer to set one.
                if ui
                    .small_button("set")
                    .on_hover_text("give this optional input a value")
                    .clicked()
                    && let Some(value) = widgets::initial_value(&port.ty)
                {
                    self.actions.push(CanvasAction::Edit(Edit::SetValue {
                        node: id.clone(),
                        input: port.name.to_string(),
                        value,
                    }));
                }
            } else if !wired && widgets::has_editor(instance, k) {
                ui.spacing_mut().slider_width = 110.0;
                let (changed, rect) = widgets::input_editor_with_rect(ui, instance, k);
                self.editors
                    .insert((id.clone(), port.name.to_string()), rect);
                // A right-click on a slider toggles its node's "locked for dragging" (the node's
                // context menu has the same switch): the Drag net tool leaves it alone.
                if port.widget() == cnets_engine::Widget::Slider
                    && ui.input(|i| i.pointer.secondary_clicked())
                    && pointer_on(ui, rect)
                {
                    self.actions
                        .push(CanvasAction::Request(UiRequest::ToggleDragLock(id.clone())));
                }
                if let Some(value) = changed {
                    self.actions.push(CanvasAction::Edit(Edit::SetValue {
                        node: id.clone(),
                        input: port.name.to_string(),
                        value,
                    }));
                }
                if port.optional
                    && port.default.is_none()
                    && ui
                        .small_button("×")
                        .on_hover_text("clear: leave this optional input empty")
                        .clicked()
                {
                    self.actions.push(CanvasAction::Edit(Edit::ClearValue {
                        node: id.clone(),
                        input: port.name.to_string(),
                    }));
                }
            } else if !wired && let Some(list) = self.list_views.on_node(instance, k) {
                // A literal list: its summary, and a button opening it as a table.
                ui.weak(&list.summary);
                if list.editable {
                    let button = ui.small_button("Edit…").on_hover_text(
                        "edit the list as a table: cells, rows, paste from a spreadsheet",
                    );
                    self.editors
                        .insert((id.clone(), port.name.to_string()), button.rect);
                    if button.clicked() {
                        self.actions
                            .push(CanvasAction::Request(UiRequest::EditList {
                                node: id.clone(),
                                input: port.name.to_string(),
                            }));
                    }
                }
            }
        });
        self.pin(key, pin_info(port))
    }

    #[allow(refining_impl_trait)]
    fn show_output(
        &mut self,
        pin: &OutPin,
        ui: &mut Ui,
        snarl: &mut Snarl<CanvasNode>,
    ) -> RecordingPin {
        let id = node_id(snarl, pin.id.node).unwrap_or_default();
        let key = (id.clone(), false, pin.id.output);
        let Some(port) = self
            .graph
            .node(&id)
            .and_then(|n| n.def.outputs.get(pin.id.output))
        else {
            return self.pin(key, PinInfo::circle());
        };
        let summary = match self.statuses.get(&id) {
            Some(NodeStatus::Ok { outputs, .. }) => outputs.get(pin.id.output).cloned(),
            _ => None,
        };
        let exported = self
            .graph
            .node(&id)
            .is_some_and(|n| n.def.has_flag(NodeFlag::Export));
        ui.horizontal(|ui| {
            if !exported {
                summary_slot(ui, summary.as_deref());
            }
            let (shown, full) = fitted_port_name(ui, &port.name);
            let label = ui
                .add(egui::Label::new(shown).sense(egui::Sense::click()))
                .on_hover_text(format!("{full}{} — {}", port.type_name(), port.doc));
            if crate::optimization::minimizable(port) {
                label.context_menu(|ui| {
                    let path = ValuePath {
                        node: id.clone(),
                        port: port.name.to_string(),
                        indices: Vec::new(),
                    };
                    if ui
                        .button("Minimize this output")
                        .on_hover_text("make it the optimization objective")
                        .clicked()
                    {
                        self.actions
                            .push(CanvasAction::Request(UiRequest::Minimize(path.clone())));
                        ui.close();
                    }
                    if ui
                        .button("Add as penalty")
                        .on_hover_text(
                            "a soft constraint of the optimization (edit it in the panel)",
                        )
                        .clicked()
                    {
                        self.actions
                            .push(CanvasAction::Request(UiRequest::Penalize(path)));
                        ui.close();
                    }
                });
            }
        });
        self.pin(key, pin_info(port))
    }

    fn has_body(&mut self, node: &CanvasNode) -> bool {
        self.graph
            .node(&node.id)
            .is_some_and(|n| mapper::is_mapper(n) || readout_output(&n.def).is_some())
    }

    fn show_body(
        &mut self,
        node: NodeId,
        _inputs: &[InPin],
        _outputs: &[OutPin],
        ui: &mut Ui,
        snarl: &mut Snarl<CanvasNode>,
    ) {
        let Some(id) = node_id(snarl, node) else {
            return;
        };
        if self
            .graph
            .node(&id)
            .is_some_and(|n| readout_output(&n.def).is_some())
        {
            let text = match self.statuses.get(&id) {
                Some(NodeStatus::Ok { readout, .. }) => readout.clone(),
                _ => None,
            };
            let rect = panel_readout(ui, &id, text.as_deref());
            self.panels.insert(id, rect);
            return;
        }
        if let Some(instance) = self.graph.node(&id) {
            let ran_on = self.statuses.get(&id).and_then(NodeStatus::ran_on);
            let r = mapper::show(ui, self.graph, instance, ran_on);
            self.plots.insert(id.clone(), r.plot);
            if let Some(shown) = r.shown {
                self.mapper_views.insert(id.clone(), shown);
            }
            if let Some(values) = r.changes {
                self.actions
                    .push(CanvasAction::Edit(Edit::SetValues { node: id, values }));
            }
            if let Some(a) = r.optimize {
                self.actions.push(a.into());
            }
        }
    }

    fn final_node_rect(
        &mut self,
        node: NodeId,
        rect: Rect,
        ui: &mut Ui,
        snarl: &mut Snarl<CanvasNode>,
    ) {
        let Some(id) = node_id(snarl, node) else {
            return;
        };
        // The pointer is in screen coordinates, the node rectangle in canvas coordinates.
        let pressed_at = ui.input(|i| {
            i.pointer
                .primary_pressed()
                .then(|| i.pointer.interact_pos())
                .flatten()
        });
        if pressed_at.is_some_and(|p| rect.contains(self.to_global.inverse() * p)) {
            self.pressed_node = Some(id.clone());
        }
        if self.chosen.contains(&id) {
            ui.painter().rect_stroke(
                rect.expand(3.0),
                6.0,
                Stroke::new(2.0, Color32::from_rgb(0x3a, 0x8e, 0xe6)),
                egui::StrokeKind::Outside,
            );
        }
        self.rects.insert(id, rect);
    }

    fn has_node_menu(&mut self, _node: &CanvasNode) -> bool {
        true
    }

    fn show_node_menu(
        &mut self,
        node: NodeId,
        _inputs: &[InPin],
        _outputs: &[OutPin],
        ui: &mut Ui,
        snarl: &mut Snarl<CanvasNode>,
    ) {
        let Some(id) = node_id(snarl, node) else {
            return;
        };
        if ui.button("Duplicate").clicked() {
            self.actions
                .push(CanvasAction::Edit(Edit::Duplicate(vec![id.clone()])));
            ui.close();
        }
        if ui.button("Delete").clicked() {
            self.actions
                .push(CanvasAction::Edit(Edit::Remove(vec![id.clone()])));
            ui.close();
        }
        self.rename_node_menu(ui, &id);
        let locked = self.drag_locked.contains(&id);
        let mut lock = locked;
        if ui
            .checkbox(&mut lock, "Locked for dragging")
            .on_hover_text(
                "the Drag net tool (G) leaves this node's inputs as they are while a cone-net is \
                 dragged",
            )
            .changed()
        {
            self.actions
                .push(CanvasAction::Request(UiRequest::ToggleDragLock(id.clone())));
            ui.close();
        }
        if self
            .graph
            .node(&id)
            .is_some_and(|n| n.def.outputs.iter().any(|p| p.ty == ValueType::Polyline))
            && ui
                .button("Internalise as editable points")
                .on_hover_text(
                    "insert a param.points node per curve, holding its points, wired into a \
                 curve.polyline: drag them in the 3D view",
                )
                .clicked()
        {
            self.actions
                .push(CanvasAction::Request(UiRequest::Internalise(id.clone())));
            ui.close();
        }
        ui.separator();
        let group = if self.selected.contains(&id) {
            self.selected.clone()
        } else {
            vec![id.clone()]
        };
        if ui
            .button(format!("Make cluster ({} nodes)", group.len()))
            .on_hover_text("replace the selected nodes by one cluster node (Ctrl+G)")
            .clicked()
        {
            self.actions.push(CanvasAction::Edit(Edit::MakeCluster {
                nodes: group,
                around: None,
            }));
            ui.close();
        }
        if self
            .graph
            .node(&id)
            .is_some_and(|n| Cluster::of(&n.def).is_some())
        {
            if ui.button("Open cluster").clicked() {
                self.actions
                    .push(CanvasAction::Request(UiRequest::OpenCluster(id.clone())));
                ui.close();
            }
            if ui
                .button("Explode cluster")
                .on_hover_text("put the cluster's nodes back in its place (Ctrl+Shift+G)")
                .clicked()
            {
                self.actions
                    .push(CanvasAction::Edit(Edit::ExplodeCluster(id.clone())));
                ui.close();
            }
        }
        if let Some(n) = self.graph.node(&id)
            && (n.def.id == cnets_engine::cluster::INPUT_TYPE
                || n.def.id == cnets_engine::cluster::OUTPUT_TYPE)
        {
            ui.separator();
            self.rename_port_menu(ui, &id);
        }
        if let Some(n) = self.graph.node(&id)
            && n.def.has_flag(NodeFlag::Export)
        {
            ui.weak("runs on File › Export");
        }
    }

    fn has_graph_menu(&mut self, _pos: Pos2, _snarl: &mut Snarl<CanvasNode>) -> bool {
        true
    }

    fn show_graph_menu(&mut self, pos: Pos2, ui: &mut Ui, _snarl: &mut Snarl<CanvasNode>) {
        if ui.button("Add node…").clicked() {
            self.actions
                .push(CanvasAction::Request(UiRequest::OpenPalette([
                    pos.x, pos.y,
                ])));
            ui.close();
        }
    }

    fn connect(&mut self, from: &OutPin, to: &InPin, snarl: &mut Snarl<CanvasNode>) {
        if let Some((from, output, to, input)) = self.names(snarl, from, to) {
            self.actions.push(CanvasAction::Edit(Edit::Connect {
                from,
                output,
                to,
                input,
                replace: !self.shift,
            }));
        }
    }

    fn disconnect(&mut self, from: &OutPin, to: &InPin, snarl: &mut Snarl<CanvasNode>) {
        if let Some((from, output, to, input)) = self.names(snarl, from, to) {
            self.actions.push(CanvasAction::Edit(Edit::Disconnect {
                from,
                output,
                to,
                input,
            }));
        }
    }

    fn drop_inputs(&mut self, pin: &InPin, snarl: &mut Snarl<CanvasNode>) {
        if let Some((node, input)) = self.pin_port(snarl, pin.id.node, true, pin.id.input) {
            self.actions
                .push(CanvasAction::Edit(Edit::DropInputs { node, input }));
        }
    }

    fn drop_outputs(&mut self, pin: &OutPin, snarl: &mut Snarl<CanvasNode>) {
        if let Some((node, output)) = self.pin_port(snarl, pin.id.node, false, pin.id.output) {
            self.actions
                .push(CanvasAction::Edit(Edit::DropOutputs { node, output }));
        }
    }

    fn current_transform(&mut self, to_global: &mut TSTransform, _snarl: &mut Snarl<CanvasNode>) {
        if let Some(fit) = self.fit.take() {
            *to_global = fit;
        }
        self.to_global = *to_global;
    }
}

/// Whether the pointer is on `rect` (in `ui`'s canvas coordinates) and no window or popup lies
/// over the canvas there. The canvas's node layers are transformed but are not areas, so egui's
/// `rect_contains_pointer` (which asks for the topmost area) does not see them.
fn pointer_on(ui: &Ui, rect: Rect) -> bool {
    let ctx = ui.ctx();
    let Some(p) = ctx.input(|i| i.pointer.interact_pos()) else {
        return false;
    };
    let to_global = ctx
        .layer_transform_to_global(ui.layer_id())
        .unwrap_or_default();
    (to_global * ui.clip_rect().intersect(rect)).contains(p)
        && ctx
            .layer_id_at(p)
            .is_none_or(|l| l.order == egui::Order::Background)
}
