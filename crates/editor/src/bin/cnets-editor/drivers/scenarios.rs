//! The scripted sessions `--drive-script NAME` plays (see [`super::script`]), each a design
//! gesture of issue 25 made with pointer events and keys only. `tests/it/window.rs` runs them in the
//! real window under Xvfb and checks what they print.

use cnets_editor::app::EditorApp;
use cnets_engine::Value;
use cnets_geometry::DVec3;
use egui::{Key, Modifiers, PointerButton, vec2};

use super::script::{Step, Target};

/// Where the 3D view draws a world point.
pub fn world(p: DVec3) -> Target {
    Box::new(move |app: &EditorApp, _: &egui::Context| app.viewport().screen_map().to_screen(p))
}

/// A world point given in grid steps of the view (x, y, z multiplied by the current grid step),
/// displaced by a fraction of a step on screen (the snap takes it away).
fn grid_point(steps: DVec3, slack: egui::Vec2) -> Target {
    Box::new(move |app: &EditorApp, _: &egui::Context| {
        let s = app.viewport().grid_step();
        let map = app.viewport().screen_map();
        let px = (s / map.world_per_point()) as f32;
        map.to_screen(steps * s).map(|p| p + slack * px)
    })
}

/// Where the 3D view draws handle `index` of node `node`, moved by a screen offset.
fn handle(node: &'static str, index: usize, offset: egui::Vec2) -> Target {
    Box::new(move |app: &EditorApp, _: &egui::Context| {
        let h = app
            .viewport()
            .handle_list()
            .iter()
            .find(|h| h.key.node == node && h.key.index == index)?;
        Some(app.viewport().screen_map().to_screen(h.position)? + offset)
    })
}

/// The points of a `param.points` node, with every digit.
pub fn points_text(app: &EditorApp, node: &str) -> String {
    let points: Vec<String> = app
        .doc()
        .graph
        .node(node)
        .and_then(|n| n.value_of("points"))
        .and_then(Value::as_list)
        .map(|items| {
            items
                .iter()
                .filter_map(Value::as_vec3)
                .map(|p| format!("{:?},{:?},{:?}", p.x, p.y, p.z))
                .collect()
        })
        .unwrap_or_default();
    points.join(" ")
}

fn print(key: &'static str, f: impl Fn(&EditorApp) -> String + 'static) -> Step {
    Step::Print(key, Box::new(f))
}

fn key(k: Key) -> Step {
    Step::Key(k, Modifiers::NONE)
}

fn click(t: Target) -> Step {
    Step::Click(t, PointerButton::Primary, Modifiers::NONE)
}

/// The grid step and the world size of a screen point, as the tests need them.
fn scale_lines() -> Vec<Step> {
    vec![
        print("step", |app| format!("{:?}", app.viewport().grid_step())),
        print("view", |app| {
            app.viewport().framing().view.label().to_string()
        }),
    ]
}

/// `handles`: on a graph with a `param.points` node `pts` (preview on), the Top view (key 1);
/// handle 1 dragged 3 grid steps right and 2 down with a third of a step of slack; the points
/// printed; Ctrl+Z; the points printed again.
fn handles() -> Vec<Step> {
    let mut steps = vec![Step::Settle, key(Key::Num1), Step::Settle];
    steps.extend(scale_lines());
    steps.extend([
        print("before", |app| points_text(app, "pts")),
        Step::Drag(
            handle("pts", 1, vec2(0.0, 0.0)),
            Box::new(|app: &EditorApp, ctx: &egui::Context| {
                let s = app.viewport().grid_step();
                let px = (s / app.viewport().screen_map().world_per_point()) as f32;
                let h = handle("pts", 1, vec2(0.0, 0.0))(app, ctx)?;
                Some(h + vec2(3.3 * px, 1.7 * px))
            }),
            PointerButton::Primary,
            Modifiers::NONE,
        ),
        Step::Settle,
        print("after", |app| points_text(app, "pts")),
        print("undo steps", |app| app.doc().history.undo_len().to_string()),
        Step::Key(Key::Z, Modifiers::COMMAND),
        Step::Settle,
        print("undone", |app| points_text(app, "pts")),
        Step::Shot("handles"),
        Step::Quit,
    ]);
    steps
}

/// Where the canvas draws pin `k` of node `node` (an input pin when `input`).
fn pin(node: &'static str, input: bool, k: usize) -> Target {
    Box::new(move |app: &EditorApp, _: &egui::Context| app.canvas().pin_screen_pos(node, input, k))
}

/// The middle of the value editor of `node.input` on the canvas.
fn field(node: &'static str, input: &'static str) -> Target {
    Box::new(move |app: &EditorApp, _: &egui::Context| {
        app.canvas()
            .editor_screen_rect(node, input)
            .map(|r| r.center())
    })
}

/// The literal value of `times.b`, as the file would write it (`none` when unset).
fn times_b(app: &EditorApp) -> String {
    app.doc()
        .graph
        .node("times")
        .and_then(|n| n.value_of("b"))
        .and_then(Value::as_f64)
        .map_or_else(|| "none".to_string(), |x| format!("{x:?}"))
}

