//! The base C-tube construction with explicit plane normals (paper Sec. 3.2, notes §2), and the raw
//! sweep output every construction finishes from. The step itself, [`step`], lives in
//! `prepare.rs` with the validated inputs and is re-exported here.

use glam::DVec3;

use super::apex::apex_points;
use super::configuration::Configurations;
use super::directrix::SweptDirectrix;
use super::inputs::{CtubeInputs, NormalsInput};
pub use super::prepare::step;
use super::prepare::{Prepared, prepare};
use super::quality::quality;
use super::result::{ConeNet, PlaneNormals, Reports};
use super::sweep::{GivenSweep, Rule, Sweep, sweep_given};
use super::tolerance;
use crate::{GeometryError, QuadGrid};

/// Orients and normalizes one user normal for column j.
fn orient(p: DVec3, e: DVec3, row: Option<usize>, column: usize) -> Result<DVec3, GeometryError> {
    if !p.is_finite() {
        return Err(match row {
            Some(row) => GeometryError::NonFiniteEntry {
                what: "normals",
                row,
                column,
            },
            None => GeometryError::NonFinite {
                what: "normals",
                index: column - 1,
            },
        });
    }
    let len = p.length();
    if !(len > 1e-300) || !len.is_finite() {
        return Err(GeometryError::ZeroNormal { row, column });
    }
    let u = p / len;
    let along = u.dot(e);
    if !(along.abs() > tolerance::EDGE_PLANE) {
        return Err(GeometryError::PlaneContainsEdge { row, column });
    }
    Ok(if along < 0.0 { -u } else { u })
}

/// Resolves the normals input to unit normals with `P·ê_j > 0`: (data, per_vertex).
fn resolve_normals(
    input: &NormalsInput,
    dx: &SweptDirectrix,
    rows: usize,
) -> Result<(Vec<DVec3>, bool), GeometryError> {
    let cols = dx.columns() - 1;
    match input {
        NormalsInput::Monge => {
            dx.check_bisectors()?;
            Ok((dx.bisectors[1..].to_vec(), false))
        }
        NormalsInput::PerColumn(list) => {
            if list.len() != cols {
                return Err(GeometryError::WrongLength {
                    what: "normals",
                    expected: format!("{cols} (one per directrix edge, M − 1) or {rows} lists"),
                    got: list.len(),
                });
            }
            let data = list
                .iter()
                .enumerate()
                .map(|(k, &p)| orient(p, dx.edges[k + 1], None, k + 1))
                .collect::<Result<_, _>>()?;
            Ok((data, false))
        }
        NormalsInput::PerVertex(table) => {
            if table.len() != rows {
                return Err(GeometryError::WrongLength {
                    what: "normals",
                    expected: format!("{rows} lists (one per generatrix point, N)"),
                    got: table.len(),
                });
            }
            let mut data = Vec::with_capacity(rows * cols);
            for (i, row) in table.iter().enumerate() {
                if row.len() != cols {
                    return Err(GeometryError::WrongRowLength {
                        what: "normals",
                        row: i,
                        expected: cols,
                        got: row.len(),
                    });
                }
                for (k, &p) in row.iter().enumerate() {
                    data.push(orient(p, dx.edges[k + 1], Some(i), k + 1)?);
                }
            }
            Ok((data, true))
        }
    }
}

/// Runs the C-tube sweep and returns the mesh only (no configurations, apices, quality): the fast
/// kernel. The vertices are those of [`construct_ctube`], bit for bit.
pub fn ctube_mesh(inputs: &CtubeInputs) -> Result<QuadGrid, GeometryError> {
    Ok(run_ctube(inputs, false)?.mesh)
}

/// The base C-tube construction (`ctube.construct`): explicit normals (or Monge planes), no
/// correction. Configurations and quality are reported.
pub fn construct_ctube(inputs: &CtubeInputs) -> Result<ConeNet, GeometryError> {
    construct_ctube_with(inputs, Reports::ALL)
}

/// [`construct_ctube`] computing only the chosen reports (the others are left empty).
pub fn construct_ctube_with(
    inputs: &CtubeInputs,
    reports: Reports,
) -> Result<ConeNet, GeometryError> {
    run_ctube(inputs, true)?.finish_with(reports)
}

/// The C-tube sweep (with the configurations when `configurations`; else they are left empty).
fn run_ctube(inputs: &CtubeInputs, configurations: bool) -> Result<Raw, GeometryError> {
    let (prep, planes, per_vertex) = prepare_ctube(inputs)?;
    if let Some(given) = sweep_given(&prep, &planes, per_vertex, configurations) {
        return Ok(Raw::from_given(&prep, given, planes, per_vertex));
    }
    // A step is not well defined: the general sweep reports which one, in its usual order.
    general_sweep(&prep, planes, per_vertex)
}

