//! What the process has allocated, when a front end counts it.
//!
//! The engine does not choose the global allocator; a binary that wants every allocation counted
//! wraps its allocator in a counter (the `cnets` binary: `cap::Cap<MiMalloc>`, a well-kept crate,
//! so no allocator code of our own) and registers a probe here once. Without a probe (tests, a
//! library embedding the engine) [`allocated`] is `None` and the checks count the values held.

use std::sync::OnceLock;

static PROBE: OnceLock<fn() -> u64> = OnceLock::new();

/// Registers the function that reads the process's allocated bytes (first registration wins).
pub fn set_allocated_probe(probe: fn() -> u64) {
    let _ = PROBE.set(probe);
}

/// The bytes the process has allocated now, when a probe is registered.
pub fn allocated() -> Option<u64> {
    PROBE.get().map(|probe| probe())
}
