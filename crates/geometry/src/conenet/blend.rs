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
//! Planes only is swept lazily, and only as far as the turn bound needs: once its running turn
//! passes a candidate's, `T0` is known to be larger (a planes-only error beyond that point does not
//! concern the blend).
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

/// Which form of the assisted correction a run took (what its derivative follows).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Taken {
    /// One sweep: no assistance, a pure form, or apex only standing in for a blend (its records
    /// are that sweep's own).
    Single,
    /// A blend: planes only on the inputs moved the fraction `lambda` of the way to apex only
    /// ([`towards`]); `mixed` when that sweep also fell back to apex or generatrix fixes.
    Blend { lambda: f64, mixed: bool },
}

/// Runs the assisted construction for `assistance` (off, or α ∈ [0, 1]); `sweep` runs one sweep of the
/// construction rule on the given inputs with a pure assistance (α = 0 or 1) or none, stopping early
/// once its total plane turn passes the given limit (infinite: the whole sweep).
pub(crate) fn assisted<F>(
    prep: &Prepared,
    assistance: Assistance,
    sweep: F,
) -> Result<Raw, GeometryError>
where
    F: Fn(&Prepared, Option<Assistance>, f64) -> Result<Raw, GeometryError>,
{
    assisted_traced(prep, assistance, sweep).map(|(raw, _)| raw)
}

/// [`assisted`], also saying which form the run took.
pub(crate) fn assisted_traced<F>(
    prep: &Prepared,
    assistance: Assistance,
    sweep: F,
) -> Result<(Raw, Taken), GeometryError>
where
    F: Fn(&Prepared, Option<Assistance>, f64) -> Result<Raw, GeometryError>,
{
    let single = |r: Result<Raw, GeometryError>| r.map(|r| (r, Taken::Single));
    let whole = f64::INFINITY;
    if !assistance.enabled() {
        return single(sweep(prep, None, whole));
    }
    let pure = |alpha: f64| Assistance {
        alpha,
        epsilon: assistance.epsilon,
    };
    let alpha = assistance.alpha;
    let mut apex_only = match sweep(prep, Some(pure(1.0)), whole) {
        Ok(q) => q,
        // Planes only does not need the apex-only plan.
        Err(_) if alpha == 0.0 => return single(sweep(prep, Some(pure(0.0)), whole)),
        Err(e) => return Err(e),
    };
    if alpha >= 1.0 || apex_only.corrections.is_empty() {
        return Ok((apex_only, Taken::Single));
    }
    if alpha == 0.0 {
        return single(sweep(prep, Some(pure(0.0)), whole));
    }
    let bound = Bounds {
        apex: apex_change(prep, &apex_only),
        scale: (1.0 - apex_only.generatrix_scale).abs(),
    };
    // The blend needs apex only's plan, not its mesh: its buffers are freed for the candidates
    // (warm memory instead of fresh pages) and it is swept again in the rare case it is the answer.
    let plan = ApexPlan {
        apex: std::mem::take(&mut apex_only.apex),
        generatrix_scale: apex_only.generatrix_scale,
    };
    drop(apex_only);
    let mut planes_only = PlanesOnlyTurn::Unknown;
    for k in 0..STEPS {
        let lambda = alpha + (1.0 - alpha) * k as f64 / STEPS as f64;
        let Some((r, mixed)) = sweep(&towards(prep, &plan, lambda), Some(pure(0.0)), whole)
            .ok()
            .map(|r| {
                let mixed = r
                    .corrections
                    .iter()
                    .any(|c| matches!(c.kind, CorrectionKind::Apex | CorrectionKind::Generatrix));
                (rebase(prep, r, lambda, plan.generatrix_scale), mixed)
            })
        else {
            continue;
        };
        if bound.holds(prep, &r)
            && planes_only.exceeds(r.turn, |limit| {
                sweep(prep, Some(pure(0.0)), limit).map(|p| p.turn)
            })?
        {
            return Ok((r, Taken::Blend { lambda, mixed }));
        }
    }
    single(sweep(prep, Some(pure(1.0)), whole))
}

/// What the blend takes from apex only: its apex values and generatrix scale.
struct ApexPlan {
    apex: Vec<f64>,
    generatrix_scale: f64,
}

