//! Quality measures (notes §9): quad planarity as in libigl, the cone check (how far the lines
//! G_{i,j}G_{i,j+1} of each strip miss a common point) and configuration counts.

use glam::DVec3;
use rayon::prelude::*;

use super::configuration::{ConfigurationCounts, Configurations};
use super::eigen::smallest_eigenvector;
use crate::{GeometryError, QuadGrid};

/// Planarity of a quad `p1 p2 p3 p4` as in libigl: with diagonals `d1 = p3 − p1`, `d2 = p4 − p2`, the
/// distance between the two diagonal lines divided by the mean diagonal length. Quads with parallel
/// (or vanishing) diagonals are planar (0).
#[inline]
pub fn quad_planarity(q: [DVec3; 4]) -> f64 {
    let d1 = q[2] - q[0];
    let d2 = q[3] - q[1];
    let (a, b) = (d1.length_squared(), d2.length_squared());
    let n = d1.cross(d2);
    let n2 = n.length_squared();
    if !(n2 > 1e-28 * a * b) {
        return 0.0;
    }
    let t = (q[1] - q[0]).dot(n);
    // (distance / mean diagonal)² = t² / (|n|² ((|d1| + |d2|) / 2)²), with
    // ((|d1| + |d2|) / 2)² = (a + b + 2 √(ab)) / 4: two square roots and one division in all.
    let mean2 = 0.25 * (a + b + 2.0 * (a * b).sqrt());
    (t * t / (n2 * mean2)).sqrt()
}

/// Planarity of every quad (row-major over quad rows × quad columns), with max and mean.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Planarity {
    /// Per quad, row-major (`i * quad_cols + j`).
    pub per_face: Vec<f64>,
    /// Maximum (0 for a mesh without quads).
    pub max: f64,
    /// Mean (0 for a mesh without quads).
    pub mean: f64,
}

/// Checks that every vertex of the mesh is finite and the vertex count matches.
fn check_mesh(mesh: &QuadGrid) -> Result<(), GeometryError> {
    mesh.validate()?;
    crate::error::check_finite_points("mesh", &mesh.vertices)
}

/// Planarity of every quad of `mesh` (`mesh.planarity`).
pub fn planarity(mesh: &QuadGrid) -> Result<Planarity, GeometryError> {
    check_mesh(mesh)?;
    let (qr, qc) = (mesh.quad_rows(), mesh.quad_cols());
    let inv = 1.0 / normalization(mesh).1;
    let mut per_face = vec![0.0; qr * qc];
    if qc > 0 {
        per_face
            .par_chunks_mut(qc)
            .enumerate()
            .for_each(|(i, out)| {
                let (a, b) = row_pair(mesh, i);
                for (j, o) in out.iter_mut().enumerate() {
                    let j1 = if j + 1 == mesh.cols { 0 } else { j + 1 };
                    *o = scaled_planarity([a[j], a[j1], b[j1], b[j]], inv);
                }
            });
    }
    let max = per_face.iter().copied().fold(0.0, f64::max);
    let mean = if per_face.is_empty() {
        0.0
    } else {
        per_face.iter().sum::<f64>() / per_face.len() as f64
    };
    if !(max.is_finite() && mean.is_finite()) {
        return Err(GeometryError::NonFiniteOutput {
            what: "planarity",
            row: 0,
            column: 0,
        });
    }
    Ok(Planarity {
        per_face,
        max,
        mean,
    })
}

/// Rows i and i + 1 (wrapping) of the mesh as slices.
#[inline]
fn row_pair(mesh: &QuadGrid, i: usize) -> (&[DVec3], &[DVec3]) {
    let i1 = if i + 1 == mesh.rows { 0 } else { i + 1 };
    let m = mesh.cols;
    (
        &mesh.vertices[i * m..(i + 1) * m],
        &mesh.vertices[i1 * m..(i1 + 1) * m],
    )
}

/// The cone check of every strip j (between columns j and j+1).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ConeCheck {
    /// Relative concurrency residual per strip (see [`cone_check`]).
    pub residuals: Vec<f64>,
    /// Maximum residual.
    pub max: f64,
    /// The fitted common point of each strip; `None` at infinity (parallel lines) or when fewer than
    /// two lines are defined.
    pub apices: Vec<Option<DVec3>>,
}

/// Homogeneous least-squares fit of the common point of the lines of one strip, in normalized
/// coordinates `(p − center) / scale`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct StripFit {
    /// Homogeneous point (v, w), unit length.
    pub h: [f64; 4],
    /// max_i |(v − w p_i) × d_i| over the lines (unit d_i).
    pub residual: f64,
    /// Number of lines used.
    pub lines: usize,
}

