//! The constructions give the same bits on any number of threads and on every run: rows are swept
//! independently, corrections are ordered by a fixed key, and the quality pass sums its floats in
//! fixed blocks merged in order (a work-stealing reduction once made `mean_planarity` differ in
//! its last bit between runs).

use crate::common;

use common::{all_constructions, design};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(60))]

    #[test]
    fn results_do_not_depend_on_threads_or_scheduling(d in design(40, 21)) {
        let on = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("a thread pool")
                .install(|| all_constructions(&d))
        };
        let one = on(1);
        for threads in [2, 3, 2, 5] {
            let other = on(threads);
            for (a, b) in one.iter().zip(&other) {
                prop_assert_eq!(a, b, "{} threads", threads);
            }
        }
    }
}
