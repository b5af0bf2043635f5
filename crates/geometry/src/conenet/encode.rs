//! Encoding any cone-net as C-tube construction inputs (paper Sec. 4.1, Proposition 1, notes §8).
//!
//! 1. Fit the apex C_j of every strip (homogeneous least squares, [`super::cone_check`]); reject the
//!    mesh when a strip's lines miss a common point by more than 1e-6 (relative).
//! 2. The directrix is row 0 shifted by an offset that scales with the strips: `X_0 = G_{0,0} + O_0`,
//!    and for every strip the scaling σ_j about C_{j−1} with factor `s_j` that maps G_{0,j−1} to
//!    G_{0,j} also maps X_{j−1} to `X_j = G_{0,j} + s_j O_{j−1}`. Then `a_j = s_j > 0` (a translation,
//!    `s_j = 1`, for an apex at infinity). When row 0 passes through the apex (`s_j ≤ 0`) the encoder
//!    uses `a_j = |s_j|` (or ½ when |s_j| ≈ 1) and `X_j = C + a_j (X_{j−1} − C)`.
//! 3. `O_0 = −h n̂`: h the mean generatrix edge length, n̂ the normal of quad (0, 0), so X_0 lies off
//!    the face planes; further candidates are tried if the first one is degenerate.
//! 4. The plane Π_{i,j} contains X_j and G_{i,j} and is perpendicular to the support plane S_{i,j}:
//!    `P = unit(ê_j − (ê_j·r̂) r̂)` with `r̂ = unit(G_{i,j} − X_j)` (so `P·ê_j > 0`).
//! 5. The encoding is verified by re-constructing the mesh.

use glam::DVec3;

use super::ctube::ctube_mesh;
use super::inputs::{ApexInput, ColumnValues, CtubeInputs, EndPlanes, NormalsInput};
use super::quality::{fit_strips, normalization};
use super::tolerance;
use crate::{GeometryError, Polyline, QuadGrid};

/// Construction inputs that reproduce a given cone-net with the C-tube construction.
#[derive(Debug, Clone, PartialEq)]
pub struct Encoding {
    /// The directrix X_0 … X_{M−1} (open).
    pub directrix: Polyline,
    /// The generatrix G_{:,0} (closed when the mesh wraps its rows).
    pub generatrix: Polyline,
    /// The apex values a_j > 0, j = 1 … M−1.
    pub apex: Vec<f64>,
    /// N lists of M−1 unit normals P_{i,j}.
    pub normals: Vec<Vec<DVec3>>,
}

impl Encoding {
    /// The C-tube inputs of this encoding (not normalized).
    pub fn to_ctube_inputs(&self) -> CtubeInputs {
        CtubeInputs {
            directrix: self.directrix.clone(),
            generatrix: self.generatrix.clone(),
            apex: ApexInput {
                values: ColumnValues::List(self.apex.clone()),
                normalized: false,
                scale: None,
                seam: None,
            },
            normals: NormalsInput::PerVertex(self.normals.clone()),
            end_planes: EndPlanes::Perpendicular,
        }
    }
}

