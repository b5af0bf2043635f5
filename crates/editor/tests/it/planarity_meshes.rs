//! Planarity mode colours every previewed polygon mesh — an imported reference, a cut and
//! mirrored cone-net — not only quad grids, and the header names the mesh its max planarity is
//! for when several are previewed (issue 32).

use crate::common;

use cnets_editor::preview::{ColorMode, LegendInfo};
use common::{graphs_dir, harness_with, settle, temp_config};

/// The editor on the catamaran hull with its reference hull (an OBJ of non-planar quads)
/// previewed.
fn hull_with_reference(name: &str) -> egui_kittest::Harness<'static, cnets_editor::EditorApp> {
    let dir = temp_config(&format!("{name}-graph"));
    std::fs::create_dir_all(dir.join("reference")).unwrap();
    std::fs::copy(
        graphs_dir().join("reference/catamaran-hull.obj"),
        dir.join("reference/catamaran-hull.obj"),
    )
    .unwrap();
    let text = std::fs::read_to_string(graphs_dir().join("catamaran-hull.ron")).unwrap();
    let at = text.find("\"reference_hull\": (").unwrap();
    let hidden = at + text[at..].find("preview: false,").unwrap();
    let text = format!(
        "{}{}",
        &text[..hidden],
        &text[hidden + "preview: false,".len()..]
    );
    std::fs::write(dir.join("hull.ron"), text).unwrap();
    harness_with(name, Some(dir.join("hull.ron")), temp_config(name))
}

/// Distinct vertex colours of the faces in the 3D view.
fn face_colours(h: &egui_kittest::Harness<'static, cnets_editor::EditorApp>) -> usize {
    let colours: std::collections::HashSet<[u8; 4]> = h
        .state()
        .viewport()
        .scene()
        .face_vertices()
        .iter()
        .map(|v| v.color.0)
        .collect();
    colours.len()
}

#[test]
fn snapshot_planarity_of_the_hull_and_its_reference() {
    let mut h = hull_with_reference("planarity-meshes");
    let mut o = h.state().viewport().display().options;
    o.color_mode = ColorMode::Planarity;
    h.state_mut()
        .run(cnets_editor::menus::MenuAction::SetPreview(o));
    settle(&mut h);
    let stats = h.state().viewport().stats().clone();
    // The reference's quads are far from planar; the cone-net's are planar to rounding.
    assert!(stats.max_planarity.unwrap() > 1e-4, "{stats:?}");
    assert_eq!(
        stats.max_planarity_mesh.as_deref(),
        Some("reference_hull.mesh"),
        "{stats:?}"
    );
    assert!(
        matches!(stats.legend, LegendInfo::Planarity(_)),
        "{stats:?}"
    );
    // Every face of both meshes is coloured by its planarity: more than one colour.
    let colours = face_colours(&h);
    assert!(colours > 10, "{colours} colours");
    h.snapshot("editor_planarity_meshes");
}

#[test]
fn snapshot_distance_to_the_reference_with_its_legend_in_metres() {
    let mut h = hull_with_reference("distance-mode");
    let reference = h.state().doc().graph.node("reference_hull").unwrap().uid();
    let mut o = h.state().viewport().display().options;
    o.color_mode = ColorMode::Distance;
    o.distance_to = Some(reference);
    h.state_mut()
        .run(cnets_editor::menus::MenuAction::SetPreview(o));
    settle(&mut h);
    let stats = h.state().viewport().stats().clone();
    let d = stats.distance.clone().expect("distance figures");
    assert_eq!(d.reference, "reference_hull", "{d:?}");
    // The net lies within centimetres to decimetres of the reference, never on it everywhere.
    assert!(d.max > 1e-3 && d.max < 1.0, "{d:?}");
    assert!(d.rms > 0.0 && d.rms <= d.max, "{d:?}");
    assert!(d.vertices > 100, "{d:?}");
    let LegendInfo::Distance(legend) = &stats.legend else {
        panic!("{stats:?}");
    };
    assert!(
        legend.title.contains("reference_hull"),
        "the legend names the reference: {legend:?}"
    );
    // The reference keeps its own colour; the net is coloured by distance (many colours).
    let colours = face_colours(&h);
    assert!(colours > 10, "{colours} colours");
    h.snapshot("editor_distance_legend");
}
