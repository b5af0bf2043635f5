//! Inlinable `atan2` and `sin_cos` for the ratio construction (one of each per vertex).
//!
//! The libm calls are opaque function calls on the sweep's critical path; these fdlibm-style kernels
//! (same polynomial coefficients as fdlibm / musl) inline into the loop and stay within about one
//! ulp of the std functions (tested below). [`atan2`] and [`sin_cos`] take one argument of any
//! value (outside the fast range they fall back to std). [`atan2_upper`] and [`sin_cos_upper`]
//! serve the sweep, which runs [`LANES`](super::lanes::LANES) rows in lock-step with angles in
//! [0, π]: they work on lanes and are branch-free (selects only), so they compile to packed SIMD.
//! The polynomial kernels are shared ([`Real`]).

// The polynomial coefficients are written with the decimal expansions they were published with;
// each literal rounds to the intended double.
#![allow(clippy::excessive_precision)]

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};
use std::ops::{Add, Mul, Sub};

use super::lanes::F;

/// The arithmetic the polynomial kernels need, for one double or a group of lanes.
pub(crate) trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Add<f64, Output = Self>
    + Mul<f64, Output = Self>
{
    /// `v` (in every lane).
    fn splat(v: f64) -> Self;
}

impl Real for f64 {
    #[inline(always)]
    fn splat(v: f64) -> Self {
        v
    }
}

impl Real for F {
    #[inline(always)]
    fn splat(v: f64) -> Self {
        F::splat(v)
    }
}

const ATAN_HI: [f64; 4] = [
    4.636_476_090_008_060_935_15e-1,
    FRAC_PI_4,
    9.827_937_232_473_290_540_82e-1,
    FRAC_PI_2,
];
const ATAN_LO: [f64; 4] = [
    2.269_877_745_296_168_709_24e-17,
    3.061_616_997_868_383_017_93e-17,
    1.390_331_103_123_099_845_16e-17,
    6.123_233_995_736_766_035_87e-17,
];
const AT: [f64; 11] = [
    3.333_333_333_333_293_180_27e-1,
    -1.999_999_999_987_648_324_76e-1,
    1.428_571_427_250_346_637_11e-1,
    -1.111_111_040_546_235_578_80e-1,
    9.090_887_133_436_506_561_96e-2,
    -7.691_876_205_044_829_994_95e-2,
    6.661_073_137_387_531_206_69e-2,
    -5.833_570_133_790_573_486_45e-2,
    4.976_877_994_615_932_360_17e-2,
    -3.653_157_274_421_691_552_70e-2,
    1.628_582_011_536_578_236_23e-2,
];

/// atan(t) for t ∈ [0, ∞) (finite).
#[inline(always)]
fn atan_pos(t: f64) -> f64 {
    let (id, x) = if t < 0.4375 {
        (usize::MAX, t)
    } else if t < 0.6875 {
        (0, (2.0 * t - 1.0) / (2.0 + t))
    } else if t < 1.1875 {
        (1, (t - 1.0) / (t + 1.0))
    } else if t < 2.4375 {
        (2, (t - 1.5) / (1.0 + 1.5 * t))
    } else {
        (3, -1.0 / t)
    };
    let p = atan_poly(x);
    if id == usize::MAX {
        x - p
    } else {
        ATAN_HI[id] - ((p - ATAN_LO[id]) - x)
    }
}

/// The fdlibm polynomial part of atan: `x · (s1 + s2)` with atan(x) ≈ x − x·(s1 + s2) for
/// |x| ≤ 7/16.
#[inline(always)]
fn atan_poly<T: Real>(x: T) -> T {
    let z = x * x;
    let w = z * z;
    let w2 = w * w;
    // Estrin's scheme: shorter dependency chains than Horner, same polynomials. (`w·c + c'` is
    // `c' + w·c`: IEEE addition commutes.)
    let s1 = z * ((w * AT[2] + AT[0]) + w2 * ((w * AT[6] + AT[4]) + w2 * (w * AT[10] + AT[8])));
    let s2 = w * ((w * AT[3] + AT[1]) + w2 * ((w * AT[7] + AT[5]) + w2 * AT[9]));
    x * (s1 + s2)
}

