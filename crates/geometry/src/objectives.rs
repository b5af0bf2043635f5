//! Optimization objectives with their exact gradients: closure with tangent continuity across the
//! seam, face-normal alignment, fairness (second differences) and the gradients of the point and
//! surface distances of [`crate::measure`].

// Tolerance tests are written `!(x > 0)` on purpose (they also fail for NaN), as in the kernel.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use glam::DVec3;

use crate::{GeometryError, PolygonMesh, QuadGrid};

/// Gradient of Σ|a_k − b_k|² (the `value` of [`crate::measure::point_distance`]) with respect to
/// `a` (that of `b` is its negative), scaled by `c`.
pub fn point_distance_gradient(a: &[DVec3], b: &[DVec3], c: f64) -> Vec<DVec3> {
    a.iter()
        .zip(b)
        .map(|(p, q)| (*p - *q) * (2.0 * c))
        .collect()
}

/// Gradient of max_k |a_k − b_k| with respect to `a` (the largest pair's unit difference; zero
/// when all coincide), scaled by `c`.
pub fn max_distance_gradient(a: &[DVec3], b: &[DVec3], c: f64) -> Vec<DVec3> {
    let mut g = vec![DVec3::ZERO; a.len()];
    let best = a
        .iter()
        .zip(b)
        .enumerate()
        .map(|(k, (p, q))| (k, p.distance(*q)))
        .fold(None, |m: Option<(usize, f64)>, (k, d)| match m {
            Some((_, md)) if md >= d => m,
            _ => Some((k, d)),
        });
    if let Some((k, d)) = best
        && d > 0.0
    {
        g[k] = (a[k] - b[k]) * (c / d);
    }
    g
}

/// The tangent part of a tube's closure: Σ_i |t_i^last − t_i^first|² with t^first = unit(G_{i,1} −
/// G_{i,0}) and t^last = unit(G_{i,M−1} − G_{i,M−2}) (0 when the first and last strips continue
/// each other across the seam), and its gradient with respect to the vertices (row-major, scaled
/// by `c`).
pub fn seam_tangents(mesh: &QuadGrid, c: f64) -> Result<(f64, Vec<DVec3>), GeometryError> {
    mesh.validate()?;
    if mesh.cols < 3 || mesh.rows == 0 {
        return Err(GeometryError::Degenerate(format!(
            "tangent continuity needs at least 3 columns and 1 row, the mesh is {} × {}",
            mesh.rows, mesh.cols
        )));
    }
    let m = mesh.cols;
    let mut g = vec![DVec3::ZERO; mesh.vertices.len()];
    let mut sum = 0.0;
    for i in 0..mesh.rows {
        let (e0, e1) = (
            mesh.at(i, 1) - mesh.at(i, 0),
            mesh.at(i, m - 1) - mesh.at(i, m - 2),
        );
        let (l0, l1) = (e0.length(), e1.length());
        if !(l0 > 0.0 && l1 > 0.0) {
            return Err(GeometryError::Degenerate(format!(
                "row {i}: a strip edge at the seam has zero length"
            )));
        }
        let (t0, t1) = (e0 / l0, e1 / l1);
        let d = t1 - t0;
        sum += d.length_squared();
        // ∂/∂t1 = 2d, ∂/∂t0 = −2d; through unit(e): (I − t tᵀ)/|e|.
        let a1 = (d * 2.0 - t1 * (2.0 * d.dot(t1))) * (c / l1);
        let a0 = (-d * 2.0 + t0 * (2.0 * d.dot(t0))) * (c / l0);
        g[i * m + m - 1] += a1;
        g[i * m + m - 2] -= a1;
        g[i * m + 1] += a0;
        g[i * m] -= a0;
    }
    Ok((sum, g))
}

/// The Newell normal N = Σ v_k × v_{k+1} of a face (twice its vector area).
fn newell(mesh: &PolygonMesh, face: &[u32]) -> DVec3 {
    let n = face.len();
    (0..n).fold(DVec3::ZERO, |acc, k| {
        let (a, b) = (
            mesh.vertices[face[k] as usize],
            mesh.vertices[face[(k + 1) % n] as usize],
        );
        acc + a.cross(b)
    })
}

/// The faces of a polygon mesh as index slices.
fn faces(mesh: &PolygonMesh) -> impl Iterator<Item = &[u32]> + '_ {
    let starts = &mesh.face_starts;
    (0..starts.len()).map(move |k| {
        let s = starts[k] as usize;
        let e = starts
            .get(k + 1)
            .map_or(mesh.indices.len(), |&e| e as usize);
        &mesh.indices[s..e.max(s)]
    })
}

