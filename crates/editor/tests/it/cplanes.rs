//! Construction planes kept with the graph, in kittest: a plane fitted through the selected
//! curve holds its points, is named, becomes the Perspective view's plane, is chosen back from
//! the list, goes with undo and is saved in the graph file; with nothing suitable selected the
//! editor says what to select.

use crate::common;

use cnets_editor::app::EditorApp;
use cnets_editor::menus::MenuAction;
use cnets_editor::viewport::{CPlane, NamedView};
use cnets_geometry::DVec3;
use common::{harness_with, settle, temp_config};
use egui_kittest::Harness;

/// Four points of a tilted plane (x + y + 2z = 3), drawn as a polyline.
const TILTED_GRAPH: &str = r#"(
    version: 1,
    nodes: {
        "pts": (
            type: "param.points",
            position: (0.0, 0.0),
            inputs: {
                "points": [(1.0, 0.0, 1.0), (3.0, 0.0, 0.0), (3.0, 2.0, -1.0), (-1.0, 2.0, 1.0)],
            },
        ),
        "outline": (type: "curve.polyline", position: (300.0, 0.0), preview: true),
    },
    edges: ["pts.points -> outline.points"],
)"#;

fn open(name: &str) -> Harness<'static, EditorApp> {
    let dir = temp_config(&format!("{name}-files"));
    let file = dir.join(format!("{name}.ron"));
    std::fs::write(&file, TILTED_GRAPH).unwrap();
    let mut h = harness_with(name, Some(file), temp_config(name));
    settle(&mut h);
    h
}

fn names(app: &EditorApp) -> Vec<String> {
    app.doc()
        .meta
        .cplanes
        .iter()
        .map(|p| p.name.clone())
        .collect()
}

#[test]
fn a_plane_fitted_through_the_selected_curve_is_named_chosen_undone_and_saved() {
    let mut h = open("cplane-fit");
    h.state_mut().select_nodes(vec!["outline".into()]);
    h.state_mut().run(MenuAction::CPlaneThroughSelection);
    let app = h.state();
    assert_eq!(names(app), ["CPlane 1"], "{}", app.message());
    assert_eq!(app.viewport().framing().perspective_name, "CPlane 1");
    assert_eq!(app.viewport().framing().view, NamedView::Perspective);
    assert!(
        app.message().contains("the curve of outline"),
        "{}",
        app.message()
    );
    let plane = app.viewport().framing().perspective_plane;
    let n = DVec3::new(1.0, 1.0, 2.0).normalize();
    assert!(plane.normal.dot(n).abs() > 1.0 - 1e-12, "{plane:?}");
    for p in [
        DVec3::new(1.0, 0.0, 1.0),
        DVec3::new(3.0, 2.0, -1.0),
        DVec3::new(-1.0, 2.0, 1.0),
    ] {
        assert!(plane.local(p).z.abs() < 1e-12, "{p} off the plane");
    }
    assert_eq!(
        app.viewport().cplane(),
        plane,
        "the Perspective view draws in it"
    );
    // World XY and back to the graph's plane from the list.
    h.state_mut().run(MenuAction::PerspectivePlane(CPlane::XY));
    assert_eq!(h.state().viewport().cplane(), CPlane::XY);
    assert_eq!(h.state().viewport().framing().perspective_name, "World XY");
    h.state_mut()
        .run(MenuAction::NamedCPlane("CPlane 1".into()));
    assert_eq!(h.state().viewport().cplane(), plane);
    // Saved in the file and read back exactly.
    let text = cnets_engine::file::to_ron(&h.state().doc().graph, &h.state().doc().meta);
    let registry = h.state().doc().graph.registry().clone();
    let again = cnets_engine::file::load_str(&text, "again.ron", &registry).unwrap();
    assert_eq!(again.meta.cplanes, h.state().doc().meta.cplanes);
    assert_eq!(CPlane::from_named(&again.meta.cplanes[0]), Some(plane));
    // A second plane gets the next name; undo takes it away again.
    h.state_mut().run(MenuAction::CPlaneThroughSelection);
    assert_eq!(names(h.state()), ["CPlane 1", "CPlane 2"]);
    h.state_mut().run(MenuAction::Undo);
    assert_eq!(names(h.state()), ["CPlane 1"]);
}

#[test]
fn with_nothing_suitable_selected_the_editor_says_what_to_select() {
    let mut h = open("cplane-none");
    h.state_mut().select_nodes(Vec::new());
    h.state_mut().focus_node(None);
    h.state_mut().run(MenuAction::CPlaneThroughSelection);
    let app = h.state();
    assert!(names(app).is_empty());
    assert!(
        app.message()
            .contains("select a node whose curve is previewed"),
        "{}",
        app.message()
    );
    assert_eq!(
        app.viewport().framing().perspective_plane,
        CPlane::XY,
        "unchanged"
    );
    h.state_mut().run(MenuAction::CPlaneFromPoints);
    assert_eq!(h.state().viewport().tool().label(), "CPlane from 3 points");
    assert!(h.state().message().contains("click its origin"));
}
