//! Runtime choice of the instruction set for the hot lane loops.
//!
//! The lane code ([`crate::conenet`]'s sweep and quality pass) is plain loops over groups of 8
//! doubles. Compiled for the x86-64 baseline they become SSE2 instructions (2 doubles each); the
//! same source compiled with AVX2 enabled uses 4 doubles an instruction, and with AVX-512 one
//! instruction holds a whole group of 8. [`run`] runs a closure through the widest copy the CPU
//! executes (checked once, then cached by `std`). No copy fuses multiplies and adds (Rust never
//! contracts `a * b + c` into an FMA on its own), so every copy rounds every operation identically
//! and the results are bit for bit the same on every x86-64 CPU (tested).
//!
//! This module holds the crate's only `unsafe`: calling a `#[target_feature]` function is unsafe
//! because it is undefined on a CPU without the feature, and each call is made only after
//! `is_x86_feature_detected!` confirmed it.

use std::sync::atomic::{AtomicBool, Ordering};

/// Whether [`run`] may use AVX2 or wider (true unless [`set_wide_vectors`] turned it off).
static WIDE_VECTORS: AtomicBool = AtomicBool::new(true);
/// Whether [`run`] may use AVX-512 (true unless [`set_avx512`] turned it off).
static AVX512: AtomicBool = AtomicBool::new(true);

/// Allows (`true`, the default) or forbids the AVX2 and AVX-512 copies of the hot loops,
/// process-wide. The results do not depend on it, only the speed; it exists to compare the copies.
pub fn set_wide_vectors(enabled: bool) {
    WIDE_VECTORS.store(enabled, Ordering::Relaxed);
}

/// Allows (`true`, the default) or forbids the AVX-512 copies alone (AVX2 is then the widest).
pub fn set_avx512(enabled: bool) {
    AVX512.store(enabled, Ordering::Relaxed);
}

/// Whether the hot loops run an AVX2 or AVX-512 copy on this CPU now.
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

/// Whether the hot loops run their AVX-512 copies on this CPU now.
pub fn avx512_vectors() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        wide_vectors()
            && AVX512.load(Ordering::Relaxed)
            && std::arch::is_x86_feature_detected!("avx512f")
            && std::arch::is_x86_feature_detected!("avx512dq")
            && std::arch::is_x86_feature_detected!("avx512vl")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Runs `f`, compiled with AVX-512 or AVX2 when [`avx512_vectors`] or [`wide_vectors`] holds.
/// Pass an `#[inline(always)]` closure whose callees are inlined too: only code inlined into it is
/// compiled for the wider instruction sets.
#[inline(always)]
pub(crate) fn run<R>(f: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    {
        if avx512_vectors() {
            // SAFETY: `avx512_vectors` returned true only after `is_x86_feature_detected!`
            // confirmed that this CPU executes AVX-512 F, DQ and VL instructions.
            #[allow(unsafe_code)]
            return unsafe { with_avx512(f) };
        }
        if wide_vectors() {
            // SAFETY: `wide_vectors` returned true only after `is_x86_feature_detected!("avx2")`
            // confirmed that this CPU executes AVX2 instructions.
            #[allow(unsafe_code)]
            return unsafe { with_avx2(f) };
        }
    }
    f()
}

/// `f()` in a function compiled with AVX2 enabled (see [`run`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn with_avx2<R>(f: impl FnOnce() -> R) -> R {
    f()
}

/// `f()` in a function compiled with AVX-512 enabled (see [`run`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512dq,avx512vl")]
fn with_avx512<R>(f: impl FnOnce() -> R) -> R {
    f()
}