/// The unit (Newell) normal of face `face` (zero for a face without area or out of range).
pub fn face_normal(mesh: &PolygonMesh, face: usize) -> DVec3 {
    faces(mesh)
        .nth(face)
        .map_or(DVec3::ZERO, |f| newell(mesh, f).normalize_or_zero())
}

/// The faces' centroids (for looking up a reference normal).
pub fn face_centroids(mesh: &PolygonMesh) -> Vec<DVec3> {
    faces(mesh)
        .map(|f| {
            let sum = f
                .iter()
                .fold(DVec3::ZERO, |a, &i| a + mesh.vertices[i as usize]);
            sum / (f.len().max(1) as f64)
        })
        .collect()
}

/// Face-normal alignment: the mean over faces of 1 − (n_f · t_f)², n_f the unit (Newell) normal
/// and t_f the unit target of face f (0 when every face normal is parallel to its target, either
/// sign), the largest term, and the gradient of the mean with respect to the vertices (scaled by
/// `c`). `targets` holds one direction per face or one for all.
pub fn normal_alignment(
    mesh: &PolygonMesh,
    targets: &[DVec3],
    c: f64,
) -> Result<(f64, f64, Vec<DVec3>), GeometryError> {
    let count = mesh.face_starts.len();
    if count == 0 {
        return Err(GeometryError::Degenerate("the mesh has no faces".into()));
    }
    if targets.len() != 1 && targets.len() != count {
        return Err(GeometryError::WrongLength {
            what: "targets",
            expected: format!("1 or {count} (one per face)"),
            got: targets.len(),
        });
    }
    let mut g = vec![DVec3::ZERO; mesh.vertices.len()];
    let (mut sum, mut max) = (0.0, 0.0f64);
    let w = c / count as f64;
    for (k, face) in faces(mesh).enumerate() {
        let t = targets[k.min(targets.len() - 1)];
        let tl = t.length();
        if !(tl > 0.0) || !tl.is_finite() {
            return Err(GeometryError::Degenerate(format!(
                "the target direction of face {k} is zero or not finite"
            )));
        }
        let t = t / tl;
        let big = newell(mesh, face);
        let len = big.length();
        if !(len > 0.0) {
            return Err(GeometryError::Degenerate(format!(
                "face {k} has no normal (zero area)"
            )));
        }
        let n = big / len;
        let s = n.dot(t);
        let term = 1.0 - s * s;
        sum += term;
        max = max.max(term);
        // ∂term/∂N = −2s (t − n s)/|N|, then ∂N/∂v_k = v_{k+1} × a + a × v_{k−1}.
        let a = (t - n * s) * (-2.0 * s * w / len);
        let m = face.len();
        for j in 0..m {
            let (prev, next) = (
                mesh.vertices[face[(j + m - 1) % m] as usize],
                mesh.vertices[face[(j + 1) % m] as usize],
            );
            g[face[j] as usize] += next.cross(a) + a.cross(prev);
        }
    }
    Ok((sum / count as f64, max, g))
}

/// Fairness of a table of numbers: Σ of squared second differences x_{i,j−1} − 2x_{i,j} + x_{i,j+1}
/// along every row and, when the rows have equal lengths, along every column; with its gradient
/// (same shape, scaled by `c`).
pub fn table_fairness(rows: &[Vec<f64>], c: f64) -> (f64, Vec<Vec<f64>>) {
    let mut g: Vec<Vec<f64>> = rows.iter().map(|r| vec![0.0; r.len()]).collect();
    let mut sum = 0.0;
    for (i, r) in rows.iter().enumerate() {
        for j in 1..r.len().saturating_sub(1) {
            let d = r[j - 1] - 2.0 * r[j] + r[j + 1];
            sum += d * d;
            let a = 2.0 * d * c;
            g[i][j - 1] += a;
            g[i][j] -= 2.0 * a;
            g[i][j + 1] += a;
        }
    }
    let width = rows.first().map_or(0, Vec::len);
    if rows.len() >= 3 && rows.iter().all(|r| r.len() == width) {
        for j in 0..width {
            for i in 1..rows.len() - 1 {
                let d = rows[i - 1][j] - 2.0 * rows[i][j] + rows[i + 1][j];
                sum += d * d;
                let a = 2.0 * d * c;
                g[i - 1][j] += a;
                g[i][j] -= 2.0 * a;
                g[i + 1][j] += a;
            }
        }
    }
    (sum, g)
}

