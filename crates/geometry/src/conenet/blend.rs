//! The assisted correction between its two pure forms (paper Sec. 4.2.2, footnote 2, Appendix A): the
//! blend of "planes only" (α = 0) and "apex only" (α = 1), defined so that it is monotone.
//!
//! * **Planes only**, P: every violation of Eq. 2 is repaired by turning the next construction plane
//!   (ratio mode: per row, θ → (1 − ε)φ; coplanar: the shared plane, nearest feasible ψ). Its total
//!   plane turn is `T0` (Σ over the vertices of the angle between corrected and uncorrected P_{i,j}).
//! * **Apex only**, Q: every violation is repaired by the apex-like fix: a_{j0} → (1 − ε) a' at a
//!   column j0 ≥ 1, the generatrix scaled about X_0 at the first column. Its total apex change is
//!   `A1 = Σ_j |Δa_j|` (and its generatrix scale t_Q).
//! * **Blend**, 0 < α < 1: the apex function moves the fraction λ of the way to Q's,
//!   `a_j(λ) = a_j + λ (a_j^Q − a_j)`, the generatrix is scaled by `1 + λ (t_Q − 1)`, and what is
//!   still bad is repaired by planes only (rule P) on top. λ = α unless that result would exceed a
//!   bound — total apex change `A1`, generatrix change `|1 − t_Q|`, plane turn `T0` — in which case λ
//!   steps towards 1 by (1 − α)/8 until the bounds hold (λ = 1 is Q itself, which always does).
//!
//! So the apex change grows linearly with α (λ·A1) and can never exceed the apex-only change, and the
//! plane turn can never exceed the planes-only turn. The pure forms are cheap to know: when Q needs no
//! fix, no form does, and the construction is the single sweep Q.

use super::correction::{Correction, CorrectionKind};
use super::ctube::Raw;
use super::inputs::Assistance;
use super::prepare::Prepared;
use crate::GeometryError;

/// The number of steps of λ from α to 1 when α itself would exceed a bound.
const STEPS: usize = 8;

/// Runs the assisted construction for `assistance` (off, or α ∈ [0, 1]); `sweep` runs one sweep of the
/// construction rule on the given inputs with a pure assistance (α = 0 or 1) or none.
pub(crate) fn assisted<F>(
    prep: &Prepared,
    assistance: Assistance,
    sweep: F,
) -> Result<Raw, GeometryError>
where
    F: Fn(&Prepared, Option<Assistance>) -> Result<Raw, GeometryError>,
{
    if !assistance.enabled() {
        return sweep(prep, None);
    }
    let pure = |alpha: f64| Assistance {
        alpha,
        epsilon: assistance.epsilon,
    };
    let alpha = assistance.alpha;
    let apex_only = match sweep(prep, Some(pure(1.0))) {
        Ok(q) => q,
        // Planes only does not need the apex-only plan.
        Err(_) if alpha == 0.0 => return sweep(prep, Some(pure(0.0))),
        Err(e) => return Err(e),
    };
    if alpha >= 1.0 || apex_only.corrections.is_empty() {
        return Ok(apex_only);
    }
    let planes_only = sweep(prep, Some(pure(0.0)))?;
    let bound = Bounds {
        apex: apex_change(prep, &apex_only),
        scale: (1.0 - apex_only.generatrix_scale).abs(),
        turn: planes_only.turn,
    };
    let mut planes_only = Some(planes_only);
    for k in 0..STEPS {
        let lambda = alpha + (1.0 - alpha) * k as f64 / STEPS as f64;
        let candidate = if lambda == 0.0 {
            planes_only.take()
        } else {
            sweep(&towards(prep, &apex_only, lambda), Some(pure(0.0)))
                .ok()
                .map(|r| rebase(prep, r, lambda, apex_only.generatrix_scale))
        };
        if let Some(r) = candidate
            && bound.holds(prep, &r)
        {
            return Ok(r);
        }
    }
    Ok(apex_only)
}

/// The bounds of the blend: Q's apex and generatrix changes, P's plane turn.
struct Bounds {
    apex: f64,
    scale: f64,
    turn: f64,
}

impl Bounds {
    fn holds(&self, prep: &Prepared, r: &Raw) -> bool {
        apex_change(prep, r) <= self.apex
            && (1.0 - r.generatrix_scale).abs() <= self.scale
            && r.turn <= self.turn
    }
}

/// Σ_j |a_j − a_j^input|.
fn apex_change(prep: &Prepared, r: &Raw) -> f64 {
    r.apex
        .iter()
        .zip(&prep.apex)
        .map(|(a, b)| (a - b).abs())
        .sum()
}

/// The inputs moved the fraction λ of the way to the apex-only result: apex values and generatrix
/// scale about X_0.
fn towards(prep: &Prepared, apex_only: &Raw, lambda: f64) -> Prepared {
    let mut p = prep.clone();
    for (a, q) in p.apex.iter_mut().zip(&apex_only.apex) {
        *a += lambda * (q - *a);
    }
    let t = 1.0 + lambda * (apex_only.generatrix_scale - 1.0);
    if t != 1.0 {
        let x0 = p.dx.points[0];
        for g in &mut p.generatrix {
            *g = x0 + (*g - x0) * t;
        }
    }
    p
}

/// A sweep on [`towards`]`(prep, λ)` restated against the user's inputs: one `Generatrix` record for
/// the total scale, one `Apex` record per changed a_j (input → final), the plane fixes as they are.
fn rebase(prep: &Prepared, mut r: Raw, lambda: f64, scale_q: f64) -> Raw {
    let scale = (1.0 + lambda * (scale_q - 1.0)) * r.generatrix_scale;
    let mut records: Vec<Correction> = Vec::with_capacity(r.corrections.len() + 1);
    if scale != 1.0 {
        records.push(Correction {
            kind: CorrectionKind::Generatrix,
            column: 0,
            row: None,
            old: 1.0,
            new: scale,
        });
    }
    for (k, (&new, &old)) in r.apex.iter().zip(&prep.apex).enumerate() {
        if new != old {
            records.push(Correction {
                kind: CorrectionKind::Apex,
                column: k + 1,
                row: None,
                old,
                new,
            });
        }
    }
    records.extend(r.corrections.iter().copied().filter(|c| {
        matches!(
            c.kind,
            CorrectionKind::Ratio | CorrectionKind::PlaneRotation
        )
    }));
    super::sweep::sort_corrections(&mut records);
    r.corrections = records;
    r.generatrix_scale = scale;
    r
}
