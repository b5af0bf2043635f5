//! The sweep engine shared by all constructions.
//!
//! For a fixed apex function the rows are independent, so rows are swept in parallel (rayon), each
//! writing only its own contiguous slice of the mesh, planes and configurations. The assisted
//! correction couples the rows of one column only. The engine therefore sweeps *optimistically*: all
//! rows run in parallel over a block of columns and each row stops at its first column that needs a
//! coupled fix. The smallest such column j0 (ties: plane errors before stops before step errors, then
//! the smallest row) is the next event; columns ≤ j0 are final for every row, the coupled correction
//! is applied at j0 over all rows, and the sweep resumes at j0. The block length adapts (doubling
//! after each block, restarting from the distance covered before the last stop), so the work wasted
//! beyond a stop stays proportional to the useful work. Results do not depend on the thread count.
//!
//! Within a task, [`LANES`] rows advance in lock-step as the lanes of packed vectors
//! ([`super::lanes`]): each step computes the planes and vertices of all of them without branches,
//! and only a row that needs more (an error, an inline fix, a stop) redoes its step on its own.

use glam::DVec3;
use rayon::prelude::*;

use super::configuration::{Configuration, generatrix_normal};
use super::coplanar::PlanePencil;
use super::correction::{Correction, CorrectionKind, apex_fix_value};
use super::directrix::SweptDirectrix;
use super::inputs::{Assistance, Grid};
use super::lanes::{F, LANES, M, V3};
use super::prepare::{Prepared, step};
use super::ratios::{RatioColumn, SupportFrame, angle_to_ratio, ratio_planes, ratio_to_angle};
use super::tolerance;
use crate::GeometryError;

/// How the construction planes are obtained.
#[derive(Clone, Copy)]
pub(crate) enum Rule<'a> {
    /// Planes are given (shared per column or per vertex): the C-tube construction.
    Given,
    /// CNets Construct: per-vertex planes from ratios.
    Ratios(&'a Grid<'a>),
    /// CNets Construct Coplanar: one plane per column from ρ_j, τ_j and support strip 0.
    Coplanar {
        /// ρ_j at index j − 1.
        rho: &'a [f64],
        /// τ_j at index j − 1.
        tau: &'a [f64],
    },
}

/// The mutable state of one construction.
pub(crate) struct Sweep<'a> {
    pub dx: &'a SweptDirectrix,
    pub n: usize,
    pub m: usize,
    /// Row-major N × M vertices; column 0 holds the generatrix.
    pub verts: Vec<DVec3>,
    /// Plane normals: N × (M−1) when `per_vertex`, else M−1 shared.
    pub planes: Vec<DVec3>,
    pub per_vertex: bool,
    /// N × (M−1) configurations (entry `i*(M−1) + j` is c_{i,j}, j = 0 … M−2).
    pub configs: Vec<Configuration>,
    /// a_j at index j − 1.
    pub apex: Vec<f64>,
    pub rule: Rule<'a>,
    pub assistance: Option<Assistance>,
    pub corrections: Vec<Correction>,
    /// Coplanar mode: ψ of the shared plane at column j (index j).
    pub psi: Vec<f64>,
    /// 1 / design size (keeps the magnitudes of the ratio hot path and the quality pass near 1).
    pub inv_scale: f64,
    /// The factor the first-column fix has scaled the generatrix by about X_0 (1: untouched).
    pub generatrix_scale: f64,
    /// Σ over the vertices of the angle between the corrected plane P_{i,j} and the plane its ratio
    /// (or τ) gives at the same place: the total plane turn of the plane fixes.
    pub turn: f64,
}

/// `len` zero points, written in parallel straight into the new buffer (rayon's in-place collect):
/// the first touch of the pages, and the page faults, are spread over the threads.
pub(crate) fn zeroed_points(len: usize) -> Vec<DVec3> {
    let mut v = Vec::with_capacity(len);
    v.par_extend(rayon::iter::repeat_n(DVec3::ZERO, len));
    v
}