/// Normalization frame of a mesh: bounding-box center and half its largest extent (1 when
/// degenerate), computed without overflow.
pub(crate) fn normalization(mesh: &QuadGrid) -> (DVec3, f64) {
    match mesh.bounds() {
        Some((lo, hi)) => {
            let half = (hi * 0.5 - lo * 0.5).max_element();
            (
                lo * 0.5 + hi * 0.5,
                if half > 0.0 && half.is_finite() {
                    half
                } else {
                    1.0
                },
            )
        }
        None => (DVec3::ZERO, 1.0),
    }
}

/// [`normalization`] computed with a parallel reduction (for large constructed meshes).
fn parallel_normalization(mesh: &QuadGrid) -> (DVec3, f64) {
    let (lo, hi) = mesh
        .vertices
        .par_chunks(4096)
        .map(|c| {
            c.iter()
                .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), p| {
                    (l.min(*p), h.max(*p))
                })
        })
        .reduce(
            || (DVec3::INFINITY, DVec3::NEG_INFINITY),
            |a, b| (a.0.min(b.0), a.1.max(b.1)),
        );
    if mesh.vertices.is_empty() {
        return (DVec3::ZERO, 1.0);
    }
    let half = (hi * 0.5 - lo * 0.5).max_element();
    (
        lo * 0.5 + hi * 0.5,
        if half > 0.0 && half.is_finite() {
            half
        } else {
            1.0
        },
    )
}

/// Planarity of a quad from its corners taken relative to the first corner and scaled by `inv` (the
/// measure is translation- and scale-invariant; this keeps the squares in range at any magnitude).
#[inline(always)]
fn scaled_planarity(q: [DVec3; 4], inv: f64) -> f64 {
    quad_planarity([
        DVec3::ZERO,
        (q[1] - q[0]) * inv,
        (q[2] - q[0]) * inv,
        (q[3] - q[0]) * inv,
    ])
}

/// One line of a strip in normalized coordinates: a point and the (unnormalized) direction with its
/// inverse squared length, or `None` for a zero-length edge. `row` is one mesh row; strip j joins
/// columns j and j + 1 (wrapping).
#[inline]
fn strip_line(row: &[DVec3], j: usize, center: DVec3, inv: f64) -> Option<(DVec3, DVec3, f64)> {
    let j1 = if j + 1 == row.len() { 0 } else { j + 1 };
    let a = (row[j] - center) * inv;
    let d = (row[j1] - row[j]) * inv;
    let l2 = d.length_squared();
    (l2 > 0.0 && l2.is_finite()).then(|| (a, d, 1.0 / l2))
}

/// The squared residual `|(v − w p) × d̂|²` of a line (point p, direction d, `inv_l2 = 1/|d|²`) for
/// the unit homogeneous point (v, w).
#[inline]
fn line_residual2(h: [f64; 4], p: DVec3, d: DVec3, inv_l2: f64) -> f64 {
    (DVec3::new(h[0], h[1], h[2]) - p * h[3])
        .cross(d)
        .length_squared()
        * inv_l2
}

/// Fits every strip: accumulates Σ AᵢᵀAᵢ per strip (rows in parallel), takes the smallest
/// eigenvector, then evaluates the residual of every line.
pub(crate) fn fit_strips(mesh: &QuadGrid, center: DVec3, scale: f64) -> Vec<StripFit> {
    let strips = mesh.quad_cols();
    let inv = 1.0 / scale;
    let zero = || vec![[0.0f64; 11]; strips];
    let sums = (0..mesh.rows)
        .into_par_iter()
        .fold(zero, |mut acc, i| {
            let row = &mesh.vertices[i * mesh.cols..(i + 1) * mesh.cols];
            for (j, s) in acc.iter_mut().enumerate() {
                if let Some((p, dd, inv_l2)) = strip_line(row, j, center, inv) {
                    // Aᵢ = [−[d]× | −(p × d)]; AᵢᵀAᵢ = [[I − ddᵀ, (p·d) d − p], [·, |p × d|²]] for
                    // the unit direction d = dd / |dd|.
                    let d = dd * inv_l2.sqrt();
                    let pd = p.dot(d);
                    let t = d * pd - p;
                    let c = p.cross(d).length_squared();
                    let upper = [
                        1.0 - d.x * d.x,
                        -d.x * d.y,
                        -d.x * d.z,
                        t.x,
                        1.0 - d.y * d.y,
                        -d.y * d.z,
                        t.y,
                        1.0 - d.z * d.z,
                        t.z,
                        c,
                    ];
                    for (k, u) in upper.iter().enumerate() {
                        s[k] += u;
                    }
                    s[10] += 1.0;
                }
            }
            acc
        })
        .reduce(zero, |mut a, b| {
            for (x, y) in a.iter_mut().zip(&b) {
                for k in 0..11 {
                    x[k] += y[k];
                }
            }
            a
        });
    let hs: Vec<[f64; 4]> = sums
        .par_iter()
        .map(|s| {
            let q = [
                [s[0], s[1], s[2], s[3]],
                [s[1], s[4], s[5], s[6]],
                [s[2], s[5], s[7], s[8]],
                [s[3], s[6], s[8], s[9]],
            ];
            smallest_eigenvector(q)
        })
        .collect();
    let residuals = (0..mesh.rows)
        .into_par_iter()
        .fold(
            || vec![0.0f64; strips],
            |mut acc, i| {
                let row = &mesh.vertices[i * mesh.cols..(i + 1) * mesh.cols];
                for (j, r) in acc.iter_mut().enumerate() {
                    if let Some((p, d, inv_l2)) = strip_line(row, j, center, inv) {
                        *r = r.max(line_residual2(hs[j], p, d, inv_l2));
                    }
                }
                acc
            },
        )
        .reduce(
            || vec![0.0f64; strips],
            |mut a, b| {
                for (x, y) in a.iter_mut().zip(&b) {
                    *x = x.max(*y);
                }
                a
            },
        );
    hs.into_iter()
        .zip(residuals)
        .zip(&sums)
        .map(|((h, residual), s)| {
            let lines = s[10] as usize;
            StripFit {
                h,
                residual: if lines >= 2 { residual } else { 0.0 },
                lines,
            }
        })
        .collect()
}