/// The bounds of the blend from apex only: its apex and generatrix changes.
struct Bounds {
    apex: f64,
    scale: f64,
}

impl Bounds {
    fn holds(&self, prep: &Prepared, r: &Raw) -> bool {
        apex_change(prep, r) <= self.apex && (1.0 - r.generatrix_scale).abs() <= self.scale
    }
}

/// What is known of planes only's total plane turn `T0` (the third bound). Planes only is swept
/// only as far as needed: to certify `turn ≤ T0` it is enough that its running turn (a sum of
/// non-negative terms) passes `turn`, and on strongly folding designs that happens within the
/// first columns (its whole sweep made 596 572 plane fixes on the benchmarks' 1000 × 1000 design
/// and took 0.58 s, most of the blend's time).
enum PlanesOnlyTurn {
    Unknown,
    /// A sweep cut short there: `T0` is larger.
    Above(f64),
    /// The whole sweep's total.
    Exactly(f64),
}

impl PlanesOnlyTurn {
    /// Whether `turn ≤ T0`; `sweep(limit)` runs planes only until its turn passes `limit` and
    /// returns the turn reached (the whole total when it did not pass it).
    fn exceeds(
        &mut self,
        turn: f64,
        sweep: impl Fn(f64) -> Result<f64, GeometryError>,
    ) -> Result<bool, GeometryError> {
        let limit = match *self {
            PlanesOnlyTurn::Exactly(t0) => return Ok(turn <= t0),
            PlanesOnlyTurn::Above(reached) if turn < reached => return Ok(true),
            // A second question sweeps the whole: no series of ever longer partial sweeps.
            PlanesOnlyTurn::Above(_) => f64::INFINITY,
            PlanesOnlyTurn::Unknown => turn,
        };
        let reached = sweep(limit)?;
        if reached > limit {
            *self = PlanesOnlyTurn::Above(reached);
            Ok(true)
        } else {
            *self = PlanesOnlyTurn::Exactly(reached);
            Ok(turn <= reached)
        }
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
fn towards(prep: &Prepared, apex_only: &ApexPlan, lambda: f64) -> Prepared {
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

#[cfg(test)]
mod tests {
    use std::cell::RefCell;

    use super::PlanesOnlyTurn;

    /// A planes-only sweep of total turn 10 that, cut at a limit, stops at the first block end
    /// (turn 7) past it; it records the limits it was asked for.
    fn sweep(asked: &RefCell<Vec<f64>>) -> impl Fn(f64) -> Result<f64, crate::GeometryError> + '_ {
        move |limit| {
            asked.borrow_mut().push(limit);
            Ok(if limit < 7.0 { 7.0 } else { 10.0 })
        }
    }

    #[test]
    fn planes_only_is_swept_only_as_far_as_the_bound_needs() {
        let asked = RefCell::new(Vec::new());
        let mut t0 = PlanesOnlyTurn::Unknown;
        // Cut short at the candidate's turn: T0 > 7 > 5.
        assert!(t0.exceeds(5.0, sweep(&asked)).unwrap());
        assert!(matches!(t0, PlanesOnlyTurn::Above(7.0)));
        // Below what was reached: no sweep.
        assert!(t0.exceeds(6.5, sweep(&asked)).unwrap());
        // Beyond it: one whole sweep, then T0 is known.
        assert!(t0.exceeds(9.0, sweep(&asked)).unwrap());
        assert!(matches!(t0, PlanesOnlyTurn::Exactly(10.0)));
        assert!(!t0.exceeds(10.5, sweep(&asked)).unwrap());
        assert!(t0.exceeds(10.0, sweep(&asked)).unwrap());
        assert_eq!(*asked.borrow(), [5.0, f64::INFINITY]);
        // A candidate turning more than the whole planes-only sweep fails at once.
        let mut t0 = PlanesOnlyTurn::Unknown;
        assert!(!t0.exceeds(12.0, sweep(&asked)).unwrap());
        assert!(matches!(t0, PlanesOnlyTurn::Exactly(10.0)));
        // NaN never certifies.
        assert!(!t0.exceeds(f64::NAN, sweep(&asked)).unwrap());
    }
}
