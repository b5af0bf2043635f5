//! Splitting unrolled strips at `max_length` (issue 43): pieces no longer than asked, cut at folds,
//! labelled `D4.1`, `D4.2`, whose joint lines match.

use crate::fab_common;

use cnets_geometry::fabrication::{
    FabricationError, StripDirection, UnrollOptions, grid_panels, split_strips, unroll_strips,
};
use cnets_geometry::{DVec3, QuadGrid};
use fab_common::*;

/// A long, gently bent strip net: 3 × 25 vertices.
fn long_net() -> QuadGrid {
    cone_net(3, 25, false).mesh
}

#[test]
fn pieces_fit_max_length_and_their_joints_match() {
    let mesh = long_net();
    let u = unroll_strips(&mesh, StripDirection::Directrix, UnrollOptions::default()).unwrap();
    let strips = grid_panels(&mesh, &u);
    let max_length = 6.0;
    let p = split_strips(&strips, max_length, None).unwrap();
    let mut worst_joint = 0.0f64;
    for (s, strip) in strips.iter().enumerate() {
        let name = format!("D{s}");
        let pieces: Vec<usize> = (0..p.pieces.len())
            .filter(|&k| p.pieces[k].name.starts_with(&format!("{name}.")))
            .collect();
        assert!(
            pieces.len() >= 3,
            "{name} split into {} pieces",
            pieces.len()
        );
        // Every panel in exactly one piece, in order.
        let panels: Vec<_> = pieces
            .iter()
            .flat_map(|&k| p.pieces[k].panels.iter().map(|q| q.source))
            .collect();
        let original: Vec<_> = strip.panels.iter().map(|q| q.source).collect();
        assert_eq!(panels, original);
        for (n, &k) in pieces.iter().enumerate() {
            assert_eq!(p.pieces[k].name, format!("{name}.{}", n + 1));
            // Laid out turned to its rectangle, long side along x: that side is the length.
            let xs = p.outlines[k].points.iter().map(|q| q.x);
            let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(x), b.max(x))
            });
            assert!(
                hi - lo <= max_length + 1e-9,
                "{} is {}",
                p.pieces[k].name,
                hi - lo
            );
        }
        for w in pieces.windows(2) {
            let (a, b) = (w[0], w[1]);
            let ja: Vec<_> = p.joints.iter().filter(|j| j.strip == a).collect();
            let jb: Vec<_> = p.joints.iter().filter(|j| j.strip == b).collect();
            let label = format!("{} | {}", p.pieces[a].name, p.pieces[b].name);
            let la = ja
                .iter()
                .find(|j| j.label == label)
                .expect("joint on the first");
            let lb = jb
                .iter()
                .find(|j| j.label == label)
                .expect("joint on the second");
            // The same rung on both pieces, at the same length, an edge of both outlines.
            let len = |l: &[DVec3]| l[0].distance(l[1]);
            worst_joint = worst_joint.max((len(&la.line) - len(&lb.line)).abs());
            for (j, k) in [(la, a), (lb, b)] {
                for q in &j.line {
                    assert!(
                        p.outlines[k].points.iter().any(|o| o.distance(*q) <= 1e-12),
                        "joint end of {} not on its outline",
                        p.pieces[k].name
                    );
                }
            }
        }
    }
    eprintln!("split: largest joint length mismatch {worst_joint:e}");
    assert!(worst_joint <= 1e-9, "{worst_joint}");
    // Pieces do not overlap: their boxes are stacked.
    for w in p.outlines.windows(2) {
        let top = w[0]
            .points
            .iter()
            .map(|q| q.y)
            .fold(f64::NEG_INFINITY, f64::max);
        let bottom = w[1]
            .points
            .iter()
            .map(|q| q.y)
            .fold(f64::INFINITY, f64::min);
        assert!(bottom > top);
    }
}

#[test]
fn short_strips_stay_whole_and_a_panel_longer_than_max_length_is_named() {
    let mesh = long_net();
    let u = unroll_strips(&mesh, StripDirection::Directrix, UnrollOptions::default()).unwrap();
    let strips = grid_panels(&mesh, &u);
    let whole = split_strips(&strips, 1e3, None).unwrap();
    let names: Vec<&str> = whole.pieces.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["D0", "D1"]);
    assert!(whole.joints.is_empty());
    match split_strips(&strips, 0.5, None) {
        Err(FabricationError::PanelTooLong { strip, panel, .. }) => {
            assert_eq!((strip.as_str(), panel), ("D0", 0));
        }
        other => panic!("expected PanelTooLong, got {other:?}"),
    }
    assert!(split_strips(&strips, f64::NAN, None).is_err());
    assert!(split_strips(&strips, 0.0, None).is_err());
}
