use proptest::prelude::*;

use super::*;
use crate::measure::closest_point_on_triangle;

/// A rows × cols grid of quads over [0, sx] × [0, sy] with the given heights (and small
/// in-plane offsets), one pentagon replacing the first two quads when `pentagon`.
fn grid(rows: usize, cols: usize, sx: f64, sy: f64, z: &[f64], pentagon: bool) -> PolygonMesh {
    let mut vertices = Vec::new();
    for i in 0..=rows {
        for j in 0..=cols {
            let k = i * (cols + 1) + j;
            let h = z[k % z.len()];
            vertices.push(DVec3::new(
                sx * j as f64 / cols as f64 + 0.05 * h,
                sy * i as f64 / rows as f64 - 0.03 * h,
                h,
            ));
        }
    }
    let id = |i: usize, j: usize| (i * (cols + 1) + j) as u32;
    let mut faces = Vec::new();
    for i in 0..rows {
        for j in 0..cols {
            if pentagon && i == 0 && j == 0 && cols > 1 {
                // The first two quads as one pentagon (vertex (1, 1) on its edge).
                faces.push(vec![id(1, 0), id(0, 0), id(0, 1), id(0, 2), id(1, 2)]);
                continue;
            }
            if pentagon && i == 0 && j == 1 {
                continue;
            }
            faces.push(vec![id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)]);
        }
    }
    PolygonMesh::from_faces(vertices, &faces).unwrap()
}

/// The distance from `p` to `mesh` by trying every triangle.
fn brute_distance(p: DVec3, mesh: &PolygonMesh) -> f64 {
    let v = &mesh.vertices;
    mesh.faces()
        .flat_map(|f| (1..f.len() - 1).map(move |c| [f[0], f[c], f[c + 1]]))
        .map(|t| {
            closest_point_on_triangle(p, v[t[0] as usize], v[t[1] as usize], v[t[2] as usize])
                .distance(p)
        })
        .fold(f64::INFINITY, f64::min)
}

/// One direction by the definition, written out again: every fan triangle split n times per
/// edge, sampled at the sub-triangles' centroids, area-weighted mean of the squared distances;
/// the largest distance also over the vertices.
fn brute_direction(from: &PolygonMesh, to: &PolygonMesh, n: usize) -> (f64, f64) {
    let v = &from.vertices;
    let (mut sum, mut area_sum, mut max) = (0.0, 0.0, 0.0f64);
    for f in from.faces() {
        for c in 1..f.len() - 1 {
            let (a, b, cc) = (v[f[0] as usize], v[f[c] as usize], v[f[c + 1] as usize]);
            let area = 0.5 * (b - a).cross(cc - a).length();
            area_sum += area;
            let nf = n as f64;
            let mut points = Vec::new();
            for i in 0..n {
                for j in 0..n - i {
                    let (i, j) = (i as f64, j as f64);
                    points.push(
                        a + (b - a) * ((i + 1.0 / 3.0) / nf) + (cc - a) * ((j + 1.0 / 3.0) / nf),
                    );
                    if i + j + 2.0 <= nf {
                        points.push(
                            a + (b - a) * ((i + 2.0 / 3.0) / nf)
                                + (cc - a) * ((j + 2.0 / 3.0) / nf),
                        );
                    }
                }
            }
            assert_eq!(points.len(), n * n);
            for p in points {
                let d = brute_distance(p, to);
                sum += area / (nf * nf) * d * d;
                max = max.max(d);
            }
        }
    }
    for &i in &from.indices {
        max = max.max(brute_distance(v[i as usize], to));
    }
    (sum / area_sum, max)
}

#[test]
fn sub_triangles_cover_the_triangle_evenly() {
    for n in 1..=6 {
        let c = sub_triangle_centroids(n);
        assert_eq!(c.len(), n * n);
        let mut mean = [0.0; 3];
        for b in &c {
            assert!(b.iter().all(|&x| x > 0.0 && x < 1.0), "{b:?}");
            assert!((b.iter().sum::<f64>() - 1.0).abs() < 1e-15);
            for (m, x) in mean.iter_mut().zip(b) {
                *m += x / c.len() as f64;
            }
        }
        for m in mean {
            assert!((m - 1.0 / 3.0).abs() < 1e-14, "{n}: {mean:?}");
        }
    }
}

#[test]
fn the_reference_far_from_a_small_patch_is_seen_only_from_the_reference() {
    // A 1 × 1 patch lying on a 3 × 3 reference plane: every point of the patch is on the
    // reference (0 towards it), yet the reference reaches √2 away from the patch (its corners).
    let patch = grid(2, 2, 1.0, 1.0, &[0.0], false);
    let mut reference = grid(3, 3, 3.0, 3.0, &[0.0], false);
    for p in &mut reference.vertices {
        p.x -= 1.0;
        p.y -= 1.0;
    }
    let d = surface_distances(&patch, &reference, 2, Directions::BOTH).unwrap();
    assert!(
        d.to_reference < 1e-28 && d.to_reference_max < 1e-14,
        "{d:?}"
    );
    assert!((d.from_reference_max - 2f64.sqrt()).abs() < 1e-12, "{d:?}");
    assert!(d.from_reference > 0.4, "{d:?}");
    assert_eq!(d.hausdorff(), d.from_reference_max);
    assert!((d.symmetric() - 0.5 * d.from_reference).abs() < 1e-15);
}

