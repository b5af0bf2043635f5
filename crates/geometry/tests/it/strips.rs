//! Strip extraction in both directions: counts, vertices and wrap flags of every strip.

use crate::fab_common;

use cnets_geometry::fabrication::{StripDirection, extract_strips};
use fab_common::*;

#[test]
fn strips_hold_the_right_rows_and_columns() {
    let net = cone_net(5, 7, true);
    let mesh = &net.mesh;
    let rows = extract_strips(mesh, StripDirection::Directrix).unwrap();
    // Closed generatrix: 5 directrix strips, the last between rows 4 and 0.
    assert_eq!(rows.len(), 5);
    for (i, s) in rows.iter().enumerate() {
        assert_eq!(
            (s.rows, s.cols, s.wrap_rows, s.wrap_cols),
            (2, 7, false, false)
        );
        for j in 0..7 {
            assert_eq!(s.at(0, j), mesh.at(i, j));
            assert_eq!(s.at(1, j), mesh.at((i + 1) % 5, j));
        }
        // Quad k of the strip is mesh quad (i, k), corners in the same order.
        assert_eq!(s.quad(0, 3), mesh.quad(i, 3));
    }
    let cols = extract_strips(mesh, StripDirection::Generatrix).unwrap();
    assert_eq!(cols.len(), 6);
    for (j, s) in cols.iter().enumerate() {
        assert_eq!((s.rows, s.cols, s.wrap_rows), (5, 2, true));
        assert_eq!(s.quad_count(), 5);
        for i in 0..5 {
            assert_eq!(s.quad(i, 0), mesh.quad(i, j));
        }
    }
    let open = cone_net(3, 4, false);
    assert_eq!(
        extract_strips(&open.mesh, StripDirection::Directrix)
            .unwrap()
            .len(),
        2
    );
    assert_eq!(
        extract_strips(&open.mesh, StripDirection::Generatrix)
            .unwrap()
            .len(),
        3
    );
    assert!(
        extract_strips(
            &cnets_geometry::QuadGrid::default(),
            StripDirection::Directrix
        )
        .is_err()
    );
}
