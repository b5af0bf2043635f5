//! Folds and collapsed edges of unrolled strips (issue 43): every fold angle equals the dihedral
//! angle of the 3D net, fold lines are the placed rungs, and an edge collapsed by a correction is
//! named and does not inflate `max_length_error`.

use crate::fab_common;

use cnets_geometry::fabrication::{
    StripDirection, StripPanels, UnrollOptions, cut_by_plane, folds, grid_panels, mesh_panels,
    mirror, unroll_mesh_strips, unroll_strips,
};
use cnets_geometry::{DVec3, Plane, PolygonMesh, QuadGrid};
use fab_common::*;

/// A plane normal of a 3D panel independent of the kernel's Newell sum: the cross product of the
/// diagonals for a quad, of two edges at the corner farthest from the centroid otherwise.
fn normal(c: &[DVec3]) -> DVec3 {
    if c.len() == 4 {
        return (c[2] - c[0]).cross(c[3] - c[1]).normalize();
    }
    let n = c.len();
    let centroid = c.iter().sum::<DVec3>() / n as f64;
    let k = (0..n)
        .max_by(|&a, &b| c[a].distance(centroid).total_cmp(&c[b].distance(centroid)))
        .unwrap();
    (c[(k + 1) % n] - c[k])
        .cross(c[(k + n - 1) % n] - c[k])
        .normalize()
}

/// The signed dihedral angle between 3D panels a and b across their shared edge p q: π minus the
/// interior angle between the perpendiculars from the edge to each panel's farthest corner, positive
/// when b lies on the −normal side of a (a mountain seen from the normal side).
fn dihedral(a: &[DVec3], b: &[DVec3], p: DVec3, q: DVec3) -> f64 {
    let t = (q - p).normalize();
    let across = |c: &[DVec3]| {
        c.iter()
            .map(|&x| {
                let d = x - p;
                d - t * d.dot(t)
            })
            .max_by(|u, v| u.length().total_cmp(&v.length()))
            .unwrap()
    };
    let (ua, ub) = (across(a), across(b));
    let interior = ua.cross(ub).length().atan2(ua.dot(ub));
    let magnitude = std::f64::consts::PI - interior;
    if ub.dot(normal(a)) < 0.0 {
        magnitude
    } else {
        -magnitude
    }
}

/// Checks every fold of the strips against the 3D net; returns the largest angle difference and
/// the number of folds.
fn check_folds(strips: &[StripPanels]) -> (f64, usize) {
    let f = folds(strips);
    let expected: usize = strips
        .iter()
        .map(|s| s.panels.len().saturating_sub(1))
        .sum();
    assert_eq!(f.len(), expected, "one fold between consecutive panels");
    let mut worst = 0.0f64;
    for fold in &f {
        let s = &strips[fold.strip];
        let (a, b) = (&s.panels[fold.panel - 1], &s.panels[fold.panel]);
        // The fold line is the placed rung: two flat corners both panels have.
        let common: Vec<usize> = a
            .ids
            .iter()
            .copied()
            .filter(|i| b.ids.contains(i))
            .collect();
        assert_eq!(common.len(), 2, "{} panel {}", s.label, fold.panel);
        let at = |id: usize| a.ids.iter().position(|&x| x == id).unwrap();
        let ends = [a.flat[at(common[0])], a.flat[at(common[1])]];
        assert!(
            (fold.line == ends) || (fold.line == [ends[1], ends[0]]),
            "fold line of {} panel {} is not its rung",
            s.label,
            fold.panel
        );
        let want = dihedral(
            &a.corners,
            &b.corners,
            a.corners[at(common[0])],
            a.corners[at(common[1])],
        );
        worst = worst.max((fold.angle - want).abs());
    }
    (worst, f.len())
}

fn grid_folds(mesh: &QuadGrid, direction: StripDirection) -> (f64, usize) {
    let u = unroll_strips(mesh, direction, UnrollOptions::default()).unwrap();
    check_folds(&grid_panels(mesh, &u))
}

#[test]
fn fold_angles_are_the_dihedral_angles_of_grid_nets() {
    let mut worst = 0.0f64;
    let mut signs = (0, 0);
    for (n, m, closed) in [(5, 7, false), (6, 9, true), (3, 12, false)] {
        let net = cone_net(n, m, closed);
        for direction in [StripDirection::Directrix, StripDirection::Generatrix] {
            let (w, count) = grid_folds(&net.mesh, direction);
            assert!(count > 0);
            worst = worst.max(w);
            let u = unroll_strips(&net.mesh, direction, UnrollOptions::default()).unwrap();
            for f in folds(&grid_panels(&net.mesh, &u)) {
                if f.angle > 1e-6 {
                    signs.0 += 1;
                } else if f.angle < -1e-6 {
                    signs.1 += 1;
                }
            }
        }
    }
    eprintln!("grid nets: largest fold-angle error {worst:e} rad, {signs:?} mountain/valley folds");
    assert!(worst <= 1e-9, "fold angle off by {worst} rad");
    assert!(
        signs.0 > 0 && signs.1 > 0,
        "both mountain and valley folds: {signs:?}"
    );
}

