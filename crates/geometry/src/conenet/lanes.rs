//! Groups of [`LANES`] doubles computed in lock-step (structure of arrays).
//!
//! The sweep advances [`LANES`] independent rows together. Every operation here is a plain loop over
//! the lanes without branches, which the compiler turns into packed SIMD instructions; comparisons
//! give all-ones / all-zeros lane masks and [`F::select`] replaces `if`. Values of lanes that are not
//! in use are computed too and ignored.

// Lane loops index several arrays at once.
#![allow(clippy::needless_range_loop)]

use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

use glam::DVec3;

/// Rows swept in lock-step. Each step of a row depends on the previous vertex of that row, so one row
/// is latency-bound; eight rows hide the latency and fill the vector units.
pub(crate) const LANES: usize = 8;

/// One double per lane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct F(pub [f64; LANES]);

/// One boolean per lane, as all-ones (true) or zero bits, like a SIMD comparison result.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct M([u64; LANES]);

/// Applies `f` lane by lane.
#[inline(always)]
fn lanes<T: Copy, const N: usize>(f: impl Fn(usize) -> T) -> [T; N]
where
    [T; N]: Default,
{
    let mut out = <[T; N]>::default();
    for (l, o) in out.iter_mut().enumerate() {
        *o = f(l);
    }
    out
}

macro_rules! binary {
    ($tr:ident, $f:ident, $op:tt) => {
        impl $tr for F {
            type Output = F;
            #[inline(always)]
            fn $f(self, o: F) -> F {
                F(lanes(|l| self.0[l] $op o.0[l]))
            }
        }
        impl $tr<f64> for F {
            type Output = F;
            #[inline(always)]
            fn $f(self, o: f64) -> F {
                F(lanes(|l| self.0[l] $op o))
            }
        }
    };
}
binary!(Add, add, +);
binary!(Sub, sub, -);
binary!(Mul, mul, *);
binary!(Div, div, /);

impl Neg for F {
    type Output = F;
    #[inline(always)]
    fn neg(self) -> F {
        F(lanes(|l| -self.0[l]))
    }
}

macro_rules! compare {
    ($f:ident, $op:tt) => {
        #[doc = concat!("Lane mask of `self ", stringify!($op), " o` (false for NaN).")]
        #[inline(always)]
        pub(crate) fn $f(self, o: F) -> M {
            M(lanes(|l| if self.0[l] $op o.0[l] { u64::MAX } else { 0 }))
        }
    };
}

impl F {
    /// The same value in every lane.
    #[inline(always)]
    pub(crate) fn splat(v: f64) -> Self {
        Self([v; LANES])
    }

    compare!(lt, <);
    compare!(le, <=);
    compare!(gt, >);
    compare!(ge, >=);
    compare!(eq, ==);

    /// `|x|`.
    #[inline(always)]
    pub(crate) fn abs(self) -> Self {
        F(lanes(|l| self.0[l].abs()))
    }

    /// `√x`.
    #[inline(always)]
    pub(crate) fn sqrt(self) -> Self {
        F(lanes(|l| self.0[l].sqrt()))
    }

    /// The larger of two values (`o` when either is NaN, as the SIMD instruction does).
    #[inline(always)]
    pub(crate) fn max(self, o: F) -> Self {
        F(lanes(|l| {
            if self.0[l] > o.0[l] {
                self.0[l]
            } else {
                o.0[l]
            }
        }))
    }

    /// The smaller of two values (`o` when either is NaN, as the SIMD instruction does).
    #[inline(always)]
    pub(crate) fn min(self, o: F) -> Self {
        F(lanes(|l| {
            if self.0[l] < o.0[l] {
                self.0[l]
            } else {
                o.0[l]
            }
        }))
    }

    /// Lanes `values[start..start + LANES]`.
    #[inline(always)]
    pub(crate) fn load(values: &[f64], start: usize) -> Self {
        let mut out = [0.0; LANES];
        out.copy_from_slice(&values[start..start + LANES]);
        Self(out)
    }

    /// Stores the lanes into `values[start..start + LANES]`.
    #[inline(always)]
    pub(crate) fn store(self, values: &mut [f64], start: usize) {
        values[start..start + LANES].copy_from_slice(&self.0);
    }

