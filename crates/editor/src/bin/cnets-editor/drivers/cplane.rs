//! `cplane`: a construction plane made from three points in the real window, then used. View ▸
//! CPlane from 3 points; three clicks a little beside the three handles of the `param.points` node
//! `tri` (each snaps to its handle); the Draw curve tool (C) in the Perspective view, four clicks
//! on the new plane's grid (a little off it), Enter. It prints the plane, the planes the graph
//! keeps, the grid step and the drawn points, and saves a screenshot of the tilted grid.

use cnets_editor::app::EditorApp;
use cnets_editor::probe;
use cnets_geometry::DVec3;
use egui::{Key, Modifiers, PointerButton, vec2};

use super::scenarios::points_text;
use super::script::{Step, Target};

/// The new plane's grid points the curve is drawn through, in grid steps along its u and v.
pub const CURVE_STEPS: [(f64, f64); 4] = [(1.0, 1.0), (3.0, 2.0), (5.0, 1.0), (6.0, 3.0)];

fn print(key: &'static str, f: impl Fn(&EditorApp) -> String + 'static) -> Step {
    Step::Print(key, Box::new(f))
}

fn click(t: Target) -> Step {
    Step::Click(t, PointerButton::Primary, Modifiers::NONE)
}

/// A control drawn under `label` (menus).
fn control(label: &'static str) -> Target {
    Box::new(move |_: &EditorApp, ctx: &egui::Context| probe::rect(ctx, label).map(|r| r.center()))
}

/// Beside handle `index` of node `node` by a few screen points (within the snap radius).
fn beside_handle(node: &'static str, index: usize) -> Target {
    Box::new(move |app: &EditorApp, _: &egui::Context| {
        let h = app
            .viewport()
            .handle_list()
            .iter()
            .find(|h| h.key.node == node && h.key.index == index)?;
        Some(app.viewport().screen_map().to_screen(h.position)? + vec2(3.0, -2.0))
    })
}

/// The Perspective plane's point `(a, b)` grid steps from its origin, nudged on screen by a
/// tenth of a step (the snap takes it away).
fn on_plane(a: f64, b: f64) -> Target {
    Box::new(move |app: &EditorApp, _: &egui::Context| {
        let s = app.viewport().grid_step();
        let map = app.viewport().screen_map();
        let px = (s / map.world_per_point()) as f32;
        let p = app
            .viewport()
            .framing()
            .perspective_plane
            .at(a * s, b * s, 0.0);
        map.to_screen(p).map(|q| q + vec2(0.1, -0.1) * px)
    })
}

fn vector(p: DVec3) -> String {
    format!("{:?},{:?},{:?}", p.x, p.y, p.z)
}

/// The script.
pub fn cplane() -> Vec<Step> {
    let mut steps = vec![
        Step::Settle,
        print("view", |app| {
            app.viewport().framing().view.label().to_string()
        }),
        click(control("View")),
        click(control("CPlane from 3 points")),
        print("tool", |app| app.viewport().tool().label().to_string()),
    ];
    for k in 0..3 {
        steps.push(click(beside_handle("tri", k)));
    }
    steps.extend([
        Step::Settle,
        print("plane", |app| {
            let p = app.viewport().framing().perspective_plane;
            [p.origin, p.u, p.v, p.normal].map(vector).join(" ")
        }),
        print("plane name", |app| {
            app.viewport().framing().perspective_name.clone()
        }),
        print("cplanes", |app| {
            let names: Vec<&str> = app
                .doc()
                .meta
                .cplanes
                .iter()
                .map(|p| p.name.as_str())
                .collect();
            names.join("|")
        }),
        print("undo steps", |app| app.doc().history.undo_len().to_string()),
        Step::Key(Key::C, Modifiers::NONE),
        print("step", |app| format!("{:?}", app.viewport().grid_step())),
    ]);
    for (a, b) in CURVE_STEPS {
        steps.push(click(on_plane(a, b)));
    }
    steps.extend([
        Step::Key(Key::Enter, Modifiers::NONE),
        Step::Settle,
        print("drawn view", |app| {
            app.viewport().framing().view.label().to_string()
        }),
        print("drawn", |app| points_text(app, "points")),
        print("saved", |app| {
            let text = cnets_engine::file::to_ron(&app.doc().graph, &app.doc().meta);
            text.contains("cplanes: [\n        (name: \"CPlane 1\"")
                .to_string()
        }),
        Step::Shot("cplane-draw"),
        Step::Quit,
    ]);
    steps
}
