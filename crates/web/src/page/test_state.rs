//! The page's test state, opt-in: `window.cnets_test` (figures for the browser test, written after
//! every frame), `window.cnets_request` (a menu action the test runs) and the flags it sets, read
//! only when the page was opened with `window.cnets_testing = true` set before the module starts
//! (the browser test's `addInitScript`). A visitor's page builds none of it.

use super::*;
use crate::opening::LargeOpen;

impl WebApp {
    /// `window.cnets_test`: figures for the browser test (frames, pictures drawn, the first
    /// picture's time, the last change-to-picture latency, where the 3D view and the first slider
    /// are, in CSS pixels).
    pub(super) fn report(&mut self) {
        let drawn = self.app.viewport().handed_version();
        if drawn > 0 && self.first_picture_ms.is_none() && !self.app.viewport().scene().is_empty() {
            self.first_picture_ms = Some(now_ms());
        }
        let Some(window) = web_sys::window() else {
            return;
        };
        let o = js_sys::Object::new();
        let set = |k: &str, v: JsValue| {
            let _ = js_sys::Reflect::set(&o, &k.into(), &v);
        };
        let rect = |r: egui::Rect| {
            let a = js_sys::Array::new();
            for x in [r.left(), r.top(), r.right(), r.bottom()] {
                a.push(&JsValue::from_f64(f64::from(x)));
            }
            JsValue::from(a)
        };
        set("frames", JsValue::from_f64(self.frames as f64));
        // A widget held by the pointer (the browser test waits for its press to be seen).
        set(
            "dragging",
            JsValue::from_bool(self.ctx.dragged_id().is_some()),
        );
        set("pictures", JsValue::from_f64(drawn as f64));
        set(
            "first_picture_ms",
            self.first_picture_ms
                .map_or(JsValue::NULL, JsValue::from_f64),
        );
        set("latency_ms", JsValue::from_f64(self.app.latency().last_ms));
        set(
            "latencies",
            JsValue::from_f64(self.app.latency().samples.len() as f64),
        );
        set(
            "busy",
            JsValue::from_bool(self.app.viewport().scene_version() != drawn),
        );
        // The worker has not answered the newest submission completely yet.
        set("evaluating", JsValue::from_bool(self.app.busy()));
        set("view", rect(self.app.viewport().rect()));
        set("title", self.app.doc().title().into());
        set(
            "tab_title",
            document().map_or(String::new(), |d| d.title()).into(),
        );
        set("welcome", self.welcome_rect.map_or(JsValue::NULL, rect));
        // The failed load's dialog, where it was drawn.
        set(
            "dialog",
            self.app
                .load_failure()
                .and_then(|f| f.shown_at)
                .map_or(JsValue::NULL, rect),
        );
        // The figures over the 3D view: [name, [left, top, right, bottom]] each.
        let overlays = js_sys::Array::new();
        for (name, r) in &self.app.viewport().last_frame().overlays {
            overlays.push(&js_sys::Array::of2(&JsValue::from_str(name), &rect(*r)).into());
        }
        set("overlays", overlays.into());
        set(
            "parameters",
            self.app.parameters_rect().map_or(JsValue::NULL, rect),
        );
        let canvas = self.app.canvas().screen_rect();
        set("canvas", rect(canvas));
        set(
            "overview",
            JsValue::from_bool(
                cnets_editor::overview::placement(self.app.canvas(), &self.app.doc().graph)
                    .is_some(),
            ),
        );
        // Nodes not wholly on the canvas: (id, type) pairs.
        let hidden = js_sys::Array::new();
        for (_, n) in self.app.doc().graph.nodes() {
            if !cnets_editor::view_errors::in_view(self.app.canvas(), &n.id) {
                hidden.push(&JsValue::from(n.id.as_str()));
            }
        }
        set("hidden", hidden.into());
        // Failed nodes: {id, message, in_view} (in view: the node's badge is on the canvas).
        let failed = js_sys::Array::new();
        for (_, n) in self.app.doc().graph.nodes() {
            let Some(message) = self.app.statuses().get(&n.id).and_then(|s| s.error()) else {
                continue;
            };
            let f = js_sys::Object::new();
            let _ = js_sys::Reflect::set(&f, &"id".into(), &n.id.as_str().into());
            let _ = js_sys::Reflect::set(&f, &"message".into(), &message.into());
            let in_view = !cnets_editor::narrow::is_narrow(&self.ctx)
                && cnets_editor::view_errors::in_view(self.app.canvas(), &n.id);
            let _ = js_sys::Reflect::set(&f, &"in_view".into(), &in_view.into());
            failed.push(&f);
        }
        set("failed", failed.into());
        let errors = js_sys::Array::new();
        for e in self.app.view_errors_shown() {
            errors.push(&JsValue::from(e.as_str()));
        }
        set("view_errors", errors.into());
        // The unsaved-changes question being asked: what it is about ("Opening x.ron"), or null.
        set(
            "question",
            self.app
                .unsaved_question()
                .map_or(JsValue::NULL, |q| q.describe().into()),
        );
        set(
            "load_failure",
            self.app
                .load_failure()
                .map_or(JsValue::NULL, |f| f.error.to_string().into()),
        );
        let worker = self.remote.figures();
        set("worker_sent", JsValue::from_f64(worker.sent as f64));
        set("worker_answers", JsValue::from_f64(worker.answers as f64));
        set("worker_decode_ms", JsValue::from_f64(worker.decode_ms));
        set("worker_started", JsValue::from_f64(worker.started as f64));
        set(
            "worker_literals_sent",
            JsValue::from_f64(worker.literals_sent as f64),
        );
        set("worker_send_ms", JsValue::from_f64(worker.send_ms.0));
        set(
            "worker_read_decode_ms",
            JsValue::from_f64(worker.read_decode_ms),
        );
        set("worker_send_ms_max", JsValue::from_f64(worker.send_ms.1));
        set(
            "narrow",
            JsValue::from_bool(cnets_editor::narrow::is_narrow(&self.ctx)),
        );
        // The layout's size in points and the pixels a point (the page lays out by CSS size).
        let screen = self.ctx.content_rect().size();
        set(
            "screen",
            js_sys::Array::of2(&f64::from(screen.x).into(), &f64::from(screen.y).into()).into(),
        );
        set(
            "pixels_per_point",
            JsValue::from_f64(f64::from(self.ctx.pixels_per_point())),
        );
        set(
            "restore_offered",
            JsValue::from_bool(self.app.restore_offered()),
        );
        set(
            "kept_recovery",
            self.app
                .kept_recovery()
                .map_or(JsValue::NULL, JsValue::from_str),
        );
        set("document", JsValue::from_str(&self.app.doc().title()));
        set("message", self.app.message().to_string().into());
        set(
            "vertices",
            JsValue::from_f64(self.app.viewport().stats().vertices as f64),
        );
        // The first number slider on the canvas (in view), else the first integer one there,
        // else the first number slider of the graph.
        let of_type = |t: &str| -> Vec<String> {
            self.app
                .doc()
                .graph
                .nodes()
                .filter(|(_, n)| n.def.id == t)
                .map(|(_, n)| n.id.clone())
                .collect()
        };
        let (numbers, integers) = (of_type("param.number"), of_type("param.integer"));
        let in_view = |id: &&String| cnets_editor::view_errors::in_view(self.app.canvas(), id);
        let drawn = |id: &&String| self.app.canvas().editor_screen_rect(id, "value").is_some();
        let slider = numbers
            .iter()
            .filter(in_view)
            .chain(integers.iter().filter(in_view))
            .find(drawn)
            .or_else(|| numbers.iter().chain(integers.iter()).find(drawn))
            .or(numbers.first())
            .cloned();
        // The parameter panel's value editors: {id, type, rect, value}.
        let panel = js_sys::Array::new();
        for (id, r) in self.app.parameter_editors() {
            let Some(node) = self.app.doc().graph.node(id) else {
                continue;
            };
            let e = js_sys::Object::new();
            let put = |k: &str, v: JsValue| {
                let _ = js_sys::Reflect::set(&e, &k.into(), &v);
            };
            put("id", id.as_str().into());
            put("type", node.def.id.as_ref().into());
            put("rect", rect(*r));
            let value = cnets_editor::parameters::edited_input(&node.def)
                .and_then(|k| node.value_of(&node.def.inputs[k].name))
                .and_then(cnets_engine::Value::as_f64);
            put("value", value.map_or(JsValue::NULL, JsValue::from_f64));
            panel.push(&e);
        }
        set("panel", panel.into());
        if let Some(id) = slider {
            if let Some(r) = self.app.canvas().editor_screen_rect(&id, "value") {
                // The rail is the left part of the editor; the value box follows it.
                let rail = r.width().min(110.0 * self.app.canvas().zoom());
                let rail = egui::Rect::from_min_size(r.min, egui::vec2(rail, r.height()));
                set("slider", rect(rail));
            }
            let value = self
                .app
                .doc()
                .graph
                .node(&id)
                .and_then(|n| n.value_of("value"))
                .and_then(cnets_engine::Value::as_f64);
            set("slider_node", id.into());
            set(
                "slider_value",
                value.map_or(JsValue::NULL, JsValue::from_f64),
            );
        }
        set(
            "opening_notice",
            self.opening
                .notice()
                .map_or(JsValue::NULL, |n| n.sentence().into()),
        );
        set(
            "large_open",
            self.opening
                .last_large
                .as_ref()
                .map_or(JsValue::NULL, large_open_object),
        );
        set(
            "drag_worker_answers",
            JsValue::from_f64(self.drag.answered() as f64),
        );
        // Only when the test asks (`window.cnets_report_net_vertex = true`): it picks.
        if test_flag("cnets_report_net_vertex") {
            set("net_vertex", net_vertex(&self.app));
        }
        set(
            "net_drag",
            self.app
                .last_net_drag()
                .map_or(JsValue::NULL, net_drag_object),
        );
        let _ = js_sys::Reflect::set(&window, &"cnets_test".into(), &o);
    }

