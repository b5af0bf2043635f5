//! Runtime choice of the instruction set for the hot lane loops.
//!
//! The lane code ([`crate::conenet`]'s sweep and quality pass) is plain loops over groups of 8
//! doubles. Compiled for the x86-64 baseline they become SSE2 instructions (2 doubles each); the
//! same source compiled with AVX2 enabled uses 4 doubles an instruction. [`run`] runs a closure
//! through a copy compiled with AVX2 when the CPU has it (checked once, then cached by `std`), and
//! through the baseline copy otherwise. FMA stays off: without fused multiply-adds both copies
//! round every operation identically, so results are bit for bit the same on every x86-64 CPU
//! (tested).
//!
//! This module holds the crate's only `unsafe`: calling a `#[target_feature]` function is unsafe
//! because it is undefined on a CPU without the feature, and the call is made only after
//! `is_x86_feature_detected!` confirmed it.

use std::sync::atomic::{AtomicBool, Ordering};

/// Whether [`run`] may use AVX2 (true unless [`set_wide_vectors`] turned it off).
static WIDE_VECTORS: AtomicBool = AtomicBool::new(true);

/// Allows (`true`, the default) or forbids the AVX2 copies of the hot loops, process-wide. The
/// results do not depend on it, only the speed; it exists to compare the two copies.
pub fn set_wide_vectors(enabled: bool) {
    WIDE_VECTORS.store(enabled, Ordering::Relaxed);
}

/// Whether the hot loops run their AVX2 copies on this CPU now.
pub fn wide_vectors() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        WIDE_VECTORS.load(Ordering::Relaxed) && std::arch::is_x86_feature_detected!("avx2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Runs `f`, compiled with AVX2 when [`wide_vectors`] holds. Pass an `#[inline(always)]` closure
/// whose callees are inlined too: only code inlined into it is compiled for AVX2.
#[inline(always)]
pub(crate) fn run<R>(f: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    if wide_vectors() {
        // SAFETY: `wide_vectors` returned true only after `is_x86_feature_detected!("avx2")`
        // confirmed that this CPU executes AVX2 instructions.
        #[allow(unsafe_code)]
        return unsafe { with_avx2(f) };
    }
    f()
}

/// `f()` in a function compiled with AVX2 enabled (see [`run`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn with_avx2<R>(f: impl FnOnce() -> R) -> R {
    f()
}
