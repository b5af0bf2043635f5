//! Command dispatch: menu actions and shortcuts, canvas and 3D-view actions, UI requests, edits.

use crate::canvas::CanvasAction;
use crate::clipboard::Clipboard;
use crate::edit;
use crate::edit::Edit;
use crate::export;
use crate::file_dialog::FileDialog;
use crate::file_dialog::Purpose;
use crate::menus::MenuAction;
use crate::request::UiRequest;
use crate::unsaved::Replace;
use crate::viewport::ViewportAction;
use cnets_engine::optimize::Variable;
use egui::Key;
use egui::KeyboardShortcut;
use egui::Modifiers;
use std::path::Path;

use super::EditorApp;
use super::files::user_folder;

/// The canvas room kept for a new node (canvas units).
const NEW_NODES_SIZE: egui::Vec2 = egui::vec2(460.0, 140.0);

/// The canvas room of a drawn curve's nodes: its `param.points` and, right of it
/// ([`crate::edit::CURVE_NODE_STEP`]), the curve node (about 390 wide with its output summary).
const CURVE_NODES_SIZE: egui::Vec2 = egui::vec2(crate::edit::CURVE_NODE_STEP[0] + 390.0, 150.0);

impl EditorApp {
    /// Adds a node of type `type_id` at a canvas position; returns its id.
    pub fn add_node(&mut self, type_id: &str, at: [f32; 2]) -> Option<String> {
        let id = self.doc.fresh_id(type_id);
        let r = self.doc.edit(None, |g, _| {
            g.add_node(&id, type_id).map_err(|e| e.to_string())?;
            g.set_position(&id, at).map_err(|e| e.to_string())
        });
        match r {
            Ok(()) => {
                self.canvas.focused = Some(id.clone());
                Some(id)
            }
            Err(e) => {
                self.message = e;
                None
            }
        }
    }

    /// In a web page: the actions the page carries out instead of files and dialogs (open by the
    /// browser's picker, save and export as downloads, copy a share link). Returns whether
    /// `action` was one of them.
    pub(super) fn run_in_page(&mut self, action: &MenuAction) -> bool {
        let name = self
            .doc
            .resolve_file()
            .and_then(Path::file_stem)
            .map_or_else(
                || "cone-net".to_string(),
                |s| s.to_string_lossy().into_owned(),
            );
        let request = match action {
            MenuAction::Open => crate::page::PageRequest::PickFile,
            MenuAction::Save | MenuAction::SaveAs => {
                let ron = self.doc.to_ron();
                self.recovery.clear();
                self.message = format!("downloaded {name}.ron");
                // Saved (as a download): the unsaved-changes question's "Save" goes on.
                self.doc.mark_saved();
                if let Some(page) = &mut self.page {
                    page.requests.push(crate::page::PageRequest::Download {
                        name: format!("{name}.ron"),
                        bytes: ron.into_bytes(),
                    });
                }
                if let Some(r) = self.modals.after_save.take() {
                    self.perform(r);
                }
                return true;
            }
            MenuAction::CopyLink => crate::page::PageRequest::CopyLink {
                ron: self.doc.to_ron(),
            },
            MenuAction::Export(_) | MenuAction::RunExports => {
                let base = self.doc.base_dir();
                let folder = Path::new("/downloads");
                let written = match action {
                    MenuAction::Export(format) => {
                        export::export(&self.doc.graph, base, &[], *format, folder, &name)
                    }
                    _ => {
                        export::run_exports(&self.doc.eval_graph(), base, &[], folder).map(|runs| {
                            export::ExportReport {
                                folder: folder.to_path_buf(),
                                runs,
                            }
                            .files()
                        })
                    }
                };
                match written {
                    Ok(files) => {
                        let mut written = cnets_engine::files::memory::take_written();
                        written.retain(|(p, _)| files.contains(p));
                        self.message = format!("exported {} file(s)", written.len());
                        if let Some(page) = &mut self.page {
                            for (p, bytes) in written {
                                let name = p.file_name().map_or_else(
                                    || "export".to_string(),
                                    |n| n.to_string_lossy().into_owned(),
                                );
                                page.requests
                                    .push(crate::page::PageRequest::Download { name, bytes });
                            }
                        }
                    }
                    Err(e) => self.message = format!("export failed: {e}"),
                }
                return true;
            }
            MenuAction::LibraryFolder | MenuAction::Quit => {
                self.message = "not in the browser: there is no file system here".into();
                return true;
            }
            _ => return false,
        };
        if let Some(page) = &mut self.page {
            page.requests.push(request);
        }
        true
    }

