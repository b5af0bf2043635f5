//! The AVX2 copies of the hot loops (`cnets_geometry::simd`) give bit-for-bit the results of the
//! baseline copies: every construction, with and without assistance, over random designs large
//! enough for full lane groups (8 rows, 8 strips) and partial ones, including designs whose wide
//! ratios trigger corrections and errors.

mod common;

use cnets_geometry::simd::{set_wide_vectors, wide_vectors};
use common::{all_constructions, design};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn wide_and_baseline_copies_agree_bit_for_bit(d in design(20, 21)) {
        set_wide_vectors(true);
        let wide_used = wide_vectors();
        // Where the CPU has AVX2 the wide copies are really used (else this compares the baseline
        // with itself).
        #[cfg(target_arch = "x86_64")]
        prop_assert_eq!(wide_used, std::arch::is_x86_feature_detected!("avx2"));
        let wide = all_constructions(&d);
        set_wide_vectors(false);
        prop_assert!(!wide_vectors());
        let baseline = all_constructions(&d);
        set_wide_vectors(true);
        for (w, b) in wide.iter().zip(&baseline) {
            prop_assert_eq!(w, b, "AVX2 used: {}", wide_used);
        }
    }
}