#[test]
fn fold_angles_are_the_dihedral_angles_of_a_cut_and_mirrored_net() {
    let net = cone_net(9, 12, false);
    let plane = Plane::from_normal(DVec3::new(6.3, 0.0, 0.0), DVec3::new(1.0, 0.45, 0.2)).unwrap();
    let half = cut_by_plane(&PolygonMesh::from(&net.mesh), &plane, false)
        .unwrap()
        .mesh;
    let whole = mirror(&half, &plane, 1e-9).unwrap();
    let mut worst = 0.0f64;
    for mesh in [&half, &whole] {
        for direction in [StripDirection::Directrix, StripDirection::Generatrix] {
            let u = unroll_mesh_strips(mesh, direction, UnrollOptions::default()).unwrap();
            let (w, count) = check_folds(&mesh_panels(mesh, &u));
            assert!(count > 0);
            worst = worst.max(w);
        }
    }
    eprintln!("cut and mirrored net: largest fold-angle error {worst:e} rad");
    assert!(worst <= 1e-9, "fold angle off by {worst} rad");
}

#[test]
fn a_flat_strip_has_zero_fold_angles() {
    // A plane grid: every fold is flat.
    let vertices = (0..3)
        .flat_map(|i| (0..5).map(move |j| DVec3::new(j as f64, i as f64 * 0.7, 0.0)))
        .collect();
    let flat = QuadGrid {
        classes: Vec::new(),
        rows: 3,
        cols: 5,
        wrap_rows: false,
        wrap_cols: false,
        vertices,
    };
    let u = unroll_strips(&flat, StripDirection::Directrix, UnrollOptions::default()).unwrap();
    let f = folds(&grid_panels(&flat, &u));
    assert_eq!(f.len(), 2 * 3);
    assert!(
        f.iter()
            .all(|f| f.angle == 0.0 && f.angle.is_sign_positive()),
        "{f:?}"
    );
}

/// A zigzag folded plate (every quad planar: the profile swept along y) whose profile points 1 and
/// 2 are 2.5e-12 apart, as a correction can leave them: the quads of column 1 are slivers.
fn collapsed_plate() -> QuadGrid {
    let profile = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.4),
        DVec3::new(1.0 + 2.5e-12, 0.0, 0.4 - 1e-12),
        DVec3::new(2.1, 0.0, -0.2),
        DVec3::new(3.0, 0.0, 0.3),
    ];
    let vertices = (0..4)
        .flat_map(|i| {
            profile
                .iter()
                .map(move |p| *p + DVec3::new(0.0, 0.9 * i as f64, 0.05 * i as f64))
        })
        .collect();
    QuadGrid {
        classes: Vec::new(),
        rows: 4,
        cols: 5,
        wrap_rows: false,
        wrap_cols: false,
        vertices,
    }
}

#[test]
fn collapsed_edges_are_named_and_do_not_inflate_the_length_error() {
    let plate = collapsed_plate();
    // Grid path: every directrix strip crosses the slivers once (panel 1, edges 0 and 2).
    let u = unroll_strips(&plate, StripDirection::Directrix, UnrollOptions::default()).unwrap();
    eprintln!(
        "collapsed plate (grid): max_length_error {:e}",
        u.max_length_error
    );
    assert!(u.max_length_error <= 1e-9, "{}", u.max_length_error);
    for s in &u.strips {
        let panels: Vec<(usize, usize)> = s.collapsed.iter().map(|c| (c.panel, c.edge)).collect();
        assert_eq!(panels, vec![(1, 0), (1, 2)], "{}", s.label);
        assert!(s.collapsed.iter().all(|c| c.length < 3e-12));
    }
    // Without the collapsed edges the other edges keep their lengths to 1e-9 as well.
    for s in &u.strips {
        for (k, (flat, &(i, j))) in s.quads.iter().zip(&s.mesh_quads).enumerate() {
            let q = plate.quad(i, j);
            for e in 0..4 {
                if s.collapsed.iter().any(|c| (c.panel, c.edge) == (k, e)) {
                    continue;
                }
                let (l3, l2) = (
                    q[e].distance(q[(e + 1) % 4]),
                    flat[e].distance(flat[(e + 1) % 4]),
                );
                assert!(
                    (l3 - l2).abs() <= 1e-9 * l3,
                    "{} panel {k} edge {e}",
                    s.label
                );
            }
        }
    }
    // Polygon-mesh path: the same plate as faces.
    let mesh = PolygonMesh::from(&plate);
    let m = unroll_mesh_strips(&mesh, StripDirection::Directrix, UnrollOptions::default()).unwrap();
    eprintln!(
        "collapsed plate (mesh): max_length_error {:e}",
        m.max_length_error
    );
    assert!(m.max_length_error <= 1e-9, "{}", m.max_length_error);
    assert!(m.strips.iter().all(|s| s.collapsed.len() == 2));
    // The generatrix strip of column 1 is all sliver: every one of its row edges is named.
    let g = unroll_strips(&plate, StripDirection::Generatrix, UnrollOptions::default()).unwrap();
    assert!(g.max_length_error <= 1e-9, "{}", g.max_length_error);
    assert_eq!(g.strips[1].collapsed.len(), 2 * 3);
    assert!(
        g.strips
            .iter()
            .enumerate()
            .all(|(j, s)| j == 1 || s.collapsed.is_empty())
    );
}
