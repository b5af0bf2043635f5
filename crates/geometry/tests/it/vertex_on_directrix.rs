//! A generatrix vertex on the first directrix point (a wall standing on its directrix): the ratio
//! construction has no support plane there, but the row is determined — it follows the directrix —
//! and every other row is built as usual.

use cnets_geometry::conenet::{ConstructInputs, construct};
use cnets_geometry::{DVec3, GeometryError, Polyline};

fn directrix() -> Polyline {
    Polyline::open(vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(2.0, 0.4, 0.0),
        DVec3::new(4.0, 0.5, 0.1),
        DVec3::new(6.0, 0.2, 0.0),
    ])
}

fn wall() -> Polyline {
    Polyline::open(vec![
        DVec3::ZERO,
        DVec3::new(0.0, 0.2, 1.5),
        DVec3::new(0.0, 0.6, 3.0),
    ])
}

#[test]
fn the_row_on_the_directrix_follows_it() {
    let inputs = ConstructInputs::new(directrix(), wall())
        .apex(vec![0.95, 1.05, 1.0])
        .ratios(vec![
            vec![0.3, 0.6, 0.5],
            vec![0.45, 0.55, 0.5],
            vec![0.5, 0.4, 0.6],
        ]);
    let net = construct(&inputs).unwrap();
    for j in 0..net.mesh.cols {
        assert_eq!(net.mesh.at(0, j), directrix().points[j], "row 0 column {j}");
    }
    assert!(net.quality.max_planarity < 1e-12);
    assert_eq!(net.quality.configurations.bad(), 0);
}

#[test]
fn other_points_on_the_directrix_line_still_have_no_support_plane() {
    let behind = Polyline::open(vec![DVec3::new(-1.0, -0.2, 0.0), DVec3::new(0.0, 0.5, 1.0)]);
    assert!(matches!(
        construct(&ConstructInputs::new(directrix(), behind).ratios(0.3)),
        Err(GeometryError::DegenerateSupport { row: 0, column: 1 })
    ));
}
