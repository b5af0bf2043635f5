//! Adjoints of the construction kernels (`cnets_geometry::conenet::adjoint`).

use cnets_engine::optimize::vjp::{VjpArgs, VjpResult};

type Product = fn(&VjpArgs<'_>) -> VjpResult;

/// The product of a construction node, by id.
pub fn product(_id: &str) -> Option<Product> {
    None
}
