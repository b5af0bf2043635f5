//! `canopy`: the design brief — a glass canopy over a courtyard — played with pointer
//! events and keys only, no typed coordinates: the S-curve directrix drawn in the Top view
//! (control points (0, 0), (1, 2), (−1, 4), (0, 6) m), the arch generatrix in the Front view
//! ((−5, 0), (−3, 3), (0, 4), (3, 3), (5, 0) m in x, z), a CNets Construct added from the palette
//! and wired by dragging pins, the folds shown from the legend and repaired by dragging the
//! assistance to ½, then File ▸ Export GLB and DXF. It prints the drawn points, the size of the
//! cone-net, the folds before and after, what was exported and how long it took, and saves a
//! screenshot after each stage.

use cnets_editor::app::EditorApp;
use cnets_editor::probe;
use cnets_engine::Value;
use cnets_geometry::DVec3;
use cnets_preview::PickGeometry;
use egui::{Key, Modifiers, PointerButton, vec2};

use super::scenarios::{points_text, world};
use super::script::{Step, Target};

/// The directrix's control points in the Top view (metres).
pub const S_CURVE: [(f64, f64); 4] = [(0.0, 0.0), (1.0, 2.0), (-1.0, 4.0), (0.0, 6.0)];
/// The arch's control points in the Front view (x, z in metres).
pub const ARCH: [(f64, f64); 5] = [(-5.0, 0.0), (-3.0, 3.0), (0.0, 4.0), (3.0, 3.0), (5.0, 0.0)];

pub(crate) fn print(key: &'static str, f: impl Fn(&EditorApp) -> String + 'static) -> Step {
    Step::Print(key, Box::new(f))
}

pub(crate) fn key(k: Key) -> Step {
    Step::Key(k, Modifiers::NONE)
}

pub(crate) fn click(t: Target) -> Step {
    Step::Click(t, PointerButton::Primary, Modifiers::NONE)
}

/// A world point nudged by a fifth of a grid step on screen (the snap takes it away).
pub(crate) fn near(p: DVec3) -> Target {
    Box::new(move |app: &EditorApp, ctx: &egui::Context| {
        let s = app.viewport().grid_step();
        let px = (s / app.viewport().screen_map().world_per_point()) as f32;
        world(p)(app, ctx).map(|q| q + vec2(0.2, -0.2) * px)
    })
}

/// A control drawn under `label` (menus, dialog buttons, palette entries).
pub(crate) fn control(label: &'static str) -> Target {
    Box::new(move |_: &EditorApp, ctx: &egui::Context| probe::rect(ctx, label).map(|r| r.center()))
}

/// A pin of a node on the canvas.
pub(crate) fn pin(node: &'static str, input: bool, port: &'static str) -> Target {
    Box::new(move |app: &EditorApp, _: &egui::Context| {
        let def = &app.doc().graph.node(node)?.def;
        let k = if input {
            def.input_index(port)?
        } else {
            def.output_index(port)?
        };
        app.canvas().pin_screen_pos(node, input, k)
    })
}

/// The middle of the view, for the wheel.
pub(crate) fn view_centre() -> Target {
    Box::new(|app: &EditorApp, _: &egui::Context| Some(app.viewport().rect().center()))
}

/// The box of the construction's mesh: (W, D, H).
pub(crate) fn mesh_size(app: &EditorApp) -> Option<DVec3> {
    let picks = app.viewport().picks();
    let mesh = picks.meshes.iter().find(|m| m.node == "construct")?;
    let PickGeometry::Grid(g) = &mesh.geometry else {
        return None;
    };
    let (lo, hi) = g.vertices.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    Some(hi - lo)
}

/// The x extent of the drawn directrix (the spline through the S-curve's points).
fn directrix_width(app: &EditorApp) -> Option<f64> {
    let picks = app.viewport().picks();
    let curve = picks.curves.iter().find(|c| c.node == "spline")?;
    let xs = curve.polyline.points.iter().map(|p| p.x);
    let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
        (lo.min(x), hi.max(x))
    });
    Some(hi - lo)
}

pub(crate) fn assistance(app: &EditorApp) -> f64 {
    app.doc()
        .graph
        .node("construct")
        .and_then(|n| n.value_of("assistance"))
        .and_then(Value::as_f64)
        .unwrap_or(f64::NAN)
}

pub(crate) fn folds(app: &EditorApp) -> String {
    app.viewport().picks().folded_faces().len().to_string()
}

/// Draws a curve through `points` with the Draw curve tool and Enter.
pub(crate) fn draw(points: impl IntoIterator<Item = DVec3>) -> Vec<Step> {
    let mut steps = vec![key(Key::C)];
    steps.extend(points.into_iter().map(|p| click(near(p))));
    steps.extend([key(Key::Enter), Step::Settle]);
    steps
}

