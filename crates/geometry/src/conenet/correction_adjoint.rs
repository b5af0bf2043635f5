//! The assisted correction in the construction's adjoint ([`super::adjoint`]): which piece a run
//! took (replayed from its correction records) and the derivatives of the corrected values on it.
//!
//! * **Plane fixes** (α = 0, per row): the plane of the fixed step is `θ = (1 − ε) φ`; the step
//!   then reads ε instead of the ratio and the bisector ([`super::adjoint::PlaneRule::Fixed`]).
//! * **Apex fixes** (apex only, α = 1) at column j0 ≥ 1: `a_{j0} = (1 − ε) v_{i*}`, with v the root
//!   of Appendix A or the pole of the row i* attaining the minimum (`sweep::correct`). v reads
//!   G_{i*,j0−1}, X_{j0−1}, X_{j0}, X_{j0+1} and the ratio planes P_{i*,j0}, P_{i*,j0+1}; the latter
//!   does not change as the fix slides G_{i*,j0} along its ruling, so it is taken at the final
//!   vertex with a_{j0} held. Repeated rounds at one column give the same form (v does not read
//!   the old value), so the last record is the piece. The user's a_{j0} no longer matters.
//! * **Generatrix fix** (apex only, first column): the generatrix is scaled about X_0 by
//!   `T = (1 − ε) t_{i*}`, `t_i = ((X_1 − X_0)·P_{i,1}) / ((G_{i,0} − X_0)·P_{i,1})` on the input
//!   generatrix (rounds multiply to the same form).
//!
//! * **Blend** (0 < α < 1, `blend.rs`): the mesh is the planes-only sweep Q_λ on the inputs
//!   moved the fraction λ towards apex only Q, `a_j(λ) = a_j + λ (a_j^Q − a_j)` and the
//!   generatrix scaled about X_0 by `t(λ) = 1 + λ (t_Q − 1)`. λ is α or one of the steps towards
//!   1 the bounds choose (piecewise constant: the construction reports it, [`Taken`]); the plane
//!   fixes of Q_λ are its `Ratio` records. Q_λ is differentiated as planes only at a_j(λ); the user's a_j keeps
//!   (1 − λ) of ā_j and the generatrix t(λ) of its column-0 cotangent, and λ ā_j, λ t̄ go to
//!   a_j^Q and t_Q as cotangents of apex only's outputs, through its own backward sweep (apex
//!   fixes, generatrix fix: smooth on its piece). A blend that fell back to Q itself is apex only.
//!
//! **Mixed runs** are declined: a plane fix followed, at the same column, by an apex fix (or at
//! the first column by the generatrix fix), in planes only or in a blend's Q_λ. θ = (1 − ε) φ
//! satisfies Eq. 2 with margin in exact arithmetic, so the fallback happens only when rounding
//! loses that margin (`sweep::mod`, a stop after an insufficient plane fix): which rows fall back
//! is decided by rounding, no open piece contains the run (a difference step leaves it), and the
//! fixed value would read the turned plane at the vertex before the fix (another form).

use super::adjoint::{PlaneRule, StepInputs, step_plane, step_vertex};
use super::blend::Taken;
use super::construct::construct_traced;
use super::correction::CorrectionKind;
use super::dual::{D3, Dual};
use super::inputs::{ConstructInputs, Grid};
use super::prepare::Prepared;
use super::result::Reports;
use crate::{GeometryError, QuadGrid};

/// An apex fix on the run's piece: column j0 (≥ 1) set from row i*'s root or pole.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct ApexFix {
    pub column: usize,
    pub row: usize,
    pub pole: bool,
}

/// The generatrix fix on the run's piece: the total scale T from row i*.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct GeneratrixFix {
    pub row: usize,
    pub scale: f64,
    /// A cotangent of T from outside the sweep (a blend's, through `t(λ)`), else 0.
    pub bar: f64,
}

/// A blend's piece: planes only on the inputs moved the fraction λ towards apex only, a_j(λ) =
/// a_j + λ (a_j^Q − a_j) and the generatrix scaled about X_0 by t(λ) = 1 + λ (t_Q − 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Blend {
    pub lambda: f64,
    /// t(λ) (1 when apex only did not scale the generatrix).
    pub scale: f64,
}

/// The piece a run took.
#[derive(Debug, Clone, PartialEq, Default)]
pub(super) struct Piece {
    /// Plane-fixed steps (N·(M−1), row-major), or empty.
    pub fixed: Vec<bool>,
    /// The apex values the sweep used (after the corrections), a_j at index j − 1.
    pub apex: Vec<f64>,
    /// Apex fixes, by decreasing column.
    pub apex_fixes: Vec<ApexFix>,
    /// The generatrix fix.
    pub generatrix_fix: Option<GeneratrixFix>,
    /// A blend: `apex` holds a_j(λ), `fixed` the plane fixes of the sweep on top.
    pub blend: Option<Blend>,
}