    /// Carries out a canvas action (an edit or a UI request); a refusal becomes the status
    /// message. Returns whether it applied.
    pub fn apply(&mut self, action: CanvasAction) -> bool {
        match action {
            CanvasAction::Edit(e) => self.edit(e),
            CanvasAction::Request(r) => self.handle(r),
        }
    }

    /// Applies a document edit ([`edit::apply`]); a refusal becomes the status message. Returns
    /// whether it applied.
    pub fn edit(&mut self, edit: Edit) -> bool {
        let made_cluster = matches!(edit, Edit::MakeCluster { .. });
        match edit::apply(&mut self.doc, edit) {
            Ok(created) => {
                if made_cluster && let Some(id) = created.first() {
                    self.canvas.selected.clear();
                    self.canvas.focused = Some(id.clone());
                    self.message =
                        format!("made cluster '{id}': double-click its title to open it");
                }
                true
            }
            Err(e) => {
                self.message = format!("refused: {e}");
                false
            }
        }
    }

    /// Carries out what the 3D view asked for: an edit, selecting a node, a drawn curve.
    pub fn apply_view(&mut self, action: ViewportAction) {
        match action {
            ViewportAction::Edit(e) => {
                self.edit(e);
            }
            ViewportAction::SelectNode(id) => {
                self.canvas.focused = Some(id.clone());
                self.canvas.select(vec![id.clone()]);
                self.message = format!("selected '{id}'");
            }
            ViewportAction::AddCurve(curve) => self.add_curve(curve),
            ViewportAction::Message(m) => self.message = m,
            ViewportAction::DragNet(target) => self.drag_net_to(target),
            ViewportAction::DragNetEnd => self.end_net_drag(),
            ViewportAction::AddCPlane(plane) => self.add_cplane(plane, "from 3 points"),
        }
    }

    /// Adds a drawn curve as a `param.points` node wired into a `curve.spline` (or
    /// `curve.polyline`), placed on the canvas below the selection (else in the middle of the
    /// canvas), and selects the curve node alone (one undo step; Delete then removes the curve,
    /// not its points too).
    pub fn add_curve(&mut self, curve: crate::viewport::DrawnCurve) {
        // Below the selection (the curve drawn before: curves stack up on the left, as
        // parameters do in Grasshopper), else in the middle of the canvas.
        let at = match self.canvas.bounds_of(&self.canvas.targets()) {
            Some(r) => {
                self.place_in_view(egui::pos2(r.left(), r.bottom() + 40.0), CURVE_NODES_SIZE)
            }
            None => {
                let centre = self.canvas.to_canvas(self.canvas.screen_rect().center());
                self.place_in_view(centre - CURVE_NODES_SIZE / 2.0, CURVE_NODES_SIZE)
            }
        };
        if let Some(created) = self.edit_created(Edit::AddCurves {
            curves: vec![curve],
            at,
        }) {
            self.message = format!(
                "added {}: wire its curve into a construction",
                created.join(" and ")
            );
            let curve: Vec<String> = created.last().cloned().into_iter().collect();
            self.canvas.focused = curve.first().cloned();
            self.canvas.select(curve);
        }
    }

    /// Most curves one "Internalise" turns into points.
    pub const MAX_INTERNALISED: usize = 64;

