//! One frame of the editor: the panels (menu, status, parameters, 3D view, canvas) and what runs
//! around them each frame.

use crate::canvas::Canvas;
use crate::canvas::CanvasAction;
use crate::document::GraphDocument;
use crate::menus;
use crate::menus::MenuContext;
use crate::palette;
use crate::palette::Pick;
use crate::recovery::Autosave;
use crate::unsaved::Replace;
use crate::viewport::ViewportInput;
use egui::Ui;
use std::collections::HashMap;
use std::path::PathBuf;
use web_time::Duration;
use web_time::Instant;

use super::{EditorApp, OVERLAP_HINT, WATCH_INTERVAL};

impl EditorApp {
    /// One frame of the editor.
    pub fn ui(&mut self, ui: &mut Ui) {
        let frame_started = web_time::Instant::now();
        let ctx = ui.ctx().clone();
        self.poll_worker();
        self.poll_net_drag();
        self.optimization.poll();
        // An active list editor window takes pasted text, Copy and Delete before the shortcuts.
        self.list_editors.claim_input(&ctx, &self.doc.view_path());
        self.shortcuts(&ctx);
        if self.watching.last_watch.elapsed() >= WATCH_INTERVAL {
            self.check_cluster_files();
            self.check_imported_files();
        }
        let version_before = self.doc.version();

        egui::Panel::top("cnets-menu").show(ui, |ui| {
            let mc = MenuContext {
                examples: &self.examples,
                recent: &self.settings.recent,
                can_undo: self.doc.history.can_undo(),
                can_redo: self.doc.history.can_redo(),
                can_paste: !self.clipboard.is_empty(),
                preview: self.viewport.display().options,
                depth: self.doc.depth(),
                optimization: self.optimization.open,
                parameters: self.panels.parameters_open,
                library: &self.library.dirs[0],
                web: self.page.is_some(),
                view: menus::ViewMenuState {
                    view: self.viewport.framing().view,
                    snap: self.viewport.display().snap,
                    grid: self.viewport.display().show_grid,
                    dimensions: self.viewport.display().show_dimensions,
                    only_selected: self.viewport.display().only_selected,
                    perspective_plane: self.viewport.framing().perspective_plane,
                },
                cplanes: &self.doc.meta.cplanes,
                kept_recovery: self.kept_recovery.as_deref(),
                exports: self
                    .doc
                    .graph
                    .nodes()
                    .filter(|(_, n)| n.enabled && n.def.has_flag(cnets_engine::NodeFlag::Export))
                    .count(),
            };
            if let Some(a) = menus::menu_bar(ui, &mc) {
                self.run(a);
            }
        });
        // Below a width threshold (a phone, a narrow window): the 3D view over the parameters,
        // the canvas behind a tab (crate::narrow).
        let narrow = crate::narrow::is_narrow(&ctx);
        self.panels.start_frame();
        egui::Panel::bottom("cnets-status").show(ui, |ui| {
            if narrow {
                crate::narrow::status_bar(ui, &self.doc.title(), &self.message);
                return;
            }
            ui.horizontal(|ui| {
                ui.label(self.doc.title());
                ui.separator();
                if self.show_timings {
                    if self.evaluation.worker.busy() {
                        ui.spinner();
                    }
                    ui.weak(format!(
                        "eval {:.1} ms · scene {:.1} ms · change-to-picture {:.1} ms",
                        self.evaluation.latency.eval_ms,
                        self.evaluation.latency.scene_ms,
                        self.evaluation.latency.last_ms
                    ));
                }
                ui.separator();
                ui.label(&self.message);
                if self.fresh.overlap_hint {
                    ui.separator();
                    ui.label(OVERLAP_HINT);
                }
            });
        });
        if self.optimization.open {
            let base = self.doc.base_dir();
            egui::Panel::bottom("cnets-optimization")
                .resizable(true)
                .default_size(270.0)
                .min_size(120.0)
                .show(ui, |ui| {
                    if let Some(m) = self.optimization.show(ui, &mut self.doc, base)
                        && !m.is_empty()
                    {
                        self.message = m;
                    }
                });
        }
        if narrow {
            crate::narrow::panels(self, ui);
        } else {
            if self.panels.parameters_open {
                let actions = egui::Panel::left("cnets-parameters")
                    .resizable(true)
                    .default_size(260.0)
                    .min_size(180.0)
                    .show(ui, |ui| self.parameters_contents(ui))
                    .inner;
                for a in actions {
                    self.apply(a);
                }
            }
            egui::Panel::right("cnets-viewport")
                .resizable(true)
                .default_size(ui.available_width() * 0.45)
                .min_size(200.0)
                .frame(egui::Frame::NONE)
                .show(ui, |ui| self.viewport_contents(ui, true));
            egui::CentralPanel::default()
                .frame(egui::Frame::NONE)
                .show(ui, |ui| self.canvas_contents(ui));
        }
        if let Some(m) = self.list_editors.show(&ctx, &mut self.doc) {
            self.message = m;
        }

        if self.palette.open && !self.palette_was_open {
            self.library.scan(&self.registry);
        }
        self.palette_was_open = self.palette.open;
        match palette::show(
            &ctx,
            &mut self.palette,
            &self.registry,
            self.library.entries(),
        ) {
            Some(Pick::Type(type_id)) => {
                let at = self.palette.at;
                self.add_node(&type_id, at);
            }
            Some(Pick::Library(entry)) => {
                let at = self.palette.at;
                self.add_library_cluster(&entry, at);
            }
            None => {}
        }
        self.fresh
            .watch_overlaps(&self.canvas, self.doc.graph.node_count());
        // A path input's Browse… clicked this frame (on the canvas or in the parameter panel).
        if let Some((node, input)) = crate::widgets::take_browse_request(&ctx) {
            self.browse(&node, &input);
        }

        // A gesture ends when the pointer is released and no text field is being typed in (so a
        // drag, or typing a name, is one undo step); a released drag of the net whose last answer
        // the drag worker still solves closes its own.
        if !ctx.input(|i| i.pointer.any_down())
            && !ctx.egui_wants_keyboard_input()
            && !self.net_drag_closing()
        {
            self.doc.history.end_gesture();
        }
        // The window's close button: ask first when there are unsaved changes.
        if ctx.input(|i| i.viewport().close_requested()) && !self.quit {
            if self.doc.is_dirty() && !self.close_confirmed {
                ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
            }
            self.request(Replace::Quit);
        }
        // A graph file dropped on the window, or sent by `cnets-editor FILE` (in a web page the
        // page reads dropped files: they have no path there).
        let in_page = self.page.is_some();
        let dropped: Vec<PathBuf> = ctx.input(|i| {
            i.raw
                .dropped_files
                .iter()
                .map(|f| f.path().to_path_buf())
                .filter(|p| !in_page && !p.as_os_str().is_empty())
                .collect()
        });
        let sent: Vec<PathBuf> = self
            .inbox
            .as_ref()
            .map(|r| r.try_iter().collect())
            .unwrap_or_default();
        if let Some(p) = dropped.into_iter().chain(sent).last() {
            self.request(Replace::Open(p));
        }
        self.poll_loading(&ctx);
        self.poll_waiting();
        self.show_modal(&ctx);
        if self.doc.version() != version_before && self.evaluation.pending_change.is_none() {
            self.evaluation.pending_change = Some(Instant::now());
        }
        self.submit_if_changed();
        // The frame that hands a new scene to the GPU closes a change-to-picture measurement.
        if let Some((version, changed_at)) = self.evaluation.awaiting_picture
            && self.viewport.handed_version() >= version
        {
            self.evaluation.latency.last_ms = changed_at.elapsed().as_secs_f64() * 1e3;
            if self.evaluation.latency.samples.len() < 10_000 {
                self.evaluation
                    .latency
                    .samples
                    .push(self.evaluation.latency.last_ms);
            }
            self.evaluation.awaiting_picture = None;
        }
        // Autosave: a committed edit (no gesture in progress) at once, a gesture within 1 s.
        let committed = !self.doc.history.in_gesture();
        let doc = &self.doc;
        let autosave = self.recovery.tick(
            doc.is_dirty(),
            doc.version(),
            committed,
            (doc.path.as_deref(), doc.origin.as_deref()),
            doc,
        );
        match autosave {
            Autosave::Due(after) => ctx.request_repaint_after(after),
            Autosave::Failed(retry) => {
                self.message = format!(
                    "cannot autosave to {}: {}; next try in {} s",
                    self.recovery.place(),
                    self.recovery.last_error().unwrap_or("refused"),
                    retry.as_secs()
                );
                ctx.request_repaint_after(retry);
            }
            Autosave::Idle | Autosave::Wrote | Autosave::Writing => {}
        }
        let title = format!("{} — cnets editor", self.doc.title());
        if title != self.last_title {
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.last_title = title;
        }
        if self.evaluation.worker.busy() {
            ctx.request_repaint_after(Duration::from_millis(30));
        }
        let base = self.doc.base_dir();
        if !crate::library::file_clusters(&self.doc.graph).is_empty()
            || !crate::import_watch::imported_files(&self.doc.graph, base.as_deref()).is_empty()
        {
            // Keep checking cluster and imported files while idle.
            ctx.request_repaint_after(WATCH_INTERVAL);
        }
        self.time_net_drag_frame(frame_started);
    }