/// How one row's sweep ended.
enum RowEnd {
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
struct Ctx<'s> {
    x: &'s [DVec3],
    /// ê_1 (for the stand-in of Π_{i,0} in c_{i,0}).
    e1: DVec3,
    apex: &'s [f64],
    check: bool,
}

/// Where a row gets its planes from.
trait PlaneSource {
    /// The plane for building column `jn` from `g = G_{i,jn−1}`.
    fn plane(&mut self, jn: usize, g: DVec3) -> Result<DVec3, GeometryError>;
    /// The stored (final) plane of column `j`.
    fn stored(&self, j: usize) -> DVec3;
    /// Stores the final plane of column `j`.
    fn store(&mut self, j: usize, p: DVec3);
    /// Eq. 2 fails at step j (vertex G_{i,j} = `g` against the plane `p` of column j + 1): a
    /// row-local fix (new plane) or `None` when the fix couples the rows.
    fn fix_inline(&mut self, j: usize, g: DVec3, p: DVec3) -> Result<Option<DVec3>, GeometryError>;
    /// The planes for building column `jn` of a batch of rows (lane l is row `slots[l]`) from the
    /// lanes `g` = G_{·,jn−1}, with the mask of the lanes whose plane can be used; for the others
    /// [`PlaneSource::plane`] gives the error. Lanes of ended rows and lanes beyond the batch may
    /// hold anything.
    #[inline(always)]
    fn planes(slots: &mut [Slot<'_, Self>], jn: usize, g: &V3) -> (V3, M)
    where
        Self: Sized,
    {
        let mut p = *g;
        let mut ok = M::splat(false);
        for (l, s) in slots.iter_mut().enumerate() {
            if s.end.is_none()
                && let Ok(q) = s.src.plane(jn, g.lane(l))
            {
                p.set_lane(l, q);
                ok.set(l, true);
            }
        }
        (p, ok)
    }
}

/// Shared planes, read only.
struct SharedRead<'p>(&'p [DVec3]);

impl PlaneSource for SharedRead<'_> {
    #[inline]
    fn plane(&mut self, jn: usize, _: DVec3) -> Result<DVec3, GeometryError> {
        Ok(self.0[jn - 1])
    }
    #[inline]
    fn stored(&self, j: usize) -> DVec3 {
        self.0[j - 1]
    }
    #[inline]
    fn store(&mut self, _: usize, _: DVec3) {}
    fn fix_inline(&mut self, _: usize, _: DVec3, _: DVec3) -> Result<Option<DVec3>, GeometryError> {
        Ok(None)
    }
}

/// The planes of one row, read only (given per-vertex normals).
struct RowRead<'p>(&'p [DVec3]);

impl PlaneSource for RowRead<'_> {
    #[inline]
    fn plane(&mut self, jn: usize, _: DVec3) -> Result<DVec3, GeometryError> {
        Ok(self.0[jn - 1])
    }
    #[inline]
    fn stored(&self, j: usize) -> DVec3 {
        self.0[j - 1]
    }
    #[inline]
    fn store(&mut self, _: usize, _: DVec3) {}
    fn fix_inline(&mut self, _: usize, _: DVec3, _: DVec3) -> Result<Option<DVec3>, GeometryError> {
        Ok(None)
    }
}

/// Ratio planes of one row, computed and stored as the row advances.
struct RatioRow<'p> {
    i: usize,
    dx: &'p SweptDirectrix,
    /// The row's ratios (entry j − 1 is column j).
    ratios: &'p [f64],
    planes: &'p mut [DVec3],
    inv_scale: f64,
    /// α: 0 (planes only) or 1 (apex-like fixes only); negative: off.
    alpha: f64,
    epsilon: f64,
    /// Inline plane fixes: (step, record, turn |Δθ| of the plane).
    fixes: Vec<(usize, Correction, f64)>,
}

