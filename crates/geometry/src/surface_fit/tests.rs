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

/// A mesh's feature size by the definition: the mean longest edge of its fan triangles.
fn brute_feature(mesh: &PolygonMesh) -> f64 {
    let v = &mesh.vertices;
    let (mut sum, mut count) = (0.0, 0.0);
    for f in mesh.faces() {
        for c in 1..f.len() - 1 {
            let (a, b, cc) = (v[f[0] as usize], v[f[c] as usize], v[f[c + 1] as usize]);
            sum += a.distance(b).max(b.distance(cc)).max(cc.distance(a));
            count += 1.0;
        }
    }
    sum / count
}

/// One direction by the definition, written out again: every fan triangle split n_t times per
/// edge (⌈longest edge / the other mesh's feature size⌉, at most `cap`), each sub-triangle
/// integrated by the 6-point rule, area-weighted mean of the squared distances; the largest
/// distance also over the vertices.
fn brute_direction(from: &PolygonMesh, to: &PolygonMesh, cap: usize) -> (f64, f64) {
    let v = &from.vertices;
    let feature = brute_feature(to) * FEATURE_RATIO;
    let rule = quadrature_rule();
    let (mut sum, mut area_sum, mut max) = (0.0, 0.0, 0.0f64);
    for f in from.faces() {
        for c in 1..f.len() - 1 {
            let (a, b, cc) = (v[f[0] as usize], v[f[c] as usize], v[f[c + 1] as usize]);
            let area = 0.5 * (b - a).cross(cc - a).length();
            area_sum += area;
            let longest = a.distance(b).max(b.distance(cc)).max(cc.distance(a));
            if longest / feature <= 1.0 + 1e-9 {
                // No larger than the other's facets: the 3-point rule, (⅔, ⅙, ⅙) and its
                // permutations, weights ⅓.
                let (big, small) = (2.0 / 3.0, 1.0 / 6.0);
                for l in [
                    [big, small, small],
                    [small, big, small],
                    [small, small, big],
                ] {
                    let d = brute_distance(a * l[0] + b * l[1] + cc * l[2], to);
                    sum += area / 3.0 * d * d;
                    max = max.max(d);
                }
                continue;
            }
            let n = ((longest / feature - 1e-9).ceil() as usize).clamp(1, cap);
            let nf = n as f64;
            // The sub-triangles' corners as points.
            let at = |i: f64, j: f64| a + (b - a) * (i / nf) + (cc - a) * (j / nf);
            let mut subs = Vec::new();
            for i in 0..n {
                for j in 0..n - i {
                    let (i, j) = (i as f64, j as f64);
                    subs.push([at(i, j), at(i + 1.0, j), at(i, j + 1.0)]);
                    if i + j + 2.0 <= nf {
                        subs.push([at(i + 1.0, j), at(i, j + 1.0), at(i + 1.0, j + 1.0)]);
                    }
                }
            }
            assert_eq!(subs.len(), n * n);
            for s in subs {
                for (l, w) in rule {
                    let p = s[0] * l[0] + s[1] * l[1] + s[2] * l[2];
                    let d = brute_distance(p, to);
                    sum += area / (nf * nf) * w * d * d;
                    max = max.max(d);
                }
            }
        }
    }
    for &i in &from.indices {
        max = max.max(brute_distance(v[i as usize], to));
    }
    (sum / area_sum, max)
}

#[test]
fn the_rule_integrates_polynomials_of_degree_four_exactly() {
    // ∫ over the unit triangle of x^i y^j = i! j! / (i + j + 2)!, area ½; split 1 to 4 times.
    let fact = |n: u32| (1..=n).map(f64::from).product::<f64>();
    for n in 1..=4 {
        for i in 0..=4u32 {
            for j in 0..=4 - i {
                let exact = fact(i) * fact(j) / fact(i + j + 2) * 2.0;
                let (mut sum, mut weights) = (0.0, 0.0);
                for_each_sample(n, &quadrature_rule(), |b, w| {
                    assert!(b.iter().all(|&x| x > 0.0 && x < 1.0), "{b:?}");
                    assert!((b.iter().sum::<f64>() - 1.0).abs() < 1e-15);
                    sum += w * b[1].powi(i as i32) * b[2].powi(j as i32);
                    weights += w;
                });
                assert!((weights - 1.0).abs() < 1e-14);
                assert!(
                    (sum - exact).abs() < 1e-14,
                    "n {n}, x^{i} y^{j}: {sum} vs {exact}"
                );
            }
        }
    }
    // The small triangles' 3-point rule: degree 2 exactly, not degree 3.
    for i in 0..=2u32 {
        for j in 0..=2 - i {
            let exact = fact(i) * fact(j) / fact(i + j + 2) * 2.0;
            let mut sum = 0.0;
            for_each_sample(0, &quadrature_rule(), |b, w| {
                sum += w * b[1].powi(i as i32) * b[2].powi(j as i32)
            });
            assert!((sum - exact).abs() < 1e-15, "x^{i} y^{j}: {sum} vs {exact}");
        }
    }
    let mut sum = 0.0;
    for_each_sample(0, &quadrature_rule(), |b, w| sum += w * b[1].powi(3));
    assert!((sum - fact(3) / fact(5) * 2.0).abs() > 1e-6);
    // Degree 5 is not exact (the rule is not better than it says).
    let mut sum = 0.0;
    for_each_sample(1, &quadrature_rule(), |b, w| sum += w * b[1].powi(5));
    assert!((sum - fact(5) / fact(7) * 2.0).abs() > 1e-6);
}

