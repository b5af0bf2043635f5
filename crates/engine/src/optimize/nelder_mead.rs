//! The Nelder–Mead simplex method, kept inside the bounds by projection: derivative-free, for
//! objectives that are not smooth.

use super::lbfgsb::project;

/// One Nelder–Mead state.
pub struct Simplex {
    /// Vertices with their values, best first after `sort`.
    pub points: Vec<(Vec<f64>, f64)>,
}

/// The initial simplex around `x0`: one step per coordinate of 5 % of the bound range (0.1 when
/// unbounded), turned inwards at a bound.
pub fn initial_points(x0: &[f64], lo: &[f64], hi: &[f64]) -> Vec<Vec<f64>> {
    let mut points = vec![x0.to_vec()];
    for i in 0..x0.len() {
        let range = hi[i] - lo[i];
        let step = if range.is_finite() && range > 0.0 {
            0.05 * range
        } else {
            0.1 * x0[i].abs().max(1.0)
        };
        let mut p = x0.to_vec();
        p[i] = if x0[i] + step <= hi[i] {
            x0[i] + step
        } else {
            x0[i] - step
        };
        project(&mut p, lo, hi);
        points.push(p);
    }
    points
}

impl Simplex {
    /// Sorts the vertices by value (ties keep their order: deterministic).
    pub fn sort(&mut self) {
        self.points.sort_by(|a, b| a.1.total_cmp(&b.1));
    }

    /// The centroid of all vertices but the worst.
    fn centroid(&self) -> Vec<f64> {
        let n = self.points.len() - 1;
        let mut c = vec![0.0; self.points[0].0.len()];
        for (p, _) in &self.points[..n] {
            for (ci, pi) in c.iter_mut().zip(p) {
                *ci += pi / n as f64;
            }
        }
        c
    }

    /// One iteration (reflection, expansion, contraction or shrink). `f` evaluates a point.
    pub fn step(&mut self, lo: &[f64], hi: &[f64], f: &mut dyn FnMut(&[f64]) -> f64) {
        self.sort();
        let n = self.points.len() - 1;
        let c = self.centroid();
        let worst = self.points[n].clone();
        let along = |t: f64| -> Vec<f64> {
            let mut p: Vec<f64> = c
                .iter()
                .zip(&worst.0)
                .map(|(ci, wi)| ci + t * (ci - wi))
                .collect();
            project(&mut p, lo, hi);
            p
        };
        let r = along(1.0);
        let fr = f(&r);
        if fr < self.points[0].1 {
            let e = along(2.0);
            let fe = f(&e);
            self.points[n] = if fe < fr { (e, fe) } else { (r, fr) };
        } else if fr < self.points[n - 1].1 {
            self.points[n] = (r, fr);
        } else {
            let (t, reference) = if fr < worst.1 {
                (0.5, fr)
            } else {
                (-0.5, worst.1)
            };
            let k = along(t);
            let fk = f(&k);
            if fk < reference {
                self.points[n] = (k, fk);
            } else {
                let best = self.points[0].0.clone();
                for (p, fp) in self.points.iter_mut().skip(1) {
                    for (pi, bi) in p.iter_mut().zip(&best) {
                        *pi = bi + 0.5 * (*pi - bi);
                    }
                    *fp = f(p);
                }
            }
        }
        self.sort();
    }

    /// Spread of values and size of the simplex.
    pub fn spread(&self) -> (f64, f64) {
        let fs = self.points.last().map_or(0.0, |p| p.1) - self.points[0].1;
        let size = self
            .points
            .iter()
            .skip(1)
            .map(|(p, _)| {
                p.iter()
                    .zip(&self.points[0].0)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max)
            })
            .fold(0.0, f64::max);
        (fs, size)
    }
}