impl PlaneSource for RatioRow<'_> {
    fn plane(&mut self, jn: usize, g: DVec3) -> Result<DVec3, GeometryError> {
        let col = RatioColumn::new(self.dx, jn);
        let r = F::splat(self.ratios[jn - 1]);
        ratio_planes(&col, &V3::splat(g), r, self.inv_scale).get(0, self.i, jn)
    }
    #[inline]
    fn stored(&self, j: usize) -> DVec3 {
        self.planes[j - 1]
    }
    #[inline(always)]
    fn store(&mut self, j: usize, p: DVec3) {
        self.planes[j - 1] = p;
    }
    fn fix_inline(&mut self, j: usize, g: DVec3, _: DVec3) -> Result<Option<DVec3>, GeometryError> {
        let jn = j + 1;
        if self.alpha >= 1.0 {
            // Apex-like fixes only: they couple the rows (a stop).
            return Ok(None);
        }
        // Plane fix: θ goes to (1 − ε) φ. It is row-local; only when the row is still bad (rounding)
        // does the coupled fix (a stop) follow, and the coupled step then redoes this column.
        let dx = self.dx;
        let frame = SupportFrame::new(dx.points[j], dx.edges[jn], g, self.i, jn)?;
        let theta_b = frame.bisector_angle(dx.bisectors[jn]);
        let r_old = self.ratios[jn - 1];
        let theta = (1.0 - self.epsilon) * frame.angle_of(g, dx.points[jn]);
        let p = frame.normal(theta);
        if !(p.dot(frame.e) > tolerance::EDGE_PLANE) {
            return Err(GeometryError::PlaneContainsEdge {
                row: Some(self.i),
                column: jn,
            });
        }
        if !((dx.points[jn] - g).dot(p) > 0.0) {
            return Ok(None);
        }
        self.fixes.push((
            j,
            Correction {
                kind: CorrectionKind::Ratio,
                column: jn,
                row: Some(self.i),
                old: r_old,
                new: angle_to_ratio(theta, theta_b),
            },
            (theta - ratio_to_angle(r_old, theta_b)).abs(),
        ));
        Ok(Some(p))
    }

    #[inline(always)]
    fn planes(slots: &mut [Slot<'_, Self>], jn: usize, g: &V3) -> (V3, M) {
        let last = slots.len() - 1;
        let mut r = F::splat(0.5);
        for l in 0..LANES {
            r.0[l] = slots[l.min(last)].src.ratios[jn - 1];
        }
        let src = &slots[0].src;
        let planes = ratio_planes(&RatioColumn::new(src.dx, jn), g, r, src.inv_scale);
        (planes.p, planes.usable)
    }
}

/// Coplanar mode, row 0: computes the shared plane of every column from support strip 0.
struct CoplanarRow0<'p> {
    dx: &'p SweptDirectrix,
    rho: &'p [f64],
    tau: &'p [f64],
    planes: &'p mut [DVec3],
    psi: &'p mut [f64],
}

impl PlaneSource for CoplanarRow0<'_> {
    fn plane(&mut self, jn: usize, g: DVec3) -> Result<DVec3, GeometryError> {
        let dx = self.dx;
        let frame = SupportFrame::new(dx.points[jn - 1], dx.edges[jn], g, 0, jn)?;
        let pencil = PlanePencil::new(
            &frame,
            dx.bisectors[jn],
            self.rho[jn - 1],
            dx.outgoing[jn],
            jn,
        )?;
        let psi = self.tau[jn - 1] * pencil.psi_out;
        let p = pencil.normal(psi);
        if !(p.dot(frame.e) > tolerance::EDGE_PLANE) {
            return Err(GeometryError::PlaneContainsEdge {
                row: None,
                column: jn,
            });
        }
        self.psi[jn] = psi;
        Ok(p)
    }
    #[inline]
    fn stored(&self, j: usize) -> DVec3 {
        self.planes[j - 1]
    }
    #[inline]
    fn store(&mut self, j: usize, p: DVec3) {
        self.planes[j - 1] = p;
    }
    fn fix_inline(&mut self, _: usize, _: DVec3, _: DVec3) -> Result<Option<DVec3>, GeometryError> {
        Ok(None)
    }
}

