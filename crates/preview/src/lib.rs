//! What a graph shows: the geometry outputs of every node whose preview is on, turned into a render
//! [`Scene`](cnets_render::Scene), plus the figures shown with it (vertex count, max planarity,
//! legend) and, for the editor, what each drawn face and vertex came from ([`Picks`]). Shared by
//! the editor's viewport and `cnets render`, so both show the same picture.
//!
//! Outputs are sorted into layers by type and port name, so each layer can be toggled:
//! quad / polygon meshes are surfaces (coloured by configuration class, planarity or plainly),
//! polylines and unnamed segment sets are curves (directrix, generatrix…), points named `apices`
//! are apices, segment sets named `…axes…` are torsion-free axes, anything named `…support…` is
//! a support layer. Lists (from nodes run per item) are flattened.

mod beside;
mod build;
mod classes;
#[cfg(test)]
mod classes_tests;
mod distance;
#[cfg(test)]
mod distance_tests;
mod legend;
mod options;
#[cfg(test)]
mod parts_tests;
mod picks;

pub use build::{
    MeshFigures, MeshKind, Preview, PreviewStats, build_preview, build_scene, distance_legend,
    format_metres, layer_of,
};
pub use classes::{class_color, face_classes};
pub use distance::{
    DistanceFigures, SAMPLE_BUDGET, default_distance_reference, gives_mesh, is_construction,
    samples_for,
};
pub use legend::{APEX_COLOR, APEX_LEGEND, LegendInfo, legend_rows, paper_class};
pub use options::{ColorMode, DistanceSide, Layer, PLANARITY_LIMIT_RANGE, PreviewOptions};
pub use picks::{PickCurve, PickGeometry, PickMesh, Picks};

#[cfg(test)]
mod tests {
    #[test]
    fn the_planarity_limit_is_user_set_and_named_in_the_legend() {
        let mut o = PreviewOptions::default();
        assert_eq!(o.planarity_limit(), 1e-3);
        assert!(o.set_planarity_limit(1e-4));
        assert!(!o.set_planarity_limit(f64::NAN) && !o.set_planarity_limit(2.0));
        assert!(!o.set_planarity_limit(1e-12), "below the planar anchor");
        let m = o.planarity_map();
        assert_eq!((m.planar, m.limit), (1e-9, 1e-4));
        assert_eq!(m.normalize(1e-4), 1.0);
        assert!(m.normalize(1e-5) < 1.0 && m.normalize(1e-5) > 0.0);
        let (title, rows) = legend_rows(&LegendInfo::Planarity(m.legend())).unwrap();
        assert!(!title.is_empty());
        assert!(rows[0].1.contains("1e-4"), "top row: {:?}", rows[0]);
        assert!(rows.last().unwrap().1.starts_with("planar"), "{rows:?}");
        let (_, classes) = legend_rows(&LegendInfo::Classes(vec![
            (FaceClass::Convex, 3),
            (FaceClass::NegativeApex, 1),
        ]))
        .unwrap();
        assert_eq!(classes[0].1, "(++)(++)  convex  3");
        assert!(classes[1].1.starts_with("(+−)/(−+)"), "{classes:?}");
    }

    use super::*;
    use cnets_engine::Value;
    use cnets_geometry::fabrication::FaceClass;
    use cnets_geometry::{DVec3, QuadGrid};
    use cnets_render::Color;

    fn grid(rows: usize, cols: usize) -> QuadGrid {
        let vertices = (0..rows)
            .flat_map(|i| (0..cols).map(move |j| DVec3::new(j as f64, i as f64, 0.0)))
            .collect();
        QuadGrid {
            classes: Vec::new(),
            rows,
            cols,
            wrap_rows: false,
            wrap_cols: false,
            vertices,
        }
    }

    fn table(rows: usize, labels: &[&str]) -> Value {
        Value::list(
            (0..rows)
                .map(|_| Value::list(labels.iter().map(Value::text).collect()))
                .collect(),
        )
    }

