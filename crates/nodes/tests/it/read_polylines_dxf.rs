//! `io.read_polylines` reads DXF drawn by an independent writer (ezdxf, scripts/write-dxf.py): every
//! curve entity, sampled where curved, in world coordinates, with the points the geometry demands.

use crate::fab_support;

use cnets_engine::eval::evaluate_node;
use cnets_engine::{NodeContext, Value};
use cnets_geometry::{DVec3, Polyline};
use fab_support::{repo_root, scratch};

fn near(a: DVec3, b: DVec3) -> bool {
    (a - b).length() < 1e-9
}

#[test]
fn every_curve_entity_of_an_ezdxf_drawing_is_read() {
    let dir = scratch("read-dxf");
    let file = dir.join("drawing.dxf");
    let status = std::process::Command::new("python3")
        .arg(repo_root().join("scripts/write-dxf.py"))
        .arg(&file)
        .status()
        .expect("python3 runs (install the test tools with scripts/install-test-deps.sh)");
    assert!(status.success(), "ezdxf wrote the drawing");
    let ctx = NodeContext::new(None, Some(dir.clone()));
    let out = evaluate_node(
        &cnets_nodes::io_read::read_polylines(),
        &ctx,
        &[
            Value::text("drawing.dxf"),
            Value::text("auto"),
            Value::Integer(16),
        ],
    )
    .unwrap();
    assert_eq!(
        out.warnings.len(),
        1,
        "the TEXT is reported: {:?}",
        out.warnings
    );
    let curves: Vec<Polyline> = out.values[0]
        .as_list()
        .unwrap()
        .iter()
        .map(|v| match v {
            Value::Polyline(p) => (**p).clone(),
            other => panic!("polyline, got {}", other.type_name()),
        })
        .collect();
    assert_eq!(curves.len(), 8);
    let [line, rect, poly3d, arc, circle, ellipse, spline, tilted] = &curves[..] else {
        unreachable!()
    };
    assert_eq!(line.points, vec![DVec3::ZERO, DVec3::new(3.0, 4.0, 5.0)]);

    assert!(rect.closed);
    assert!(
        rect.points
            .iter()
            .any(|p| near(*p, DVec3::new(1.0, 2.0, 0.0))),
        "the bulge's top"
    );
    assert!(
        rect.points
            .iter()
            .all(|p| p.y <= 2.0 + 1e-12 && p.y >= -1e-12)
    );

    assert_eq!(
        poly3d.points,
        vec![
            DVec3::ZERO,
            DVec3::new(1.0, 0.0, 1.0),
            DVec3::new(1.0, 1.0, 2.0)
        ]
    );

    assert_eq!(arc.points.len(), 17);
    assert!(near(arc.points[0], DVec3::new(7.0, 5.0, 0.0)));
    assert!(near(arc.points[16], DVec3::new(5.0, 7.0, 0.0)));
    assert!(
        arc.points
            .iter()
            .all(|p| (p.distance(DVec3::new(5.0, 5.0, 0.0)) - 2.0).abs() < 1e-12)
    );

    assert!(circle.closed);
    assert_eq!(circle.points.len(), 16);
    assert!(
        circle
            .points
            .iter()
            .all(|p| (p.distance(DVec3::new(-5.0, 0.0, 0.0)) - 1.5).abs() < 1e-12)
    );

    assert!(ellipse.closed);
    for p in &ellipse.points {
        let e = (p.x / 3.0).powi(2) + ((p.y + 5.0) / 1.5).powi(2);
        assert!((e - 1.0).abs() < 1e-12, "{p} is off the ellipse");
    }

    assert!(near(spline.points[0], DVec3::ZERO));
    assert!(near(
        *spline.points.last().unwrap(),
        DVec3::new(4.0, 0.0, 0.0)
    ));
    assert!(
        spline
            .points
            .iter()
            .any(|p| near(*p, DVec3::new(2.0, 1.5, 0.0))),
        "the cubic's midpoint (P0 + 3P1 + 3P2 + P3) / 8"
    );

    for p in &tilted.points {
        assert!(
            (p.x - 10.0).abs() < 1e-12,
            "{p}: the arc lies in the plane x = 10"
        );
        assert!((p.distance(DVec3::new(10.0, 0.0, 0.0)) - 1.0).abs() < 1e-12);
    }
    assert!(near(tilted.points[0], DVec3::new(10.0, 1.0, 0.0)));
}