/// Encodes a cone-net (`cnets.encode`). Fails on meshes that are not cone-nets (naming the strip),
/// that wrap their columns, have fewer than 2 × 2 vertices, non-finite vertices or zero-length
/// directrix-direction edges.
pub fn encode(mesh: &QuadGrid) -> Result<Encoding, GeometryError> {
    mesh.validate()?;
    let (n, m) = (mesh.rows, mesh.cols);
    if n < 2 {
        return Err(GeometryError::TooFewPoints {
            what: "mesh rows",
            needed: 2,
            got: n,
        });
    }
    if m < 2 {
        return Err(GeometryError::TooFewPoints {
            what: "mesh columns",
            needed: 2,
            got: m,
        });
    }
    if mesh.wrap_cols {
        return Err(GeometryError::Unsupported(
            "the encoder needs an open directrix direction (wrap_cols = false)",
        ));
    }
    crate::error::check_finite_points("mesh", &mesh.vertices)?;
    for i in 0..n {
        for j in 0..m - 1 {
            if mesh.at(i, j).distance_squared(mesh.at(i, j + 1)) <= f64::MIN_POSITIVE {
                return Err(GeometryError::ZeroLengthEdge {
                    what: "mesh (row-major vertex indices)",
                    index: i * m + j,
                    next: i * m + j + 1,
                });
            }
        }
    }
    let (center, scale) = normalization(mesh);
    let fits = fit_strips(mesh, center, scale);
    for (j, f) in fits.iter().enumerate() {
        if !(f.residual <= tolerance::CONE_NET) {
            return Err(GeometryError::NotAConeNet {
                column: j,
                residual: f.residual,
            });
        }
    }
    // s_j: the factor of the scaling about C_{j−1} mapping G_{0,j−1} to G_{0,j} (normalized coords).
    let inv = 1.0 / scale;
    let mut factors = Vec::with_capacity(m - 1);
    let mut apices = Vec::with_capacity(m - 1);
    for (k, f) in fits.iter().enumerate() {
        let v = DVec3::new(f.h[0], f.h[1], f.h[2]);
        let w = f.h[3];
        let a = (mesh.at(0, k) - center) * inv * w - v;
        let b = (mesh.at(0, k + 1) - center) * inv * w - v;
        let aa = a.length_squared();
        if !(aa > 1e-24) {
            return Err(GeometryError::Degenerate(format!(
                "mesh vertex (0, {k}) is the apex of strip {k}; the encoder needs row 0 off the apices"
            )));
        }
        factors.push(a.dot(b) / aa);
        apices.push((w.abs() > 1e-300).then(|| center + v * (scale / w)));
    }
    let generatrix_edge = (0..n - 1)
        .map(|i| mesh.at(i, 0).distance(mesh.at(i + 1, 0)))
        .sum::<f64>()
        / (n - 1) as f64;
    let q = mesh.quad(0, 0);
    let normal = (q[2] - q[0]).cross(q[3] - q[1]);
    let normal = if normal.length() > 0.0 {
        normal.normalize()
    } else {
        (q[1] - q[0]).any_orthonormal_vector()
    };
    let along = (q[3] - q[0]).normalize_or_zero();
    let h = generatrix_edge;
    let candidates = [
        -normal * h,
        normal * h,
        (-normal + along * 0.5) * h,
        -normal * (2.0 * h),
        normal * (0.5 * h),
    ];
    let size = mesh.size().max(f64::MIN_POSITIVE);
    let mut last_error = None;
    for offset in candidates {
        match try_offset(mesh, offset, &factors, &apices) {
            Ok(enc) => match ctube_mesh(&enc.to_ctube_inputs()) {
                Ok(rebuilt) => {
                    let dev = rebuilt
                        .vertices
                        .iter()
                        .zip(&mesh.vertices)
                        .map(|(a, b)| a.distance(*b))
                        .fold(0.0, f64::max);
                    if dev <= tolerance::CONE_NET * size {
                        return Ok(enc);
                    }
                    last_error = Some(GeometryError::Degenerate(format!(
                        "the encoding does not reproduce the mesh (deviation {dev:.3e})"
                    )));
                }
                Err(e) => last_error = Some(e),
            },
            Err(e) => last_error = Some(e),
        }
    }
    Err(last_error.unwrap_or(GeometryError::Degenerate("no valid directrix found".into())))
}

/// Builds the encoding for the directrix offset `O_0 = X_0 − G_{0,0}`.
fn try_offset(
    mesh: &QuadGrid,
    offset: DVec3,
    factors: &[f64],
    apices: &[Option<DVec3>],
) -> Result<Encoding, GeometryError> {
    let (n, m) = (mesh.rows, mesh.cols);
    let mut x = Vec::with_capacity(m);
    x.push(mesh.at(0, 0) + offset);
    let mut apex = Vec::with_capacity(m - 1);
    let mut o = offset;
    for j in 1..m {
        let s = factors[j - 1];
        let prev = x[j - 1];
        let (a, xj) = if s > 0.0 {
            let a = if (s - 1.0).abs() <= 1e-13 { 1.0 } else { s };
            o *= a;
            (a, mesh.at(0, j) + o)
        } else {
            let c = apices[j - 1].ok_or_else(|| {
                GeometryError::Degenerate(format!("strip {} has no finite apex", j - 1))
            })?;
            let a = if (s.abs() - 1.0).abs() < 0.05 {
                0.5
            } else {
                s.abs()
            };
            let xj = c + (prev - c) * a;
            o = xj - mesh.at(0, j);
            (a, xj)
        };
        if !(xj.distance(prev) > 1e-12 * mesh.size()) || !xj.is_finite() {
            return Err(GeometryError::Degenerate(format!(
                "encoder: directrix edge {j} degenerates for this offset"
            )));
        }
        apex.push(a);
        x.push(xj);
    }
    let mut normals = vec![Vec::with_capacity(m - 1); n];
    for j in 1..m {
        let e = (x[j] - x[j - 1]).normalize();
        for (i, row) in normals.iter_mut().enumerate() {
            let r = mesh.at(i, j) - x[j];
            let rl = r.length();
            let p = if rl > 1e-12 * mesh.size() {
                let rh = r / rl;
                let p = e - rh * e.dot(rh);
                let pl = p.length();
                if !(pl > 1e-9) {
                    return Err(GeometryError::Degenerate(format!(
                        "encoder: vertex ({i}, {j}) lies on the directrix line"
                    )));
                }
                p / pl
            } else {
                e
            };
            row.push(p);
        }
    }
    Ok(Encoding {
        directrix: Polyline::open(x),
        generatrix: Polyline {
            points: (0..n).map(|i| mesh.at(i, 0)).collect(),
            closed: mesh.wrap_rows,
        },
        apex,
        normals,
    })
}