/// `y.atan2(x)` per lane for `y ≥ 0` (an angle in [0, π]), branch-free. Both arguments must be
/// finite and not both zero (else the result is NaN). The argument of the polynomial is `|x|/y` or
/// `y/|x|` (whichever is ≤ 1), reduced to |t| ≤ 7/16 by `atan(u) = π/4 + atan((u − 1)/(u + 1))`
/// when u ≥ 7/16: one division in all.
#[inline(always)]
pub(crate) fn atan2_upper(y: F, x: F) -> F {
    let ax = x.abs();
    let swap = y.gt(ax);
    let (lo, hi) = (ax.min(y), y.max(ax));
    let mid = lo.ge(hi * 0.4375);
    // t = (lo − hi) / (lo + hi) for mid, else lo / hi.
    let t = (lo - hi.and(mid)) / (hi + lo.and(mid));
    // atan(lo / hi) ∈ [0, π/4], as fdlibm writes it (offset 0 gives exactly t − t·(s1 + s2)).
    let (off_hi, off_lo) = (F::splat(ATAN_HI[1]).and(mid), F::splat(ATAN_LO[1]).and(mid));
    let a = off_hi - ((atan_poly(t) - off_lo) - t);
    let a = F::select(swap, F::splat(FRAC_PI_2) - a, a);
    F::select(x.lt(F::splat(0.0)), F::splat(PI) - a, a)
}

/// `y.atan2(x)`, inlined. Falls back to std for zero, non-finite or extreme ratios.
#[inline(always)]
pub(crate) fn atan2(y: f64, x: f64) -> f64 {
    let (ax, ay) = (x.abs(), y.abs());
    if !(ax > 1e-300 && ay > 1e-300 && ax < 1e300 && ay < 1e300) {
        return y.atan2(x);
    }
    // Angle of (|x|, |y|) in [0, π/2].
    let a = if ay <= ax {
        atan_pos(ay / ax)
    } else {
        FRAC_PI_2 - atan_pos(ax / ay)
    };
    let a = if x < 0.0 { PI - a } else { a };
    if y < 0.0 { -a } else { a }
}

const S1: f64 = -1.666_666_666_666_663_243_48e-1;
const S2: f64 = 8.333_333_333_322_489_461_24e-3;
const S3: f64 = -1.984_126_982_985_794_931_34e-4;
const S4: f64 = 2.755_731_370_707_006_767_89e-6;
const S5: f64 = -2.505_076_025_340_686_341_95e-8;
const S6: f64 = 1.589_690_995_211_550_102_21e-10;
const C1: f64 = 4.166_666_666_666_660_190_37e-2;
const C2: f64 = -1.388_888_888_887_410_957_49e-3;
const C3: f64 = 2.480_158_728_947_672_941_78e-5;
const C4: f64 = -2.755_731_435_139_066_330_35e-7;
const C5: f64 = 2.087_572_321_298_174_827_90e-9;
const C6: f64 = -1.135_964_755_778_819_482_65e-11;
/// π/2 split in two parts for an exact-enough argument reduction.
const PIO2_HI: f64 = 1.570_796_326_734_125_614_17;
const PIO2_LO: f64 = 6.077_100_506_506_192_249_30e-11;

/// (sin x, cos x) for |x| ≤ π/4.
#[inline(always)]
fn kernel<T: Real>(x: T) -> (T, T) {
    let z = x * x;
    let v = z * x;
    let z2 = z * z;
    // Estrin's scheme for both polynomials.
    let r = (z * S3 + S2) + z2 * ((z * S5 + S4) + z2 * S6);
    let sin = x + v * (z * r + S1);
    let rc = z * ((z * C2 + C1) + z2 * ((z * C4 + C3) + z2 * (z * C6 + C5)));
    let hz = z * 0.5;
    let one = T::splat(1.0);
    let w = one - hz;
    let cos = w + (((one - w) - hz) + z * rc);
    (sin, cos)
}

/// Adding and subtracting this rounds a double of magnitude < 2⁵¹ to an integer (ties to even).
const ROUND_SHIFT: f64 = 6_755_399_441_055_744.0;

/// `k = round(x / (π/2))` (as a double) and the reduced argument `x − k π/2` (|·| ≤ π/4 + tiny),
/// for |x| ≤ 8.
#[inline(always)]
fn reduce<T: Real>(x: T) -> (T, T) {
    let k = (x * (2.0 / PI) + ROUND_SHIFT) - T::splat(ROUND_SHIFT);
    (k, (x - k * PIO2_HI) - k * PIO2_LO)
}

/// `x.sin_cos()` per lane for x ∈ [0, π] (the ruling angles of the ratio construction),
/// branch-free. Within the same error as [`sin_cos`] on that interval; arguments up to about 5π/4
/// are still reduced correctly.
#[inline(always)]
pub(crate) fn sin_cos_upper(x: F) -> (F, F) {
    let (k, r) = reduce(x);
    let (s, c) = kernel(r);
    // Quadrant k ∈ {0, 1, 2}: (s, c), (c, −s), (−s, −c).
    let odd = k.eq(F::splat(1.0));
    let (s, c) = (F::select(odd, c, s), F::select(odd, s, c).neg_where(odd));
    let half_turn = k.eq(F::splat(2.0));
    (s.neg_where(half_turn), c.neg_where(half_turn))
}