    /// The parameter panel's contents; returns the edits made in it.
    pub(crate) fn parameters_contents(&mut self, ui: &mut Ui) -> Vec<CanvasAction> {
        self.panels.parameters_rect = Some(ui.clip_rect().intersect(ui.max_rect()));
        ui.heading("Parameters");
        let (actions, rects) =
            crate::parameters::show_with_rects(ui, &self.doc.graph, &self.evaluation.statuses);
        self.panels.parameter_editors = rects;
        actions
    }

    /// The colour mode, the planarity scale's top (in that mode) and Fit: the 3D view's first
    /// controls.
    fn view_mode_controls(&mut self, ui: &mut Ui) {
        let mut o = self.viewport.display().options;
        egui::ComboBox::from_id_salt("color-mode")
            .selected_text(o.color_mode.label())
            .show_ui(ui, |ui| {
                for m in crate::preview::ColorMode::ALL {
                    ui.selectable_value(&mut o.color_mode, m, m.label());
                }
            });
        if o.color_mode == crate::preview::ColorMode::Planarity {
            // The top of the scale (planar below 1e-9 stays the anchor).
            let (lo, hi) = crate::preview::PLANARITY_LIMIT_RANGE;
            let mut limit = o.planarity_limit();
            let r = ui
                .add(
                    egui::Slider::new(&mut limit, lo..=hi)
                        .logarithmic(true)
                        .text("not planar from")
                        .custom_formatter(|v, _| format!("{v:.0e}")),
                )
                .on_hover_text(
                    "the top of the planarity colour scale: faces from this relative \
                     planarity up are not planar (saved with the editor settings)",
                );
            if r.changed() && o.set_planarity_limit(limit) && !r.dragged() {
                self.settings.set_planarity_limit(o.planarity_limit());
            }
            if r.drag_stopped() {
                self.settings.set_planarity_limit(o.planarity_limit());
            }
        }
        if ui.button("Fit (F)").clicked() {
            self.viewport.fit();
        }
        self.viewport.display_mut().options = o;
    }