    /// `a` where `m` is set, else `b`.
    #[inline(always)]
    pub(crate) fn select(m: M, a: F, b: F) -> Self {
        F(lanes(|l| {
            f64::from_bits((a.0[l].to_bits() & m.0[l]) | (b.0[l].to_bits() & !m.0[l]))
        }))
    }

    /// `self` where `m` is set, else +0.
    #[inline(always)]
    pub(crate) fn and(self, m: M) -> Self {
        F(lanes(|l| f64::from_bits(self.0[l].to_bits() & m.0[l])))
    }

    /// `−self` where `m` is set, else `self` (a sign flip, exact).
    #[inline(always)]
    pub(crate) fn neg_where(self, m: M) -> Self {
        F(lanes(|l| {
            f64::from_bits(self.0[l].to_bits() ^ (m.0[l] & 0x8000_0000_0000_0000))
        }))
    }

    /// Whether each lane is finite (not NaN, not ±∞).
    #[inline(always)]
    pub(crate) fn is_finite(self) -> M {
        self.abs().lt(F::splat(f64::INFINITY))
    }
}

impl M {
    /// The same value in every lane.
    #[inline(always)]
    pub(crate) fn splat(v: bool) -> Self {
        Self([if v { u64::MAX } else { 0 }; LANES])
    }

    /// Sets lane `l` to `v`.
    #[inline(always)]
    pub(crate) fn set(&mut self, l: usize, v: bool) {
        self.0[l] = if v { u64::MAX } else { 0 };
    }

    /// Whether lane `l` is set.
    #[inline(always)]
    pub(crate) fn get(self, l: usize) -> bool {
        self.0[l] != 0
    }

    /// Whether every lane is set.
    #[inline(always)]
    pub(crate) fn all(self) -> bool {
        self.0.iter().fold(u64::MAX, |a, &m| a & m) != 0
    }

    /// Whether some lane is set.
    #[inline(always)]
    pub(crate) fn any(self) -> bool {
        self.0.iter().fold(0, |a, &m| a | m) != 0
    }
}

impl BitAnd for M {
    type Output = M;
    #[inline(always)]
    fn bitand(self, o: M) -> M {
        M(lanes(|l| self.0[l] & o.0[l]))
    }
}

impl BitOr for M {
    type Output = M;
    #[inline(always)]
    fn bitor(self, o: M) -> M {
        M(lanes(|l| self.0[l] | o.0[l]))
    }
}

impl Not for M {
    type Output = M;
    #[inline(always)]
    fn not(self) -> M {
        M(lanes(|l| !self.0[l]))
    }
}

/// One 3-vector per lane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct V3 {
    pub x: F,
    pub y: F,
    pub z: F,
}

impl V3 {
    /// Zero in every lane.
    pub(crate) const ZERO: V3 = V3 {
        x: F([0.0; LANES]),
        y: F([0.0; LANES]),
        z: F([0.0; LANES]),
    };

    /// The same vector in every lane.
    #[inline(always)]
    pub(crate) fn splat(v: DVec3) -> Self {
        Self {
            x: F::splat(v.x),
            y: F::splat(v.y),
            z: F::splat(v.z),
        }
    }

    /// Lane l from `points[l]` (a slice of exactly [`LANES`] points).
    #[inline(always)]
    pub(crate) fn gather(points: &[DVec3]) -> Self {
        let points: &[DVec3; LANES] = points.try_into().expect("LANES points");
        let (mut x, mut y, mut z) = ([0.0; LANES], [0.0; LANES], [0.0; LANES]);
        for l in 0..LANES {
            (x[l], y[l], z[l]) = (points[l].x, points[l].y, points[l].z);
        }
        Self {
            x: F(x),
            y: F(y),
            z: F(z),
        }
    }

    /// Copies `o` into `self` (component by component: small copies stay inline).
    #[inline(always)]
    pub(crate) fn assign(&mut self, o: &V3) {
        self.x = o.x;
        self.y = o.y;
        self.z = o.z;
    }

    /// Lane `l`.
    #[inline(always)]
    pub(crate) fn lane(&self, l: usize) -> DVec3 {
        DVec3::new(self.x.0[l], self.y.0[l], self.z.0[l])
    }

    /// Sets lane `l`.
    #[inline(always)]
    pub(crate) fn set_lane(&mut self, l: usize, v: DVec3) {
        self.x.0[l] = v.x;
        self.y.0[l] = v.y;
        self.z.0[l] = v.z;
    }