#[test]
fn bad_inputs_are_errors() {
    let a = grid(2, 2, 1.0, 1.0, &[0.0], false);
    assert!(surface_distances(&a, &a, 0, Directions::BOTH).is_err());
    assert!(surface_distances(&a, &a, MAX_SAMPLES + 1, Directions::BOTH).is_err());
    let flat = PolygonMesh::from_faces(
        vec![DVec3::ZERO, DVec3::X, DVec3::X * 2.0],
        &[vec![0, 1, 2]],
    )
    .unwrap();
    assert!(surface_distances(&flat, &a, 2, Directions::BOTH).is_err());
    assert!(surface_distances(&a, &flat, 2, Directions::BOTH).is_err());
    assert!(surface_distances(&a, &PolygonMesh::new(), 2, Directions::BOTH).is_err());
}

/// Σ c_k · measure_k of the four numbers.
fn weighted(d: &SurfaceDistances, c: &DistanceCotangents) -> f64 {
    c.to_reference * d.to_reference
        + c.to_reference_max * d.to_reference_max
        + c.from_reference * d.from_reference
        + c.from_reference_max * d.from_reference_max
}

#[test]
fn the_gradient_matches_central_differences() {
    let z: Vec<f64> = (0..20).map(|k| (k as f64 * 0.7).sin() * 0.3).collect();
    let mesh = grid(3, 4, 2.0, 1.5, &z, true);
    let zr: Vec<f64> = (0..30)
        .map(|k| (k as f64 * 1.3).cos() * 0.2 - 0.4)
        .collect();
    let mut reference = grid(4, 5, 2.6, 2.0, &zr, false);
    for p in &mut reference.vertices {
        p.x -= 0.3;
        p.y -= 0.2;
    }
    for c in [
        DistanceCotangents {
            to_reference: 1.0,
            ..Default::default()
        },
        DistanceCotangents {
            from_reference: 1.0,
            ..Default::default()
        },
        DistanceCotangents {
            to_reference_max: 1.0,
            ..Default::default()
        },
        DistanceCotangents {
            from_reference_max: 1.0,
            ..Default::default()
        },
        DistanceCotangents {
            to_reference: 0.7,
            to_reference_max: -0.2,
            from_reference: 1.3,
            from_reference_max: 0.4,
        },
    ] {
        for n in [1, 3] {
            let g = surface_distances_gradient(&mesh, &reference, n, c).unwrap();
            let (mut diff, mut scale) = (0.0f64, 0.0f64);
            for (i, gi) in g.iter().enumerate() {
                for (axis, exact) in gi.to_array().into_iter().enumerate() {
                    let h = 1e-6;
                    let mut m = mesh.clone();
                    m.vertices[i][axis] += h;
                    let up = weighted(
                        &surface_distances(&m, &reference, n, Directions::BOTH).unwrap(),
                        &c,
                    );
                    m.vertices[i][axis] -= 2.0 * h;
                    let down = weighted(
                        &surface_distances(&m, &reference, n, Directions::BOTH).unwrap(),
                        &c,
                    );
                    let fd = (up - down) / (2.0 * h);
                    diff = diff.max((fd - exact).abs());
                    scale = scale.max(fd.abs());
                }
            }
            assert!(scale > 0.0, "{c:?}");
            assert!(
                diff / scale < 1e-6,
                "{c:?} n = {n}: relative {}",
                diff / scale
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn both_directions_match_a_brute_force_search(
        rows in 1usize..4,
        cols in 2usize..5,
        z in prop::collection::vec(-0.5f64..0.5, 4..30),
        zr in prop::collection::vec(-1.0f64..0.2, 4..30),
        sx in 0.5f64..3.0,
        n in 1usize..4,
        pentagon in any::<bool>(),
    ) {
        let mesh = grid(rows, cols, sx, 1.0, &z, pentagon);
        let reference = grid(cols, rows + 1, 2.0, 1.5, &zr, !pentagon);
        let d = surface_distances(&mesh, &reference, n, Directions::BOTH).unwrap();
        let (to, to_max) = brute_direction(&mesh, &reference, n);
        let (from, from_max) = brute_direction(&reference, &mesh, n);
        prop_assert!((d.to_reference - to).abs() <= 1e-12 * to.max(1.0), "{} vs {to}", d.to_reference);
        prop_assert!((d.to_reference_max - to_max).abs() <= 1e-12, "{} vs {to_max}", d.to_reference_max);
        prop_assert!((d.from_reference - from).abs() <= 1e-12 * from.max(1.0), "{} vs {from}", d.from_reference);
        prop_assert!((d.from_reference_max - from_max).abs() <= 1e-12, "{} vs {from_max}", d.from_reference_max);
        // One direction asked for: the other stays 0, the asked one is the same.
        let only = surface_distances(&mesh, &reference, n, Directions { to_reference: false, from_reference: true }).unwrap();
        prop_assert_eq!(only.to_reference, 0.0);
        prop_assert_eq!(only.from_reference, d.from_reference);
    }
}