#[test]
fn triangles_are_split_by_their_size_against_the_other_mesh() {
    // Lengths in units of the other mesh's feature size times FEATURE_RATIO.
    let f = FEATURE_RATIO;
    assert_eq!(split_count(0.5 * f, 1.0, 8), 0);
    assert_eq!(split_count(f, 1.0, 8), 0);
    assert_eq!(split_count(f * (1.0 + 1e-12), 1.0, 8), 0);
    assert_eq!(split_count(1.5 * f, 1.0, 1), 1);
    assert_eq!(split_count(2.5 * f, 1.0, 8), 3);
    assert_eq!(split_count(2.5 * f, 1.0, 2), 2);
    assert_eq!(split_count(100.0, 0.0, 5), 5);
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
        // With the vertices (one hierarchy for both): the same directions, and the vertices' mean
        // of d² and largest distance as a search over every triangle finds them.
        let (same, (mean, max)) =
            surface_and_vertex_distances(&mesh, &reference, n, Directions::BOTH, true).unwrap();
        prop_assert_eq!(same, d);
        let brute: Vec<f64> = mesh.vertices.iter().map(|&p| brute_distance(p, &reference)).collect();
        let brute_mean = brute.iter().map(|d| d * d).sum::<f64>() / brute.len() as f64;
        let brute_max = brute.iter().copied().fold(0.0, f64::max);
        prop_assert!((mean - brute_mean).abs() <= 1e-12 * brute_mean.max(1.0), "{mean} vs {brute_mean}");
        prop_assert!((max - brute_max).abs() <= 1e-12, "{max} vs {brute_max}");
        prop_assert_eq!(vertex_distances(&mesh.vertices, &reference).unwrap(), (mean, max));
        // One direction asked for: the other stays 0, the asked one is the same.
        let only = surface_distances(&mesh, &reference, n, Directions { to_reference: false, from_reference: true }).unwrap();
        prop_assert_eq!(only.to_reference, 0.0);
        prop_assert_eq!(only.from_reference, d.from_reference);
    }
}

/// The RMS distance both ways, measured densely and independently of the rule: every fan
/// triangle split `n` times per edge and sampled at its sub-triangles' centroids (the midpoint
/// rule), the closest points from [`crate::mesh_query::MeshQuery`] (parry's hierarchy, not
/// [`TriangleBvh`]): √(½ (mean d² to + mean d² from)).
pub(super) fn dense_rms(mesh: &PolygonMesh, reference: &PolygonMesh, n: usize) -> f64 {
    let one = |from: &PolygonMesh, to: &PolygonMesh| {
        let query = crate::mesh_query::MeshQuery::new(to).unwrap();
        let v = &from.vertices;
        let nf = n as f64;
        let (mut points, mut weights) = (Vec::new(), Vec::new());
        for f in from.faces() {
            for c in 1..f.len() - 1 {
                let (a, b, cc) = (v[f[0] as usize], v[f[c] as usize], v[f[c + 1] as usize]);
                let area = 0.5 * (b - a).cross(cc - a).length();
                for i in 0..n {
                    for j in 0..n - i {
                        let (i, j) = (i as f64, j as f64);
                        let at = |x: f64, y: f64| a + (b - a) * (x / nf) + (cc - a) * (y / nf);
                        points.push((at(i, j) + at(i + 1.0, j) + at(i, j + 1.0)) / 3.0);
                        weights.push(area / (nf * nf));
                        if i + j + 2.0 <= nf {
                            points.push(
                                (at(i + 1.0, j) + at(i, j + 1.0) + at(i + 1.0, j + 1.0)) / 3.0,
                            );
                            weights.push(area / (nf * nf));
                        }
                    }
                }
            }
        }
        let hits = query.closest_all(&points).unwrap();
        let total: f64 = weights.iter().sum();
        hits.iter()
            .zip(&weights)
            .map(|(h, w)| w * h.distance * h.distance)
            .sum::<f64>()
            / total
    };
    (0.5 * (one(mesh, reference) + one(reference, mesh))).sqrt()
}

