//! Seeded random numbers (`math.random`), the same on every platform and version.
//!
//! The generator is PCG-64 (`rand_pcg::Pcg64`, O'Neill's 128-bit LCG with the XSL-RR output; its
//! stream is fixed by the PCG specification and the crate's version-stability promise), seeded
//! with `SeedableRng::seed_from_u64(seed)`. Each number takes one 64-bit output `w` and is
//! `min + u · (max − min)` with `u = (w >> 11) · 2⁻⁵³`, a multiple of 2⁻⁵³ in [0, 1): portable,
//! integer-only until the last step. A value that rounds up to `max` is moved just below it.

use cnets_engine::prelude::*;
use rand_core::{Rng, SeedableRng};
use rand_pcg::Pcg64;

/// Most numbers one node makes.
pub const MAX_RANDOM_COUNT: i64 = 10_000_000;

/// `count` numbers in [min, max) from `seed`.
pub fn random_values(count: usize, min: f64, max: f64, seed: i64) -> Vec<f64> {
    let mut rng = Pcg64::seed_from_u64(seed as u64);
    let span = max - min;
    (0..count)
        .map(|_| {
            let u = (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
            let v = min + u * span;
            if span > 0.0 && v >= max {
                max.next_down()
            } else if span < 0.0 && v <= max {
                max.next_up()
            } else {
                v
            }
        })
        .collect()
}

node! {
    /// `count` random numbers between `min` (included) and `max` (excluded), from a seed: the same
    /// seed gives the same numbers on every platform and version, another seed others. The
    /// generator is PCG-64 (`rand_pcg`) seeded with the seed's 64 bits (docs/inputs.md). `min` >
    /// `max` gives numbers in (max, min].
    #[node(id = "math.random", category = "Math")]
    pub fn random(
        /// How many numbers (0 to 10 000 000).
        count: k::Integer = 10,
        /// Lower end (included).
        min: k::Number = 0.0,
        /// Upper end (excluded).
        max: k::Number = 1.0,
        /// The seed.
        seed: k::Integer = 0,
    ) -> (
        /// The numbers, in [min, max).
        values: k::List<k::Number>,
    ) {
        if !(0..=MAX_RANDOM_COUNT).contains(&count) {
            return Err(format!("count must be 0 to {MAX_RANDOM_COUNT}, got {count}").into());
        }
        if !min.is_finite() || !max.is_finite() || !(max - min).is_finite() {
            return Err(format!("min and max must be finite numbers a finite distance apart, got {min} and {max}").into());
        }
        Ok((random_values(count as usize, min, max, seed),))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOLDEN_SEED_0: [f64; 3] = [0.12765728561943035, 0.34755282876335303, 0.709750523336854];

    #[test]
    fn the_stream_is_fixed_by_the_seed() {
        let a = random_values(1000, 0.0, 1.0, 7);
        assert_eq!(a, random_values(1000, 0.0, 1.0, 7));
        assert_ne!(a, random_values(1000, 0.0, 1.0, 8));
        assert!(a.iter().all(|v| (0.0..1.0).contains(v)));
        let mean = a.iter().sum::<f64>() / a.len() as f64;
        assert!((mean - 0.5).abs() < 0.05, "{mean}");
    }

    #[test]
    fn golden_values_pin_the_stream_across_versions() {
        // Recorded once from this implementation: a change of generator, seeding or scaling (or of
        // the crate's stream) fails here, so saved designs keep their random numbers.
        assert_eq!(random_values(3, 0.0, 1.0, 0), GOLDEN_SEED_0);
    }

    #[test]
    fn ranges_scale_and_stay_half_open() {
        let v = random_values(10_000, -2.0, 3.0, 1);
        assert!(v.iter().all(|x| (-2.0..3.0).contains(x)));
        assert!(v.iter().any(|x| *x < -1.9) && v.iter().any(|x| *x > 2.9));
        let reversed = random_values(100, 1.0, 0.0, 1);
        assert!(reversed.iter().all(|x| *x > 0.0 && *x <= 1.0));
        let tiny = random_values(1000, 1.0, 1.0 + f64::EPSILON, 3);
        assert!(tiny.iter().all(|x| *x == 1.0));
    }
}
