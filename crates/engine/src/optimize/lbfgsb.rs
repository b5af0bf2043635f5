//! Bounded L-BFGS: limited-memory quasi-Newton steps projected onto the box, with a backtracking
//! Armijo line search along the projected path. Variables held at a bound by the gradient are fixed
//! for the step (a simple active-set variant of L-BFGS-B).

use std::collections::VecDeque;

/// Pairs of (step, gradient change) kept.
const MEMORY: usize = 10;

/// Projects `x` into the box.
pub fn project(x: &mut [f64], lo: &[f64], hi: &[f64]) {
    for ((x, &l), &h) in x.iter_mut().zip(lo).zip(hi) {
        *x = x.clamp(l, h);
    }
}

/// The gradient with components that push out of an active bound set to zero.
pub fn projected_gradient(x: &[f64], g: &[f64], lo: &[f64], hi: &[f64]) -> Vec<f64> {
    x.iter()
        .zip(g)
        .zip(lo.iter().zip(hi))
        .map(|((&x, &g), (&l, &h))| {
            if (x <= l && g > 0.0) || (x >= h && g < 0.0) {
                0.0
            } else {
                g
            }
        })
        .collect()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The L-BFGS memory and the two-loop recursion.
#[derive(Debug, Default)]
pub struct Memory {
    pairs: VecDeque<(Vec<f64>, Vec<f64>, f64)>,
}

impl Memory {
    /// Remembers a step `s` and gradient change `y` when the curvature condition holds.
    pub fn push(&mut self, s: Vec<f64>, y: Vec<f64>) {
        let sy = dot(&s, &y);
        if sy > 1e-14 * dot(&s, &s).sqrt() * dot(&y, &y).sqrt() && sy > 0.0 {
            if self.pairs.len() == MEMORY {
                self.pairs.pop_front();
            }
            self.pairs.push_back((s, y, 1.0 / sy));
        }
    }

    /// Forgets everything (after a failed step).
    pub fn clear(&mut self) {
        self.pairs.clear();
    }

    /// True when nothing is remembered.
    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// `−H g` restricted to the `free` components (others zero).
    pub fn direction(&self, g: &[f64], free: &[bool]) -> Vec<f64> {
        let mask = |v: &[f64]| -> Vec<f64> {
            v.iter()
                .zip(free)
                .map(|(&x, &f)| if f { x } else { 0.0 })
                .collect()
        };
        let mut q = mask(g);
        let mut alphas = Vec::with_capacity(self.pairs.len());
        for (s, y, rho) in self.pairs.iter().rev() {
            let (s, y) = (mask(s), mask(y));
            let a = rho * dot(&s, &q);
            for (qi, yi) in q.iter_mut().zip(&y) {
                *qi -= a * yi;
            }
            alphas.push(a);
        }
        if let Some((s, y, _)) = self.pairs.back() {
            let (s, y) = (mask(s), mask(y));
            let yy = dot(&y, &y);
            if yy > 0.0 {
                let gamma = dot(&s, &y) / yy;
                if gamma.is_finite() && gamma > 0.0 {
                    q.iter_mut().for_each(|v| *v *= gamma);
                }
            }
        }
        for ((s, y, rho), a) in self.pairs.iter().zip(alphas.into_iter().rev()) {
            let (s, y) = (mask(s), mask(y));
            let b = rho * dot(&y, &q);
            for (qi, si) in q.iter_mut().zip(&s) {
                *qi += (a - b) * si;
            }
        }
        q.iter().map(|v| -v).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn projection_and_projected_gradient() {
        let (lo, hi) = (vec![0.0, 0.0], vec![1.0, 1.0]);
        let mut x = vec![-1.0, 2.0];
        project(&mut x, &lo, &hi);
        assert_eq!(x, vec![0.0, 1.0]);
        assert_eq!(
            projected_gradient(&x, &[1.0, 1.0], &lo, &hi),
            vec![0.0, 1.0]
        );
        assert_eq!(
            projected_gradient(&x, &[-1.0, -1.0], &lo, &hi),
            vec![-1.0, 0.0]
        );
    }

    #[test]
    fn two_loop_recovers_a_quadratic_hessian() {
        // f = x² + 10 y²: with the two exact curvature pairs, −H g is the Newton step.
        let mut m = Memory::default();
        m.push(vec![1.0, 0.0], vec![2.0, 0.0]);
        m.push(vec![0.0, 1.0], vec![0.0, 20.0]);
        let d = m.direction(&[2.0, 20.0], &[true, true]);
        assert!(
            (d[0] + 1.0).abs() < 1e-12 && (d[1] + 1.0).abs() < 1e-12,
            "{d:?}"
        );
    }
}