/// The piece of the run of `inputs` (prepared as `prep`, ratios `grid`) that built `mesh`, or the
/// error that declines a run whose corrections the adjoint does not follow. Without assistance:
/// nothing fixed; with it the construction is run again for its records.
pub(super) fn piece(
    inputs: &ConstructInputs,
    prep: &Prepared,
    grid: &Grid<'_>,
    mesh: &QuadGrid,
) -> Result<Piece, GeometryError> {
    let (n, m) = (prep.generatrix.len(), prep.dx.columns());
    let mut piece = Piece {
        apex: prep.apex.clone(),
        ..Piece::default()
    };
    if !inputs.assistance.enabled() {
        return Ok(piece);
    }
    let (net, taken) = construct_traced(
        inputs,
        Reports {
            apices: false,
            quality: false,
        },
    )?;
    let planes = net.corrections.iter().any(|c| {
        matches!(
            c.kind,
            CorrectionKind::Ratio | CorrectionKind::PlaneRotation
        )
    });
    let others = net
        .corrections
        .iter()
        .any(|c| matches!(c.kind, CorrectionKind::Apex | CorrectionKind::Generatrix));
    let mixed = match taken {
        Taken::Single => others && planes,
        Taken::Blend { mixed, .. } => mixed,
    };
    if mixed {
        return Err(GeometryError::Degenerate(
            "the assisted correction changed planes and then, where rounding left a turned plane \
             still failing, the apex function or the generatrix at the same column (a mixed run: \
             the rows that fall back are chosen by rounding, no smooth piece): its derivative is \
             not implemented"
                .into(),
        ));
    }
    if let Taken::Blend { lambda, .. } = taken {
        // The planes only sweep on top of the moved inputs: its plane fixes; the rebased records
        // state the moved apex values and the generatrix scale t(λ) (no fixes of their own).
        let mut fixed = vec![false; n * (m - 1)];
        let mut scale = 1.0;
        for c in &net.corrections {
            match (c.kind, c.row) {
                (CorrectionKind::Ratio, Some(i)) if i < n && (1..m).contains(&c.column) => {
                    fixed[i * (m - 1) + c.column - 1] = true;
                }
                (CorrectionKind::Generatrix, None) => scale = c.new,
                (CorrectionKind::Apex, None) => {}
                _ => {
                    return Err(GeometryError::Degenerate(format!(
                        "the assisted correction changed a value whose derivative is not \
                         implemented ({c})"
                    )));
                }
            }
        }
        return Ok(Piece {
            fixed: if planes { fixed } else { Vec::new() },
            apex: net.apex,
            blend: Some(Blend { lambda, scale }),
            ..Piece::default()
        });
    }
    piece.apex = net.apex.clone();
    let eps = inputs.assistance.epsilon;
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0);
    let mut fixed = vec![false; n * (m - 1)];
    // The last record of each column is its final value (records are sorted by column).
    let mut last_apex: Vec<Option<(f64, f64)>> = vec![None; m];
    for c in &net.corrections {
        match (c.kind, c.row) {
            (CorrectionKind::Ratio, Some(i)) if i < n && (1..m).contains(&c.column) => {
                fixed[i * (m - 1) + c.column - 1] = true;
            }
            (CorrectionKind::Apex, None) if (1..m - 1).contains(&c.column) => {
                last_apex[c.column] = Some((c.old, c.new));
            }
            (CorrectionKind::Generatrix, None) => {
                // t_i on the input generatrix; the row whose (1 − ε) t_i is the total scale.
                let row = (0..n).find(|&i| {
                    let t = generatrix_scale::<0>(prep, grid, i, eps).v;
                    close(t, c.new)
                });
                let Some(row) = row else {
                    return Err(GeometryError::Degenerate(format!(
                        "the assisted correction changed the generatrix, and its fix could not \
                         be replayed ({c})"
                    )));
                };
                piece.generatrix_fix = Some(GeneratrixFix {
                    row,
                    scale: c.new,
                    bar: 0.0,
                });
            }
            _ => {
                return Err(GeometryError::Degenerate(format!(
                    "the assisted correction changed a value whose derivative is not \
                     implemented ({c})"
                )));
            }
        }
    }
    for j0 in (1..m).rev() {
        let Some((old, new)) = last_apex[j0] else {
            continue;
        };
        let inside = |v: f64| v > 0.0 && v < old;
        let found = (0..n).find_map(|i| {
            let [root, pole] = [false, true].map(|p| {
                apex_fix::<0>(prep, grid, mesh, &piece.apex, j0, i, eps, p).v / (1.0 - eps)
            });
            let (v, is_pole) = match (inside(root), inside(pole)) {
                (true, true) if pole < root => (pole, true),
                (false, true) => (pole, true),
                _ => (root, false),
            };
            close((1.0 - eps) * v, new).then_some((i, is_pole))
        });
        let Some((row, pole)) = found else {
            return Err(GeometryError::Degenerate(format!(
                "the assisted correction changed a_{j0}, and its fix could not be replayed"
            )));
        };
        piece.apex_fixes.push(ApexFix {
            column: j0,
            row,
            pole,
        });
    }
    if planes {
        piece.fixed = fixed;
    }
    Ok(piece)
}