/// Minimizes the symmetric measure (`samples` per edge) over every vertex coordinate of `mesh` by
/// L-BFGS (5 pairs, backtracking), as a fit would: the optimizer is free to exploit where the
/// samples are.
fn fit_vertices(
    mesh: &mut PolygonMesh,
    reference: &PolygonMesh,
    samples: usize,
    iterations: usize,
) {
    let c = DistanceCotangents {
        to_reference: 0.5,
        from_reference: 0.5,
        ..Default::default()
    };
    let f = |m: &PolygonMesh| {
        surface_distances(m, reference, samples, Directions::BOTH)
            .unwrap()
            .symmetric()
    };
    let grad = |m: &PolygonMesh| -> Vec<f64> {
        surface_distances_gradient(m, reference, samples, c)
            .unwrap()
            .iter()
            .flat_map(|g| g.to_array())
            .collect()
    };
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let set = |m: &mut PolygonMesh, x: &[f64]| {
        for (p, q) in m.vertices.iter_mut().zip(x.chunks(3)) {
            *p = DVec3::new(q[0], q[1], q[2]);
        }
    };
    let mut x: Vec<f64> = mesh.vertices.iter().flat_map(|p| p.to_array()).collect();
    let (mut fx, mut g) = (f(mesh), grad(mesh));
    let mut pairs: Vec<(Vec<f64>, Vec<f64>)> = Vec::new();
    for _ in 0..iterations {
        // The two-loop recursion.
        let mut q = g.clone();
        let mut alphas = Vec::new();
        for (s, y) in pairs.iter().rev() {
            let a = dot(s, &q) / dot(y, s);
            q.iter_mut().zip(y).for_each(|(qi, yi)| *qi -= a * yi);
            alphas.push(a);
        }
        if let Some((s, y)) = pairs.last() {
            let gamma = dot(s, y) / dot(y, y);
            q.iter_mut().for_each(|qi| *qi *= gamma);
        } else {
            let scale = 0.01 / dot(&g, &g).sqrt().max(1e-300);
            q.iter_mut().for_each(|qi| *qi *= scale);
        }
        for ((s, y), a) in pairs.iter().zip(alphas.iter().rev()) {
            let b = dot(y, &q) / dot(y, s);
            q.iter_mut().zip(s).for_each(|(qi, si)| *qi += (a - b) * si);
        }
        let slope = -dot(&g, &q);
        if slope >= 0.0 {
            pairs.clear();
            continue;
        }
        let mut t = 1.0;
        let mut trial = mesh.clone();
        let accepted = loop {
            let xt: Vec<f64> = x.iter().zip(&q).map(|(xi, qi)| xi - t * qi).collect();
            set(&mut trial, &xt);
            let ft = f(&trial);
            if ft <= fx + 1e-4 * t * slope {
                break Some((xt, ft));
            }
            t *= 0.5;
            if t < 1e-12 {
                break None;
            }
        };
        let Some((xt, ft)) = accepted else { break };
        let gt = grad(&trial);
        let s: Vec<f64> = xt.iter().zip(&x).map(|(a, b)| a - b).collect();
        let y: Vec<f64> = gt.iter().zip(&g).map(|(a, b)| a - b).collect();
        if dot(&s, &y) > 1e-300 {
            pairs.push((s, y));
            if pairs.len() > 5 {
                pairs.remove(0);
            }
        }
        (x, fx, g) = (xt, ft, gt);
        *mesh = trial;
    }
}

#[test]
fn after_a_fit_the_figure_is_within_five_percent_of_a_dense_measure() {
    // A doubly curved reference, finely triangulated, and a coarse quad mesh over the same square
    // fitted to it with every vertex coordinate free (the optimizer may put the samples where it
    // likes): the node's figure (default `samples` 2) against 20 midpoint samples per edge.
    let reference_z = |x: f64, y: f64| 0.35 * (1.4 * x).sin() * (1.1 * y).cos() + 0.25 * x * y;
    let grid_on = |n: usize, z: &dyn Fn(f64, f64) -> f64| {
        let mut vertices = Vec::new();
        for i in 0..=n {
            for j in 0..=n {
                let (x, y) = (
                    2.0 * j as f64 / n as f64 - 1.0,
                    2.0 * i as f64 / n as f64 - 1.0,
                );
                vertices.push(DVec3::new(x, y, z(x, y)));
            }
        }
        let id = |i: usize, j: usize| (i * (n + 1) + j) as u32;
        let faces: Vec<Vec<u32>> = (0..n)
            .flat_map(|i| {
                (0..n).map(move |j| vec![id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)])
            })
            .collect();
        PolygonMesh::from_faces(vertices, &faces).unwrap()
    };
    let reference = grid_on(32, &reference_z);
    for n in [4, 6] {
        let mut mesh = grid_on(n, &|_, _| 0.0);
        let start = surface_distances(&mesh, &reference, 2, Directions::BOTH).unwrap();
        fit_vertices(&mut mesh, &reference, 2, 150);
        let fitted = surface_distances(&mesh, &reference, 2, Directions::BOTH).unwrap();
        let (node, dense) = (fitted.symmetric().sqrt(), dense_rms(&mesh, &reference, 20));
        eprintln!(
            "{n} × {n} quads: start RMS {:.4}, fitted RMS {node:.5} (node), {dense:.5} (dense), \
             {:+.1} %",
            start.symmetric().sqrt(),
            100.0 * (node / dense - 1.0)
        );
        assert!(
            fitted.symmetric() < 0.2 * start.symmetric(),
            "the fit worked"
        );
        assert!((node / dense - 1.0).abs() <= 0.05, "{node} vs {dense}");
    }
}