/// `x.sin_cos()`, inlined for |x| ≤ 8 (std beyond).
#[inline(always)]
pub(crate) fn sin_cos(x: f64) -> (f64, f64) {
    if !(x.abs() <= 8.0) {
        return x.sin_cos();
    }
    let (k, r) = reduce(x);
    let (s, c) = kernel(r);
    match (k as i64) & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

#[cfg(test)]
mod tests {
    use super::super::lanes::LANES;
    use super::*;

    /// A deterministic pseudo-random sequence in [0, 1).
    fn lcg(state: &mut u64) -> f64 {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*state >> 11) as f64 / (1u64 << 53) as f64
    }

    #[test]
    fn atan2_matches_std_to_an_ulp() {
        let mut s = 7;
        let mut worst = 0.0f64;
        for _ in 0..200_000 {
            let scale = 10f64.powf(lcg(&mut s) * 12.0 - 6.0);
            let (y, x) = (
                (lcg(&mut s) - 0.5) * scale,
                (lcg(&mut s) - 0.5) * 10f64.powf(lcg(&mut s) * 4.0 - 2.0),
            );
            let (a, b) = (atan2(y, x), y.atan2(x));
            worst = worst.max((a - b).abs() / b.abs().max(f64::MIN_POSITIVE));
        }
        assert!(worst <= 4.0 * f64::EPSILON, "relative error {worst:e}");
        for (y, x) in [
            (0.0, 1.0),
            (1.0, 0.0),
            (0.0, -1.0),
            (-0.0, -1.0),
            (1.0, 1.0),
            (1.0, -1.0),
            (3.0, 4.0),
        ] {
            assert!((atan2(y, x) - f64::atan2(y, x)).abs() <= 2.0 * f64::EPSILON);
        }
    }

    #[test]
    fn lane_variants_match_std_on_their_domain() {
        let mut s = 5;
        let (mut worst_atan, mut worst_sc) = (0.0f64, 0.0f64);
        for _ in 0..50_000 {
            let mut y = F::splat(0.0);
            let mut x = F::splat(0.0);
            let mut t = F::splat(0.0);
            for l in 0..LANES {
                y.0[l] = lcg(&mut s) * 10f64.powf(lcg(&mut s) * 12.0 - 6.0);
                x.0[l] = (lcg(&mut s) - 0.5) * 10f64.powf(lcg(&mut s) * 4.0 - 2.0);
                t.0[l] = lcg(&mut s) * PI;
            }
            let a = atan2_upper(y, x);
            let (sin, cos) = sin_cos_upper(t);
            for l in 0..LANES {
                let b = y.0[l].atan2(x.0[l]);
                worst_atan = worst_atan.max((a.0[l] - b).abs() / b.abs().max(f64::MIN_POSITIVE));
                let (bs, bc) = t.0[l].sin_cos();
                worst_sc = worst_sc
                    .max((sin.0[l] - bs).abs())
                    .max((cos.0[l] - bc).abs());
            }
        }
        assert!(
            worst_atan <= 4.0 * f64::EPSILON,
            "atan2 relative error {worst_atan:e}"
        );
        assert!(
            worst_sc <= 2.0 * f64::EPSILON,
            "sin_cos absolute error {worst_sc:e}"
        );
        for (y, x) in [
            (0.0, 1.0),
            (1.0, 0.0),
            (0.0, -1.0),
            (1.0, 1.0),
            (1.0, -1.0),
            (3.0, 4.0),
        ] {
            let a = atan2_upper(F::splat(y), F::splat(x)).0[0];
            assert!((a - f64::atan2(y, x)).abs() <= 2.0 * f64::EPSILON);
        }
        for t in [0.0, FRAC_PI_4, FRAC_PI_2, 3.0 * FRAC_PI_4, PI] {
            let ((sin, cos), (bs, bc)) = (sin_cos_upper(F::splat(t)), t.sin_cos());
            assert!((sin.0[0] - bs).abs() <= f64::EPSILON && (cos.0[0] - bc).abs() <= f64::EPSILON);
        }
    }

    #[test]
    fn sin_cos_matches_std_to_an_ulp() {
        let mut s = 11;
        let mut worst = 0.0f64;
        for _ in 0..200_000 {
            let x = (lcg(&mut s) - 0.3) * 9.0;
            let (a, b) = (sin_cos(x), x.sin_cos());
            worst = worst.max((a.0 - b.0).abs()).max((a.1 - b.1).abs());
        }
        assert!(worst <= 2.0 * f64::EPSILON, "absolute error {worst:e}");
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        assert_eq!(sin_cos(100.0), 100f64.sin_cos());
    }
}