    /// `window.cnets_request = "copy_link"` (or `"restore_kept"`): the browser test runs File ▸
    /// Copy link (File ▸ Restore kept work); egui menus have no DOM to click.
    pub(super) fn test_request(&mut self) {
        let Some(window) = web_sys::window() else {
            return;
        };
        let key = JsValue::from("cnets_request");
        let Ok(v) = js_sys::Reflect::get(&window, &key) else {
            return;
        };
        let action = match v.as_string().as_deref() {
            Some("copy_link") => cnets_editor::menus::MenuAction::CopyLink,
            Some("restore_kept") => cnets_editor::menus::MenuAction::RestoreKept,
            _ => return,
        };
        let _ = js_sys::Reflect::delete_property(&window, &key);
        self.app.run(action);
    }
}

/// `window.cnets_test.net_vertex`: `[x, y, node, i, j]`, a vertex of a previewed net the Drag net
/// tool can grab where the view draws it (not on the net's border), the nearest the view's centre
/// of the first 64 tried nearest first, or null.
fn net_vertex(app: &EditorApp) -> JsValue {
    use cnets_editor::viewport::net_drag::vertex_at;
    let picks = app.viewport().picks();
    let map = app.viewport().screen_map();
    let inner = app.viewport().rect().shrink(60.0);
    let centre = app.viewport().rect().center();
    let mut candidates: Vec<(f32, egui::Pos2, &str, usize, usize)> = Vec::new();
    for m in &picks.meshes {
        let cnets_editor::preview::PickGeometry::Grid(g) = &m.geometry else {
            continue;
        };
        for (k, p) in g.vertices.iter().enumerate() {
            let (i, j) = (k / g.cols, k % g.cols);
            if i == 0 || j == 0 || i + 1 == g.rows || j + 1 == g.cols {
                continue;
            }
            if let Some(at) = map.to_screen(*p).filter(|s| inner.contains(*s)) {
                candidates.push((at.distance(centre), at, m.node.as_str(), i, j));
            }
        }
    }
    candidates.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Drawn there, not hidden behind another face: what a press would grab.
    let best = candidates
        .into_iter()
        .take(64)
        .find(|&(_, at, node, i, j)| {
            vertex_at(picks, &map, at).is_some_and(|v| v.node == node && v.vertex == (i, j))
        });
    let Some((_, at, node, i, j)) = best else {
        return JsValue::NULL;
    };
    let a = js_sys::Array::new();
    a.push(&JsValue::from_f64(f64::from(at.x)));
    a.push(&JsValue::from_f64(f64::from(at.y)));
    a.push(&JsValue::from(node));
    a.push(&JsValue::from_f64(i as f64));
    a.push(&JsValue::from_f64(j as f64));
    a.into()
}