    /// Dot product, as glam computes it (`x·x' + y·y' + z·z'`, left to right).
    #[inline(always)]
    pub(crate) fn dot(self, o: V3) -> F {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// `|v|²`.
    #[inline(always)]
    pub(crate) fn length_squared(self) -> F {
        self.dot(self)
    }

    /// Cross product, as glam computes it.
    #[inline(always)]
    pub(crate) fn cross(self, o: V3) -> V3 {
        V3 {
            x: self.y * o.z - o.y * self.z,
            y: self.z * o.x - o.z * self.x,
            z: self.x * o.y - o.x * self.y,
        }
    }

    /// Componentwise minimum (see [`F::min`]).
    #[inline(always)]
    pub(crate) fn min(self, o: V3) -> V3 {
        V3 {
            x: self.x.min(o.x),
            y: self.y.min(o.y),
            z: self.z.min(o.z),
        }
    }

    /// Componentwise maximum (see [`F::max`]).
    #[inline(always)]
    pub(crate) fn max(self, o: V3) -> V3 {
        V3 {
            x: self.x.max(o.x),
            y: self.y.max(o.y),
            z: self.z.max(o.z),
        }
    }

    /// `|x|` per component.
    #[inline(always)]
    pub(crate) fn abs(self) -> Self {
        Self {
            x: self.x.abs(),
            y: self.y.abs(),
            z: self.z.abs(),
        }
    }

    /// The largest component (inputs must not be NaN).
    #[inline(always)]
    pub(crate) fn max_element(self) -> F {
        self.x.max(self.y).max(self.z)
    }

    /// Whether every component is finite.
    #[inline(always)]
    pub(crate) fn is_finite(self) -> M {
        self.x.is_finite() & self.y.is_finite() & self.z.is_finite()
    }

    /// `a` where `m` is set, else `b`.
    #[inline(always)]
    pub(crate) fn select(m: M, a: V3, b: V3) -> Self {
        Self {
            x: F::select(m, a.x, b.x),
            y: F::select(m, a.y, b.y),
            z: F::select(m, a.z, b.z),
        }
    }
}

impl Add for V3 {
    type Output = V3;
    #[inline(always)]
    fn add(self, o: V3) -> V3 {
        V3 {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }
}

impl Sub for V3 {
    type Output = V3;
    #[inline(always)]
    fn sub(self, o: V3) -> V3 {
        V3 {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }
}

impl Mul<F> for V3 {
    type Output = V3;
    #[inline(always)]
    fn mul(self, s: F) -> V3 {
        V3 {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }
}

impl Mul<f64> for V3 {
    type Output = V3;
    #[inline(always)]
    fn mul(self, s: f64) -> V3 {
        V3 {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lane_ops_match_scalar_ops() {
        let a = F(std::array::from_fn(|l| l as f64 - 3.5));
        let b = F(std::array::from_fn(|l| 0.25 * l as f64 + 0.1));
        for l in 0..LANES {
            let (x, y) = (a.0[l], b.0[l]);
            assert_eq!((a + b).0[l], x + y);
            assert_eq!((a * b - a / b).0[l], x * y - x / y);
            assert_eq!(a.abs().sqrt().0[l], x.abs().sqrt());
            assert_eq!(a.max(b).0[l], x.max(y));
            assert_eq!(a.lt(b).get(l), x < y);
            assert_eq!(F::select(a.lt(b), a, b).0[l], if x < y { x } else { y });
            assert_eq!(a.and(a.lt(b)).0[l], if x < y { x } else { 0.0 });
            assert_eq!(a.neg_where(a.lt(b)).0[l], if x < y { -x } else { x });
        }
        assert!(!F::splat(f64::NAN).is_finite().get(0));
        assert!(!F::splat(f64::NEG_INFINITY).is_finite().get(1));
        assert!(F::splat(-1e300).is_finite().all());
        let v = V3::splat(DVec3::new(1.0, -2.0, 3.0));
        assert_eq!(v.dot(v).0[0], 14.0);
        assert_eq!(v.abs().max_element().0[2], 3.0);
        assert_eq!(v.lane(5), DVec3::new(1.0, -2.0, 3.0));
    }
}