/// `wire-click` (issue 26: "the first click on a field right after a wire drag does nothing"):
/// on a graph of a slider `apex` and a `math.multiply` `times`, a wire dragged from the slider
/// into `times.a`, then at once one click on `times.b`'s field, `7` typed and Enter; then a wire
/// dragged out of `times.result` and dropped on the background, one click on the field, `5` and
/// Enter. The wires and `b` are printed after each: a first click that did nothing leaves `b`.
/// Then the Browse… button of `site`'s path (an `io.read_polylines`) is clicked: the file dialog
/// it opens is printed.
fn wire_click() -> Vec<Step> {
    let settle_type = |text: &str| {
        vec![
            Step::Wait(2),
            Step::Key(Key::A, Modifiers::COMMAND),
            Step::Text(text.to_string()),
            key(Key::Enter),
            Step::Settle,
        ]
    };
    let mut steps = vec![
        Step::Settle,
        // The canvas framed (its first framing after the results moves the pins).
        key(Key::Home),
        Step::Wait(6),
        print("b before", times_b),
        Step::Drag(
            pin("apex", false, 0),
            pin("times", true, 0),
            PointerButton::Primary,
            Modifiers::NONE,
        ),
        click(field("times", "b")),
    ];
    steps.extend(settle_type("7"));
    steps.extend([
        print("wires after connect", |app| {
            app.doc().graph.wires().len().to_string()
        }),
        print("b after connect", times_b),
        Step::Drag(
            pin("times", false, 0),
            Box::new(|app: &EditorApp, ctx: &egui::Context| {
                Some(pin("times", false, 0)(app, ctx)? + vec2(90.0, 140.0))
            }),
            PointerButton::Primary,
            Modifiers::NONE,
        ),
        click(field("times", "b")),
    ]);
    steps.extend(settle_type("5"));
    steps.extend([
        print("wires after drop", |app| {
            app.doc().graph.wires().len().to_string()
        }),
        print("b after drop", times_b),
        // A path input's Browse… (the right end of its editor), clicked on the canvas.
        click(Box::new(|app: &EditorApp, _: &egui::Context| {
            let r = app.canvas().editor_screen_rect("site", "path")?;
            Some(egui::pos2(r.right() - 8.0, r.center().y))
        })),
        Step::Wait(3),
        print("browse dialog", |app| {
            app.dialog()
                .map_or_else(|| "none".to_string(), |d| format!("{:?}", d.purpose))
        }),
        Step::Shot("wire-click"),
        Step::Quit,
    ]);
    steps
}

/// The nodes added since the script started that have type `type_id`.
fn nodes_of(app: &EditorApp, type_id: &str) -> Vec<String> {
    let mut ids: Vec<String> = app
        .doc()
        .graph
        .nodes()
        .filter(|(_, n)| n.def.id == type_id)
        .map(|(_, n)| n.id.clone())
        .collect();
    ids.sort();
    ids
}

/// `draw`: the Front view (key 2), the Draw curve tool (key C), four clicks at grid points
/// (0, 0), (2, 3), (5, 3), (7, 0) of XZ in grid steps, each off the grid by less than half a
/// step, Enter; the new nodes, their wire and their points printed.
fn draw() -> Vec<Step> {
    let mut steps = vec![Step::Settle, key(Key::Num2), Step::Settle, key(Key::C)];
    steps.extend(scale_lines());
    for (x, z) in [(0.0, 0.0), (2.0, 3.0), (5.0, 3.0), (7.0, 0.0)] {
        steps.push(click(grid_point(DVec3::new(x, 0.0, z), vec2(0.3, -0.2))));
    }
    steps.extend([
        key(Key::Enter),
        Step::Settle,
        print("splines", |app| nodes_of(app, "curve.spline").join(" ")),
        print("points nodes", |app| {
            nodes_of(app, "param.points").join(" ")
        }),
        print("wires", |app| {
            app.doc()
                .graph
                .wires()
                .iter()
                .map(|w| format!("{}.{}->{}.{}", w.from, w.output, w.to, w.input))
                .collect::<Vec<_>>()
                .join(" ")
        }),
        print("drawn", |app| points_text(app, "points")),
        print("selected", |app| app.canvas().selected.join(" ")),
        Step::Shot("draw-front"),
        Step::Quit,
    ]);
    steps
}

/// The centre of the face of the first previewed quad mesh that is highest (z) among the faces
/// whose centre is well inside the view.
fn top_face(app: &EditorApp) -> Option<(String, usize, DVec3)> {
    let picks = app.viewport().picks();
    let map = app.viewport().screen_map();
    let mesh = picks
        .meshes
        .iter()
        .find(|m| m.geometry.face_row_col(0).is_some())?;
    (0..mesh.geometry.face_count())
        .map(|f| {
            let c = mesh.geometry.face_corners(f);
            (f, c.iter().copied().sum::<DVec3>() / c.len() as f64)
        })
        .filter(|(_, c)| {
            map.to_screen(*c)
                .is_some_and(|s| app.viewport().rect().shrink(40.0).contains(s))
        })
        .max_by(|a, b| a.1.z.total_cmp(&b.1.z))
        .map(|(f, c)| (mesh.node.clone(), f, c))
}

