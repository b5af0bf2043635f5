//! Marks on unrolled strips (issue 43): one tick per neighbour on each long edge, on the shared edge,
//! labelled with the neighbour; station lines that map back onto the station plane.

use crate::fab_common;

use cnets_geometry::fabrication::{
    StripDirection, StripPanels, UnrollOptions, cut_by_plane, grid_panels, mesh_panels, mirror,
    neighbour_marks, station_marks, unroll_mesh_strips, unroll_strips,
};
use cnets_geometry::{DVec3, Plane, PolygonMesh};
use fab_common::*;

/// The panel edge (panel, edge, parameter) of strip `s` a flat point lies on, within `tol`.
fn on_edge(strip: &StripPanels, p: DVec3, tol: f64) -> Option<(usize, usize, f64)> {
    for (k, panel) in strip.panels.iter().enumerate() {
        let n = panel.flat.len();
        for t in 0..n {
            let (a, b) = (panel.flat[t], panel.flat[(t + 1) % n]);
            let d = b - a;
            let s = ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0);
            if (a + d * s).distance(p) <= tol {
                return Some((k, t, s));
            }
        }
    }
    None
}

#[test]
fn every_inner_strip_is_marked_with_both_neighbours_on_the_shared_edges() {
    let net = cone_net(6, 9, false);
    let u = unroll_strips(
        &net.mesh,
        StripDirection::Directrix,
        UnrollOptions::default(),
    )
    .unwrap();
    let strips = grid_panels(&net.mesh, &u);
    let marks = neighbour_marks(&strips);
    for (s, strip) in strips.iter().enumerate() {
        let mut labels: Vec<&str> = marks
            .iter()
            .filter(|m| m.strip == s)
            .map(|m| m.label.as_str())
            .collect();
        labels.sort_unstable();
        let mut want: Vec<String> = Vec::new();
        if s > 0 {
            want.push(format!("D{}", s - 1));
        }
        if s + 1 < strips.len() {
            want.push(format!("D{}", s + 1));
        }
        want.sort();
        assert_eq!(labels, want, "{}", strip.label);
    }
    for m in &marks {
        let strip = &strips[m.strip];
        assert_eq!(m.line.len(), 2);
        assert!(m.line[0].distance(m.line[1]) > 0.0);
        // The tick starts at the midpoint of an edge that is, in 3D, an edge of the neighbour.
        let (k, t, at) = on_edge(strip, m.line[0], 1e-9).expect("on an edge");
        assert!((at - 0.5).abs() < 1e-9, "{at}");
        let p = &strip.panels[k];
        let edge = [p.ids[t], p.ids[(t + 1) % p.ids.len()]];
        let other = strips.iter().find(|s| s.name == m.label).unwrap();
        assert!(
            other
                .panels
                .iter()
                .any(|q| edge.iter().all(|v| q.ids.contains(v))),
            "{} mark {} is not on a shared edge",
            strip.label,
            m.label
        );
    }
}

#[test]
fn station_lines_map_back_onto_their_planes() {
    let net = cone_net(6, 9, false);
    let stations = [
        Plane::from_normal(DVec3::new(2.5, 0.0, 0.0), DVec3::X).unwrap(),
        Plane::from_normal(DVec3::new(5.2, 0.0, 0.0), DVec3::new(1.0, 0.2, 0.1)).unwrap(),
    ];
    let half = cut_by_plane(
        &PolygonMesh::from(&net.mesh),
        &Plane::from_normal(DVec3::new(6.3, 0.0, 0.0), DVec3::new(1.0, 0.45, 0.2)).unwrap(),
        false,
    )
    .unwrap()
    .mesh;
    let u = unroll_strips(
        &net.mesh,
        StripDirection::Directrix,
        UnrollOptions::default(),
    )
    .unwrap();
    let m = unroll_mesh_strips(&half, StripDirection::Directrix, UnrollOptions::default()).unwrap();
    let mut worst = 0.0f64;
    for strips in [grid_panels(&net.mesh, &u), mesh_panels(&half, &m)] {
        let marks = station_marks(&strips, &stations);
        // Both stations cross every directrix strip once, in one piece.
        for (s, strip) in strips.iter().enumerate() {
            let labels: Vec<&str> = marks
                .iter()
                .filter(|m| m.strip == s)
                .map(|m| m.label.as_str())
                .collect();
            assert_eq!(labels, ["S0", "S1"], "{}", strip.label);
        }
        for mark in &marks {
            let strip = &strips[mark.strip];
            let plane = &stations[mark.label[1..].parse::<usize>().unwrap()];
            assert!(mark.line.len() >= 2);
            for &p in &mark.line {
                let (k, t, at) = on_edge(strip, p, 1e-9).expect("on a panel edge");
                let c = &strip.panels[k].corners;
                let q = c[t] + (c[(t + 1) % c.len()] - c[t]) * at;
                worst = worst.max(plane.signed_distance(q).abs());
            }
        }
    }
    // Along a generatrix strip the plane x = 2.5 runs through every panel of G2: one polyline.
    let g = unroll_strips(
        &net.mesh,
        StripDirection::Generatrix,
        UnrollOptions::default(),
    )
    .unwrap();
    let strips = grid_panels(&net.mesh, &g);
    let marks = station_marks(&strips, &stations[..1]);
    assert_eq!(marks.len(), 1, "{marks:?}");
    assert_eq!(strips[marks[0].strip].name, "G2");
    assert_eq!(marks[0].line.len(), strips[marks[0].strip].panels.len() + 1);
    for &p in &marks[0].line {
        let strip = &strips[marks[0].strip];
        let (k, t, at) = on_edge(strip, p, 1e-9).expect("on a panel edge");
        let c = &strip.panels[k].corners;
        let q = c[t] + (c[(t + 1) % c.len()] - c[t]) * at;
        worst = worst.max(stations[0].signed_distance(q).abs());
    }
    eprintln!("station marks: largest distance of a mapped-back point from its plane {worst:e}");
    assert!(worst <= 1e-9, "{worst}");
}

#[test]
fn the_mirrored_half_is_marked_at_the_seam() {
    let net = cone_net(6, 9, false);
    let plane = Plane::from_normal(DVec3::new(4.3, 0.0, 0.0), DVec3::new(1.0, 0.3, 0.1)).unwrap();
    let half = cut_by_plane(&PolygonMesh::from(&net.mesh), &plane, false)
        .unwrap()
        .mesh;
    let whole = mirror(&half, &plane, 1e-9).unwrap();
    let u =
        unroll_mesh_strips(&whole, StripDirection::Directrix, UnrollOptions::default()).unwrap();
    let strips = mesh_panels(&whole, &u);
    let marks = neighbour_marks(&strips);
    // Each strip of one half is marked with its mirror image across the seam.
    for (s, strip) in u.strips.iter().enumerate() {
        let Some(a) = strip.mirror_of else { continue };
        let name = &strips[a].name;
        assert!(
            marks.iter().any(|m| m.strip == s && &m.label == name),
            "{} has no mark of {name}",
            strip.label
        );
    }
}