/// The fitted point of a strip in world coordinates; `None` at infinity.
pub(crate) fn fitted_point(fit: &StripFit, center: DVec3, scale: f64) -> Option<DVec3> {
    let [x, y, z, w] = fit.h;
    if fit.lines < 2 || !(w.abs() > 1e-12) {
        return None;
    }
    let c = center + DVec3::new(x, y, z) * (scale / w);
    c.is_finite().then_some(c)
}

/// The cone check of `mesh`: for each strip j, the lines through G_{i,j} and G_{i,j+1} (all rows i)
/// are fitted with a common point (possibly at infinity) by homogeneous least squares, in coordinates
/// centered on the mesh and scaled by half its bounding-box diagonal. The residual of a line is
/// `|(v − w pᵢ) × dᵢ|` for the unit fit (v, w) and unit direction dᵢ: for a finite point C this is
/// `dist(C, line) / √(|C|² + 1)` (relative to the mesh size), for a point at infinity the sine of the
/// angle between the line and the common direction. The strip residual is the maximum over its lines.
pub fn cone_check(mesh: &QuadGrid) -> Result<ConeCheck, GeometryError> {
    check_mesh(mesh)?;
    let (center, scale) = normalization(mesh);
    let fits = fit_strips(mesh, center, scale);
    let residuals: Vec<f64> = fits.iter().map(|f| f.residual).collect();
    let max = residuals.iter().copied().fold(0.0, f64::max);
    if !max.is_finite() {
        return Err(GeometryError::NonFiniteOutput {
            what: "cone residual",
            row: 0,
            column: 0,
        });
    }
    let apices = fits
        .iter()
        .map(|f| fitted_point(f, center, scale))
        .collect();
    Ok(ConeCheck {
        residuals,
        max,
        apices,
    })
}

/// Quality of a constructed cone-net (the nodes' `quality` record).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Quality {
    /// Maximum quad planarity (libigl measure).
    pub max_planarity: f64,
    /// Mean quad planarity.
    pub mean_planarity: f64,
    /// Cone residual per strip j = 0 … M−2: how far the lines G_{i,j}G_{i,j+1} miss the
    /// construction's apex C_j (same normalization as [`cone_check`]).
    pub cone_residuals: Vec<f64>,
    /// Maximum cone residual.
    pub max_cone_residual: f64,
    /// Configuration counts.
    pub configurations: ConfigurationCounts,
    /// The first vertex (i, j) not in (++), by column then row.
    pub first_bad: Option<(usize, usize)>,
}

