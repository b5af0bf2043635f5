//! Quality measures (notes §9): quad planarity as in libigl, the cone check (how far the lines
//! G_{i,j}G_{i,j+1} of each strip miss a common point) and configuration counts.

use glam::DVec3;
use rayon::prelude::*;

use super::configuration::{ConfigurationCounts, Configurations};
use super::eigen::smallest_eigenvector;
use super::lanes::{F, LANES, M, V3};
use super::ordered::fold_rows;
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
        Some((lo, hi)) => normalization_of(lo, hi),
        None => (DVec3::ZERO, 1.0),
    }
}

/// The normalization frame of the bounding box `lo`–`hi`: its center and half its largest extent
/// (1 when degenerate), computed without overflow.
fn normalization_of(lo: DVec3, hi: DVec3) -> (DVec3, f64) {
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

/// Edges shorter than this, in normalized coordinates (a millionth of the mesh's half diagonal),
/// are collapsed: their direction is rounding noise (1e-16 / length), so they neither constrain
/// the fit nor count in the residual. A rung of 1.6e-7 on a 6 m design read as a cone residual of
/// 1.1e-9 before (found by `scripts/test-explore.sh`).
const COLLAPSED_EDGE: f64 = 1e-6;

/// One line of a strip in normalized coordinates: a point and the (unnormalized) direction with its
/// inverse squared length, or `None` for a collapsed edge ([`COLLAPSED_EDGE`]). `row` is one mesh
/// row; strip j joins columns j and j + 1 (wrapping).
#[inline]
fn strip_line(row: &[DVec3], j: usize, center: DVec3, inv: f64) -> Option<(DVec3, DVec3, f64)> {
    let j1 = if j + 1 == row.len() { 0 } else { j + 1 };
    let a = (row[j] - center) * inv;
    let d = (row[j1] - row[j]) * inv;
    let l2 = d.length_squared();
    (l2 > COLLAPSED_EDGE * COLLAPSED_EDGE && l2.is_finite()).then(|| (a, d, 1.0 / l2))
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
    let sums = fold_rows(
        mesh.rows,
        zero,
        |acc, i| {
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
        },
        |a, b| {
            for (x, y) in a.iter_mut().zip(&b) {
                for k in 0..11 {
                    x[k] += y[k];
                }
            }
        },
    );
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

/// Per-strip constants of the cone residual, one array per component (see [`quality`]).
struct StripConstants {
    /// (X_{j+1} − X_j) · inv_scale.
    e: [Vec<f64>; 3],
    /// X_j.
    x: [Vec<f64>; 3],
    /// (1 − a_{j+1}) · inv_scale.
    one_minus_a: Vec<f64>,
}

impl StripConstants {
    /// Lanes of component array `c` from strip j0.
    #[inline(always)]
    fn lanes(c: &[Vec<f64>; 3], j0: usize) -> V3 {
        V3 {
            x: F::load(&c[0], j0),
            y: F::load(&c[1], j0),
            z: F::load(&c[2], j0),
        }
    }
}

/// What one task of the quality pass accumulates.
struct QualityAcc {
    /// The scale of the coordinates.
    inv_scale: f64,
    /// Largest planarity per lane.
    max: F,
    /// Sum of planarities per lane.
    sum: F,
    /// Bounding box per lane.
    lo: V3,
    hi: V3,
    /// Per strip, the largest squared residual as a fraction (numerator, denominator): fractions
    /// are compared by cross-multiplication, so no division per line.
    num: Vec<f64>,
    den: Vec<f64>,
}

impl QualityAcc {
    /// The normalization frame (see [`normalization`]) of the bounding box of the vertices seen.
    fn normalization(&self) -> (DVec3, f64) {
        let lo = (0..LANES).fold(DVec3::INFINITY, |m, l| m.min(self.lo.lane(l)));
        let hi = (0..LANES).fold(DVec3::NEG_INFINITY, |m, l| m.max(self.hi.lane(l)));
        normalization_of(lo, hi)
    }

    /// Adds the quads (or, when not `quads`, only the lines) of strips j0 … j0 + LANES − 1 of one
    /// row pair, given their corners `G_{i,j}, G_{i,j+1}, G_{i+1,j+1}, G_{i+1,j}`; lanes outside
    /// `valid` repeat a valid quad.
    #[inline(always)]
    fn add(
        &mut self,
        strip: &StripConstants,
        j0: usize,
        [p, p1, q1, q]: [V3; 4],
        quads: bool,
        valid: M,
    ) {
        let inv_scale = self.inv_scale;
        self.lo = self.lo.min(p).min(p1);
        self.hi = self.hi.max(p).max(p1);
        // Corners relative to the first, scaled: the line direction d is the first edge.
        let d = (p1 - p) * inv_scale;
        if quads {
            let planarity = planarity_lanes(d, (q1 - p) * inv_scale, (q - p) * inv_scale);
            self.max = self.max.max(planarity);
            self.sum = self.sum + F::select(valid, planarity, F::splat(0.0));
        }
        let e = StripConstants::lanes(&strip.e, j0);
        let x = StripConstants::lanes(&strip.x, j0);
        let k = e + (x - p) * F::load(&strip.one_minus_a, j0);
        let num = k.cross(d).length_squared();
        let den = d.length_squared();
        let (r0, r1) = (F::load(&self.num, j0), F::load(&self.den, j0));
        // num / den > r0 / r1, skipping collapsed edges (den ≤ COLLAPSED_EDGE², as `cone_check`).
        let up = den.gt(F::splat(COLLAPSED_EDGE * COLLAPSED_EDGE)) & (num * r1).gt(r0 * den);
        F::select(up, num, r0).store(&mut self.num, j0);
        F::select(up, den, r1).store(&mut self.den, j0);
    }
}

/// Computes the quality record of a constructed mesh in one pass over the rows, [`LANES`] quads at a
/// time: planarity of every quad (max, mean), the cone residual of every line against the
/// construction's own apex, and the bounding box the residuals are normalized with.
///
/// The residual of the line through `p = G_{i,j}`, `d = G_{i,j+1} − G_{i,j}` against the apex
/// `C_j = (X_{j+1} − a X_j) / (1 − a)` (a = a_{j+1}), taken homogeneously as `(v, w) = (X_{j+1} −
/// a X_j, 1 − a)` in the mesh's normalized coordinates (center c, scale s; exact for a = 1, a point
/// at infinity) and made unit, is `|(v − w p) × d̂|` (see [`cone_check`]). The center cancels in
/// `v − w p = (K / s) / |(v, w)|` with `K = (X_{j+1} − X_j) + (1 − a)(X_j − G_{i,j})`, so the pass
/// accumulates `max_i |K × d|² / |d|²` per strip (in coordinates scaled by `inv_scale`, 1 / design
/// size, which keeps the magnitudes near 1) and the bounding box, and applies the per-strip factor
/// at the end. The planarity measure is scale-invariant; `inv_scale` only keeps its squares in range.
pub(crate) fn quality(
    mesh: &QuadGrid,
    directrix: &[DVec3],
    apex: &[f64],
    configurations: &Configurations,
    inv_scale: f64,
) -> Result<Quality, GeometryError> {
    // The sweep has checked every vertex for finiteness already.
    mesh.validate()?;
    let strips = mesh.cols.saturating_sub(1);
    let counts = configurations.counts();
    let first_bad = if counts.bad() == 0 {
        None
    } else {
        configurations.first_bad()
    };
    if mesh.rows == 0 || strips == 0 {
        return Ok(Quality {
            configurations: counts,
            first_bad,
            ..Quality::default()
        });
    }
    let mut acc = quality_pass(mesh, directrix, apex, inv_scale);
    let (center, scale) = acc.normalization();
    // The mesh can be far larger (or smaller) than its design, e.g. for extreme apex values: then
    // the pass is redone in the mesh's own scale, which keeps every square in range.
    if !(scale * inv_scale < 1e30 && scale * inv_scale > 1e-30) {
        acc = quality_pass(mesh, directrix, apex, 1.0 / scale);
    }
    let inv = 1.0 / scale;
    let residuals: Vec<f64> = (0..strips)
        .map(|j| {
            // |(v, w)| for the apex in normalized coordinates, as in `cone_check`.
            let a = apex[j];
            let v = (directrix[j + 1] - center) * inv - (directrix[j] - center) * (inv * a);
            let w = 1.0 - a;
            let norm = (v.length_squared() + w * w).sqrt();
            (acc.num[j] / acc.den[j]).sqrt() * (inv / acc.inv_scale) / norm
        })
        .collect();
    let count = mesh.quad_count();
    let max = acc.max.0.iter().copied().fold(0.0, f64::max);
    let mean = if count == 0 {
        0.0
    } else {
        acc.sum.0.iter().sum::<f64>() / count as f64
    };
    let max_cone = residuals.iter().copied().fold(0.0, f64::max);
    if !(max.is_finite() && mean.is_finite() && residuals.iter().all(|r| r.is_finite())) {
        return Err(GeometryError::NonFiniteOutput {
            what: "quality",
            row: 0,
            column: 0,
        });
    }
    Ok(Quality {
        max_planarity: max,
        mean_planarity: mean,
        cone_residuals: residuals,
        max_cone_residual: max_cone,
        configurations: counts,
        first_bad,
    })
}

/// The pass of [`quality`] over all rows (in parallel), in coordinates scaled by `inv_scale`.
fn quality_pass(mesh: &QuadGrid, directrix: &[DVec3], apex: &[f64], inv_scale: f64) -> QualityAcc {
    let strips = mesh.cols - 1;
    let padded = strips.div_ceil(LANES) * LANES;
    // Per-strip constants, one array per component, padded by repeating the last strip.
    let constant = |f: &dyn Fn(usize) -> f64| -> Vec<f64> {
        (0..padded).map(|k| f(k.min(strips - 1))).collect()
    };
    let edge = |j: usize| (directrix[j + 1] - directrix[j]) * inv_scale;
    let strip = StripConstants {
        e: [
            constant(&|j| edge(j).x),
            constant(&|j| edge(j).y),
            constant(&|j| edge(j).z),
        ],
        x: [
            constant(&|j| directrix[j].x),
            constant(&|j| directrix[j].y),
            constant(&|j| directrix[j].z),
        ],
        one_minus_a: constant(&|j| (1.0 - apex[j]) * inv_scale),
    };
    let empty = || QualityAcc {
        inv_scale,
        max: F::splat(0.0),
        sum: F::splat(0.0),
        lo: V3::splat(DVec3::INFINITY),
        hi: V3::splat(DVec3::NEG_INFINITY),
        num: vec![0.0; padded],
        den: vec![1.0; padded],
    };
    // In fixed blocks, merged in order: the mean planarity is a sum of floats, and its bits must
    // not depend on how threads were scheduled.
    fold_rows(
        mesh.rows,
        empty,
        |acc, i| {
            crate::simd::run(
                #[inline(always)]
                || add_row(acc, &strip, mesh, i),
            )
        },
        |x, y| {
            x.max = x.max.max(y.max);
            x.sum = x.sum + y.sum;
            x.lo = x.lo.min(y.lo);
            x.hi = x.hi.max(y.hi);
            for j in 0..padded {
                if y.num[j] * x.den[j] > x.num[j] * y.den[j] {
                    (x.num[j], x.den[j]) = (y.num[j], y.den[j]);
                }
            }
        },
    )
}

/// Adds the quads between rows i and i + 1 (none when i is the last row of an open mesh) and the
/// cone residuals of row i to `acc`, [`LANES`] strips at a time.
#[inline(always)]
fn add_row(acc: &mut QualityAcc, strip: &StripConstants, mesh: &QuadGrid, i: usize) {
    let strips = mesh.cols - 1;
    let (a, b) = row_pair(mesh, i);
    let quads = i < mesh.quad_rows();
    // Full groups of LANES strips, then the last group padded by repeating its last strip.
    let full = strips / LANES * LANES;
    for j0 in (0..full).step_by(LANES) {
        let corners = [
            V3::gather(&a[j0..j0 + LANES]),
            V3::gather(&a[j0 + 1..j0 + 1 + LANES]),
            V3::gather(&b[j0 + 1..j0 + 1 + LANES]),
            V3::gather(&b[j0..j0 + LANES]),
        ];
        acc.add(strip, j0, corners, quads, M::splat(true));
    }
    if full < strips {
        let mut valid = M::splat(true);
        let mut corners = [V3::ZERO; 4];
        for l in 0..LANES {
            let j = (full + l).min(strips - 1);
            valid.set(l, full + l < strips);
            corners[0].set_lane(l, a[j]);
            corners[1].set_lane(l, a[j + 1]);
            corners[2].set_lane(l, b[j + 1]);
            corners[3].set_lane(l, b[j]);
        }
        acc.add(strip, full, corners, quads, valid);
    }
}

/// [`quad_planarity`] per lane for the quads `[0, d, q2, q3]` (corners relative to the first).
#[inline(always)]
fn planarity_lanes(q1: V3, q2: V3, q3: V3) -> F {
    let d1 = q2;
    let d2 = q3 - q1;
    let (a, b) = (d1.length_squared(), d2.length_squared());
    let n = d1.cross(d2);
    let n2 = n.length_squared();
    let t = q1.dot(n);
    let mean2 = (a + b + (a * b).sqrt() * 2.0) * 0.25;
    let p = (t * t / (n2 * mean2)).sqrt();
    F::select(n2.gt(F::splat(1e-28) * a * b), p, F::splat(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The quality record computed the direct way: every quad and line on its own, in coordinates
    /// normalized by the mesh's bounding box.
    fn reference(mesh: &QuadGrid, directrix: &[DVec3], apex: &[f64]) -> (f64, f64, Vec<f64>) {
        let p = planarity(mesh).unwrap();
        let (center, scale) = normalization(mesh);
        let inv = 1.0 / scale;
        let residuals = (0..mesh.cols - 1)
            .map(|j| {
                let a = apex[j];
                let v = (directrix[j + 1] - center) * inv - (directrix[j] - center) * (inv * a);
                let w = 1.0 - a;
                let norm = (v.length_squared() + w * w).sqrt();
                let h = v / norm;
                (0..mesh.rows)
                    .map(|i| {
                        let q = (mesh.at(i, j) - center) * inv;
                        let d = (mesh.at(i, j + 1) - mesh.at(i, j)) * inv;
                        ((h - q * (w / norm)).cross(d).length_squared() / d.length_squared()).sqrt()
                    })
                    .fold(0.0, f64::max)
            })
            .collect();
        (p.max, p.mean, residuals)
    }

    #[test]
    fn quality_pass_matches_the_definitions() {
        let mut state = 9u64;
        let mut rnd = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        // Column counts around the lane width, open and closed rows, and a mesh far larger than
        // its design scale (the pass is redone in the mesh's own scale).
        for (rows, cols, wrap, size, design) in [
            (3, 2, false, 1.0, 4.0),
            (4, 9, true, 1.0, 4.0),
            (5, 17, false, 3.0, 12.0),
            (2, 8, false, 1.0, 4.0),
            (6, 23, true, 1e200, 1.0),
        ] {
            let directrix: Vec<DVec3> = (0..cols)
                .map(|j| DVec3::new(j as f64, 0.3 * rnd(), 0.2 * rnd()) * size)
                .collect();
            let apex: Vec<f64> = (0..cols - 1).map(|j| [1.0, 0.9 + rnd()][j % 2]).collect();
            let vertices = (0..rows * cols)
                .map(|k| {
                    let (i, j) = (k / cols, k % cols);
                    (DVec3::new(j as f64, 1.0 + i as f64, 0.5 * i as f64)
                        + DVec3::new(rnd(), rnd(), rnd()) * 0.2)
                        * size
                })
                .collect();
            let mesh = QuadGrid::new(rows, cols, vertices)
                .unwrap()
                .with_wrap(wrap, false);
            let configurations = Configurations::from_padded(
                rows,
                cols - 1,
                cols - 1,
                vec![Default::default(); rows * (cols - 1)],
            );
            let q = quality(&mesh, &directrix, &apex, &configurations, 1.0 / design).unwrap();
            let (max, mean, residuals) = reference(&mesh, &directrix, &apex);
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1e-300);
            assert!(max > 1e-3 && close(q.max_planarity, max), "{q:?} vs {max}");
            assert!(close(q.mean_planarity, mean), "{q:?} vs {mean}");
            assert_eq!(q.cone_residuals.len(), residuals.len());
            for (a, b) in q.cone_residuals.iter().zip(&residuals) {
                assert!(*b > 1e-4 && close(*a, *b), "{a} vs {b}");
            }
        }
    }

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
