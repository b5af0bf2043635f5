//! Lane batches: up to [`LANES`] rows of one block advance in lock-step as the lanes of packed
//! vectors ([`super::super::lanes`]); a row that needs more (an error, an inline fix, a stop) redoes
//! its step on its own ([`advance`]). Also the per-row state ([`Slot`]), how a row ended ([`RowEnd`])
//! and the first event of a block over all rows.

use glam::DVec3;
use rayon::prelude::*;

use super::super::configuration::{Configuration, generatrix_normal};
use super::super::lanes::{F, LANES, M, V3};
use super::super::prepare::step;
use super::given::vertex_lanes;
use super::sources::PlaneSource;
use crate::GeometryError;

/// How one row's sweep ended.
pub(super) enum RowEnd {
    Done,
    /// Needs a coupled fix at step j (before building column j + 1).
    Stop(usize),
    /// Failed at step j, phase (0 plane, 1 fix, 2 build).
    Error(usize, u8, GeometryError),
}

impl RowEnd {
    fn key(&self, i: usize) -> Option<(usize, u8, usize)> {
        match self {
            Self::Done => None,
            Self::Stop(j) => Some((*j, 1, i)),
            Self::Error(j, phase, _) => Some((*j, *phase, i)),
        }
    }
}

/// Read-only data shared by every row of a block.
pub(super) struct Ctx<'s> {
    pub(super) x: &'s [DVec3],
    /// ê_1 (for the stand-in of Π_{i,0} in c_{i,0}).
    pub(super) e1: DVec3,
    pub(super) apex: &'s [f64],
    pub(super) check: bool,
}

/// One row being swept: its output slices, its plane source and its running state.
pub(super) struct Slot<'r, S> {
    pub(super) i: usize,
    pub(super) row: &'r mut [DVec3],
    pub(super) cfg: &'r mut [Configuration],
    pub(super) src: S,
    pub(super) g: DVec3,
    pub(super) p_prev: DVec3,
    pub(super) end: Option<RowEnd>,
}

impl<'r, S> Slot<'r, S> {
    pub(super) fn new(
        i: usize,
        row: &'r mut [DVec3],
        cfg: &'r mut [Configuration],
        src: S,
    ) -> Self {
        Self {
            i,
            row,
            cfg,
            src,
            g: DVec3::ZERO,
            p_prev: DVec3::ZERO,
            end: None,
        }
    }
}

