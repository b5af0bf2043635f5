//! Typed errors of the geometry kernel.

use thiserror::Error;

/// Everything that can go wrong in the geometry kernel. Each variant names the offending indices.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum GeometryError {
    /// A coordinate or scalar is NaN or infinite.
    #[error("{what} is not finite (at index {index})")]
    NonFinite {
        /// What kind of input held the bad value.
        what: &'static str,
        /// Index of the offending item.
        index: usize,
    },
    /// Two consecutive points coincide, so an edge has zero length.
    #[error("{what} has a zero-length edge between points {index} and {next}")]
    ZeroLengthEdge {
        /// Which polyline.
        what: &'static str,
        /// First point of the edge.
        index: usize,
        /// Second point of the edge.
        next: usize,
    },
    /// Not enough points for the operation.
    #[error("{what} needs at least {needed} points, got {got}")]
    TooFewPoints {
        /// Which polyline.
        what: &'static str,
        /// Minimum count.
        needed: usize,
        /// Actual count.
        got: usize,
    },
    /// A list has the wrong length.
    #[error("{what} has {got} entries, expected {expected}")]
    WrongLength {
        /// Which list.
        what: &'static str,
        /// Expected length (or a description of it).
        expected: String,
        /// Actual length.
        got: usize,
    },
    /// A grid's vertex count does not match rows × cols.
    #[error("quad grid of {rows} × {cols} needs {expected} vertices, got {got}")]
    GridSize {
        /// Row count.
        rows: usize,
        /// Column count.
        cols: usize,
        /// rows × cols.
        expected: usize,
        /// Actual vertex count.
        got: usize,
    },
    /// A vector that must have a direction has (almost) zero length.
    #[error("{what} is a zero-length vector")]
    ZeroVector {
        /// Which vector.
        what: &'static str,
    },
    /// A face refers to a vertex that does not exist, or has fewer than three corners.
    #[error("face {face} is invalid: {reason}")]
    InvalidFace {
        /// Face index.
        face: usize,
        /// What is wrong with it.
        reason: String,
    },
    /// A generic degenerate configuration, described in words, with the offending location.
    #[error("degenerate input: {0}")]
    Degenerate(String),
}

/// Checks that every component of every point is finite.
pub fn check_finite_points(what: &'static str, points: &[glam::DVec3]) -> Result<(), GeometryError> {
    match points.iter().position(|p| !p.is_finite()) {
        Some(index) => Err(GeometryError::NonFinite { what, index }),
        None => Ok(()),
    }
}

/// Checks that every scalar is finite.
pub fn check_finite_scalars(what: &'static str, values: &[f64]) -> Result<(), GeometryError> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(GeometryError::NonFinite { what, index }),
        None => Ok(()),
    }
}
