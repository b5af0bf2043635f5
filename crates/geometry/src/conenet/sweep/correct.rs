//! The coupled corrections of the sweep (paper Sec. 4.2.2, footnote 2, Appendix A): at a stop the
//! planes of the next column are fixed over all rows (planes only), or the apex value of the column
//! (apex only; at the first column the generatrix is scaled about X_0); and the record order.

use super::super::configuration::Configuration;
use super::super::coplanar::PlanePencil;
use super::super::correction::{Correction, CorrectionKind, apex_fix_value};
use super::super::inputs::Grid;
use super::super::prepare::step;
use super::super::ratios::{SupportFrame, angle_to_ratio, ratio_to_angle};
use super::super::tolerance;
use super::{Rule, Sweep};
use crate::GeometryError;

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

impl Sweep<'_> {
    /// The coupled correction at step j0: vertex column j0 against planes Π_{·,j0+1}.
    pub(super) fn correct(&mut self, j0: usize) -> Result<(), GeometryError> {
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
        // The ratio per row (the input's; a plane fix overwrites it). The ruling angle is taken from
        // it in the current support frame every round: an apex-like fix moves the vertices of
        // column j0, hence the frames, and the planes of column j0 + 1 keep their ratios (not their
        // angles), so that apex only changes no plane against its ratio.
        let mut ratios: Vec<f64> = (0..self.n).map(|i| grid.get(i, jn)).collect();
        for round in 0..tolerance::MAX_CORRECTION_ROUNDS {
            let mut frames = Vec::with_capacity(self.n);
            for (i, &ratio) in ratios.iter().enumerate() {
                let frame =
                    SupportFrame::new(dx.points[j0], dx.edges[jn], self.vert(i, j0), i, jn)?;
                let theta_b = frame.bisector_angle(b);
                let theta = ratio_to_angle(ratio, theta_b);
                let p = frame.normal(theta);
                if !(p.dot(frame.e) > tolerance::EDGE_PLANE) {
                    return Err(GeometryError::PlaneContainsEdge {
                        row: Some(i),
                        column: jn,
                    });
                }
                self.planes[i * (self.m - 1) + jn - 1] = p;
                frames.push((frame, theta_b, theta));
            }
            let bad = self.bad_rows(j0);
            if bad.is_empty() {
                return Ok(());
            }
            if round == 0 && a.alpha < 1.0 {
                for &i in &bad {
                    let (frame, theta_b, theta) = frames[i];
                    let phi = frame.angle_of(self.vert(i, j0), dx.points[jn]);
                    let new = (1.0 - a.epsilon) * phi;
                    let ratio = angle_to_ratio(new, theta_b);
                    self.corrections.push(Correction {
                        kind: CorrectionKind::Ratio,
                        column: jn,
                        row: Some(i),
                        old: ratios[i],
                        new: ratio,
                    });
                    self.turn += (new - theta).abs();
                    ratios[i] = ratio;
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