/// Fairness of a quad mesh's polylines: Σ |G_{i,j−1} − 2G_{i,j} + G_{i,j+1}|² along every row and
/// column (wrapping where the mesh wraps), with its gradient (row-major, scaled by `c`).
pub fn mesh_fairness(mesh: &QuadGrid, c: f64) -> Result<(f64, Vec<DVec3>), GeometryError> {
    mesh.validate()?;
    let (n, m) = (mesh.rows, mesh.cols);
    let mut g = vec![DVec3::ZERO; mesh.vertices.len()];
    let mut sum = 0.0;
    let mut triple = |a: usize, b: usize, d: usize| {
        let v = &mesh.vertices;
        let s = v[a] - v[b] * 2.0 + v[d];
        sum += s.length_squared();
        let w = s * (2.0 * c);
        g[a] += w;
        g[b] -= w * 2.0;
        g[d] += w;
    };
    for i in 0..n {
        let wrap = mesh.wrap_cols && m >= 3;
        for j in 0..m {
            if (j == 0 || j == m - 1) && !wrap {
                continue;
            }
            triple(i * m + (j + m - 1) % m, i * m + j, i * m + (j + 1) % m);
        }
    }
    for j in 0..m {
        let wrap = mesh.wrap_rows && n >= 3;
        for i in 0..n {
            if (i == 0 || i == n - 1) && !wrap {
                continue;
            }
            triple(((i + n - 1) % n) * m + j, i * m + j, ((i + 1) % n) * m + j);
        }
    }
    Ok((sum, g))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn numeric(f: &dyn Fn(&[DVec3]) -> f64, x: &[DVec3]) -> Vec<DVec3> {
        let mut g = vec![DVec3::ZERO; x.len()];
        let mut p = x.to_vec();
        for k in 0..x.len() {
            for c in 0..3 {
                let h = 1e-6;
                p[k][c] = x[k][c] + h;
                let up = f(&p);
                p[k][c] = x[k][c] - h;
                let down = f(&p);
                p[k][c] = x[k][c];
                g[k][c] = (up - down) / (2.0 * h);
            }
        }
        g
    }

    fn grid() -> QuadGrid {
        let mut vertices = Vec::new();
        for i in 0..3 {
            for j in 0..4 {
                let (x, y) = (j as f64, i as f64);
                vertices.push(DVec3::new(x, y, 0.1 * x * x - 0.2 * y + 0.05 * x * y));
            }
        }
        QuadGrid {
            classes: Vec::new(),
            rows: 3,
            cols: 4,
            wrap_rows: false,
            wrap_cols: false,
            vertices,
        }
    }

    fn close(a: &[DVec3], b: &[DVec3]) {
        for (p, q) in a.iter().zip(b) {
            assert!((*p - *q).length() < 1e-7, "{p} vs {q}");
        }
    }

    #[test]
    fn seam_tangent_gradient_matches_differences() {
        let m = grid();
        let f = |v: &[DVec3]| {
            seam_tangents(
                &QuadGrid {
                    classes: Vec::new(),
                    vertices: v.to_vec(),
                    ..m.clone()
                },
                1.0,
            )
            .unwrap()
            .0
        };
        close(
            &seam_tangents(&m, 1.0).unwrap().1,
            &numeric(&f, &m.vertices),
        );
    }

    #[test]
    fn fairness_and_alignment_gradients_match_differences() {
        let m = grid();
        let f = |v: &[DVec3]| {
            mesh_fairness(
                &QuadGrid {
                    classes: Vec::new(),
                    vertices: v.to_vec(),
                    ..m.clone()
                },
                1.0,
            )
            .unwrap()
            .0
        };
        close(
            &mesh_fairness(&m, 1.0).unwrap().1,
            &numeric(&f, &m.vertices),
        );
        let poly = PolygonMesh::from(&m);
        let t = [DVec3::new(0.1, 0.2, 1.0)];
        let f = |v: &[DVec3]| {
            let mut p = poly.clone();
            p.vertices = v.to_vec();
            normal_alignment(&p, &t, 1.0).unwrap().0
        };
        close(
            &normal_alignment(&poly, &t, 1.0).unwrap().2,
            &numeric(&f, &poly.vertices),
        );
        let rows = vec![
            vec![0.1, 0.5, 0.3, 0.9],
            vec![0.2, 0.4, 0.8, 0.1],
            vec![0.7, 0.6, 0.5, 0.2],
        ];
        let (v, g) = table_fairness(&rows, 1.0);
        assert!(v > 0.0);
        let h = 1e-6;
        for i in 0..3 {
            for j in 0..4 {
                let mut p = rows.clone();
                p[i][j] += h;
                let up = table_fairness(&p, 1.0).0;
                p[i][j] -= 2.0 * h;
                let down = table_fairness(&p, 1.0).0;
                assert!(((up - down) / (2.0 * h) - g[i][j]).abs() < 1e-7);
            }
        }
    }
}