    /// Turns the curves node `id` outputs into `param.points` + `curve.polyline` pairs right of
    /// it (one undo step): the node is evaluated now, on the document's graph and folder.
    pub fn internalise(&mut self, id: &str) -> Result<String, String> {
        let graph = self.doc.eval_graph();
        let index = graph.index(id).map_err(|e| e.to_string())?;
        let ctx = self.session().context(self.doc.base_dir());
        let mut evaluator = cnets_engine::Evaluator::new();
        evaluator.evaluate(&graph, &[index], &ctx, &mut |_, _| {});
        let result = evaluator
            .result(&graph, id)
            .ok_or_else(|| format!("'{id}' did not run"))?;
        let outputs = result.outputs().ok_or_else(|| {
            result
                .error()
                .map_or("it failed".into(), |e| e.into_owned())
        })?;
        let mut curves = Vec::new();
        fn gather(v: &cnets_engine::Value, into: &mut Vec<crate::viewport::DrawnCurve>) {
            match v {
                cnets_engine::Value::Polyline(p) => into.push(crate::viewport::DrawnCurve {
                    points: p.points.clone(),
                    closed: p.closed,
                    spline: false,
                }),
                cnets_engine::Value::List(items) => items.iter().for_each(|i| gather(i, into)),
                _ => {}
            }
        }
        for v in &outputs.values {
            gather(v, &mut curves);
        }
        if curves.is_empty() {
            return Err(format!("'{id}' outputs no curves"));
        }
        let total = curves.len();
        curves.truncate(Self::MAX_INTERNALISED);
        let at = match self.canvas.node_rect(id) {
            Some(r) => [r.right() + 60.0, r.top()],
            None => self.new_node_place(),
        };
        let created = self
            .edit_created(Edit::AddCurves { curves, at })
            .ok_or_else(|| self.message.clone())?;
        self.canvas.select(created.clone());
        Ok(if total > Self::MAX_INTERNALISED {
            format!(
                "internalised the first {} of {total} curves of '{id}'",
                Self::MAX_INTERNALISED
            )
        } else {
            format!("internalised {total} curve(s) of '{id}' as editable points")
        })
    }

    /// Where new nodes go on the canvas: right of the selected (or focused) nodes, else the
    /// middle of the visible canvas — moved down past any node there.
    pub fn new_node_place(&mut self) -> [f32; 2] {
        let start = match self.canvas.bounds_of(&self.canvas.targets()) {
            Some(r) => egui::pos2(r.right() + 60.0, r.top()),
            None => {
                // Centred in the visible canvas.
                self.canvas.to_canvas(self.canvas.screen_rect().center()) - NEW_NODES_SIZE / 2.0
            }
        };
        self.place_in_view(start, NEW_NODES_SIZE)
    }

    /// The first free place at or below `start` (canvas coordinates) for new nodes of about
    /// `size`, moved into the visible part of the canvas (never under the 3D view beside it);
    /// when the free place is out of view (the view is full of nodes) or larger than the view,
    /// the canvas pans to it and zooms out until it shows it whole.
    pub fn place_in_view(&mut self, start: egui::Pos2, size: egui::Vec2) -> [f32; 2] {
        let screen = self.canvas.screen_rect();
        if !screen.is_positive() {
            // Not drawn yet (a narrow layout's hidden canvas): where it was asked.
            let p = self.canvas.free_spot(start, size);
            return [p.x, p.y];
        }
        let margin = egui::vec2(20.0, 20.0) / self.canvas.zoom().max(1e-3);
        let view = egui::Rect::from_min_max(
            self.canvas.to_canvas(screen.min),
            self.canvas.to_canvas(screen.max),
        )
        .shrink2(margin);
        // The box inside the view: its right and bottom edges first, then its left and top
        // (a box larger than the view keeps its top-left corner in view).
        let mut p = start;
        p.x = p.x.min(view.right() - size.x).max(view.left());
        p.y = p.y.min(view.bottom() - size.y).max(view.top());
        let p = self.canvas.free_spot(p, size);
        let placed = egui::Rect::from_min_size(p, size);
        if !view.contains_rect(placed) {
            // Out of view, or larger than the view: centre it, zooming out as far as it must
            // (down to the canvas's smallest zoom).
            let room = screen.shrink(20.0).size();
            let fits = (room.x / size.x).min(room.y / size.y);
            let zoom = self.canvas.zoom().min(fits).max(crate::canvas::MIN_ZOOM);
            self.canvas.zoom_to(zoom, Some(placed.center()));
        }
        [p.x, p.y]
    }

