//! `drag-net`: the Drag net tool played with pointer events only, on the editor's start-up graph
//! (the gallery's torus-monge): the Top view zoomed in on `varying_ratios` (the wheel), the tool
//! (G), a vertex of the net pinned with Shift+click, another dragged 0.632 m (±0.6 m in x and
//! ±0.2 m in y, the first direction the net can follow with the pin held; else half that), then
//! Ctrl+Z. It prints what the
//! view shows before, after and undone (every input's literal, the grabbed and pinned vertices,
//! the faces that are not (++)(++)), the target the pointer asked for and the solver's figures.

use std::cell::Cell;
use std::rc::Rc;

use cnets_editor::app::EditorApp;
use cnets_editor::viewport::net_drag::vertex_at;
use cnets_geometry::DVec3;
use cnets_preview::PickGeometry;
use egui::{Key, Modifiers, PointerButton, Pos2};

use super::script::{Step, Target};

/// The net dragged.
const NET: &str = "varying_ratios";
/// How many times the pair to drag and pin is searched for before the script gives up, and the
/// frames between searches.
const SEARCHES: u32 = 5;
const SEARCH_EVERY: u32 = 10;
/// The searching ends (the script reports a skip) once it has taken this long: a search that
/// finds nothing solves thousands of drags, and the script's step must end within its patience
/// (a full-suite run here timed out after two searches of about 90 s each).
const SEARCH_BUDGET: std::time::Duration = std::time::Duration::from_secs(100);
/// The moves tried, in metres (the Top view's plane): one known distance (0.632 m) in four
/// directions. Which direction a net can follow depends on the vertex: at some zooms (the wheel's
/// last step varies with the machine's load, and with it the vertices in view) no vertex in view
/// could follow the first one with a pin held (a full-suite run here: 64 vertices × 10 pins, the
/// nearest try 0.41 m short), so the others are tried before giving up.
/// Then the same directions at half the distance (0.316 m).
const MOVES: [DVec3; 8] = [
    DVec3::new(0.6, 0.2, 0.0),
    DVec3::new(-0.6, 0.2, 0.0),
    DVec3::new(0.6, -0.2, 0.0),
    DVec3::new(-0.6, -0.2, 0.0),
    DVec3::new(0.3, 0.1, 0.0),
    DVec3::new(-0.3, 0.1, 0.0),
    DVec3::new(0.3, -0.1, 0.0),
    DVec3::new(-0.3, -0.1, 0.0),
];

fn print(key: &'static str, f: impl Fn(&EditorApp) -> String + 'static) -> Step {
    Step::Print(key, Box::new(f))
}

