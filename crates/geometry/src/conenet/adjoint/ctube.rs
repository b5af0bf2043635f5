//! The adjoint of the C-tube construction (`ctube.construct`, [`super::super::construct_ctube`]):
//! the backward sweep of [`super`] with the planes given beforehand. A step's plane is then the
//! step's `b` itself ([`super::PlaneRule::Given`]), so its cotangent is what the sweep collects
//! for `b`: on the bisectors (the directrix) for the Monge planes, else per vertex, pulled back
//! through the normalization and orientation of the user's normals (`P = ±p / |p|`, `P·ê_j > 0`)
//! and summed over the rows when the normals are shared.

use glam::DVec3;

use super::super::correction_adjoint::Piece;
use super::super::inputs::{CtubeInputs, GridValues, NormalsInput};
use super::super::prepare::prepare;
use super::{
    Backward, ConstructAdjoint, GivenPlanes, OutputBars, Wrt, check_sizes, finite, sweep_and_pull,
};
use crate::{GeometryError, QuadGrid};

/// The unit normal the construction uses for the user's normal `p` at an edge `e`
/// (`ctube::orient`): `p / |p|`, flipped so that it points along `e`; and the sign taken.
fn oriented(p: DVec3, e: DVec3) -> (DVec3, f64) {
    let sign = if p.dot(e) < 0.0 { -1.0 } else { 1.0 };
    (p.normalize() * sign, sign)
}

/// The pull-back of `P = s p / |p|` for the cotangent `bar` of P: `s (I − P Pᵀ) bar / |p|`.
fn normal_pullback(p: DVec3, e: DVec3, bar: DVec3) -> DVec3 {
    let (unit, sign) = oriented(p, e);
    (bar - unit * unit.dot(bar)) * (sign / p.length())
}