/// Computes the quality record of a constructed mesh in one pass over the rows: planarity of every
/// quad (max, mean) and the cone residual of every line against the construction's own apex
/// `C_j = (X_{j+1} − a_{j+1} X_j) / (1 − a_{j+1})`, taken homogeneously as
/// `(X_{j+1} − a X_j, 1 − a)` in normalized coordinates (exact for a = 1, a point at infinity).
pub(crate) fn quality(
    mesh: &QuadGrid,
    directrix: &[DVec3],
    apex: &[f64],
    configurations: &Configurations,
) -> Result<Quality, GeometryError> {
    // The sweep has checked every vertex for finiteness already.
    mesh.validate()?;
    let (center, scale) = parallel_normalization(mesh);
    let inv = 1.0 / scale;
    let strips = mesh.cols.saturating_sub(1);
    let hs: Vec<[f64; 4]> = (0..strips)
        .map(|j| {
            let a = apex[j];
            let v = (directrix[j + 1] - center) * inv - (directrix[j] - center) * (inv * a);
            let w = 1.0 - a;
            let norm = (v.length_squared() + w * w).sqrt();
            [v.x / norm, v.y / norm, v.z / norm, w / norm]
        })
        .collect();
    let qr = mesh.quad_rows();
    struct Acc {
        max: f64,
        sum: f64,
        /// Per strip, the largest squared residual as a fraction (numerator, denominator): fractions
        /// are compared by cross-multiplication, so no division per line.
        residuals: Vec<(f64, f64)>,
    }
    let empty = || Acc {
        max: 0.0,
        sum: 0.0,
        residuals: vec![(0.0, 1.0); strips],
    };
    let acc = (0..mesh.rows)
        .into_par_iter()
        .fold(empty, |mut acc, i| {
            let (a, b) = row_pair(mesh, i);
            let quads = i < qr;
            for j in 0..strips {
                if quads {
                    let p = scaled_planarity([a[j], a[j + 1], b[j + 1], b[j]], inv);
                    acc.max = acc.max.max(p);
                    acc.sum += p;
                }
                let (p, d) = ((a[j] - center) * inv, (a[j + 1] - a[j]) * inv);
                let den = d.length_squared();
                let h = hs[j];
                let num = (DVec3::new(h[0], h[1], h[2]) - p * h[3])
                    .cross(d)
                    .length_squared();
                let r = &mut acc.residuals[j];
                // num / den > r.0 / r.1, skipping zero-length edges (den = 0).
                if den > 0.0 && num * r.1 > r.0 * den {
                    *r = (num, den);
                }
            }
            acc
        })
        .reduce(empty, |mut x, y| {
            x.max = x.max.max(y.max);
            x.sum += y.sum;
            for (r, s) in x.residuals.iter_mut().zip(&y.residuals) {
                if s.0 * r.1 > r.0 * s.1 {
                    *r = *s;
                }
            }
            x
        });
    let count = mesh.quad_count();
    let mean = if count == 0 {
        0.0
    } else {
        acc.sum / count as f64
    };
    let residuals: Vec<f64> = acc.residuals.iter().map(|(n, d)| (n / d).sqrt()).collect();
    let max_cone = residuals.iter().copied().fold(0.0, f64::max);
    if !(acc.max.is_finite() && mean.is_finite() && max_cone.is_finite()) {
        return Err(GeometryError::NonFiniteOutput {
            what: "quality",
            row: 0,
            column: 0,
        });
    }
    Ok(Quality {
        max_planarity: acc.max,
        mean_planarity: mean,
        cone_residuals: residuals,
        max_cone_residual: max_cone,
        configurations: configurations.counts(),
        first_bad: configurations.first_bad(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planar_and_twisted_quads() {
        let flat = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
        assert_eq!(quad_planarity(flat), 0.0);
        // Lift one corner by h: diagonals (0,0,0)-(1,1,0) and (1,0,0)-(0,1,h).
        // d1 = (1,1,0), d2 = (−1,1,h): n = (h, −h, 2); (p2 − p1)·n = h; |n| = √(2h² + 4).
        let h = 0.2;
        let twisted = [
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, h),
        ];
        let dist = h / (2.0 * h * h + 4.0f64).sqrt();
        let mean = 0.5 * (2.0f64.sqrt() + (2.0 + h * h).sqrt());
        assert!((quad_planarity(twisted) - dist / mean).abs() < 1e-15);
    }

    #[test]
    fn cone_check_detects_concurrent_and_skew_lines() {
        // Three lines through the apex (0, 0, 5): a cone strip.
        let apex = DVec3::new(0.0, 0.0, 5.0);
        let base = [
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(-1.0, 0.2, 0.0),
        ];
        let mut v = Vec::new();
        for b in base {
            v.push(b);
            v.push(b + (apex - b) * 0.3);
        }
        let mesh = QuadGrid::new(3, 2, v.clone()).unwrap();
        let c = cone_check(&mesh).unwrap();
        assert!(c.max < 1e-14, "{}", c.max);
        assert!((c.apices[0].unwrap() - apex).length() < 1e-12);
        v[5] += DVec3::new(0.5, 0.0, 0.0);
        let skew = cone_check(&QuadGrid::new(3, 2, v).unwrap()).unwrap();
        assert!(skew.max > 1e-3, "{skew:?}");
    }
}