/// `window.cnets_test.net_drag`: what the last drag of the net measured.
fn net_drag_object(f: &cnets_editor::app::NetDragFigures) -> JsValue {
    let o = js_sys::Object::new();
    let set = |k: &str, v: JsValue| {
        let _ = js_sys::Reflect::set(&o, &k.into(), &v);
    };
    set("node", f.node.as_str().into());
    set("solves", JsValue::from_f64(f.solves as f64));
    set("rate", JsValue::from_f64(f.rate()));
    set("solve_ms", JsValue::from_f64(f.solve_ms));
    let mut frames = f.ui_frame_ms.clone();
    frames.sort_by(f64::total_cmp);
    let median = frames.get(frames.len() / 2).copied();
    set(
        "ui_frame_median_ms",
        median.map_or(JsValue::NULL, JsValue::from_f64),
    );
    set(
        "ui_frame_max_ms",
        frames
            .last()
            .copied()
            .map_or(JsValue::NULL, JsValue::from_f64),
    );
    set("frames", JsValue::from_f64(frames.len() as f64));
    set("release_ms", JsValue::from_f64(f.release_ms));
    let solved = f.solved.as_ref();
    set(
        "distance_left",
        solved.map_or(JsValue::NULL, |s| JsValue::from_f64(s.distance_left)),
    );
    set(
        "not_convex",
        solved.map_or(JsValue::NULL, |s| JsValue::from_f64(s.not_convex as f64)),
    );
    o.into()
}

/// Whether the browser test has set `window.<name>` to a true value.
pub(super) fn test_flag(name: &str) -> bool {
    web_sys::window()
        .and_then(|w| js_sys::Reflect::get(&w, &name.into()).ok())
        .is_some_and(|v| v.is_truthy())
}

/// `window.cnets_test.large_open`: how the last large graph was opened.
fn large_open_object(large: &LargeOpen) -> JsValue {
    let o = js_sys::Object::new();
    let set = |k: &str, v: JsValue| {
        let _ = js_sys::Reflect::set(&o, &k.into(), &v);
    };
    set("name", large.name.as_str().into());
    set("bytes", JsValue::from_f64(large.bytes as f64));
    set(
        "frames_while_reading",
        JsValue::from_f64(f64::from(large.frames_while_reading)),
    );
    let ms = |v: Option<f64>| v.map_or(JsValue::NULL, JsValue::from_f64);
    set("open_ms", ms(large.open_ms));
    set("page_ms", ms(large.page_ms));
    o.into()
}
