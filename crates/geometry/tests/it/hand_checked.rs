//! Small constructions checked by hand: a straight directrix with a = ½ (apices and vertices in closed
//! form), a closed square directrix swept with Monge planes (the sweep closes up), a closed generatrix
//! (the mesh wraps its rows).

use cnets_geometry::conenet::{ConstructInputs, CtubeInputs, construct, construct_ctube};
use cnets_geometry::{DVec3, Polyline};

fn p(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

fn close(a: DVec3, b: DVec3) -> bool {
    a.distance(b) < 1e-14
}

/// X = (0,0,0), (1,0,0), (2,0,0); G_{:,0} = (0,1,0), (0,2,0); a = ½; Monge planes x = 1, x = 2.
/// C_0 = (X_1 − ½ X_0)/½ = (2,0,0): the line from C_0 through (0,1,0) meets x = 1 at (1, ½, 0).
/// C_1 = (X_2 − ½ X_1)/½ = (3,0,0): the line from C_1 through (1,½,0) meets x = 2 at (2, ¼, 0).
#[test]
fn straight_directrix_with_half_apex() {
    let directrix = Polyline::open(vec![p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(2.0, 0.0, 0.0)]);
    let generatrix = Polyline::open(vec![p(0.0, 1.0, 0.0), p(0.0, 2.0, 0.0)]);
    let net = construct_ctube(&CtubeInputs::new(directrix, generatrix).apex(0.5)).unwrap();
    let m = &net.mesh;
    assert_eq!(
        (m.rows, m.cols, m.wrap_rows, m.wrap_cols),
        (2, 3, false, false)
    );
    let expected = [
        [p(0.0, 1.0, 0.0), p(1.0, 0.5, 0.0), p(2.0, 0.25, 0.0)],
        [p(0.0, 2.0, 0.0), p(1.0, 1.0, 0.0), p(2.0, 0.5, 0.0)],
    ];
    for (i, row) in expected.iter().enumerate() {
        for (j, e) in row.iter().enumerate() {
            assert!(
                close(m.at(i, j), *e),
                "G[{i}][{j}] = {} expected {e}",
                m.at(i, j)
            );
        }
    }
    assert_eq!(
        net.apices,
        vec![Some(p(2.0, 0.0, 0.0)), Some(p(3.0, 0.0, 0.0))]
    );
    assert_eq!(net.apex, vec![0.5, 0.5]);
    assert_eq!(net.normals.get(0, 1), DVec3::X);
    assert_eq!(net.normals.get(1, 2), DVec3::X);
    // c_{i,0}: s1 = (G_{i,1} − X_0)·x̂ = 1 > 0 (x = 0 is the plane through X_0 and G_{i,0}
    // perpendicular to the support plane), s2 = (X_1 − G_{i,0})·x̂ = 1 > 0.
    // c_{i,1}: s1 = (G_{i,2} − X_1)·x̂ = 1 > 0, s2 = (X_2 − G_{i,1})·x̂ = 1 > 0.
    assert_eq!(
        net.configurations.to_strings(),
        vec![vec!["++", "++"], vec!["++", "++"]]
    );
    assert!(net.quality.max_planarity < 1e-15);
    assert!(net.corrections.is_empty());
}

/// A closed square directrix is swept once around (5 columns, the last one at X_0 again, with the
/// bisecting plane of the last and the first edge). With a ≡ 1 and Monge planes the points move
/// parallel to each edge to the next bisecting plane: a generatrix lying in the bisecting plane at X_0
/// comes back onto itself after one turn.
#[test]
fn closed_square_directrix_sweeps_back_onto_the_generatrix() {
    let square = Polyline::closed(vec![
        p(0.0, 0.0, 0.0),
        p(2.0, 0.0, 0.0),
        p(2.0, 2.0, 0.0),
        p(0.0, 2.0, 0.0),
    ]);
    // Bisecting plane at X_0 between the last edge (0,−1,0) and the first edge (1,0,0): normal ∝ (1,−1,0);
    // points (t, t, z) lie in it; t > 0 is inside the square.
    let generatrix = Polyline::open(vec![p(0.3, 0.3, -0.5), p(0.5, 0.5, 0.0), p(0.4, 0.4, 0.7)]);
    let net = construct_ctube(&CtubeInputs::new(square, generatrix.clone())).unwrap();
    assert_eq!(net.mesh.cols, 5);
    assert_eq!(net.directrix[4], p(0.0, 0.0, 0.0));
    let last = net.normals.get(0, 4);
    assert!((last - p(1.0, -1.0, 0.0).normalize()).length() < 1e-15);
    for (i, g) in generatrix.points.iter().enumerate() {
        assert!(
            close(net.mesh.at(i, 4), *g),
            "row {i}: {} vs {g}",
            net.mesh.at(i, 4)
        );
        // At the corner (2,0,0) the point (t,t,z) has moved to (2 − t, t, z).
        assert!(close(net.mesh.at(i, 1), p(2.0 - g.x, g.y, g.z)));
    }
    assert_eq!(net.apices, vec![None; 4]);
}

/// A closed generatrix wraps the rows: N quad rows instead of N − 1.
#[test]
fn closed_generatrix_wraps_rows() {
    let directrix = Polyline::open(vec![p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(2.0, 0.2, 0.0)]);
    let ring = Polyline::closed(
        (0..6)
            .map(|k| {
                let t = k as f64 * std::f64::consts::TAU / 6.0;
                p(0.0, t.cos(), t.sin())
            })
            .collect(),
    );
    let net = construct(&ConstructInputs::new(directrix, ring)).unwrap();
    assert!(net.mesh.wrap_rows && !net.mesh.wrap_cols);
    assert_eq!(net.mesh.quad_rows(), 6);
    assert_eq!(net.mesh.quad_count(), 12);
    assert!(net.quality.max_planarity < 1e-12);
}