/// Sweeps a batch of at most [`LANES`] rows in lock-step over steps `js..je` (building columns
/// js+1 … je). Columns ≤ js are built; when `plane_final`, the plane of column js+1 is already final
/// (set by a coupled correction). Each step computes the planes and vertices of all rows as lanes
/// ([`super::super::lanes`]); a row whose step needs more (an error, an inline fix, a stop) redoes it on its
/// own with [`advance`]. Inlined into its callers so that [`crate::simd::run`] compiles it wide.
#[inline(always)]
pub(super) fn run_batch<S: PlaneSource>(
    ctx: &Ctx<'_>,
    slots: &mut [Slot<'_, S>],
    js: usize,
    je: usize,
    plane_final: bool,
) {
    debug_assert!(!slots.is_empty() && slots.len() <= LANES);
    let last = slots.len() - 1;
    // Lane state: G_{·,j} and P_{·,j}. Lanes beyond the batch repeat its last row.
    let mut g = V3::ZERO;
    let mut p_prev = V3::ZERO;
    for l in 0..LANES {
        let s = &slots[l.min(last)];
        g.set_lane(l, s.row[js]);
        p_prev.set_lane(
            l,
            if js >= 1 {
                s.src.stored(js)
            } else {
                generatrix_normal(ctx.x[0], ctx.e1, s.row[0])
            },
        );
    }
    // Bit l: row `slots[l]` is still running.
    let all = (1u32 << slots.len()) - 1;
    let mut live = all;
    for j in js..je {
        if live == 0 {
            break;
        }
        let jn = j + 1;
        let fixed = plane_final && j == js;
        let (mut p, usable) = if fixed {
            let mut p = V3::ZERO;
            for l in 0..LANES {
                p.set_lane(l, slots[l.min(last)].src.stored(jn));
            }
            (p, M::splat(true))
        } else {
            S::planes(slots, jn, &g)
        };
        let mut step = step_lanes(ctx, j, &g, &p, &p_prev, ctx.check && !fixed);
        let fine = usable & step.ok;
        if live == all && fine.all() {
            for (l, s) in slots.iter_mut().enumerate() {
                commit(s, j, l, &p, &step);
            }
        } else {
            for (l, s) in slots.iter_mut().enumerate() {
                if live & (1 << l) == 0 {
                    continue;
                }
                if fine.get(l) {
                    commit(s, j, l, &p, &step);
                    continue;
                }
                // The row on its own: the plane's error, an inline fix, a stop or a step error.
                (s.g, s.p_prev) = (g.lane(l), p_prev.lane(l));
                let plane = if fixed || usable.get(l) {
                    Ok(p.lane(l))
                } else {
                    s.src.plane(jn, s.g)
                };
                let end = match plane {
                    Ok(plane) => advance(ctx, s, j, fixed, plane).err(),
                    Err(e) => Some(RowEnd::Error(j, 0, e)),
                };
                if end.is_some() {
                    s.end = end;
                    live &= !(1 << l);
                } else {
                    step.g1.set_lane(l, s.g);
                    p.set_lane(l, s.p_prev);
                }
            }
        }
        g.assign(&step.g1);
        p_prev.assign(&p);
    }
}

/// Writes lane l of a step (plane of column j + 1, vertex G_{i,j+1}, configuration c_{i,j}) to its
/// row.
#[inline(always)]
fn commit<S: PlaneSource>(s: &mut Slot<'_, S>, j: usize, l: usize, p: &V3, step: &StepLanes) {
    s.src.store(j + 1, p.lane(l));
    s.row[j + 1] = step.g1.lane(l);
    s.cfg[j] = Configuration::from_signs(step.s1.0[l], step.s2.0[l]);
}

/// One construction step of a batch of rows (see [`step_lanes`]).
struct StepLanes {
    /// G_{·,j+1}.
    g1: V3,
    /// s1 = (G_{·,j+1} − X_j) · P_{·,j}.
    s1: F,
    /// s2 = (X_{j+1} − G_{·,j}) · P_{·,j+1}.
    s2: F,
    /// The step is well defined, its vertex finite and, with `check`, Eq. 2 holds (s2 > 0).
    ok: M,
}

/// Step j of every lane: G_{·,j+1} from G_{·,j} = `g` and the planes `p` of column j + 1; `p_prev`
/// are the planes of column j (for s1). The same arithmetic as [`super::super::prepare::step`].
#[inline(always)]
fn step_lanes(ctx: &Ctx<'_>, j: usize, g: &V3, p: &V3, p_prev: &V3, check: bool) -> StepLanes {
    let x0 = ctx.x[j];
    let (g1, s2, mut ok) = vertex_lanes(g, x0, ctx.x[j + 1], ctx.apex[j], p);
    if check {
        ok = ok & s2.gt(F::splat(0.0));
    }
    StepLanes {
        g1,
        s1: (g1 - V3::splat(x0)).dot(*p_prev),
        s2,
        ok,
    }
}

/// One step of one row given its plane for column j+1: Eq. 2 check (inline fix or stop), vertex
/// G_{i,j+1}, configuration c_{i,j}.
fn advance<S: PlaneSource>(
    ctx: &Ctx<'_>,
    s: &mut Slot<'_, S>,
    j: usize,
    fixed: bool,
    plane: DVec3,
) -> Result<(), RowEnd> {
    let x = ctx.x;
    let (i, g) = (s.i, s.g);
    let jn = j + 1;
    let mut p = plane;
    let mut s2 = (x[jn] - g).dot(p);
    if ctx.check && !fixed && !(s2 > 0.0) {
        match s.src.fix_inline(j, g, p) {
            Ok(Some(q)) => {
                p = q;
                s2 = (x[jn] - g).dot(p);
            }
            Ok(None) => return Err(RowEnd::Stop(j)),
            Err(e) => return Err(RowEnd::Error(j, 1, e)),
        }
    }
    s.src.store(jn, p);
    let Some(g1) = step(g, x[j], x[jn], ctx.apex[j], p) else {
        return Err(RowEnd::Error(
            j,
            2,
            GeometryError::ParallelStep { row: i, column: jn },
        ));
    };
    if !g1.is_finite() {
        return Err(RowEnd::Error(
            j,
            2,
            GeometryError::NonFiniteOutput {
                what: "mesh vertex",
                row: i,
                column: jn,
            },
        ));
    }
    s.row[jn] = g1;
    s.cfg[j] = Configuration::from_signs((g1 - x[j]).dot(s.p_prev), s2);
    s.p_prev = p;
    s.g = g1;
    Ok(())
}

/// Sweeps all slots in parallel batches.
pub(super) fn sweep_slots<S: PlaneSource + Send>(
    ctx: &Ctx<'_>,
    slots: &mut [Slot<'_, S>],
    js: usize,
    je: usize,
    plane_final: bool,
) {
    slots.par_chunks_mut(LANES).for_each(|batch| {
        crate::simd::run(
            #[inline(always)]
            || run_batch(ctx, batch, js, je, plane_final),
        )
    });
}

/// The ends of all slots, in row order.
pub(super) fn ends<S>(slots: Vec<Slot<'_, S>>) -> Vec<RowEnd> {
    slots
        .into_iter()
        .map(|s| s.end.unwrap_or(RowEnd::Done))
        .collect()
}

/// The first event of a block over all rows, as (step, phase, row) plus the error if any.
pub(super) fn first_event(ends: Vec<RowEnd>) -> Option<(usize, Option<GeometryError>)> {
    let mut best: Option<((usize, u8, usize), RowEnd)> = None;
    for (i, end) in ends.into_iter().enumerate() {
        if let Some(k) = end.key(i)
            && best.as_ref().is_none_or(|(b, _)| k < *b)
        {
            best = Some((k, end));
        }
    }
    best.map(|((j, _, _), end)| match end {
        RowEnd::Error(_, _, e) => (j, Some(e)),
        _ => (j, None),
    })
}
