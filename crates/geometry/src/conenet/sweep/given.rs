//! The sweep of given planes without correction (the C-tube construction): nothing can stop a row,
//! so there are no plane sources, stops or per-row state. Rows advance [`LANES`] at a time as in
//! the general driver, with the same arithmetic ([`vertex_lanes`], shared with [`super::batch`]),
//! so the vertices and configurations are bit for bit those of the general sweep; the
//! configurations are computed only when asked for. A step that the general sweep would report (a
//! plane parallel to the step, a non-finite vertex) makes it give up: the caller then runs the
//! general sweep, which reports the error in its usual order.

// Lane loops index several arrays at once.
#![allow(clippy::needless_range_loop)]

use glam::DVec3;
use rayon::prelude::*;

use super::super::configuration::{Configuration, generatrix_normal};
use super::super::lanes::{F, LANES, M, V3};
use super::super::prepare::Prepared;
use super::super::tolerance;
use super::zeroed_points;

/// G_{·,j+1} of a step from G_{·,j} = `g`, X_j = `x0`, X_{j+1} = `x1`, a_j = `a` and the planes `p`
/// of column j + 1; also s2 = (X_{j+1} − G_{·,j}) · P_{·,j+1} and the lanes whose step is well
/// defined with a finite vertex. The same arithmetic as [`super::super::prepare::step`].
#[inline(always)]
pub(super) fn vertex_lanes(g: &V3, x0: DVec3, x1: DVec3, a: f64, p: &V3) -> (V3, F, M) {
    let (x0, x1) = (V3::splat(x0), V3::splat(x1));
    let s2 = (x1 - *g).dot(*p);
    let v = (*g - x0) * a + x1 - *g;
    let vp = v.dot(*p);
    let bound = v.abs().max_element() * (3.0 * tolerance::PARALLEL) * p.abs().max_element();
    let g1 = *g + v * (s2 / vp);
    let ok = vp.abs().gt(bound) & g1.is_finite();
    (g1, s2, ok)
}

/// The output of [`sweep_given`].
pub(crate) struct GivenSweep {
    /// N × M vertices, row-major.
    pub verts: Vec<DVec3>,
    /// N × (M − 1) configurations (entry `i*(M−1) + j` is c_{i,j}); empty when not asked for.
    pub configs: Vec<Configuration>,
}

/// The sweep of `prep` through the given plane normals (`planes`: M − 1 shared by every row, or
/// N × (M − 1) when `per_vertex`), with the configurations when `configurations`; `None` when some
/// step is not well defined (the general sweep then says where and why).
pub(crate) fn sweep_given(
    prep: &Prepared,
    planes: &[DVec3],
    per_vertex: bool,
    configurations: bool,
) -> Option<GivenSweep> {
    let (n, m) = (prep.generatrix.len(), prep.dx.columns());
    let mut verts = zeroed_points(n * m);
    let mut configs: Vec<Configuration> = if configurations {
        bytemuck::zeroed_vec(n * (m - 1))
    } else {
        Vec::new()
    };
    // One slice of configurations a batch (empty ones when they are not asked for).
    let config_rows: Vec<&mut [Configuration]> = if configurations {
        configs.chunks_mut(LANES * (m - 1)).collect()
    } else {
        std::iter::repeat_with(<&mut [Configuration]>::default)
            .take(n.div_ceil(LANES))
            .collect()
    };
    let fine = verts
        .par_chunks_mut(LANES * m)
        .zip(prep.generatrix.par_chunks(LANES))
        .zip(config_rows.into_par_iter())
        .enumerate()
        .all(|(b, ((rows, generatrix), cfg))| {
            let batch = Batch {
                prep,
                planes,
                per_vertex,
                first: b * LANES,
                generatrix,
            };
            // One copy of the loop with the configurations and one without.
            crate::simd::run(
                #[inline(always)]
                || {
                    if cfg.is_empty() {
                        batch.sweep::<false>(rows, cfg)
                    } else {
                        batch.sweep::<true>(rows, cfg)
                    }
                },
            )
        });
    fine.then_some(GivenSweep { verts, configs })
}

/// Up to [`LANES`] rows swept together.
struct Batch<'a> {
    prep: &'a Prepared,
    planes: &'a [DVec3],
    per_vertex: bool,
    /// The batch's first row.
    first: usize,
    /// Its generatrix points, one per row.
    generatrix: &'a [DVec3],
}

impl Batch<'_> {
    /// Sweeps the batch's rows into `rows` (M vertices each) and, with `CONFIGURATIONS`, their
    /// configurations into `cfg` (M − 1 each); false when a step is not well defined.
    #[inline(always)]
    fn sweep<const CONFIGURATIONS: bool>(
        &self,
        rows: &mut [DVec3],
        cfg: &mut [Configuration],
    ) -> bool {
        let (x, apex, m) = (
            &self.prep.dx.points,
            &self.prep.apex,
            self.prep.dx.columns(),
        );
        let count = self.generatrix.len();
        let last = count - 1;
        // Lanes beyond the batch repeat its last row (computed, never stored).
        let mut g = V3::ZERO;
        // The stand-in for Π_{·,0} in c_{·,0}.
        let mut p0 = V3::ZERO;
        for l in 0..LANES {
            let g0 = self.generatrix[l.min(last)];
            g.set_lane(l, g0);
            if CONFIGURATIONS {
                p0.set_lane(l, generatrix_normal(x[0], self.prep.dx.edges[1], g0));
            }
        }
        for (l, p) in self.generatrix.iter().enumerate() {
            rows[l * m] = *p;
        }
        let mut bad = M::splat(false);
        for j in 0..m - 1 {
            let p = self.planes_at(j + 1);
            let (g1, s2, ok) = vertex_lanes(&g, x[j], x[j + 1], apex[j], &p);
            bad = bad | !ok;
            for l in 0..count {
                rows[l * m + j + 1] = g1.lane(l);
            }
            if CONFIGURATIONS {
                // Read again rather than carried: the loop keeps fewer registers live.
                let p_prev = if j == 0 { p0 } else { self.planes_at(j) };
                let s1 = (g1 - V3::splat(x[j])).dot(p_prev);
                let codes = Configuration::lane_codes(s1, s2);
                for l in 0..count {
                    cfg[l * (m - 1) + j] = codes[l];
                }
            }
            g = g1;
        }
        !bad.any()
    }

    /// The planes of column `jn` (≥ 1) of the batch's rows.
    #[inline(always)]
    fn planes_at(&self, jn: usize) -> V3 {
        if !self.per_vertex {
            return V3::splat(self.planes[jn - 1]);
        }
        let (cols, last) = (self.prep.dx.columns() - 1, self.generatrix.len() - 1);
        let mut p = V3::ZERO;
        for l in 0..LANES {
            p.set_lane(l, self.planes[(self.first + l.min(last)) * cols + jn - 1]);
        }
        p
    }
}