/// `pick`: the Top view (key 1), the pointer on the centre of the highest face in view; the
/// tooltip's text printed, then a click and the node focused on the canvas.
fn pick() -> Vec<Step> {
    let target = || -> Target {
        Box::new(|app: &EditorApp, _: &egui::Context| {
            let (_, _, c) = top_face(app)?;
            app.viewport().screen_map().to_screen(c)
        })
    };
    vec![
        Step::Settle,
        key(Key::Num1),
        Step::Settle,
        print("expected", |app| {
            top_face(app).map_or(String::new(), |(node, f, _)| {
                let picks = app.viewport().picks();
                let mesh = picks.meshes.iter().find(|m| m.node == node).unwrap();
                let (i, j) = mesh.geometry.face_row_col(f).unwrap_or_default();
                format!("{node} face (i {i}, j {j})")
            })
        }),
        Step::Move(target()),
        Step::Wait(3),
        print("hover", |app| {
            app.viewport()
                .tools()
                .hover
                .as_ref()
                .map(|h| {
                    cnets_editor::viewport::pick::describe(
                        app.viewport().picks(),
                        h,
                        &app.doc().graph,
                    )
                    .replace('\n', " | ")
                })
                .unwrap_or_default()
        }),
        Step::Shot("pick"),
        click(target()),
        Step::Wait(2),
        print("focused", |app| {
            app.canvas().focused.clone().unwrap_or_default()
        }),
        Step::Quit,
    ]
}

/// `folds`: the legend's fold entry clicked; whether every folded face is framed and outlined.
fn folds() -> Vec<Step> {
    vec![
        Step::Settle,
        print("folds", |app| {
            app.viewport().picks().folded_faces().len().to_string()
        }),
        click(Box::new(|app: &EditorApp, _: &egui::Context| {
            app.viewport().last_frame().fold_entry.map(|r| r.center())
        })),
        Step::Wait(3),
        print("framed", |app| {
            let picks = app.viewport().picks();
            let map = app.viewport().screen_map();
            let inside = picks.folded_faces().iter().all(|(m, f)| {
                picks.meshes[*m].geometry.face_corners(*f).iter().all(|p| {
                    map.to_screen(*p)
                        .is_some_and(|s| app.viewport().rect().expand(1.0).contains(s))
                })
            });
            inside.to_string()
        }),
        print("outlined", |app| {
            app.viewport().highlight().len().to_string()
        }),
        Step::Shot("folds"),
        Step::Quit,
    ]
}

/// `rename-menu`: the node `R` of the start-up graph renamed from its context menu by pointer and
/// keys only — a right-click on its title, a click in the menu's Name field, Ctrl+A, the new name
/// typed, Enter — as a designer does it (the menu must not close on the click in its field).
fn rename_menu() -> Vec<Step> {
    let label = |app: &EditorApp| {
        app.doc()
            .graph
            .node("R")
            .map_or("(none)".to_string(), |n| n.label().to_string())
    };
    let title: Target = Box::new(|app: &EditorApp, _: &egui::Context| {
        app.canvas()
            .node_screen_rect("R")
            // On the title's words, left of the header's buttons (the eye and the enable
            // toggle sit near the middle of a wide node).
            .map(|r| egui::pos2(r.left() + 0.3 * r.width(), r.top() + 12.0))
    });
    let name_field: Target = Box::new(|_: &EditorApp, ctx: &egui::Context| {
        ctx.read_response(egui::Id::new(("rename-node", "R")).with("field"))
            .map(|r| r.rect.center())
    });
    vec![
        Step::Settle,
        key(Key::Home),
        Step::Wait(6),
        print("label before", label),
        Step::Click(title, PointerButton::Secondary, Modifiers::NONE),
        Step::Wait(3),
        click(name_field),
        Step::Wait(2),
        Step::Key(Key::A, Modifiers::COMMAND),
        Step::Text("Radius".into()),
        key(Key::Enter),
        Step::Settle,
        print("label after", label),
        print("saved", |app| {
            cnets_engine::file::to_ron(&app.doc().graph, &Default::default())
                .contains("name: \"Radius\"")
                .to_string()
        }),
        Step::Shot("rename-menu"),
        Step::Quit,
    ]
}

/// The script called `name`.
pub fn script(name: &str) -> Option<Vec<Step>> {
    Some(match name {
        "handles" => handles(),
        "draw" => draw(),
        "pick" => pick(),
        "folds" => folds(),
        "canopy" => super::canopy::canopy(),
        "tutorial" => super::tutorial::tutorial(),
        "wire-click" => wire_click(),
        "drag-net" => super::drag_net::drag_net(),
        "rename-menu" => rename_menu(),
        "cplane" => super::cplane::cplane(),
        _ => return None,
    })
}

/// The names of the scripts.
pub const NAMES: &str =
    "handles, draw, pick, folds, canopy, tutorial, wire-click, drag-net, rename-menu, cplane";