    /// Applies an edit and returns the nodes it created (`None` when refused: the message says
    /// why).
    pub fn edit_created(&mut self, edit: Edit) -> Option<Vec<String>> {
        match edit::apply(&mut self.doc, edit) {
            Ok(created) => Some(created),
            Err(e) => {
                self.message = format!("refused: {e}");
                None
            }
        }
    }

    /// Carries out a UI request; a refusal becomes the status message. Returns whether it was
    /// carried out.
    pub fn handle(&mut self, request: UiRequest) -> bool {
        let handled = match request {
            UiRequest::OpenPalette(at) => {
                // At the click: the canvas point on screen.
                let screen = self.canvas.to_screen(egui::pos2(at[0], at[1]));
                self.palette.open_at_screen(at, screen);
                return true;
            }
            UiRequest::OpenCluster(id) => {
                self.open_cluster(&id);
                return true;
            }
            UiRequest::Optimize {
                path,
                min,
                max,
                prepare,
            } => {
                let variable = Variable {
                    input: path,
                    min,
                    max,
                };
                self.optimization.open = true;
                self.optimization
                    .add_variable(&mut self.doc, variable, prepare)
            }
            UiRequest::Minimize(path) => {
                self.optimization.open = true;
                self.optimization.set_objective(&mut self.doc, path)
            }
            UiRequest::Penalize(path) => {
                self.optimization.open = true;
                self.optimization.add_penalty(&mut self.doc, path)
            }
            UiRequest::Internalise(id) => self.internalise(&id),
            UiRequest::ToggleDragLock(id) => {
                self.toggle_drag_lock(id);
                return true;
            }
            UiRequest::EditList { node, input } => {
                // Beside the Edit… button clicked (else the pointer).
                let at = self
                    .canvas
                    .editor_screen_rect(&node, &input)
                    .map(|r| r.right_top() + egui::vec2(16.0, -8.0))
                    .or(self.pointer);
                self.list_editors
                    .open(self.doc.view_path(), &node, &input, at);
                return true;
            }
        };
        match handled {
            Ok(m) => {
                self.message = m;
                true
            }
            Err(e) => {
                self.message = format!("refused: {e}");
                false
            }
        }
    }

