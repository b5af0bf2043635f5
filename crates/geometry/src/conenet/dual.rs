//! Forward-mode dual numbers for the local Jacobians of the construction's adjoint
//! ([`super::adjoint`]): a value with its derivatives along `N` directions, and points of them.
//!
//! A direction index `k ≥ N` seeds nothing ([`Dual::seed`] gives a constant), so one generic step
//! serves every set of wanted inputs: the first directions are the ones always needed and the
//! later ones are left out by a smaller `N`.

use std::ops::{Add, Div, Mul, Neg, Sub};

use glam::DVec3;

/// A number with its derivatives along `N` directions (forward mode).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Dual<const N: usize> {
    /// The value.
    pub v: f64,
    /// ∂value/∂direction.
    pub d: [f64; N],
}

impl<const N: usize> Dual<N> {
    /// A constant (no derivative).
    #[inline(always)]
    pub fn constant(v: f64) -> Self {
        Self { v, d: [0.0; N] }
    }

    /// The variable of direction `k`, or a constant when `k ≥ N` (a direction not followed).
    #[inline(always)]
    pub fn seed(v: f64, k: usize) -> Self {
        let mut d = [0.0; N];
        if k < N {
            d[k] = 1.0;
        }
        Self { v, d }
    }

    /// `f(self)` with `f(v) = value` and `f'(v) = slope`.
    #[inline(always)]
    fn map(self, value: f64, slope: f64) -> Self {
        Self {
            v: value,
            d: self.d.map(|x| x * slope),
        }
    }

    /// √self.
    #[inline(always)]
    pub fn sqrt(self) -> Self {
        let s = self.v.sqrt();
        self.map(s, 0.5 / s)
    }

    /// sin(self).
    #[inline(always)]
    pub fn sin(self) -> Self {
        self.map(self.v.sin(), self.v.cos())
    }

    /// cos(self).
    #[inline(always)]
    pub fn cos(self) -> Self {
        self.map(self.v.cos(), -self.v.sin())
    }

    /// atan2(y, x).
    #[inline(always)]
    pub fn atan2(y: Self, x: Self) -> Self {
        let r2 = x.v * x.v + y.v * y.v;
        let mut d = [0.0; N];
        for (k, dk) in d.iter_mut().enumerate() {
            *dk = (x.v * y.d[k] - y.v * x.d[k]) / r2;
        }
        Self {
            v: y.v.atan2(x.v),
            d,
        }
    }
}

impl<const N: usize> Add for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        let mut d = self.d;
        d.iter_mut().zip(o.d).for_each(|(a, b)| *a += b);
        Self { v: self.v + o.v, d }
    }
}

impl<const N: usize> Sub for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        let mut d = self.d;
        d.iter_mut().zip(o.d).for_each(|(a, b)| *a -= b);
        Self { v: self.v - o.v, d }
    }
}

impl<const N: usize> Neg for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self {
            v: -self.v,
            d: self.d.map(|x| -x),
        }
    }
}

impl<const N: usize> Mul for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        let mut d = [0.0; N];
        for (k, dk) in d.iter_mut().enumerate() {
            *dk = self.d[k] * o.v + self.v * o.d[k];
        }
        Self { v: self.v * o.v, d }
    }
}

impl<const N: usize> Mul<f64> for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: f64) -> Self {
        self.map(self.v * o, o)
    }
}

impl<const N: usize> Div for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        let inv = 1.0 / o.v;
        let mut d = [0.0; N];
        for (k, dk) in d.iter_mut().enumerate() {
            *dk = (self.d[k] - self.v * inv * o.d[k]) * inv;
        }
        Self { v: self.v * inv, d }
    }
}

/// A point (or vector) of dual numbers.
#[derive(Debug, Clone, Copy)]
pub(crate) struct D3<const N: usize>(pub [Dual<N>; 3]);

impl<const N: usize> D3<N> {
    /// The point whose x, y, z are the variables of directions `k`, `k + 1`, `k + 2` (each a
    /// constant when not followed, see [`Dual::seed`]).
    #[inline(always)]
    pub fn seed(p: DVec3, k: usize) -> Self {
        Self([
            Dual::seed(p.x, k),
            Dual::seed(p.y, k + 1),
            Dual::seed(p.z, k + 2),
        ])
    }

    /// The values.
    #[inline(always)]
    pub fn value(self) -> DVec3 {
        DVec3::new(self.0[0].v, self.0[1].v, self.0[2].v)
    }

    /// `Jᵀ λ` for direction `k`: Σ_c ∂self_c/∂k · λ_c.
    #[inline(always)]
    pub fn pull(&self, lambda: DVec3, k: usize) -> f64 {
        self.0[0].d[k] * lambda.x + self.0[1].d[k] * lambda.y + self.0[2].d[k] * lambda.z
    }

    /// The point pulled back along directions `k`, `k + 1`, `k + 2` (zero when not followed).
    #[inline(always)]
    pub fn pull3(&self, lambda: DVec3, k: usize) -> DVec3 {
        if k + 2 < N {
            DVec3::new(
                self.pull(lambda, k),
                self.pull(lambda, k + 1),
                self.pull(lambda, k + 2),
            )
        } else {
            DVec3::ZERO
        }
    }

    /// The dot product.
    #[inline(always)]
    pub fn dot(self, o: Self) -> Dual<N> {
        self.0[0] * o.0[0] + self.0[1] * o.0[1] + self.0[2] * o.0[2]
    }

    #[inline(always)]
    fn zip(self, o: Self, f: impl Fn(Dual<N>, Dual<N>) -> Dual<N>) -> Self {
        Self([
            f(self.0[0], o.0[0]),
            f(self.0[1], o.0[1]),
            f(self.0[2], o.0[2]),
        ])
    }

    /// `self · s`.
    #[inline(always)]
    pub fn scale(self, s: Dual<N>) -> Self {
        Self(self.0.map(|x| x * s))
    }

    /// `self + o`.
    #[inline(always)]
    pub fn add(self, o: Self) -> Self {
        self.zip(o, |a, b| a + b)
    }

    /// `self − o`.
    #[inline(always)]
    pub fn sub(self, o: Self) -> Self {
        self.zip(o, |a, b| a - b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_of_the_elementary_functions() {
        let (x, y) = (Dual::<2>::seed(0.7, 0), Dual::<2>::seed(-0.4, 1));
        let f = (x * y).sin() / (x * x + y * y).sqrt() - Dual::atan2(y, x).cos() * 3.0;
        let g = |x: f64, y: f64| (x * y).sin() / (x * x + y * y).sqrt() - y.atan2(x).cos() * 3.0;
        let h = 1e-6;
        let dx = (g(0.7 + h, -0.4) - g(0.7 - h, -0.4)) / (2.0 * h);
        let dy = (g(0.7, -0.4 + h) - g(0.7, -0.4 - h)) / (2.0 * h);
        assert!((f.v - g(0.7, -0.4)).abs() < 1e-15);
        assert!((f.d[0] - dx).abs() < 1e-9 && (f.d[1] - dy).abs() < 1e-9);
        // A direction beyond N is a constant.
        assert_eq!(Dual::<2>::seed(1.0, 5).d, [0.0; 2]);
        let p = D3::<4>::seed(DVec3::new(1.0, 2.0, 3.0), 1);
        assert_eq!(
            p.pull3(DVec3::new(5.0, 6.0, 7.0), 1),
            DVec3::new(5.0, 6.0, 7.0)
        );
        assert_eq!(p.pull3(DVec3::ONE, 2), DVec3::ZERO);
    }
}
