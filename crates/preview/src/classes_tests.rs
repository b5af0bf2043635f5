//! A cone-net cut and mirrored keeps its faces' configuration classes, so the view colours the
//! trimmed, mirrored structure by class and its fold finder finds the folds that were kept.

use cnets_engine::{Evaluator, NodeContext, Value};
use cnets_geometry::fabrication::{FaceClass, face_classes};
use cnets_geometry::{DVec3, Plane, PolygonMesh, QuadGrid};

use crate::{ColorMode, LegendInfo, PreviewOptions, build_preview};

fn mesh(eval: &Evaluator, g: &cnets_engine::Graph, node: &str) -> PolygonMesh {
    match eval.output(g, node, "mesh") {
        Some(Value::Mesh(m)) => (**m).clone(),
        Some(Value::QuadMesh(q)) => PolygonMesh::from(&**q),
        other => panic!("{node}.mesh: {other:?}"),
    }
}

fn folds(classes: &[FaceClass]) -> usize {
    classes.iter().filter(|c| **c != FaceClass::Convex).count()
}

fn centroid(m: &PolygonMesh, f: usize) -> DVec3 {
    let face = m.face(f);
    face.iter().map(|&v| m.vertices[v as usize]).sum::<DVec3>() / face.len() as f64
}

#[test]
fn a_cut_mirrored_net_keeps_its_classes_and_the_view_finds_its_folds() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../graphs/correction.ron");
    let registry = std::sync::Arc::new(cnets_nodes::registry());
    let mut doc = cnets_engine::file::load_file(std::path::Path::new(path), &registry).unwrap();
    let ctx = NodeContext::new(None, None);
    let mut eval = Evaluator::new();
    eval.evaluate_all(&doc.graph, &ctx);
    // The first net, unassisted (assistance −1): its ratios fold quads over.
    let first = |output: &str| {
        eval.output(&doc.graph, "nets", output)
            .and_then(Value::as_list)
            .and_then(|l| l.first())
            .cloned()
            .unwrap_or_else(|| panic!("nets.{output}: a list"))
    };
    let grid: QuadGrid = match first("mesh") {
        Value::QuadMesh(q) => (*q).clone(),
        other => panic!("nets.mesh: {}", other.type_name()),
    };
    let classes = grid
        .face_classes()
        .expect("the construction's classes on its mesh");
    let labels: Vec<Vec<String>> = first("configurations")
        .as_list()
        .unwrap()
        .iter()
        .map(|row| {
            row.as_list()
                .unwrap()
                .iter()
                .map(|t| match t {
                    Value::Text(t) => t.to_string(),
                    other => panic!("a label: {other:?}"),
                })
                .collect()
        })
        .collect();
    assert_eq!(classes, face_classes(&grid, &labels).unwrap().as_slice());
    let planted = folds(classes);
    assert!(planted > 0, "the unassisted net folds");

    // Cut across the directrix through the net's middle, keeping the side with more folds, and
    // mirror the kept part in the cut plane.
    let whole = PolygonMesh::from(&grid);
    let along = (grid.at(0, grid.cols - 1) - grid.at(0, 0)).normalize();
    let middle = grid.vertices.iter().copied().sum::<DVec3>() / grid.vertices.len() as f64;
    let ahead = (0..whole.face_count())
        .filter(|&f| classes[f] != FaceClass::Convex)
        .filter(|&f| (centroid(&whole, f) - middle).dot(along) > 0.0)
        .count();
    let normal = if 2 * ahead >= planted { along } else { -along };
    let plane = Plane::from_normal(middle, normal).unwrap();
    let g = &mut doc.graph;
    g.add_node("cut", "mesh.cut_by_plane").unwrap();
    g.add_node("mirrored", "mesh.mirror").unwrap();
    g.set_value("cut", "mesh", Value::from(grid.clone()))
        .unwrap();
    g.connect("cut", "mesh", "mirrored", "mesh").unwrap();
    g.set_value("cut", "plane", Value::from(plane)).unwrap();
    g.set_value("mirrored", "plane", Value::from(plane))
        .unwrap();
    eval.evaluate_all(&doc.graph, &ctx);
    let (cut, mirrored) = (
        mesh(&eval, &doc.graph, "cut"),
        mesh(&eval, &doc.graph, "mirrored"),
    );

    // Every face of the cut has a class; a face kept whole has its source face's.
    let cut_classes = cut.face_classes().expect("the cut keeps the classes");
    let corners = |m: &PolygonMesh, f: usize| -> Vec<DVec3> {
        m.face(f).iter().map(|&v| m.vertices[v as usize]).collect()
    };
    let mut whole_faces = 0;
    for (f, class) in cut_classes.iter().enumerate() {
        let c = corners(&cut, f);
        if let Some(src) = (0..whole.face_count()).find(|&s| corners(&whole, s) == c) {
            assert_eq!(*class, classes[src], "face {f} (source {src})");
            whole_faces += 1;
        }
    }
    assert!(
        whole_faces > whole.face_count() / 4,
        "{whole_faces} faces kept whole"
    );
    let kept = folds(cut_classes);
    assert!(
        kept > 0 && kept <= planted,
        "{kept} of {planted} folds kept"
    );

    // The mirror image has its source faces' classes: twice the folds.
    let mirrored_classes = mirrored
        .face_classes()
        .expect("the mirror keeps the classes");
    assert_eq!(mirrored.face_count(), 2 * cut.face_count());
    assert_eq!(folds(mirrored_classes), 2 * kept);

    // The view: the mirrored structure coloured by class, and every fold of it found.
    let mut options = PreviewOptions::default();
    options.color_mode = ColorMode::Configuration;
    let preview = build_preview(&doc.graph, &eval, &options);
    let m = preview
        .picks
        .meshes
        .iter()
        .position(|p| p.node == "mirrored")
        .expect("the mirrored structure is drawn");
    assert_eq!(
        preview.picks.meshes[m].classes.as_deref(),
        Some(mirrored_classes)
    );
    let found = preview
        .picks
        .folded_faces()
        .iter()
        .filter(|(k, _)| *k == m)
        .count();
    assert_eq!(found, 2 * kept, "the fold finder on the mirrored structure");
    assert!(
        matches!(preview.stats.legend, LegendInfo::Classes(_)),
        "the legend lists the classes"
    );
}