    /// Carries out a menu action or shortcut.
    pub fn run(&mut self, action: MenuAction) {
        if self.page.is_some() && self.run_in_page(&action) {
            return;
        }
        match action {
            MenuAction::New => self.request(Replace::New),
            MenuAction::Open => {
                let start = self
                    .doc
                    .path
                    .as_deref()
                    .and_then(Path::parent)
                    .map_or_else(|| self.examples_dir.clone(), Path::to_path_buf);
                self.modals
                    .open(super::Modal::File(FileDialog::new(Purpose::Open, &start)));
            }
            MenuAction::OpenPath(p) => self.request(Replace::Open(p)),
            MenuAction::OpenExample(p) => self.request(Replace::Example(p)),
            MenuAction::Save => match self.doc.path.clone() {
                Some(p) => self.save_as(&p),
                None => self.run(MenuAction::SaveAs),
            },
            MenuAction::SaveAs => {
                let start = self.doc.path.clone().unwrap_or_else(|| {
                    // An untitled copy of an example is saved into the designer's own folder
                    // (never next to the shipped file), under the example's name.
                    let name = self
                        .doc
                        .origin
                        .as_deref()
                        .and_then(Path::file_name)
                        .map_or_else(|| "untitled.ron".into(), |n| n.to_os_string());
                    user_folder(&self.examples_dir).join(name)
                });
                self.modals
                    .open(super::Modal::File(FileDialog::new(Purpose::SaveAs, &start)));
            }
            MenuAction::Export(format) => {
                if export::export_node(&self.registry, format).is_none() {
                    self.message = format!(
                        "no {} export node is registered in this build",
                        format.extension()
                    );
                } else {
                    // Asks for the name, starting with the document's (no fixed names).
                    self.modals
                        .remove(|m| matches!(m, super::Modal::ExportReport(_)));
                    let start = self.export_folder().join(format!(
                        "{}.{}",
                        self.export_name(),
                        format.extension()
                    ));
                    self.modals.open(super::Modal::File(FileDialog::new(
                        Purpose::ExportFile(format),
                        &start,
                    )));
                }
            }
            MenuAction::RunExports => {
                if export::export_nodes(&self.doc.eval_graph()).is_empty() {
                    self.message = "this graph has no export nodes".into();
                } else {
                    let start = self.export_folder();
                    self.modals
                        .remove(|m| matches!(m, super::Modal::ExportReport(_)));
                    self.modals.open(super::Modal::File(FileDialog::new(
                        Purpose::RunExports,
                        &start,
                    )));
                }
            }
            MenuAction::Undo => {
                if !self.doc.undo() {
                    self.message = "nothing to undo".into();
                }
            }
            MenuAction::Redo => {
                if !self.doc.redo() {
                    self.message = "nothing to redo".into();
                }
            }
            MenuAction::Delete => {
                let targets = self.canvas.targets();
                if !targets.is_empty() {
                    self.edit(Edit::Remove(targets));
                    self.canvas.focused = None;
                }
            }
            MenuAction::Duplicate => {
                let targets = self.canvas.targets();
                if !targets.is_empty() {
                    self.edit(Edit::Duplicate(targets));
                }
            }
            MenuAction::Copy => {
                self.clipboard = Clipboard::copy(&self.doc.graph, &self.canvas.targets());
                self.message = format!("copied {} nodes", self.clipboard.len());
            }
            MenuAction::Paste => {
                let clip = self.clipboard.clone();
                if !clip.is_empty() {
                    let r = self
                        .doc
                        .edit(None, |g, _| clip.paste(g, [40.0, 40.0], false));
                    if let Err(e) = r {
                        self.message = e;
                    }
                }
            }
            MenuAction::AddNode => {
                let at = self.new_node_place();
                self.palette.open_at(at);
            }
            MenuAction::Fit => self.viewport.fit(),
            MenuAction::FitCanvas => self.canvas.fit(),
            MenuAction::Arrange => {
                let moves = self.canvas.arrangement(&self.doc.graph);
                if !moves.is_empty() && self.edit(Edit::Move(moves)) {
                    self.doc.history.end_gesture();
                    self.canvas.fit();
                }
            }
            MenuAction::SetPreview(o) => self.viewport.display_mut().options = o,
            MenuAction::MakeCluster => {
                let targets = self.canvas.targets();
                if targets.is_empty() {
                    self.message =
                        "select the nodes to put in a cluster (Shift+click, Shift+drag)".into();
                } else {
                    self.make_cluster(&targets);
                }
            }
            MenuAction::ExplodeCluster => match self.targeted_cluster() {
                Some(id) => {
                    self.edit(Edit::ExplodeCluster(id));
                }
                None => self.message = "focus a cluster node to explode it".into(),
            },
            MenuAction::OpenCluster => match self.targeted_cluster() {
                Some(id) => self.open_cluster(&id),
                None => self.message = "focus a cluster node to open it".into(),
            },
            MenuAction::LeaveTo(depth) => self.leave_to(depth),
            MenuAction::ToggleOptimization => self.optimization.open = !self.optimization.open,
            MenuAction::ToggleParameters => toggle(&mut self.panels.parameters_open),
            MenuAction::LibraryFolder => {
                let start = self.settings.library_dir();
                self.modals.open(super::Modal::File(FileDialog::new(
                    Purpose::LibraryFolder,
                    &start,
                )));
            }
            MenuAction::Quit => self.request_close(),
            MenuAction::RestoreKept => self.restore_kept(),
            MenuAction::CopyLink => {
                self.message = "share links are made by the web page (cnets in the browser)".into()
            }
            MenuAction::View(v) => self.viewport.set_view(v),
            MenuAction::FrameSelection => {
                let targets = self.canvas.targets();
                self.viewport.frame_selection(&targets);
            }
            MenuAction::Tool(t) => self.viewport.toggle_tool(t),
            MenuAction::ToggleSnap => toggle(&mut self.viewport.display_mut().snap),
            MenuAction::ToggleGrid => toggle(&mut self.viewport.display_mut().show_grid),
            MenuAction::ToggleDimensions => {
                toggle(&mut self.viewport.display_mut().show_dimensions)
            }
            MenuAction::ToggleOnlySelected => {
                toggle(&mut self.viewport.display_mut().only_selected)
            }
            MenuAction::PerspectivePlane(p) => {
                self.viewport.set_perspective_plane(p, p.label());
            }
            MenuAction::NamedCPlane(name) => self.choose_cplane(&name),
            MenuAction::CPlaneFromPoints => self.start_three_point_cplane(),
            MenuAction::CPlaneThroughSelection => self.cplane_through_selection(),
        }
    }

