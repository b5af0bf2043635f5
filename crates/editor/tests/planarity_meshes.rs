//! Planarity mode colours every previewed polygon mesh — an imported reference, a cut and
//! mirrored cone-net — not only quad grids, and the header names the mesh its max planarity is
//! for when several are previewed (issue 32).

mod common;

use cnets_editor::preview::{ColorMode, LegendInfo};
use common::{graphs_dir, harness_with, settle, temp_config};

#[test]
fn snapshot_planarity_of_the_hull_and_its_reference() {
    // The catamaran hull with its reference hull (an OBJ of non-planar quads) previewed.
    let dir = temp_config("planarity-meshes-graph");
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
    let mut h = harness_with(
        "planarity-meshes",
        Some(dir.join("hull.ron")),
        temp_config("planarity-meshes"),
    );
    let mut o = h.state().viewport.options;
    o.color_mode = ColorMode::Planarity;
    h.state_mut()
        .run(cnets_editor::menus::MenuAction::SetPreview(o));
    settle(&mut h);
    let stats = h.state().viewport.stats.clone();
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
    let colours: std::collections::HashSet<[u8; 4]> = h
        .state()
        .viewport
        .scene()
        .face_vertices()
        .iter()
        .map(|v| v.color.0)
        .collect();
    assert!(colours.len() > 10, "{} colours", colours.len());
    h.snapshot("editor_planarity_meshes");
}
