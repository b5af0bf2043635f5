//! Property tests of the curve operations and graph mappers.

use glam::{DVec2, DVec3};
use proptest::prelude::*;

use super::*;
use crate::{Plane, Polyline};

fn point() -> impl Strategy<Value = DVec3> {
    (-10.0..10.0f64, -10.0..10.0f64, -10.0..10.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// Polylines with 2–10 points whose consecutive points are at least 0.1 apart.
fn polyline() -> impl Strategy<Value = Vec<DVec3>> {
    prop::collection::vec(point(), 2..10).prop_filter("distinct consecutive points", |ps| {
        ps.windows(2).all(|w| w[0].distance(w[1]) > 0.1)
    })
}

/// x-monotone polylines whose edges stay within 40° of the x axis: the distance from any point to
/// the points after it grows along the curve, so equal chords always exist.
fn gentle() -> impl Strategy<Value = Vec<DVec3>> {
    prop::collection::vec((0.2..2.0f64, -0.8..0.8f64, -0.3..0.3f64), 1..12).prop_map(|steps| {
        let mut p = DVec3::ZERO;
        let mut out = vec![p];
        for (dx, sy, sz) in steps {
            p += DVec3::new(dx, dx * sy, dx * sz);
            out.push(p);
        }
        out
    })
}

fn edge_lengths(p: &Polyline) -> Vec<f64> {
    p.edges().map(|(a, b)| a.distance(b)).collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn resample_keeps_the_ends_and_never_exceeds_the_arc_spacing(
        pts in polyline(), count in 2usize..60, closed in any::<bool>()
    ) {
        let curve = Polyline { points: pts.clone(), closed: closed && pts.len() >= 3 };
        let count = if curve.closed { count.max(3) } else { count };
        let r = resample_by_count(&curve, count).unwrap();
        prop_assert_eq!(r.points.len(), count);
        prop_assert_eq!(r.points[0], pts[0]);
        if !curve.closed {
            prop_assert_eq!(r.points[count - 1], pts[pts.len() - 1]);
        }
        let spacing = curve.length() / r.edge_count() as f64;
        for l in edge_lengths(&r) {
            prop_assert!(l <= spacing * (1.0 + 1e-9) + 1e-12);
        }
    }

    #[test]
    fn resample_of_a_straight_polyline_has_equal_edges(
        cuts in prop::collection::vec(0.01..1.0f64, 1..8), count in 2usize..40, dir in point()
    ) {
        prop_assume!(dir.length() > 0.1);
        let mut s = 0.0;
        let mut pts = vec![DVec3::ZERO];
        for c in cuts {
            s += c;
            pts.push(dir * s);
        }
        let r = resample_by_count(&Polyline::open(pts), count).unwrap();
        let lengths = edge_lengths(&r);
        for l in &lengths {
            prop_assert!((l - lengths[0]).abs() <= 1e-9 * (1.0 + lengths[0]));
        }
    }

    #[test]
    fn equal_chords_are_equal_and_keep_the_ends(pts in gentle(), count in 2usize..30) {
        let curve = Polyline::open(pts.clone());
        let r = divide_equal_chords(&curve, count).unwrap();
        prop_assert_eq!(r.points.len(), count);
        prop_assert_eq!(r.points[0], pts[0]);
        prop_assert_eq!(r.points[count - 1], pts[pts.len() - 1]);
        let lengths = edge_lengths(&r);
        for l in &lengths {
            prop_assert!((l - lengths[0]).abs() <= 1e-8 * curve.length());
        }
    }

    #[test]
    fn rigid_transforms_preserve_distances_and_scaling_scales_them(
        pts in polyline(), mv in point(), axis in point(), centre in point(),
        angle in -360.0..360.0f64, scale in prop_oneof![-3.0..-0.1f64, 0.1..3.0f64],
        mirror in any::<bool>(), normal in point()
    ) {
        prop_assume!(axis.length() > 0.1 && normal.length() > 0.1);
        let plane = Plane::from_normal(centre, normal).unwrap();
        let t = Transform {
            translation: mv,
            angle,
            axis,
            centre,
            scale,
            mirror: mirror.then_some(plane),
        };
        let curve = Polyline::open(pts.clone());
        let out = t.apply_polyline(&curve).unwrap();
        for i in 0..pts.len() {
            for j in 0..pts.len() {
                let before = pts[i].distance(pts[j]) * scale.abs();
                let after = out.points[i].distance(out.points[j]);
                prop_assert!((before - after).abs() <= 1e-9 * (1.0 + before));
            }
        }
    }

    #[test]
    fn splines_pass_through_their_control_points(pts in polyline(), closed in any::<bool>(),
                                                 natural in any::<bool>()) {
        let closed = closed && pts.len() >= 3 && pts[0].distance(pts[pts.len() - 1]) > 0.1;
        let kind = if natural { SplineKind::Natural } else { SplineKind::CatmullRom };
        let s = Spline::new(kind, &pts, closed).unwrap();
        for (i, p) in pts.iter().enumerate() {
            prop_assert!((s.eval(s.knots()[i]) - *p).length() < 1e-9);
        }
        let sampled = s.sample_even(17).unwrap();
        prop_assert!(sampled.points.iter().all(|q| q.is_finite()));
    }

    #[test]
    fn join_reassembles_a_cut_polyline(pts in polyline(), seed in any::<u64>()) {
        // Cut after every interior point, flip every other piece, rotate the order.
        let n = pts.len();
        let mut pieces: Vec<Polyline> = (0..n - 1)
            .map(|k| {
                let piece = Polyline::open(vec![pts[k], pts[k + 1]]);
                if (seed >> (k % 64)) & 1 == 1 { reverse(&piece) } else { piece }
            })
            .collect();
        let shift = (seed as usize) % pieces.len();
        pieces.rotate_left(shift);
        let joined = join(&pieces, 1e-9).unwrap();
        // Pieces may touch in more places than the cuts; the total length is always kept.
        let total: f64 = joined.iter().map(Polyline::length).sum();
        let original = Polyline::open(pts.clone()).length();
        prop_assert!((total - original).abs() < 1e-9 * (1.0 + original));
        prop_assert!(joined.len() <= pieces.len());
    }

    #[test]
    fn linear_subdivision_keeps_the_length(pts in polyline(), levels in 0usize..4) {
        let curve = Polyline::open(pts);
        let s = subdivide(&curve, levels, SubdivisionScheme::Linear).unwrap();
        prop_assert!((s.length() - curve.length()).abs() < 1e-9 * (1.0 + curve.length()));
        prop_assert_eq!(s.points.len(), (curve.points.len() - 1) * (1 << levels) + 1);
    }

    #[test]
    fn monotone_handles_give_monotone_mappers(
        ys in prop::collection::vec(0.0..1.0f64, 2..8), gaps in prop::collection::vec(0.01..1.0f64, 8)
    ) {
        let mut ys = ys;
        ys.sort_by(f64::total_cmp);
        let mut x = 0.0;
        let handles: Vec<DVec2> = ys
            .iter()
            .zip(&gaps)
            .map(|(&y, &g)| {
                x += g;
                DVec2::new(x, y)
            })
            .collect();
        for kind in [MapperKind::Piecewise, MapperKind::Spline] {
            let m = GraphMapper::new(kind, &handles).unwrap();
            for h in &handles {
                prop_assert!((m.eval(h.x) - h.y).abs() < 1e-12);
            }
            let mut prev = f64::NEG_INFINITY;
            for k in 0..=200 {
                let v = m.eval(-0.5 + 6.0 * k as f64 / 200.0);
                prop_assert!(v >= prev - 1e-12, "{:?} not monotone", kind);
                prev = v;
            }
        }
    }

    #[test]
    fn bezier_conic_and_power_are_monotone_between_ordered_handles(
        c1 in (0.0..1.0f64, 0.0..1.0f64), c2 in (0.0..1.0f64, 0.0..1.0f64),
        s in (0.05..0.95f64, 0.05..0.95f64)
    ) {
        let (lo, hi) = (c1.1.min(c2.1), c1.1.max(c2.1));
        let p0 = DVec2::ZERO;
        let p3 = DVec2::ONE;
        let bez = GraphMapper::new(
            MapperKind::Bezier,
            &[p0, DVec2::new(c1.0, lo), DVec2::new(c2.0, hi), p3],
        ).unwrap();
        let pow = GraphMapper::new(MapperKind::Power, &[p0, p3, DVec2::new(s.0, s.1)]).unwrap();
        prop_assert!((pow.eval(s.0) - s.1).abs() < 1e-12);
        // A conic whose control point is above the chord and shoulder inside the triangle.
        let ctrl = DVec2::new(c1.0, c1.0.max(c1.1));
        let conic = if ctrl.y > ctrl.x + 0.01 {
            let shoulder = (p0 + ctrl + p3) / 3.0;
            let m = GraphMapper::new(MapperKind::Conic, &[p0, ctrl, p3, shoulder]).unwrap();
            prop_assert!((m.eval(shoulder.x) - shoulder.y).abs() < 1e-9);
            Some(m)
        } else {
            None
        };
        let mut prev = [f64::NEG_INFINITY; 3];
        for k in 0..=200 {
            let u = k as f64 / 200.0;
            let vals = [bez.eval(u), pow.eval(u), conic.as_ref().map_or(0.0, |m| m.eval(u))];
            for (i, v) in vals.iter().enumerate() {
                prop_assert!(*v >= prev[i] - 1e-9, "mapper {} not monotone at {}", i, u);
            }
            prev = vals;
        }
    }
}
