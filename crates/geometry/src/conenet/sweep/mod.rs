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
//! Within a task, [`super::lanes::LANES`] rows advance in lock-step as the lanes of packed vectors
//! ([`super::lanes`]): each step computes the planes and vertices of all of them without branches,
//! and only a row that needs more (an error, an inline fix, a stop) redoes its step on its own.
//!
//! One concern a file: this driver (the [`Sweep`] state, its blocks and stops), `sources.rs` (the
//! plane sources), `batch.rs` (lane batches and per-row state), `correct.rs` (the coupled
//! corrections), `given.rs` (given planes without correction: no plane sources, no stops).

mod batch;
mod correct;
mod given;
mod sources;

use glam::DVec3;
use rayon::prelude::*;

use super::configuration::{Configuration, generatrix_normal};
use super::correction::Correction;
use super::directrix::SweptDirectrix;
use super::inputs::{Assistance, Grid};
use super::prepare::Prepared;
use crate::GeometryError;
use batch::{Ctx, RowEnd, Slot, ends, first_event, run_batch, sweep_slots};
pub(crate) use correct::sort_corrections;
pub(crate) use given::{GivenSweep, sweep_given};
use sources::{CoplanarRow0, RatioRow, ReadOnly};

/// The first and the longest block of a sweep with a finite turn limit (see
/// [`Sweep::turn_limit`]), in columns.
const LIMITED_FIRST_BLOCK: usize = 4;
const LIMITED_LONGEST_BLOCK: usize = 64;

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
    /// The sweep stops early once `turn` exceeds this (the blend only needs to know that planes
    /// only turns more than a candidate does); infinite by default.
    pub turn_limit: f64,
}

/// `len` zero points from the allocator's zeroed memory: fresh pages come zeroed from the system and
/// are not written a second time, so their first touch (and its page faults) happens where the
/// sweep writes them, spread over the threads.
pub(crate) fn zeroed_points(len: usize) -> Vec<DVec3> {
    bytemuck::zeroed_vec(len)
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
        // Column 0 touches every page of the buffer: written in parallel, as the rows are swept.
        verts
            .par_chunks_mut(m)
            .zip(generatrix.par_iter())
            .for_each(|(row, g)| row[0] = *g);
        Self {
            dx,
            n,
            m,
            verts,
            planes,
            per_vertex,
            configs: bytemuck::zeroed_vec(n * (m - 1)),
            apex: prep.apex.clone(),
            rule,
            assistance: assistance.filter(Assistance::enabled),
            corrections: Vec::new(),
            psi: vec![0.0; m],
            inv_scale: 1.0 / prep.scale,
            generatrix_scale: 1.0,
            turn: 0.0,
            turn_limit: f64::INFINITY,
        }
    }

    /// Normal of Π_{i,j}.
    #[inline]
    pub(super) fn plane_at(&self, i: usize, j: usize) -> DVec3 {
        if self.per_vertex {
            self.planes[i * (self.m - 1) + j - 1]
        } else {
            self.planes[j - 1]
        }
    }

    /// Normal of Π_{i,j}, or for j = 0 its stand-in in c_{i,0} (the plane through X_0 and G_{i,0}
    /// perpendicular to the support plane, [`generatrix_normal`]).
    pub(super) fn plane_before(&self, i: usize, j: usize) -> DVec3 {
        if j == 0 {
            generatrix_normal(self.dx.points[0], self.dx.edges[1], self.vert(i, 0))
        } else {
            self.plane_at(i, j)
        }
    }

    #[inline]
    pub(super) fn vert(&self, i: usize, j: usize) -> DVec3 {
        self.verts[i * self.m + j]
    }

    /// Runs the whole sweep.
    pub fn run(&mut self) -> Result<(), GeometryError> {
        let steps = self.m - 1;
        // Without assistance nothing can stop a row: one block. With assistance start short and
        // double, so that an early stop wastes little of the optimistic work.
        // A sweep that may be cut short at a turn limit starts with short blocks and keeps them
        // short, so it stops soon after passing the limit (the plane turns of a folding design
        // pile up in its first columns) instead of at the end of an ever longer block.
        let limited = self.turn_limit.is_finite();
        let first = match (limited, self.assistance.is_some()) {
            (true, _) => LIMITED_FIRST_BLOCK,
            (false, true) => 16,
            (false, false) => steps,
        };
        let longest = if limited {
            LIMITED_LONGEST_BLOCK
        } else {
            usize::MAX
        };
        let (mut js, mut plane_final, mut block) = (0, false, first);
        while js < steps {
            if self.turn > self.turn_limit {
                // Cut short: the caller only asked whether the total turn passes the limit.
                break;
            }
            let je = (js + block).min(steps);
            match self.block(js, je, plane_final)? {
                None => {
                    js = je;
                    plane_final = false;
                    block = block.saturating_mul(2).min(longest);
                }
                Some(j0) => {
                    // A stop: the coupled correction (an α = 0 plane fix that is numerically
                    // insufficient also ends here and falls back to the apex fix).
                    self.correct(j0)?;
                    block = (2 * (j0 - js)).max(4).min(longest);
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
                    .map(|((i, (r, c)), p)| Slot::new(i, r, c, ReadOnly(p)))
                    .collect();
                sweep_slots(&ctx, &mut slots, js, je, plane_final);
                (ends(slots), Vec::new())
            }
            Rule::Given => {
                let shared = &planes[..];
                let mut slots: Vec<_> = rows
                    .map(|(i, (r, c))| Slot::new(i, r, c, ReadOnly(shared)))
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
                    .map(|(i, (r, c))| Slot::new(i, r, c, ReadOnly(shared)))
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
}