/// The validated inputs and the plane normals (shared, or per vertex when the flag is set).
fn prepare_ctube(inputs: &CtubeInputs) -> Result<(Prepared, Vec<DVec3>, bool), GeometryError> {
    let prep = prepare(
        &inputs.directrix,
        &inputs.generatrix,
        &inputs.apex,
        inputs.end_planes,
    )?;
    let (planes, per_vertex) = resolve_normals(&inputs.normals, &prep.dx, prep.generatrix.len())?;
    Ok((prep, planes, per_vertex))
}

/// The general sweep (plane sources, per-row state) through the given planes.
fn general_sweep(
    prep: &Prepared,
    planes: Vec<DVec3>,
    per_vertex: bool,
) -> Result<Raw, GeometryError> {
    let mut sweep = Sweep::new(prep, planes, per_vertex, Rule::Given, None);
    sweep.run()?;
    Ok(Raw::from_sweep(sweep, prep.wrap_rows))
}

/// The raw output of a sweep, before apices and quality are computed.
pub(crate) struct Raw {
    pub mesh: QuadGrid,
    pub directrix: Vec<DVec3>,
    pub apex: Vec<f64>,
    pub normals: PlaneNormals,
    pub configurations: Configurations,
    pub corrections: Vec<super::correction::Correction>,
    /// 1 / design size (see [`super::prepare::Prepared::scale`]).
    pub inv_scale: f64,
    /// The first-column fix's scale factor of the generatrix about X_0 (1: as given).
    pub generatrix_scale: f64,
    /// The total plane turn of the plane fixes (radians summed over the vertices).
    pub turn: f64,
}

impl Raw {
    pub(crate) fn from_sweep(sweep: Sweep<'_>, wrap_rows: bool) -> Self {
        let (n, m) = (sweep.n, sweep.m);
        let normals = if sweep.per_vertex {
            PlaneNormals::per_vertex(n, m - 1, sweep.planes)
        } else {
            PlaneNormals::shared(n, sweep.planes)
        };
        Self {
            mesh: QuadGrid {
                classes: Vec::new(),
                rows: n,
                cols: m,
                wrap_rows,
                wrap_cols: false,
                vertices: sweep.verts,
            },
            directrix: sweep.dx.points.clone(),
            apex: sweep.apex,
            normals,
            configurations: Configurations::from_padded(n, m - 1, m - 1, sweep.configs),
            corrections: sweep.corrections,
            inv_scale: sweep.inv_scale,
            generatrix_scale: sweep.generatrix_scale,
            turn: sweep.turn,
        }
    }

    /// The output of the sweep of given planes ([`sweep_given`]): no corrections, the apex values
    /// and generatrix as prepared.
    fn from_given(
        prep: &Prepared,
        given: GivenSweep,
        planes: Vec<DVec3>,
        per_vertex: bool,
    ) -> Self {
        let (n, m) = (prep.generatrix.len(), prep.dx.columns());
        let normals = if per_vertex {
            PlaneNormals::per_vertex(n, m - 1, planes)
        } else {
            PlaneNormals::shared(n, planes)
        };
        let configurations = if given.configs.is_empty() {
            Configurations::default()
        } else {
            Configurations::from_padded(n, m - 1, m - 1, given.configs)
        };
        Self {
            mesh: QuadGrid {
                classes: Vec::new(),
                rows: n,
                cols: m,
                wrap_rows: prep.wrap_rows,
                wrap_cols: false,
                vertices: given.verts,
            },
            directrix: prep.dx.points.clone(),
            apex: prep.apex.clone(),
            normals,
            configurations,
            corrections: Vec::new(),
            inv_scale: 1.0 / prep.scale,
            generatrix_scale: 1.0,
            turn: 0.0,
        }
    }