    pub(super) fn shortcuts(&mut self, ctx: &egui::Context) {
        let typing = ctx.egui_wants_keyboard_input();
        let cmd = Modifiers::COMMAND;
        let shift_cmd = Modifiers::COMMAND | Modifiers::SHIFT;
        let mut actions = Vec::new();
        ctx.input_mut(|i| {
            // Longer shortcuts first, so Ctrl+Shift+Z is not taken as Ctrl+Z.
            let mut take = |m: Modifiers, k: Key, a: MenuAction| {
                if i.consume_shortcut(&KeyboardShortcut::new(m, k)) {
                    actions.push(a);
                }
            };
            take(shift_cmd, Key::Z, MenuAction::Redo);
            take(shift_cmd, Key::G, MenuAction::ExplodeCluster);
            take(shift_cmd, Key::S, MenuAction::SaveAs);
            take(cmd, Key::S, MenuAction::Save);
            take(cmd, Key::O, MenuAction::Open);
            take(cmd, Key::Q, MenuAction::Quit);
            if !typing {
                take(cmd, Key::Z, MenuAction::Undo);
                take(cmd, Key::Y, MenuAction::Redo);
                take(cmd, Key::D, MenuAction::Duplicate);
                take(cmd, Key::L, MenuAction::Arrange);
                take(cmd, Key::P, MenuAction::ToggleParameters);
                take(cmd, Key::G, MenuAction::MakeCluster);
                take(cmd, Key::C, MenuAction::Copy);
                take(cmd, Key::V, MenuAction::Paste);
                take(Modifiers::NONE, Key::Delete, MenuAction::Delete);
                take(Modifiers::NONE, Key::F, MenuAction::Fit);
                take(Modifiers::NONE, Key::Home, MenuAction::FitCanvas);
            }
        });
        // Esc backs out of an opened cluster (the palette and dialogs take it first).
        let depth = self.doc.depth();
        if depth > 0
            && !typing
            && !self.palette.open
            && self.modals.file_dialog().is_none()
            && ctx.input(|i| i.key_pressed(Key::Escape))
        {
            actions.push(MenuAction::LeaveTo(depth - 1));
        }
        // Copy and paste arrive as events, not key presses, on some platforms.
        if !typing {
            ctx.input(|i| {
                for e in &i.events {
                    match e {
                        egui::Event::Copy => actions.push(MenuAction::Copy),
                        egui::Event::Paste(_) => actions.push(MenuAction::Paste),
                        _ => {}
                    }
                }
            });
        }
        for a in actions {
            self.run(a);
        }
    }
}

/// Flips a display toggle.
fn toggle(flag: &mut bool) {
    *flag = !*flag;
}