/// The backward sweep of the C-tube construction for the mesh it built (`mesh`) and the
/// cotangents of its outputs (`bars`: mesh, apex values, apices, plane normals, margins): the
/// generatrix's cotangent, and those `wrt` asks for among the apex input's and the scale's
/// (`apex`), the directrix's and the given normals' (`normals`: in the shape of the input, M−1
/// shared or N·(M−1) row-major; `None` for the Monge planes, which follow the directrix). The
/// ratios' and ε's are empty and `None` (the construction has neither).
pub fn ctube_adjoint_for(
    inputs: &CtubeInputs,
    mesh: &QuadGrid,
    bars: OutputBars<'_>,
    wrt: Wrt,
) -> Result<ConstructAdjoint, GeometryError> {
    let prep = prepare(
        &inputs.directrix,
        &inputs.generatrix,
        &inputs.apex,
        inputs.end_planes,
    )?;
    let (n, m) = (prep.generatrix.len(), prep.dx.columns());
    check_sizes(n, m, mesh, &bars)?;
    let edges = &prep.dx.edges;
    let wrong = || {
        GeometryError::Degenerate(format!(
            "the adjoint needs the normals the construction used ({} per row)",
            m - 1
        ))
    };
    let (planes, per_vertex, monge) = match &inputs.normals {
        NormalsInput::Monge => (prep.dx.bisectors[1..].to_vec(), false, true),
        NormalsInput::PerColumn(list) => {
            if list.len() != m - 1 {
                return Err(wrong());
            }
            let planes = (list.iter().enumerate())
                .map(|(k, &p)| oriented(p, edges[k + 1]).0)
                .collect();
            (planes, false, false)
        }
        NormalsInput::PerVertex(table) => {
            if table.len() != n || table.iter().any(|row| row.len() != m - 1) {
                return Err(wrong());
            }
            let planes = (table.iter())
                .flat_map(|row| (row.iter().enumerate()).map(|(k, &p)| oriented(p, edges[k + 1]).0))
                .collect();
            (planes, true, false)
        }
    };
    // No ratios: the step reads none (a placeholder grid).
    let ratios = GridValues::Uniform(0.5);
    let grid = ratios.resolve("ratios", n, m - 1, (0.0, 1.0, "a value in [0, 1]"))?;
    let piece = Piece {
        apex: prep.apex.clone(),
        ..Piece::default()
    };
    let sweep = Backward {
        prep: &prep,
        grid: &grid,
        mesh,
        mesh_bar: bars.mesh,
        plane_bar: &[],
        piece: &piece,
        epsilon: 0.0,
        given: Some(GivenPlanes {
            planes: &planes,
            per_vertex,
            monge,
            pencil: None,
        }),
    };
    let wrt = Wrt {
        epsilon: false,
        ..wrt
    };
    let mut result = sweep_and_pull(
        sweep,
        &bars,
        wrt,
        &inputs.apex,
        inputs.end_planes,
        inputs.directrix.points.len(),
    )?;
    result.ratios = Vec::new();
    result.epsilon = None;
    result.normals = match (&inputs.normals, result.normals.take()) {
        (NormalsInput::PerColumn(list), Some(per_vertex)) => Some(
            (list.iter().enumerate())
                .map(|(k, &p)| {
                    let bar = (0..n).map(|i| per_vertex[i * (m - 1) + k]).sum();
                    normal_pullback(p, edges[k + 1], bar)
                })
                .collect(),
        ),
        (NormalsInput::PerVertex(table), Some(per_vertex)) => Some(
            (table.iter().flatten().enumerate())
                .map(|(k, &p)| normal_pullback(p, edges[k % (m - 1) + 1], per_vertex[k]))
                .collect(),
        ),
        _ => None,
    };
    finite(result)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Polyline;
    use crate::conenet::construct_ctube;
    use crate::conenet::inputs::{ApexInput, ColumnValues, EndPlanes};
    use proptest::prelude::*;

    /// L = Σ w_k · G_k with fixed weights.
    fn loss(c: &CtubeInputs, w: &[DVec3]) -> f64 {
        let net = construct_ctube(c).unwrap();
        net.mesh
            .vertices
            .iter()
            .zip(w)
            .map(|(g, w)| g.dot(*w))
            .sum()
    }

    /// The largest difference between `exact` and central differences (Richardson) of `loss`
    /// over the scalars `set(c, k, ·)` moves, relative to the largest difference quotient.
    fn compare(
        c: &CtubeInputs,
        w: &[DVec3],
        exact: &[f64],
        set: impl Fn(&mut CtubeInputs, usize, f64),
    ) -> f64 {
        let central = |k: usize, h: f64| {
            let (mut p, mut q) = (c.clone(), c.clone());
            set(&mut p, k, h);
            set(&mut q, k, -h);
            (loss(&p, w) - loss(&q, w)) / (2.0 * h)
        };
        let (mut worst, mut size) = (0.0f64, 0.0f64);
        for (k, &x) in exact.iter().enumerate() {
            let fd = (4.0 * central(k, 5e-7) - central(k, 1e-6)) / 3.0;
            worst = worst.max((fd - x).abs());
            size = size.max(fd.abs());
        }
        assert!(size > 0.0, "the gradient is zero");
        worst / size
    }

    /// A wavy open or closed directrix of 6 points, 4 generatrix points, apex values near 1 and
    /// normals `kind` (0: Monge, 1: shared, 2: per vertex) near the Monge planes, some reversed.
    fn design(closed: bool, kind: u8, tilt: &[f64], apex: &[f64], end: EndPlanes) -> CtubeInputs {
        let step = if closed {
            std::f64::consts::PI / 3.0
        } else {
            0.4
        };
        let points: Vec<DVec3> = (0..6)
            .map(|k| {
                let t = k as f64 * step;
                DVec3::new(3.0 * t.cos(), 3.0 * t.sin(), 0.4 * (2.0 * t).sin())
            })
            .collect();
        let directrix = if closed {
            Polyline::closed(points)
        } else {
            Polyline::open(points)
        };
        let generatrix = Polyline::open(
            (0..4)
                .map(|k| DVec3::new(3.4 + 0.4 * k as f64, 0.1, 0.3 * k as f64 - 0.4))
                .collect(),
        );
        let cols = if closed { 6 } else { 5 };
        let normal = |i: usize, k: usize| {
            let t = (k as f64 + 0.5) * step;
            let at = 3 * (i * cols + k);
            let p = DVec3::new(-t.sin(), t.cos(), 0.0)
                + DVec3::new(tilt[at], tilt[at + 1], tilt[at + 2]);
            if (i + k) % 3 == 1 { -2.0 * p } else { p }
        };
        let normals = match kind {
            0 => NormalsInput::Monge,
            1 => NormalsInput::PerColumn((0..cols).map(|k| normal(0, k)).collect()),
            _ => NormalsInput::PerVertex(
                (0..4)
                    .map(|i| (0..cols).map(|k| normal(i, k)).collect())
                    .collect(),
            ),
        };
        CtubeInputs {
            directrix,
            generatrix,
            apex: ApexInput {
                values: ColumnValues::List(apex[..cols].to_vec()),
                ..ApexInput::default()
            },
            normals,
            end_planes: end,
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]
        #[test]
        fn ctube_gradients_match_differences(
            closed in any::<bool>(),
            kind in 0u8..3,
            mirror in any::<bool>(),
            tilt in proptest::collection::vec(-0.3f64..0.3, 72),
            apex in proptest::collection::vec(0.85f64..1.15, 6),
        ) {
            let end = if mirror { EndPlanes::Mirror } else { EndPlanes::Perpendicular };
            let c = design(closed, kind, &tilt, &apex, end);
            prop_assume!(construct_ctube(&c).is_ok());
            let net = construct_ctube(&c).unwrap();
            let w: Vec<DVec3> = (0..net.mesh.vertices.len())
                .map(|k| DVec3::new((k as f64 * 0.7).sin(), (k as f64 * 1.3).cos(), 0.5))
                .collect();
            let bars = OutputBars { mesh: &w, apex: &[], apices: &[], planes: &[], margins: &[] };
            let adj = ctube_adjoint_for(&c, &net.mesh, bars, Wrt::ALL).unwrap();
            let flat = |p: &[DVec3]| p.iter().flat_map(|p| p.to_array()).collect::<Vec<f64>>();
            let directrix = compare(&c, &w, &flat(&adj.directrix.unwrap()), |c, k, h| {
                c.directrix.points[k / 3][k % 3] += h;
            });
            let generatrix = compare(&c, &w, &flat(&adj.generatrix), |c, k, h| {
                c.generatrix.points[k / 3][k % 3] += h;
            });
            let apex = compare(&c, &w, &adj.apex.unwrap(), |c, k, h| {
                if let ColumnValues::List(v) = &mut c.apex.values {
                    v[k] += h;
                }
            });
            let normals = match adj.normals {
                None => {
                    prop_assert_eq!(kind, 0);
                    0.0
                }
                Some(bars) => compare(&c, &w, &flat(&bars), |c, k, h| match &mut c.normals {
                    NormalsInput::PerColumn(list) => list[k / 3][k % 3] += h,
                    NormalsInput::PerVertex(rows) => {
                        let cols = rows[0].len();
                        rows[k / 3 / cols][k / 3 % cols][k % 3] += h;
                    }
                    NormalsInput::Monge => {}
                }),
            };
            let rel = [directrix, generatrix, apex, normals];
            prop_assert!(rel.iter().all(|r| *r < 1e-6), "directrix, generatrix, apex, normals: {:?}", rel);
        }
    }
}