    #[test]
    fn the_flat_layer_is_drawn_beside_the_design_and_flagged_out_of_its_size() {
        let mut g = cnets_engine::Graph::new(std::sync::Arc::new(cnets_nodes::registry()));
        g.add_node("net", "param.list").unwrap();
        g.set_value("net", "item_type", Value::text("any")).unwrap();
        // A 4 × 6 sheet bent along its length: its strips unroll over its own plan.
        let mut bent = grid(4, 6);
        bent.vertices
            .iter_mut()
            .for_each(|p| p.z = 0.3 * (p.x - 2.5).powi(2));
        g.set_value(
            "net",
            "values",
            Value::list(vec![Value::from(bent.clone())]),
        )
        .unwrap();
        g.add_node("flat", "pq.unroll_strips").unwrap();
        g.connect("net", "values", "flat", "mesh").unwrap();
        let mut eval = cnets_engine::Evaluator::new();
        eval.evaluate_all(&g, &cnets_engine::NodeContext::new(None, None));
        let mut opts = PreviewOptions::default();
        opts.set(Layer::Unrolled, true);
        let preview = build_preview(&g, &eval, &opts);
        let scene = &preview.scene;
        let beside: Vec<_> = scene
            .segments()
            .iter()
            .filter(|s| s.flags & cnets_render::FLAG_BESIDE != 0)
            .collect();
        assert!(!beside.is_empty(), "the unrolled outlines are drawn");
        let design_max_x = bent.vertices.iter().map(|p| p.x).fold(f64::MIN, f64::max) as f32;
        assert!(
            beside
                .iter()
                .all(|s| s.a[0] > design_max_x + 0.5 && s.b[0] > design_max_x + 0.5),
            "every flat segment lies past the design's +X side"
        );
        // The rest (the net's edges) is the design: its box is the net's.
        let design: Vec<_> = scene
            .segments()
            .iter()
            .filter(|s| s.flags & cnets_render::FLAG_BESIDE == 0)
            .flat_map(|s| [s.a[0], s.b[0]])
            .collect();
        let hi = design.iter().copied().fold(f32::MIN, f32::max);
        assert!((hi - design_max_x).abs() < 1e-4, "{hi} vs {design_max_x}");
        // Off (the default), nothing of it is drawn.
        let plain = build_preview(&g, &eval, &PreviewOptions::default());
        assert!(
            plain
                .scene
                .segments()
                .iter()
                .all(|s| s.flags & cnets_render::FLAG_BESIDE == 0)
        );
    }

    #[test]
    fn a_list_shows_its_meshes_under_their_own_item_numbers_and_its_numbers_not_at_all() {
        let mut g = cnets_engine::Graph::new(std::sync::Arc::new(cnets_nodes::registry()));
        g.add_node("mixed", "param.list").unwrap();
        g.set_value("mixed", "item_type", Value::text("any"))
            .unwrap();
        let mesh = Value::from(grid(2, 3));
        let mut items = vec![Value::Number(1.0), mesh.clone()];
        items.extend((0..50_000).map(|k| Value::Number(k as f64)));
        items.push(mesh);
        g.set_value("mixed", "values", Value::list(items)).unwrap();
        let mut eval = cnets_engine::Evaluator::new();
        let ctx = cnets_engine::NodeContext::new(None, None);
        eval.evaluate_all(&g, &ctx);
        let preview = build_preview(&g, &eval, &PreviewOptions::default());
        let items: Vec<Option<usize>> = preview.picks.meshes.iter().map(|m| m.item).collect();
        assert_eq!(items, [Some(1), Some(50_002)]);
        assert_eq!(preview.stats.vertices, 12);
        // A packed list of numbers (as the JSON reader makes) shows nothing.
        let packed = Value::List(cnets_engine::Items::numbers(
            std::sync::Arc::new(vec![0.5; 10]),
            0..10,
        ));
        g.set_value("mixed", "values", packed).unwrap();
        eval.evaluate_all(&g, &ctx);
        let preview = build_preview(&g, &eval, &PreviewOptions::default());
        assert!(preview.picks.meshes.is_empty() && preview.stats.vertices == 0);
    }

