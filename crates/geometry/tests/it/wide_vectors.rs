//! The AVX-512 and AVX2 copies of the hot loops (`cnets_geometry::simd`) give bit-for-bit the
//! results of the baseline copies: every construction, with and without assistance, over random designs large
//! enough for full lane groups (8 rows, 8 strips) and partial ones, including designs whose wide
//! ratios trigger corrections and errors.

use crate::common;

use cnets_geometry::simd::{avx512_vectors, set_avx512, set_wide_vectors, wide_vectors};
use common::{all_constructions, design};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn wide_and_baseline_copies_agree_bit_for_bit(d in design(20, 21)) {
        set_wide_vectors(true);
        set_avx512(true);
        let widest_used = avx512_vectors();
        // Where the CPU has AVX-512 (F, DQ, VL) the widest copies are really used.
        #[cfg(target_arch = "x86_64")]
        prop_assert_eq!(
            widest_used,
            std::arch::is_x86_feature_detected!("avx512f")
                && std::arch::is_x86_feature_detected!("avx512dq")
                && std::arch::is_x86_feature_detected!("avx512vl")
        );
        let widest = all_constructions(&d);
        set_avx512(false);
        prop_assert!(!avx512_vectors());
        let wide_used = wide_vectors();
        // Where the CPU has AVX2 the AVX2 copies are really used (else this compares the baseline
        // with itself).
        #[cfg(target_arch = "x86_64")]
        prop_assert_eq!(wide_used, std::arch::is_x86_feature_detected!("avx2"));
        let wide = all_constructions(&d);
        set_wide_vectors(false);
        prop_assert!(!wide_vectors() && !avx512_vectors());
        let baseline = all_constructions(&d);
        set_wide_vectors(true);
        set_avx512(true);
        for ((x, w), b) in widest.iter().zip(&wide).zip(&baseline) {
            prop_assert_eq!(x, w, "AVX-512 used: {}", widest_used);
            prop_assert_eq!(w, b, "AVX2 used: {}", wide_used);
        }
    }
}