// The directions of an apex fix: G_{i*,j0−1} (3), r_{i*,j0}, r_{i*,j0+1}, ε, X_{j0−1}, X_{j0},
// X_{j0+1}, ê_{j0}, b_{j0}, ê_{j0+1}, b_{j0+1} (3 each).
pub(super) const FIX_G: usize = 0;
pub(super) const FIX_R0: usize = 3;
pub(super) const FIX_R1: usize = 4;
pub(super) const FIX_EPS: usize = 5;
pub(super) const FIX_XM: usize = 6;
pub(super) const FIX_X: usize = 9;
pub(super) const FIX_XP: usize = 12;
pub(super) const FIX_E0: usize = 15;
pub(super) const FIX_B0: usize = 18;
pub(super) const FIX_E1: usize = 21;
pub(super) const FIX_B1: usize = 24;
/// The number of directions of an apex fix.
pub(super) const N_FIX: usize = 27;

/// a_{j0} = (1 − ε) v from row i (the root, or with `pole` the pole) on dual numbers, the planes
/// from the ratios; `apex` holds the values the sweep used (a_{j0} held in P_{i,j0+1}'s vertex).
#[allow(clippy::too_many_arguments)]
pub(super) fn apex_fix<const N: usize>(
    prep: &Prepared,
    grid: &Grid<'_>,
    mesh: &QuadGrid,
    apex: &[f64],
    j0: usize,
    i: usize,
    epsilon: f64,
    pole: bool,
) -> Dual<N> {
    let (dx, m) = (&prep.dx, prep.dx.columns());
    let inv_scale = 1.0 / prep.scale;
    let ratios = grid.row(i);
    let eps = Dual::seed(epsilon, FIX_EPS);
    let (xm, x, xp) = (
        D3::seed(dx.points[j0 - 1], FIX_XM),
        D3::seed(dx.points[j0], FIX_X),
        D3::seed(dx.points[j0 + 1], FIX_XP),
    );
    let g = D3::seed(mesh.vertices[i * m + j0 - 1], FIX_G);
    let s0 = StepInputs {
        g,
        r: Dual::seed(ratios[j0 - 1], FIX_R0),
        a: Dual::constant(apex[j0 - 1]),
        epsilon: eps,
        x0: xm,
        x1: x,
        e: D3::seed(dx.edges[j0], FIX_E0),
        b: D3::seed(dx.bisectors[j0], FIX_B0),
    };
    let p0 = step_plane(&s0, PlaneRule::Ratio, inv_scale);
    let v = if pole {
        -(x.sub(g).dot(p0)) / g.sub(xm).dot(p0)
    } else {
        let g1 = step_vertex(g, s0.a, xm, x, p0);
        let s1 = StepInputs {
            g: g1,
            r: Dual::seed(ratios[j0], FIX_R1),
            a: Dual::constant(apex[j0]),
            epsilon: eps,
            x0: x,
            x1: xp,
            e: D3::seed(dx.edges[j0 + 1], FIX_E1),
            b: D3::seed(dx.bisectors[j0 + 1], FIX_B1),
        };
        let p1 = step_plane(&s1, PlaneRule::Ratio, inv_scale);
        // `correction::apex_fix_value`.
        let k1 = g.sub(xp).dot(p1);
        let k2 = -(g.sub(x).dot(p0));
        let w = p0.scale(k1).add(p1.scale(k2));
        g.sub(x).dot(w) / g.sub(xm).dot(w)
    };
    (Dual::constant(1.0) - eps) * v
}

/// T = (1 − ε) t_i of the generatrix fix on dual numbers, in the directions of a step
/// (`adjoint`'s layout: G_{i,0}, r_{i,1}, ε, X_0, X_1, ê_1, b_1).
pub(super) fn generatrix_scale<const N: usize>(
    prep: &Prepared,
    grid: &Grid<'_>,
    i: usize,
    epsilon: f64,
) -> Dual<N> {
    use super::adjoint::layout::{B, E, EPS, G, R, X0, X1};
    let dx = &prep.dx;
    let s = StepInputs {
        g: D3::seed(prep.generatrix[i], G),
        r: Dual::seed(grid.row(i)[0], R),
        a: Dual::constant(prep.apex[0]),
        epsilon: Dual::seed(epsilon, EPS),
        x0: D3::seed(dx.points[0], X0),
        x1: D3::seed(dx.points[1], X1),
        e: D3::seed(dx.edges[1], E),
        b: D3::seed(dx.bisectors[1], B),
    };
    let p = step_plane(&s, PlaneRule::Ratio, 1.0 / prep.scale);
    let t = s.x1.sub(s.x0).dot(p) / s.g.sub(s.x0).dot(p);
    (Dual::constant(1.0) - s.epsilon) * t
}
