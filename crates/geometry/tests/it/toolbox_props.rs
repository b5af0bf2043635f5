//! Property tests of the toolbox geometry over random inputs: curve queries by arc length, mitred
//! offsets, welding, NURBS, and BVH closest points against a brute-force search.

use cnets_geometry::curves::{Nurbs, closest_point, evaluate, offset};
use cnets_geometry::measure::closest_point_on_triangle;
use cnets_geometry::mesh_query::MeshQuery;
use cnets_geometry::mesh_weld::weld;
use cnets_geometry::{DVec3, Plane, PolygonMesh, Polyline};
use proptest::prelude::*;

fn point() -> impl Strategy<Value = DVec3> {
    (-10.0..10.0f64, -10.0..10.0f64, -10.0..10.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

fn polyline() -> impl Strategy<Value = Polyline> {
    (prop::collection::vec(point(), 2..12), any::<bool>()).prop_map(|(points, closed)| Polyline {
        closed: closed && points.len() >= 3,
        points,
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// The point at t is on the curve: its closest point is itself, at the same t (up to rounding;
    /// where the curve passes through the same place twice the distance is still zero).
    #[test]
    fn evaluate_then_closest_point_finds_the_same_place(curve in polyline(), t in 0.0..1.0f64) {
        prop_assume!(curve.length() > 1e-6);
        let (p, tangent) = evaluate(&curve, t).unwrap();
        prop_assert!((tangent.length() - 1.0).abs() < 1e-12);
        let (q, _, d) = closest_point(&curve, p).unwrap();
        prop_assert!(d <= 1e-9 * (1.0 + curve.length()), "distance {d}");
        prop_assert!((p - q).length() <= 1e-9 * (1.0 + curve.length()));
    }

    /// Each edge of a mitred offset lies on the line parallel to its original edge at the offset
    /// distance (in the plane; heights kept).
    #[test]
    fn offset_edges_are_parallel_at_the_distance(
        points in prop::collection::vec((-10.0..10.0f64, -10.0..10.0f64), 3..9),
        closed in any::<bool>(),
        distance in -2.0..2.0f64,
    ) {
        let curve = Polyline {
            points: points.iter().map(|&(x, y)| DVec3::new(x, y, 0.0)).collect(),
            closed,
        };
        let edges_ok = curve.edges().all(|(a, b)| a.distance(b) > 1e-3);
        prop_assume!(edges_ok);
        let Ok(out) = offset(&curve, distance, &Plane::XY) else {
            return Ok(()); // a U-turn: refused, checked in the unit tests
        };
        let scale = 1.0 + out.points.iter().map(|p| p.length()).fold(0.0, f64::max);
        for (k, (a, b)) in curve.edges().enumerate() {
            let d = (b - a).normalize();
            let left = DVec3::new(-d.y, d.x, 0.0);
            let (p, q) = out.edge(k);
            for r in [p, q] {
                let signed = (r - a).dot(left);
                prop_assert!((signed - distance).abs() <= 1e-9 * scale, "edge {k}: {signed} vs {distance}");
            }
        }
    }

    /// Welding keeps vertices more than the tolerance apart, keeps original positions, and with
    /// tolerance 0 changes nothing.
    #[test]
    fn weld_merges_exactly_the_near_vertices(
        points in prop::collection::vec(point(), 3..40),
        tolerance in 0.0..3.0f64,
    ) {
        let n = points.len() as u32;
        let faces: Vec<Vec<u32>> = (0..n - 2).map(|k| vec![k, k + 1, k + 2]).collect();
        let mesh = PolygonMesh::from_faces(points.clone(), &faces).unwrap();
        let welded = weld(&mesh, tolerance).unwrap();
        for (i, a) in welded.vertices.iter().enumerate() {
            for b in &welded.vertices[i + 1..] {
                prop_assert!(a.distance(*b) > tolerance);
            }
        }
        // Each kept vertex is an original position (the first of its cluster), never an average.
        for v in &welded.vertices {
            prop_assert!(points.iter().any(|p| p.distance(*v) == 0.0), "welded vertices are original ones");
        }
        // Tolerance 0 on distinct points changes nothing.
        let exact = weld(&mesh, 0.0).unwrap();
        prop_assert_eq!(&exact.vertices, &points);
        prop_assert_eq!(exact.face_count(), mesh.face_count());
        prop_assert!(welded.validate().is_ok());
        prop_assert!(welded.face_count() <= mesh.face_count());
    }

    /// A clamped B-spline starts and ends at its end control points and stays in their bounding box.
    #[test]
    fn clamped_nurbs_interpolate_their_ends_and_stay_in_the_hull(
        control in prop::collection::vec(point(), 4..10),
        weights in prop::collection::vec(0.2..5.0f64, 10),
        degree in 1usize..4,
    ) {
        let n = control.len();
        let inner = n - degree - 1;
        let mut knots = vec![0.0; degree + 1];
        knots.extend((1..=inner).map(|k| k as f64 / (inner + 1) as f64));
        knots.extend(vec![1.0; degree + 1]);
        let curve = Nurbs { degree, knots, control: control.clone(), weights: weights[..n].to_vec() };
        let samples = curve.sample(8).unwrap();
        prop_assert!((samples[0] - control[0]).length() < 1e-12);
        prop_assert!((samples[samples.len() - 1] - control[n - 1]).length() < 1e-12);
        let lo = control.iter().fold(DVec3::splat(f64::INFINITY), |a, b| a.min(*b));
        let hi = control.iter().fold(DVec3::splat(f64::NEG_INFINITY), |a, b| a.max(*b));
        for p in samples {
            prop_assert!(p.cmpge(lo - 1e-9).all() && p.cmple(hi + 1e-9).all(), "{p} leaves the hull");
        }
    }

    /// The BVH answers what a brute-force search over every triangle answers.
    #[test]
    fn closest_points_match_brute_force(
        points in prop::collection::vec(point(), 4..30),
        queries in prop::collection::vec(point(), 1..20),
    ) {
        let n = points.len() as u32;
        let faces: Vec<Vec<u32>> = (0..n - 3).map(|k| vec![k, k + 1, k + 2, k + 3]).collect();
        let mesh = PolygonMesh::from_faces(points.clone(), &faces).unwrap();
        let query = MeshQuery::new(&mesh).unwrap();
        for q in queries {
            let brute = faces
                .iter()
                .flat_map(|f| [[f[0], f[1], f[2]], [f[0], f[2], f[3]]])
                .map(|t| closest_point_on_triangle(q, points[t[0] as usize], points[t[1] as usize], points[t[2] as usize]).distance(q))
                .fold(f64::INFINITY, f64::min);
            let hit = query.closest(q).unwrap();
            prop_assert!((hit.distance - brute).abs() <= 1e-9, "{} vs {brute}", hit.distance);
        }
    }
}