/// Exports through File ▸ Export ▸ `entry` into the document's folder, under the name the
/// dialog offers (the document's), and closes the list of what was written.
pub(crate) fn export(entry: &'static str) -> Vec<Step> {
    vec![
        click(control("File")),
        Step::Wait(2),
        Step::Move(control("Export")),
        Step::Wait(3),
        click(control(entry)),
        Step::Wait(3),
        click(control("Export file")),
        Step::Wait(3),
        print("exported", |app| app.message().to_string()),
        click(control("Close export list")),
        Step::Wait(3),
    ]
}

/// The canopy script.
pub fn canopy() -> Vec<Step> {
    let mut steps = vec![
        Step::Settle,
        // The Top view of an empty design frames 20 m around the origin.
        key(Key::Num1),
        Step::Settle,
        print("top step", |app| {
            format!("{:?}", app.viewport().grid_step())
        }),
    ];
    steps.extend(draw(S_CURVE.map(|(x, y)| DVec3::new(x, y, 0.0))));
    steps.extend([
        print("directrix points", |app| points_text(app, "points")),
        Step::Shot("canopy-1-top-directrix"),
        // The Front view frames the curve seen edge-on: zoom out to see 12 m.
        key(Key::Num2),
        Step::Settle,
        Step::WheelUntil(
            view_centre(),
            -60.0,
            Box::new(|app| {
                let map = app.viewport().screen_map();
                let half_width = map.world_per_point() * f64::from(map.rect.width()) / 2.0;
                half_width > 7.0 && app.viewport().grid_step() <= 1.0
            }),
        ),
        Step::Wait(3),
        print("front step", |app| {
            format!("{:?}", app.viewport().grid_step())
        }),
    ]);
    steps.extend(draw(ARCH.map(|(x, z)| DVec3::new(x, 0.0, z))));
    steps.extend([
        print("arch points", |app| points_text(app, "points_2")),
        Step::Shot("canopy-2-front-arch"),
        // A CNets Construct from the palette (Add ▸ Node…, type, Enter), wired by its pins.
        click(control("Add")),
        Step::Wait(2),
        click(control("Node…")),
        Step::Wait(3),
        Step::Text("construct".into()),
        Step::Wait(2),
        key(Key::Enter),
        Step::Wait(3),
        key(Key::Home),
        Step::Wait(6),
        Step::Drag(
            pin("spline", false, "curve"),
            pin("construct", true, "directrix"),
            PointerButton::Primary,
            Modifiers::NONE,
        ),
        Step::Wait(3),
        Step::Drag(
            pin("spline_2", false, "curve"),
            pin("construct", true, "generatrix"),
            PointerButton::Primary,
            Modifiers::NONE,
        ),
        Step::Settle,
        key(Key::Num4),
        Step::Settle,
        print("wires", |app| {
            app.doc()
                .graph
                .wires()
                .iter()
                .map(|w| format!("{}.{}->{}.{}", w.from, w.output, w.to, w.input))
                .collect::<Vec<_>>()
                .join(" ")
        }),
        print("mesh size", |app| {
            mesh_size(app).map_or("none".into(), |s| format!("{:?},{:?},{:?}", s.x, s.y, s.z))
        }),
        print("directrix width", |app| {
            directrix_width(app).map_or("none".into(), |w| format!("{w:?}"))
        }),
        print("shown size", |app| {
            app.viewport().bounds().map_or("none".into(), |b| {
                cnets_editor::viewport::overlay::dimensions(&b)
            })
        }),
        print("folds before", folds),
        Step::Shot("canopy-3-constructed"),
        // The legend's fold entry frames and outlines the folds.
        click(Box::new(|app: &EditorApp, _: &egui::Context| {
            app.viewport().last_frame().fold_entry.map(|r| r.center())
        })),
        Step::Wait(4),
        print("outlined", |app| {
            app.viewport().highlight().len().to_string()
        }),
        Step::Shot("canopy-4-folds"),
        // Repair: drag the assistance from −1 to ½ or a little above.
        Step::DragUntil(
            Box::new(|app: &EditorApp, _: &egui::Context| {
                app.canvas()
                    .editor_screen_rect("construct", "assistance")
                    .map(|r| r.center())
            }),
            vec2(3.0, 0.0),
            Box::new(|app| assistance(app) >= 0.45),
        ),
        Step::Settle,
        print("assistance", |app| format!("{:?}", assistance(app))),
        print("folds after", folds),
        print("mesh size after", |app| {
            mesh_size(app).map_or("none".into(), |s| format!("{:?},{:?},{:?}", s.x, s.y, s.z))
        }),
        print("corrections", |app| match app.statuses().get("construct") {
            Some(cnets_editor::worker::NodeStatus::Ok { outputs, .. }) => outputs
                .get(
                    app.doc()
                        .graph
                        .node("construct")
                        .and_then(|n| n.def.output_index("corrections"))
                        .unwrap_or(usize::MAX),
                )
                .cloned()
                .unwrap_or_default(),
            _ => "no result".into(),
        }),
        key(Key::F),
        Step::Settle,
        Step::Shot("canopy-5-repaired"),
    ]);
    steps.extend(export("GLB…"));
    steps.extend(export("DXF…"));
    steps.extend([Step::Quit]);
    steps
}