    #[test]
    fn faces_are_classed_by_their_two_support_strip_quads() {
        let g = grid(3, 4); // interior vertex columns 1 and 2
        let classes = face_classes(&g, &table(3, &["++", "--"])).unwrap();
        assert_eq!(classes.len(), 2 * 3);
        // An older table without column 0 (M − 2 labels): quad column 0 is unclassified; column 1
        // pairs (++, ++); column 2 pairs (--, --).
        assert_eq!(
            classes[..3],
            [
                FaceClass::Unclassified,
                FaceClass::Convex,
                FaceClass::MinusMinus
            ]
        );
        assert!(
            face_classes(&g, &table(2, &["++", "--"])).is_none(),
            "row count must match"
        );
        // The constructions' full tables (M − 1 labels) class column 0 as well.
        let full = face_classes(&g, &table(3, &["--", "++", "--"])).unwrap();
        assert_eq!(
            full[..3],
            [
                FaceClass::MinusMinus,
                FaceClass::Convex,
                FaceClass::MinusMinus
            ]
        );
        assert_eq!(class_color(FaceClass::NonConvex), {
            let c = FaceClass::NonConvex.colour();
            Color::from_f32([c.x as f32, c.y as f32, c.z as f32, 1.0])
        });
    }

    #[test]
    fn layers_by_the_ports_declared_layer_and_toggles() {
        use cnets_engine::value::{Access, ValueType};
        use cnets_engine::{PortDef, PortHint};
        let port = |name: &'static str, layer: Option<Layer>| {
            PortDef::new(name, ValueType::Point, Access::List).with_hint(PortHint {
                layer,
                ..PortHint::default()
            })
        };
        assert_eq!(layer_of(&port("p", Some(Layer::Apices))), Layer::Apices);
        assert_eq!(layer_of(&port("p", Some(Layer::Axes))), Layer::Axes);
        assert_eq!(
            layer_of(&port("mesh", Some(Layer::Supports))),
            Layer::Supports
        );
        assert_eq!(layer_of(&port("o", Some(Layer::Unrolled))), Layer::Unrolled);
        // A name alone says nothing: no guessing from "apices" or "support".
        assert_eq!(layer_of(&port("apices", None)), Layer::Surfaces);
        assert_eq!(layer_of(&port("support", None)), Layer::Surfaces);
        // Apex dots and unrolled strips are off until asked for; every other layer is on.
        let mut o = PreviewOptions::default();
        assert!(
            Layer::ALL
                .iter()
                .all(|&l| o.shows(l) != Layer::OFF_BY_DEFAULT.contains(&l))
        );
        o.set(Layer::Apices, true);
        assert!(o.shows(Layer::Apices) && o.shows(Layer::Axes));
        o.set(Layer::Apices, false);
        assert!(!o.shows(Layer::Apices) && !o.shows(Layer::Unrolled));
    }

    #[test]
    fn the_distance_legend_reads_in_metres() {
        assert_eq!(format_metres(0.0), "0 m");
        assert_eq!(format_metres(0.0441), "0.0441 m");
        assert_eq!(format_metres(1.25), "1.25 m");
        assert_eq!(format_metres(17.9), "17.9 m");
        let (title, rows) = legend_rows(&LegendInfo::Distance(distance_legend(
            "distance to hull",
            0.179,
        )))
        .unwrap();
        assert_eq!(title, "distance to hull");
        assert_eq!(rows.len(), 6);
        assert_eq!(rows[0].1, "0.179 m", "largest on top: {rows:?}");
        assert_eq!(rows[5].1, "0 m");
        assert_ne!(rows[0].0, rows[5].0);
        assert_eq!(
            ColorMode::ALL
                .iter()
                .filter(|m| **m == ColorMode::Distance)
                .count(),
            1
        );
        assert_eq!(PreviewOptions::default().distance_to, None);
    }
}