/// The vertices of the net (with `interior_only`, not on its first column, the generatrix the
/// mapper handles do not move, nor on its first or last row) the pointer can grab where the view draws them
/// (not hidden behind another face): the middle row's first, nearest the view's centre first.
fn grabbable(app: &EditorApp, interior_only: bool) -> Vec<((usize, usize), DVec3, Pos2)> {
    let picks = app.viewport().picks();
    let map = app.viewport().screen_map();
    let inner = app.viewport().rect().shrink(60.0);
    let Some(PickGeometry::Grid(g)) = picks
        .meshes
        .iter()
        .find(|m| m.node == NET)
        .map(|m| &m.geometry)
    else {
        return Vec::new();
    };
    let mut found: Vec<((usize, usize), DVec3, Pos2)> = g
        .vertices
        .iter()
        .enumerate()
        .filter_map(|(k, p)| {
            let at = map.to_screen(*p).filter(|s| inner.contains(*s))?;
            let v = vertex_at(picks, &map, at)?;
            let ij = (k / g.cols, k % g.cols);
            let interior = !interior_only || (ij.0 > 0 && ij.0 + 1 < g.rows && ij.1 > 0);
            (interior && v.node == NET && v.vertex == ij).then_some((ij, *p, at))
        })
        .collect();
    let centre = app.viewport().rect().center();
    let middle = g.rows / 2;
    found.sort_by(|a, b| {
        (a.0.0.abs_diff(middle), a.2.distance(centre))
            .partial_cmp(&(b.0.0.abs_diff(middle), b.2.distance(centre)))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    found
}

/// A move of [`MOVES`], a vertex to drag by it and one to pin, both grabbable, for which the engine's drag (the
/// CLI's `cnets drag`) reaches the target with the pin held: the script's claim is that the tool
/// takes a reachable target, not that every target is reachable. The first pair found, nearest
/// the view's centre. Every grabbable vertex is tried (the wheel's zoom, and so the vertices in
/// view, varies with the machine's load: the nearest few may have no reachable pin).
type Grabbable = ((usize, usize), DVec3, Pos2);
fn reachable_pair(
    app: &EditorApp,
    grabs: &[Grabbable],
    found: &[Grabbable],
    deadline: std::time::Instant,
) -> Option<(DVec3, Grabbable, Grabbable)> {
    use cnets_engine::optimize::drag::{DragRequest, drag};
    let graph = app.doc().eval_graph();
    let ctx = cnets_engine::NodeContext::default();
    let far = |a: &Grabbable, b: &Grabbable| a.0.0.abs_diff(b.0.0) + a.0.1.abs_diff(b.0.1);
    for step in MOVES {
        for grab in grabs {
            // Pins far from the grabbed vertex first; a pair that needs more than 12 steps is
            // passed over (reachable ones took 7–11 on this net).
            let mut pins: Vec<&Grabbable> = found.iter().filter(|p| far(p, grab) >= 4).collect();
            pins.sort_by_key(|p| std::cmp::Reverse(far(p, grab)));
            for pin in pins.into_iter().take(10) {
                if std::time::Instant::now() > deadline {
                    return None;
                }
                let mut request = DragRequest::new(NET, grab.0, grab.1 + step);
                request.pins = vec![pin.0];
                request.max_iter = 12;
                if drag(&graph, &request, &ctx).is_ok_and(|r| r.distance_left < 1e-6) {
                    return Some((step, *grab, *pin));
                }
            }
        }
    }
    None
}

/// What the first pair of a failed search gave: how far the picture's vertex is from the engine's
/// (a drag to where the picture shows it), and the drag's own answer.
fn first_try(app: &EditorApp, grabs: &[Grabbable], found: &[Grabbable]) -> String {
    use cnets_engine::optimize::drag::{DragRequest, drag};
    let (Some(grab), Some(pin)) = (grabs.first(), found.last()) else {
        return "nothing to try".into();
    };
    let graph = app.doc().eval_graph();
    let ctx = cnets_engine::NodeContext::default();
    let mut still = DragRequest::new(NET, grab.0, grab.1);
    still.max_iter = 0;
    let stale = match drag(&graph, &still, &ctx) {
        Ok(r) => format!("{:.3e}", r.distance_left),
        Err(e) => format!("error {e}"),
    };
    let mut request = DragRequest::new(NET, grab.0, grab.1 + MOVES[0]);
    request.pins = vec![pin.0];
    request.max_iter = 12;
    let tried = match drag(&graph, &request, &ctx) {
        Ok(r) => format!(
            "left {:.3e} m after {} steps, pin drift {:.1e}",
            r.distance_left, r.iterations, r.pin_drift
        ),
        Err(e) => format!("error {e}"),
    };
    format!(
        "first try {:?} pinned {:?}: picture to engine {stale} m; {tried}",
        grab.0, pin.0
    )
}

/// Where the net's vertex (i, j) is in the picture shown.
fn position(app: &EditorApp, ij: (usize, usize)) -> Option<DVec3> {
    let picks = app.viewport().picks();
    match &picks.meshes.iter().find(|m| m.node == NET)?.geometry {
        PickGeometry::Grid(g) => g.vertices.get(ij.0 * g.cols + ij.1).copied(),
        PickGeometry::Mesh(_) => None,
    }
}

fn vec(p: Option<DVec3>) -> String {
    p.map_or("none".into(), |p| format!("{:?},{:?},{:?}", p.x, p.y, p.z))
}

/// Every literal input of the document, with every digit.
fn inputs(app: &EditorApp) -> String {
    let mut lines: Vec<String> = app
        .doc()
        .graph
        .nodes()
        .flat_map(|(_, n)| {
            (0..n.def.inputs.len()).filter_map(move |k| {
                Some(format!(
                    "{}.{}={:?}",
                    n.id,
                    n.def.inputs[k].name,
                    n.value(k)?
                ))
            })
        })
        .collect();
    lines.sort();
    lines.join(";")
}

/// The script.
pub fn drag_net() -> Vec<Step> {
    // The grabbed vertex and the pinned one, chosen once the Top view is drawn.
    let grabbed: Rc<Cell<Option<(usize, usize)>>> = Rc::default();
    let pinned: Rc<Cell<Option<(usize, usize)>>> = Rc::default();
    let (g1, g2, g3, g4, g5) = (
        grabbed.clone(),
        grabbed.clone(),
        grabbed.clone(),
        grabbed.clone(),
        grabbed.clone(),
    );
    let (p1, p2, p3, p4) = (
        pinned.clone(),
        pinned.clone(),
        pinned.clone(),
        pinned.clone(),
    );
    // Searched once the net is in view, again every [`SEARCH_EVERY`] frames while no pair is
    // found (the picture the picks come from may still be catching up with the zoom on a busy
    // machine), at most [`SEARCHES`] times: the search solves drags, not every frame.
    let frames = Rc::new(Cell::new(0u32));
    // When the first search began (the searching has [`SEARCH_BUDGET`]).
    let search_began = Rc::new(std::cell::OnceCell::new());
    // The move the search found a pair for.
    let chosen = Rc::new(Cell::new(MOVES[0]));
    let step = chosen.clone();
    let pin_at: Target = Box::new(move |app: &EditorApp, _: &egui::Context| {
        let found = grabbable(app, false);
        if let (Some(ij), Some(pin)) = (g1.get(), p1.get()) {
            return found.iter().find(|v| v.0 == pin && ij != pin).map(|v| v.2);
        }
        let frame = frames.get();
        frames.set(frame + 1);
        if found.is_empty() || !frame.is_multiple_of(SEARCH_EVERY) {
            return None;
        }
        let interior = grabbable(app, true);
        println!(
            "script: in view = {} vertices, {} interior, {:.4} m a point",
            found.len(),
            interior.len(),
            app.viewport().screen_map().world_per_point()
        );
        let deadline = *search_began.get_or_init(std::time::Instant::now) + SEARCH_BUDGET;
        let Some((step, ij, pin)) = reachable_pair(app, &interior, &found, deadline) else {
            println!(
                "script: search {} = {} vertices in view, {} interior, no reachable pair; {}",
                frame / SEARCH_EVERY + 1,
                found.len(),
                interior.len(),
                first_try(app, &interior, &found)
            );
            if frame / SEARCH_EVERY + 1 >= SEARCHES || std::time::Instant::now() > deadline {
                // Reported, not failed: no vertex in view can follow any of the moves with a pin
                // held (which vertices are in view varies with the wheel's last step on a busy
                // machine). The line above says what the first try gave; the test says it
                // skipped.
                println!(
                    "script: skipped = no grabbable vertex has a reachable pinned pair in view"
                );
                println!("script: end");
                std::process::exit(0);
            }
            return None;
        };
        g1.set(Some(ij.0));
        p1.set(Some(pin.0));
        chosen.set(step);
        println!("script: move = {:?},{:?},{:?}", step.x, step.y, step.z);
        Some(pin.2)
    });
    let from: Target = Box::new(move |app: &EditorApp, _: &egui::Context| {
        let ij = g2.get()?;
        app.viewport().screen_map().to_screen(position(app, ij)?)
    });
    let to: Target = Box::new(move |app: &EditorApp, _: &egui::Context| {
        let ij = g3.get()?;
        app.viewport()
            .screen_map()
            .to_screen(position(app, ij)? + step.get())
    });
    // The middle of the net on screen, for the wheel.
    let net_centre: Target = Box::new(|app: &EditorApp, _: &egui::Context| {
        let picks = app.viewport().picks();
        let mesh = picks.meshes.iter().find(|m| m.node == NET)?;
        let points = mesh.geometry.vertices();
        let mean = points.iter().copied().sum::<DVec3>() / points.len().max(1) as f64;
        app.viewport().screen_map().to_screen(mean)
    });
    vec![
        Step::Settle,
        Step::Key(Key::Num1, Modifiers::NONE),
        Step::Settle,
        // Zoomed in until 0.6 m is about 13 points on screen.
        Step::WheelUntil(
            net_centre,
            120.0,
            Box::new(|app: &EditorApp| app.viewport().screen_map().world_per_point() < 0.05),
        ),
        Step::Settle,
        Step::Key(Key::G, Modifiers::NONE),
        Step::Wait(2),
        print("tool", |app| app.viewport().tool().label().to_string()),
        print("inputs before", inputs),
        Step::Click(pin_at, PointerButton::Primary, Modifiers::SHIFT),
        Step::Wait(2),
        print("grabbed", move |_| format!("{:?}", g4.get())),
        print("pinned", move |_| format!("{:?}", p2.get())),
        print("pins", |app| match &app.viewport().tool() {
            cnets_editor::viewport::Tool::DragNet(d) => d.pins.len().to_string(),
            _ => "no tool".into(),
        }),
        print("grabbed before", move |app| {
            vec(g5.get().and_then(|ij| position(app, ij)))
        }),
        print("pinned before", move |app| {
            vec(p3.get().and_then(|ij| position(app, ij)))
        }),
        Step::Drag(from, to, PointerButton::Primary, Modifiers::NONE),
        Step::Settle,
        Step::Shot("drag-net"),
        print("figures", |app| match app.last_net_drag() {
            Some(f) => format!(
                "{}|{:?}|{}|{}|{}|{:.3}|{:.2}",
                f.node,
                f.vertex,
                vec(f.target),
                f.solved.as_ref().map_or(f64::NAN, |s| s.distance_left),
                f.solves,
                f.seconds,
                f.solve_ms
            ),
            None => "none".into(),
        }),
        // The window's side of the drag: the UI thread's time a frame while it ran (median,
        // p90, max, frames) and the release frame's wait for the last answer (ms).
        print("ui frames", |app| match app.last_net_drag() {
            Some(f) => {
                let mut v = f.ui_frame_ms.clone();
                v.sort_by(f64::total_cmp);
                let q = |p: f64| {
                    v.get(((v.len().max(1) - 1) as f64 * p).round() as usize)
                        .copied()
                        .unwrap_or(f64::NAN)
                };
                format!(
                    "{:.2}|{:.2}|{:.2}|{}|{:.1}",
                    q(0.5),
                    q(0.9),
                    q(1.0),
                    v.len(),
                    f.release_ms
                )
            }
            None => "none".into(),
        }),
        print("target", |app| {
            vec(app.last_net_drag().and_then(|f| f.target))
        }),
        print("grabbed after", move |app| {
            let ij = app.last_net_drag().map(|f| f.vertex);
            vec(ij.and_then(|ij| position(app, ij)))
        }),
        print("pinned after", move |app| {
            vec(p4.get().and_then(|ij| position(app, ij)))
        }),
        print("not convex", |app| {
            let picks = app.viewport().picks();
            let folded = picks
                .folded_faces()
                .iter()
                .filter(|(m, _)| picks.meshes[*m].node == NET)
                .count();
            let classified = picks
                .meshes
                .iter()
                .any(|m| m.node == NET && m.classes.is_some());
            format!("{folded}|{classified}")
        }),
        print("inputs after", inputs),
        print("undo steps", |app| app.doc().history.undo_len().to_string()),
        print("status", |app| app.message().to_string()),
        Step::Key(Key::Z, Modifiers::COMMAND),
        Step::Settle,
        print("inputs undone", inputs),
        Step::Quit,
    ]
}
