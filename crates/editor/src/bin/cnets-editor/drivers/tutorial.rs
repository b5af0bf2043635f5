//! `tutorial`: the steps of docs/tutorial.md ("your first cone-net in five minutes") played with
//! pointer events and keys only — File › New, a directrix drawn in the Top view, a generatrix
//! in the Front view, a CNets Construct added from the palette and wired by its pins, the
//! assistance dragged until no face folds, File › Export › GLB and DXF — with a screenshot after
//! each step (`tutorial-N-….png`). It prints what the steps made: the drawn points, the wires,
//! the net's size, the folds, what was exported. `tests/it/window.rs` checks the lines and keeps
//! the screenshots (`UPDATE_TUTORIAL=1` copies them into docs/tutorial/).

use cnets_editor::app::EditorApp;
use cnets_geometry::DVec3;
use egui::{Key, Modifiers, PointerButton, vec2};

use super::canopy::{
    ARCH, S_CURVE, assistance, click, control, draw, export, folds, key, mesh_size, pin, print,
    view_centre,
};
use super::scenarios::points_text;
use super::script::Step;

/// The size of the construction's net as `W,D,H` (or `none`).
fn size_text(app: &EditorApp) -> String {
    mesh_size(app).map_or("none".into(), |s| format!("{:?},{:?},{:?}", s.x, s.y, s.z))
}

/// The tutorial script.
pub fn tutorial() -> Vec<Step> {
    let mut steps = vec![
        Step::Settle,
        // Step 1: File › New.
        click(control("File")),
        Step::Wait(2),
        click(control("New")),
        Step::Settle,
        print("nodes after new", |app| {
            app.doc().graph.node_count().to_string()
        }),
        Step::Shot("tutorial-1-new"),
        // Step 2: the directrix, drawn in the Top view.
        key(Key::Num1),
        Step::Settle,
        print("top step", |app| {
            format!("{:?}", app.viewport().grid_step())
        }),
    ];
    steps.extend(draw(S_CURVE.map(|(x, y)| DVec3::new(x, y, 0.0))));
    steps.extend([
        print("directrix points", |app| points_text(app, "points")),
        Step::Shot("tutorial-2-directrix"),
        // Step 3: the generatrix, drawn in the Front view (zoomed out to see 12 m).
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
        print("generatrix points", |app| points_text(app, "points_2")),
        Step::Shot("tutorial-3-generatrix"),
        // Step 4: a CNets Construct from Add › Node…, wired by dragging pins.
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
        print("mesh size", size_text),
        print("folds before", folds),
        Step::Shot("tutorial-4-cone-net"),
        // Step 5: no folded faces — the assistance dragged from −1 to ½.
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
        key(Key::F),
        Step::Settle,
        print("assistance", |app| format!("{:?}", assistance(app))),
        print("folds after", folds),
        print("mesh size after", size_text),
        Step::Shot("tutorial-5-repaired"),
    ]);
    // Step 6: File › Export › GLB… and DXF…; the list of what was written is shown.
    steps.extend(export("GLB…"));
    let mut dxf = export("DXF…");
    // The list of the files written, photographed before its Close (the export's last click).
    let close = dxf.len() - 2;
    dxf.insert(close, Step::Shot("tutorial-6-exported"));
    steps.extend(dxf);
    steps.push(Step::Quit);
    steps
}