    /// Computes the chosen reports (apices, quality) and checks every output is finite.
    pub(crate) fn finish_with(self, reports: Reports) -> Result<ConeNet, GeometryError> {
        if let Some(k) = self.apex.iter().position(|a| !a.is_finite()) {
            return Err(GeometryError::NonFiniteOutput {
                what: "apex value",
                row: 0,
                column: k + 1,
            });
        }
        let apices = if reports.apices {
            apex_points(&self.directrix, &self.apex)
        } else {
            Vec::new()
        };
        let quality = if reports.quality {
            quality(
                &self.mesh,
                &self.directrix,
                &self.apex,
                &self.configurations,
                self.inv_scale,
            )?
        } else {
            Default::default()
        };
        Ok(ConeNet {
            mesh: self.mesh,
            directrix: self.directrix,
            apex: self.apex,
            apices,
            normals: self.normals,
            configurations: self.configurations,
            corrections: self.corrections,
            quality,
        })
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::Polyline;
    use crate::conenet::inputs::{ApexInput, ColumnValues, EndPlanes};

    /// The general sweep alone: what [`sweep_given`] must reproduce bit for bit.
    fn general(inputs: &CtubeInputs) -> Result<Raw, GeometryError> {
        let (prep, planes, per_vertex) = prepare_ctube(inputs)?;
        general_sweep(&prep, planes, per_vertex)
    }

    /// A wavy directrix, a generatrix ellipse around its start, apex values near 1 (some far from
    /// it, so that some designs fold or fail) and Monge, shared or per-vertex planes.
    fn design() -> impl Strategy<Value = CtubeInputs> {
        (
            1usize..21,
            2usize..21,
            (0.1f64..2.0, 0.1f64..2.0, 0.0f64..1.5),
            (0.2f64..3.0, 0.2f64..3.0, any::<bool>(), any::<bool>()),
            prop::collection::vec(0.3f64..1.7, 20),
            (0u8..3, prop::collection::vec(-0.6f64..0.6, 3 * 20 * 20)),
        )
            .prop_map(
                |(n, m, (ky, kz, amp), (ra, rb, closed_g, closed_d), apex, (normals, tilt))| {
                    let points = (0..m)
                        .map(|j| {
                            let t = j as f64;
                            DVec3::new(t, amp * (ky * t).sin(), amp * (kz * t).cos())
                        })
                        .collect();
                    let directrix = if closed_d && m >= 3 {
                        Polyline::closed(points)
                    } else {
                        Polyline::open(points)
                    };
                    let ring = (0..n).map(|i| {
                        let u = std::f64::consts::TAU * i as f64 / n.max(2) as f64;
                        DVec3::new(0.1 * u.sin(), ra * u.cos() + 0.3, rb * u.sin() + amp)
                    });
                    let generatrix = if closed_g && n >= 3 {
                        Polyline::closed(ring.collect())
                    } else {
                        Polyline::open(ring.collect())
                    };
                    let columns = directrix.len() + usize::from(directrix.closed) - 1;
                    let normal = |k: usize| {
                        DVec3::new(1.0, tilt[3 * k + 1], tilt[3 * k + 2])
                            + DVec3::X * tilt[3 * k].abs()
                    };
                    let normals = match normals {
                        0 => NormalsInput::Monge,
                        1 => NormalsInput::PerColumn((0..columns).map(normal).collect()),
                        _ => NormalsInput::PerVertex(
                            (0..generatrix.len())
                                .map(|i| (0..columns).map(|j| normal(i * columns + j)).collect())
                                .collect(),
                        ),
                    };
                    CtubeInputs {
                        directrix,
                        generatrix,
                        apex: ApexInput {
                            values: ColumnValues::List(apex[..columns].to_vec()),
                            ..ApexInput::default()
                        },
                        normals,
                        end_planes: EndPlanes::default(),
                    }
                },
            )
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// The sweep of given planes gives the general sweep's vertices and configurations bit
        /// for bit, and its error when a step is not well defined; the mesh alone is the same.
        #[test]
        fn the_given_sweep_is_the_general_sweep(inputs in design()) {
            let reference = general(&inputs);
            let fast = run_ctube(&inputs, true);
            match (&reference, &fast) {
                (Ok(r), Ok(f)) => {
                    prop_assert_eq!(&r.mesh, &f.mesh);
                    prop_assert_eq!(&r.configurations, &f.configurations);
                    prop_assert_eq!(&r.normals, &f.normals);
                    prop_assert_eq!(&r.apex, &f.apex);
                    prop_assert_eq!(&r.directrix, &f.directrix);
                    prop_assert_eq!(r.inv_scale, f.inv_scale);
                    prop_assert_eq!(&ctube_mesh(&inputs).expect("the mesh alone"), &f.mesh);
                }
                (Err(r), Err(f)) => {
                    prop_assert_eq!(r.to_string(), f.to_string());
                    prop_assert!(ctube_mesh(&inputs).is_err());
                }
                _ => prop_assert!(false, "general {:?} / given {:?}", reference.is_ok(), fast.is_ok()),
            }
        }
    }
}