/// One row being swept: its output slices, its plane source and its running state.
struct Slot<'r, S> {
    i: usize,
    row: &'r mut [DVec3],
    cfg: &'r mut [Configuration],
    src: S,
    g: DVec3,
    p_prev: DVec3,
    end: Option<RowEnd>,
}

impl<'r, S> Slot<'r, S> {
    fn new(i: usize, row: &'r mut [DVec3], cfg: &'r mut [Configuration], src: S) -> Self {
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
/// ([`super::lanes`]); a row whose step needs more (an error, an inline fix, a stop) redoes it on its
/// own with [`advance`]. Inlined into its callers so that [`crate::simd::run`] compiles it wide.
#[inline(always)]
fn run_batch<S: PlaneSource>(
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
/// are the planes of column j (for s1). The same arithmetic as [`super::prepare::step`].
#[inline(always)]
fn step_lanes(ctx: &Ctx<'_>, j: usize, g: &V3, p: &V3, p_prev: &V3, check: bool) -> StepLanes {
    let (x0, x1, a) = (V3::splat(ctx.x[j]), V3::splat(ctx.x[j + 1]), ctx.apex[j]);
    let s2 = (x1 - *g).dot(*p);
    let v = (*g - x0) * a + x1 - *g;
    let vp = v.dot(*p);
    let bound = v.abs().max_element() * (3.0 * tolerance::PARALLEL) * p.abs().max_element();
    let g1 = *g + v * (s2 / vp);
    let mut ok = vp.abs().gt(bound) & g1.is_finite();
    if check {
        ok = ok & s2.gt(F::splat(0.0));
    }
    StepLanes {
        g1,
        s1: (g1 - x0).dot(*p_prev),
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

/// Orders correction records by column, then kind (generatrix, apex, planes), then row.
pub(crate) fn sort_corrections(records: &mut [Correction]) {
    records.sort_by_key(|c| {
        let rank = match c.kind {
            CorrectionKind::Generatrix => 0,
            CorrectionKind::Apex => 1,
            CorrectionKind::Ratio | CorrectionKind::PlaneRotation => 2,
        };
        (c.column, rank, c.row)
    });
}

/// Sweeps all slots in parallel batches.
fn sweep_slots<S: PlaneSource + Send>(
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
fn ends<S>(slots: Vec<Slot<'_, S>>) -> Vec<RowEnd> {
    slots
        .into_iter()
        .map(|s| s.end.unwrap_or(RowEnd::Done))
        .collect()
}

/// The first event of a block over all rows, as (step, phase, row) plus the error if any.
fn first_event(ends: Vec<RowEnd>) -> Option<(usize, Option<GeometryError>)> {
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

impl<'a> Sweep<'a> {
    /// A sweep over the prepared inputs (N generatrix points) with the given planes.
    pub fn new(
        prep: &'a Prepared,
        planes: Vec<DVec3>,
        per_vertex: bool,
        rule: Rule<'a>,
        assistance: Option<Assistance>,
    ) -> Self {
        let (dx, generatrix) = (&prep.dx, &prep.generatrix);
        let (n, m) = (generatrix.len(), dx.columns());
        let mut verts = zeroed_points(n * m);
        for (i, g) in generatrix.iter().enumerate() {
            verts[i * m] = *g;
        }
        Self {
            dx,
            n,
            m,
            verts,
            planes,
            per_vertex,
            configs: {
                let mut c = Vec::with_capacity(n * (m - 1));
                c.par_extend(rayon::iter::repeat_n(Configuration::PlusPlus, n * (m - 1)));
                c
            },
            apex: prep.apex.clone(),
            rule,
            assistance: assistance.filter(Assistance::enabled),
            corrections: Vec::new(),
            psi: vec![0.0; m],
            inv_scale: 1.0 / prep.scale,
            generatrix_scale: 1.0,
            turn: 0.0,
        }
    }

    /// Normal of Π_{i,j}.
    #[inline]
    fn plane_at(&self, i: usize, j: usize) -> DVec3 {
        if self.per_vertex {
            self.planes[i * (self.m - 1) + j - 1]
        } else {
            self.planes[j - 1]
        }
    }

    /// Normal of Π_{i,j}, or for j = 0 its stand-in in c_{i,0} (the plane through X_0 and G_{i,0}
    /// perpendicular to the support plane, [`generatrix_normal`]).
    fn plane_before(&self, i: usize, j: usize) -> DVec3 {
        if j == 0 {
            generatrix_normal(self.dx.points[0], self.dx.edges[1], self.vert(i, 0))
        } else {
            self.plane_at(i, j)
        }
    }

    #[inline]
    fn vert(&self, i: usize, j: usize) -> DVec3 {
        self.verts[i * self.m + j]
    }

    /// Runs the whole sweep.
    pub fn run(&mut self) -> Result<(), GeometryError> {
        let steps = self.m - 1;
        // Without assistance nothing can stop a row: one block. With assistance start short and
        // double, so that an early stop wastes little of the optimistic work.
        let first = if self.assistance.is_some() { 16 } else { steps };
        let (mut js, mut plane_final, mut block) = (0, false, first);
        while js < steps {
            let je = (js + block).min(steps);
            match self.block(js, je, plane_final)? {
                None => {
                    js = je;
                    plane_final = false;
                    block = block.saturating_mul(2);
                }
                Some(j0) => {
                    // A stop: the coupled correction (an α = 0 plane fix that is numerically
                    // insufficient also ends here and falls back to the apex fix).
                    self.correct(j0)?;
                    block = (2 * (j0 - js)).max(4);
                    js = j0;
                    plane_final = true;
                }
            }
        }
        sort_corrections(&mut self.corrections);
        Ok(())
    }

    /// Sweeps every row over steps `js..je`; returns the step of the first coupled stop, if any.
    fn block(
        &mut self,
        js: usize,
        je: usize,
        plane_final: bool,
    ) -> Result<Option<usize>, GeometryError> {
        let m = self.m;
        let check = self.assistance.is_some();
        let (alpha, epsilon) = self
            .assistance
            .map_or((-1.0, 0.01), |a| (a.alpha, a.epsilon));
        let dx = self.dx;
        let rule = self.rule;
        let per_vertex = self.per_vertex;
        let inv_scale = self.inv_scale;
        let Self {
            verts,
            planes,
            configs,
            apex,
            psi,
            ..
        } = self;
        let ctx = Ctx {
            x: &dx.points,
            e1: dx.edges[1],
            apex,
            check,
        };
        let rows = verts
            .chunks_mut(m)
            .zip(configs.chunks_mut(m - 1))
            .enumerate();
        let (ends, fixes): (Vec<RowEnd>, Vec<(usize, Correction, f64)>) = match rule {
            Rule::Given if per_vertex => {
                let mut slots: Vec<_> = rows
                    .zip(planes.chunks(m - 1))
                    .map(|((i, (r, c)), p)| Slot::new(i, r, c, RowRead(p)))
                    .collect();
                sweep_slots(&ctx, &mut slots, js, je, plane_final);
                (ends(slots), Vec::new())
            }
            Rule::Given => {
                let shared = &planes[..];
                let mut slots: Vec<_> = rows
                    .map(|(i, (r, c))| Slot::new(i, r, c, SharedRead(shared)))
                    .collect();
                sweep_slots(&ctx, &mut slots, js, je, plane_final);
                (ends(slots), Vec::new())
            }
            Rule::Ratios(grid) => {
                let mut slots: Vec<_> = rows
                    .zip(planes.chunks_mut(m - 1))
                    .map(|((i, (r, c)), p)| {
                        let src = RatioRow {
                            i,
                            dx,
                            ratios: grid.row(i),
                            planes: p,
                            inv_scale,
                            alpha,
                            epsilon,
                            fixes: Vec::new(),
                        };
                        Slot::new(i, r, c, src)
                    })
                    .collect();
                sweep_slots(&ctx, &mut slots, js, je, plane_final);
                let mut fixes = Vec::new();
                let mut out = Vec::with_capacity(slots.len());
                for s in slots {
                    fixes.extend(s.src.fixes);
                    out.push(s.end.unwrap_or(RowEnd::Done));
                }
                (out, fixes)
            }
            Rule::Coplanar { rho, tau } => {
                let mut rows = rows;
                let Some((i0, (r0, c0))) = rows.next() else {
                    return Ok(None);
                };
                let mut first = [Slot::new(
                    i0,
                    r0,
                    c0,
                    CoplanarRow0 {
                        dx,
                        rho,
                        tau,
                        planes,
                        psi,
                    },
                )];
                crate::simd::run(
                    #[inline(always)]
                    || run_batch(&ctx, &mut first, js, je, plane_final),
                );
                let [first] = first;
                let end0 = first.end.unwrap_or(RowEnd::Done);
                // The other rows can go as far as row 0 has produced planes.
                let limit = match end0 {
                    RowEnd::Done => je,
                    RowEnd::Error(j, 0, _) => j,
                    RowEnd::Stop(j) | RowEnd::Error(j, _, _) => j + 1,
                };
                let shared = &planes[..];
                let mut slots: Vec<_> = rows
                    .map(|(i, (r, c))| Slot::new(i, r, c, SharedRead(shared)))
                    .collect();
                sweep_slots(&ctx, &mut slots, js, limit.max(js), plane_final);
                let mut all = vec![end0];
                all.extend(ends(slots));
                (all, Vec::new())
            }
        };
        let event = first_event(ends);
        match event {
            Some((_, Some(err))) => Err(err),
            Some((j0, None)) => {
                self.keep_fixes(fixes.into_iter().filter(|(j, _, _)| *j < j0));
                Ok(Some(j0))
            }
            None => {
                self.keep_fixes(fixes);
                Ok(None)
            }
        }
    }

    /// Records the inline plane fixes that stay (and their turn).
    fn keep_fixes(&mut self, fixes: impl IntoIterator<Item = (usize, Correction, f64)>) {
        for (_, c, turn) in fixes {
            self.corrections.push(c);
            self.turn += turn;
        }
    }

    /// The coupled correction at step j0: vertex column j0 against planes Π_{·,j0+1}.
    fn correct(&mut self, j0: usize) -> Result<(), GeometryError> {
        match self.rule {
            Rule::Ratios(grid) => self.correct_ratio(j0, grid),
            Rule::Coplanar { rho, .. } => self.correct_coplanar(j0, rho[j0]),
            Rule::Given => Ok(()),
        }
    }

    /// Rows i with `(X_{j0+1} − G_{i,j0}) · P_{i,j0+1} ≤ 0`.
    fn bad_rows(&self, j0: usize) -> Vec<usize> {
        let x1 = self.dx.points[j0 + 1];
        (0..self.n)
            .filter(|&i| !((x1 - self.vert(i, j0)).dot(self.plane_at(i, j0 + 1)) > 0.0))
            .collect()
    }

    fn correct_ratio(&mut self, j0: usize, grid: &Grid<'_>) -> Result<(), GeometryError> {
        let a = self
            .assistance
            .expect("correction only runs with assistance");
        let dx = self.dx;
        let jn = j0 + 1;
        let b = dx.bisectors[jn];
        // Current ruling angle per row (from the ratio; plane fixes overwrite it).
        let mut thetas = Vec::with_capacity(self.n);
        for i in 0..self.n {
            let frame = SupportFrame::new(dx.points[j0], dx.edges[jn], self.vert(i, j0), i, jn)?;
            thetas.push(ratio_to_angle(grid.get(i, jn), frame.bisector_angle(b)));
        }
        for round in 0..tolerance::MAX_CORRECTION_ROUNDS {
            let mut frames = Vec::with_capacity(self.n);
            for (i, &theta) in thetas.iter().enumerate() {
                let frame =
                    SupportFrame::new(dx.points[j0], dx.edges[jn], self.vert(i, j0), i, jn)?;
                let p = frame.normal(theta);
                if !(p.dot(frame.e) > tolerance::EDGE_PLANE) {
                    return Err(GeometryError::PlaneContainsEdge {
                        row: Some(i),
                        column: jn,
                    });
                }
                self.planes[i * (self.m - 1) + jn - 1] = p;
                frames.push(frame);
            }
            let bad = self.bad_rows(j0);
            if bad.is_empty() {
                return Ok(());
            }
            if round == 0 && a.alpha < 1.0 {
                for &i in &bad {
                    let frame = frames[i];
                    let theta_b = frame.bisector_angle(b);
                    let phi = frame.angle_of(self.vert(i, j0), dx.points[jn]);
                    let new = (1.0 - a.epsilon) * phi;
                    self.corrections.push(Correction {
                        kind: CorrectionKind::Ratio,
                        column: jn,
                        row: Some(i),
                        old: angle_to_ratio(thetas[i], theta_b),
                        new: angle_to_ratio(new, theta_b),
                    });
                    self.turn += (new - thetas[i]).abs();
                    thetas[i] = new;
                }
                continue;
            }
            self.apex_like_fix(j0, &bad, a.epsilon)?;
        }
        Err(GeometryError::CorrectionFailed { column: j0 })
    }

    fn correct_coplanar(&mut self, j0: usize, rho: f64) -> Result<(), GeometryError> {
        let a = self
            .assistance
            .expect("correction only runs with assistance");
        let dx = self.dx;
        let jn = j0 + 1;
        let mut psi = self.psi[jn];
        for round in 0..tolerance::MAX_CORRECTION_ROUNDS {
            let frame = SupportFrame::new(dx.points[j0], dx.edges[jn], self.vert(0, j0), 0, jn)?;
            let pencil = PlanePencil::new(&frame, dx.bisectors[jn], rho, dx.outgoing[jn], jn)?;
            let p = pencil.normal(psi);
            if !(p.dot(frame.e) > tolerance::EDGE_PLANE) {
                return Err(GeometryError::PlaneContainsEdge {
                    row: None,
                    column: jn,
                });
            }
            self.planes[jn - 1] = p;
            self.psi[jn] = psi;
            let bad = self.bad_rows(j0);
            if bad.is_empty() {
                return Ok(());
            }
            if round == 0 && a.alpha < 1.0 {
                let x1 = dx.points[jn];
                let qs = (0..self.n).map(|i| x1 - self.vert(i, j0));
                if let Some((lo, hi)) = pencil.feasible(qs, a.epsilon) {
                    let new = psi.clamp(lo, hi);
                    self.corrections.push(Correction {
                        kind: CorrectionKind::PlaneRotation,
                        column: jn,
                        row: None,
                        old: psi / pencil.psi_out,
                        new: new / pencil.psi_out,
                    });
                    // The shared plane turns at every row.
                    self.turn += self.n as f64 * (new - psi).abs();
                    psi = new;
                    continue;
                }
            }
            self.apex_like_fix(j0, &bad, a.epsilon)?;
        }
        Err(GeometryError::CorrectionFailed { column: j0 })
    }

    /// The apex fix at column j0 ≥ 1, or at the first column (j0 = 0) its counterpart of footnote 2.
    fn apex_like_fix(
        &mut self,
        j0: usize,
        bad: &[usize],
        epsilon: f64,
    ) -> Result<(), GeometryError> {
        if j0 == 0 {
            self.generatrix_fix(bad, epsilon)
        } else {
            self.apex_fix(j0, bad, epsilon)
        }
    }

    /// The first-column fix of footnote 2 (the apex-like fix at j = 0): the generatrix is scaled about
    /// X_0 by `t = (1 − ε) min t_i` over the bad rows, `t_i = ((X_1 − X_0)·P_{i,1}) / ((G_{i,0} −
    /// X_0)·P_{i,1})` ∈ (0, 1] being the factor that puts G_{i,0} on Π_{i,1}. Each G_{i,0} moves
    /// towards X_0 along the line X_0 G_{i,0}, so the support frames, hence the planes Π_{·,1} of the
    /// ratio and coplanar rules, do not change, and Eq. 2 then holds with margin ε·(X_1 − X_0)·P_{i,1}
    /// for every bad row (and keeps holding for the good ones). One record, the generatrix's total
    /// scale factor old → new.
    fn generatrix_fix(&mut self, bad: &[usize], epsilon: f64) -> Result<(), GeometryError> {
        let (x0, x1) = (self.dx.points[0], self.dx.points[1]);
        let mut t_min = f64::INFINITY;
        for &i in bad {
            let p = self.plane_at(i, 1);
            let t = (x1 - x0).dot(p) / (self.vert(i, 0) - x0).dot(p);
            t_min = if t.is_nan() { f64::NAN } else { t_min.min(t) };
        }
        let t = (1.0 - epsilon) * t_min;
        if !(t > 0.0 && t < 1.0) {
            return Err(GeometryError::CorrectionFailed { column: 0 });
        }
        for i in 0..self.n {
            let g = &mut self.verts[i * self.m];
            *g = x0 + (*g - x0) * t;
        }
        let old = self.generatrix_scale;
        self.generatrix_scale *= t;
        self.corrections.push(Correction {
            kind: CorrectionKind::Generatrix,
            column: 0,
            row: None,
            old,
            new: self.generatrix_scale,
        });
        Ok(())
    }

    /// The apex fix at column j0 ≥ 1 (Appendix A): a' = min over the bad rows; a_{j0} = (1 − ε) a';
    /// rebuilds column j0 for every row.
    ///
    /// Per bad row the value is the first critical value of `s2(a)` in (0, a_old): the root of the
    /// paper's formula, or the pole where `V·P_{i,j0} = 0` (the vertex passed through infinity: the
    /// root then lies beyond a_old and would not help). Without a critical value in (0, a_old) the
    /// paper's root is used as is, and a non-positive a' is the impossible case.
    fn apex_fix(&mut self, j0: usize, bad: &[usize], epsilon: f64) -> Result<(), GeometryError> {
        let x = &self.dx.points;
        let xs = [x[j0 - 1], x[j0], x[j0 + 1]];
        let old = self.apex[j0 - 1];
        let mut a_min = f64::INFINITY;
        for &i in bad {
            let (g, p0) = (self.vert(i, j0 - 1), self.plane_at(i, j0));
            let root = apex_fix_value(g, xs, p0, self.plane_at(i, j0 + 1));
            let pole = -(xs[1] - g).dot(p0) / (g - xs[0]).dot(p0);
            let inside = |v: f64| v > 0.0 && v < old;
            let v = match (inside(root), inside(pole)) {
                (true, true) => root.min(pole),
                (true, false) => root,
                (false, true) => pole,
                (false, false) => root,
            };
            if v.is_nan() {
                // A NaN candidate means the fix is undefined for that row: impossible.
                a_min = f64::NAN;
                break;
            }
            a_min = a_min.min(v);
        }
        if !(a_min > 0.0 && a_min.is_finite()) {
            return Err(GeometryError::ApexFixImpossible {
                column: j0,
                value: a_min,
            });
        }
        let new = (1.0 - epsilon) * a_min;
        self.corrections.push(Correction {
            kind: CorrectionKind::Apex,
            column: j0,
            row: None,
            old,
            new,
        });
        self.apex[j0 - 1] = new;
        for i in 0..self.n {
            let p = self.plane_at(i, j0);
            let g = step(self.vert(i, j0 - 1), xs[0], xs[1], new, p)
                .ok_or(GeometryError::ParallelStep { row: i, column: j0 })?;
            if !g.is_finite() {
                return Err(GeometryError::NonFiniteOutput {
                    what: "mesh vertex",
                    row: i,
                    column: j0,
                });
            }
            self.verts[i * self.m + j0] = g;
            let p_prev = self.plane_before(i, j0 - 1);
            let s1 = (g - xs[0]).dot(p_prev);
            let s2 = (xs[1] - self.vert(i, j0 - 1)).dot(p);
            self.configs[i * (self.m - 1) + j0 - 1] = Configuration::from_signs(s1, s2);
        }
        Ok(())
    }
}
