//! Forward-mode dual numbers with a fixed number of tangent directions: the local Jacobians of
//! small closed-form pieces (a spline span's basis weights, a face's central projection), which
//! the reverse products then apply transposed.

use std::ops::{Add, Div, Mul, Neg, Sub};

use cnets_engine::prelude::DVec3;

/// A number with its partial derivatives in `N` directions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Dual<const N: usize> {
    /// The value.
    pub v: f64,
    /// The partial derivatives.
    pub d: [f64; N],
}

impl<const N: usize> Dual<N> {
    /// A constant (zero derivatives).
    pub fn constant(v: f64) -> Self {
        Self { v, d: [0.0; N] }
    }

    /// The variable number `k`: value `v`, derivative 1 in direction `k`.
    pub fn variable(v: f64, k: usize) -> Self {
        let mut d = [0.0; N];
        d[k] = 1.0;
        Self { v, d }
    }

    /// The square root.
    pub fn sqrt(self) -> Self {
        let r = self.v.sqrt();
        let f = 0.5 / r;
        Self {
            v: r,
            d: self.d.map(|x| x * f),
        }
    }
}

impl<const N: usize> Add for Dual<N> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        let mut d = self.d;
        d.iter_mut().zip(o.d).for_each(|(a, b)| *a += b);
        Self { v: self.v + o.v, d }
    }
}

impl<const N: usize> Sub for Dual<N> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        let mut d = self.d;
        d.iter_mut().zip(o.d).for_each(|(a, b)| *a -= b);
        Self { v: self.v - o.v, d }
    }
}

#[allow(clippy::suspicious_arithmetic_impl)]
impl<const N: usize> Mul for Dual<N> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        let mut d = self.d;
        d.iter_mut()
            .zip(o.d)
            .for_each(|(a, b)| *a = *a * o.v + self.v * b);
        Self { v: self.v * o.v, d }
    }
}

impl<const N: usize> Mul<f64> for Dual<N> {
    type Output = Self;
    fn mul(self, o: f64) -> Self {
        Self {
            v: self.v * o,
            d: self.d.map(|x| x * o),
        }
    }
}

#[allow(clippy::suspicious_arithmetic_impl)]
impl<const N: usize> Div for Dual<N> {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        let q = self.v / o.v;
        let mut d = self.d;
        d.iter_mut()
            .zip(o.d)
            .for_each(|(a, b)| *a = (*a - q * b) / o.v);
        Self { v: q, d }
    }
}

impl<const N: usize> Neg for Dual<N> {
    type Output = Self;
    fn neg(self) -> Self {
        Self {
            v: -self.v,
            d: self.d.map(|x| -x),
        }
    }
}

/// A point or vector of dual numbers.
pub(crate) type V3<const N: usize> = [Dual<N>; 3];

/// A constant vector.
pub(crate) fn constant3<const N: usize>(p: DVec3) -> V3<N> {
    [
        Dual::constant(p.x),
        Dual::constant(p.y),
        Dual::constant(p.z),
    ]
}

/// The vector `p` as variables `first`, `first + 1`, `first + 2`.
pub(crate) fn variable3<const N: usize>(p: DVec3, first: usize) -> V3<N> {
    [
        Dual::variable(p.x, first),
        Dual::variable(p.y, first + 1),
        Dual::variable(p.z, first + 2),
    ]
}

/// a + b.
pub(crate) fn add3<const N: usize>(a: V3<N>, b: V3<N>) -> V3<N> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// a − b.
pub(crate) fn sub3<const N: usize>(a: V3<N>, b: V3<N>) -> V3<N> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// a s.
pub(crate) fn scale3<const N: usize>(a: V3<N>, s: Dual<N>) -> V3<N> {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// a · b.
pub(crate) fn dot3<const N: usize>(a: V3<N>, b: V3<N>) -> Dual<N> {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// a × b.
pub(crate) fn cross3<const N: usize>(a: V3<N>, b: V3<N>) -> V3<N> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The values of a dual vector.
pub(crate) fn value3<const N: usize>(a: V3<N>) -> DVec3 {
    DVec3::new(a[0].v, a[1].v, a[2].v)
}

/// The transposed Jacobian of `a` applied to `g`: Σ_c g_c ∂a_c/∂x_k for every direction k.
pub(crate) fn pull3<const N: usize>(a: V3<N>, g: DVec3) -> [f64; N] {
    let mut out = [0.0; N];
    for (c, gc) in a.iter().zip(g.to_array()) {
        out.iter_mut().zip(c.d).for_each(|(o, d)| *o += gc * d);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_of_a_quotient_and_a_root() {
        // f(x, y) = sqrt(x) / (x y) at (4, 0.5): ∂f/∂x = −1/(2 x^{3/2} y), ∂f/∂y = −sqrt(x)/(x y²).
        let (x, y) = (Dual::<2>::variable(4.0, 0), Dual::<2>::variable(0.5, 1));
        let f = x.sqrt() / (x * y);
        assert!((f.v - 1.0).abs() < 1e-15);
        assert!((f.d[0] + 1.0 / (2.0 * 8.0 * 0.5)).abs() < 1e-15);
        assert!((f.d[1] + 2.0 / (4.0 * 0.25)).abs() < 1e-15);
        let c = cross3(variable3::<3>(DVec3::X, 0), constant3(DVec3::Y));
        assert_eq!(value3(c), DVec3::Z);
        // x × Y = (−x_z, 0, x_x).
        assert_eq!(pull3(c, DVec3::Z), [1.0, 0.0, 0.0]);
        assert_eq!(pull3(c, DVec3::new(-1.0, 0.0, 0.0)), [0.0, 0.0, 1.0]);
    }
}