    /// The 3D view with its toolbar, and what it asked for carried out. `canvas_shown`: the
    /// canvas is on screen too (else every failed node's error is listed in the view).
    pub(crate) fn viewport_contents(&mut self, ui: &mut Ui, canvas_shown: bool) {
        if crate::narrow::is_narrow(ui.ctx()) {
            // A phone: the view's controls in one row that scrolls sideways, so the 3D view keeps
            // the height three wrapped rows would take.
            egui::ScrollArea::horizontal()
                .id_salt("cnets-narrow-view-toolbar")
                .show(ui, |ui| {
                    ui.horizontal(|ui| {
                        self.view_mode_controls(ui);
                        self.viewport.toolbar(ui);
                    })
                });
        } else {
            ui.horizontal(|ui| self.view_mode_controls(ui));
            ui.horizontal_wrapped(|ui| self.viewport.toolbar(ui));
        }
        let selected = self.canvas.targets();
        let input = ViewportInput {
            graph: &self.doc.graph,
            selected: &selected,
            typing: ui.ctx().egui_wants_keyboard_input(),
        };
        let actions = self.viewport.show(ui, self.gpu.as_ref(), &input);
        for a in actions {
            self.apply_view(a);
        }
        let on_canvas = |id: &str| canvas_shown && crate::view_errors::in_view(&self.canvas, id);
        self.panels.view_errors_shown = crate::view_errors::hidden_failures(
            &self.doc.graph,
            &self.evaluation.statuses,
            &on_canvas,
        )
        .into_iter()
        .map(|(id, message)| format!("{id}: {message}"))
        .collect();
        if let Some(id) = crate::view_errors::show(
            ui,
            self.viewport.rect(),
            &self.doc.graph,
            &self.evaluation.statuses,
            &on_canvas,
        ) {
            self.show_node(ui.ctx(), &id);
        }
    }

    /// Selects node `id` and brings it into the canvas's view (narrow layouts: shows the canvas).
    pub(super) fn show_node(&mut self, ctx: &egui::Context, id: &str) {
        self.canvas.focused = Some(id.to_string());
        self.canvas.select(vec![id.to_string()]);
        if let Some(r) = self.canvas.node_rect(id) {
            self.canvas.zoom_to(self.canvas.zoom(), Some(r.center()));
        }
        crate::narrow::show_canvas(ctx);
        self.message = format!("selected '{id}'");
    }

    /// The node canvas, with the breadcrumbs inside opened clusters.
    pub(crate) fn canvas_contents(&mut self, ui: &mut Ui) {
        if self.canvas_view != self.doc.view_path() {
            // Another graph level: a fresh canvas framing it.
            self.canvas_serial += 1;
            self.canvas = Canvas::with_id(egui::Id::new(("cnets-canvas", self.canvas_serial)));
            self.canvas.fit_later();
            self.canvas_view = self.doc.view_path();
        }
        if self.doc.depth() > 0
            && let Some(to) = breadcrumbs(ui, &self.doc)
        {
            self.leave_to(to);
        }
        // Statuses of another level (the worker has not answered yet) are not shown.
        let none = HashMap::new();
        let statuses = if self.evaluation.statuses_view == self.canvas_view {
            &self.evaluation.statuses
        } else {
            &none
        };
        let actions = self.canvas.show(ui, &self.doc.graph, statuses);
        for a in actions {
            self.apply(a);
        }
        if self.page.is_some()
            && let Some(at) =
                crate::overview::show(ui, &self.canvas, &self.doc.graph, &self.evaluation.statuses)
        {
            self.canvas.zoom_to(self.canvas.zoom(), Some(at));
        }
    }
}

/// The breadcrumb bar above the canvas inside an opened cluster: `main › bay (inline)`; returns
/// the level clicked (0: the document's own graph).
pub(super) fn breadcrumbs(ui: &mut Ui, doc: &GraphDocument) -> Option<usize> {
    let mut picked = None;
    let crumbs = doc.breadcrumbs();
    egui::Frame::new()
        .fill(ui.visuals().faint_bg_color)
        .inner_margin(egui::Margin::symmetric(8, 4))
        .show(ui, |ui| {
            ui.set_width(ui.available_width());
            ui.horizontal(|ui| {
                let last = crumbs.len() - 1;
                for (k, crumb) in crumbs.iter().enumerate() {
                    if k > 0 {
                        ui.weak("›");
                    }
                    if k == last {
                        ui.strong(crumb);
                    } else if ui
                        .link(crumb)
                        .on_hover_text("go back to this graph (the cluster is rebuilt)")
                        .clicked()
                    {
                        picked = Some(k);
                    }
                }
                ui.weak("   Esc: back");
                if let Some(e) = &doc.live_error {
                    ui.colored_label(egui::Color32::from_rgb(0xd6, 0x2f, 0x2f), e);
                }
            });
        });
    picked
}
