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
    /// One row of a nested list (N lists of M−1 values) has the wrong length.
    #[error("{what}: row {row} has {got} entries, expected {expected}")]
    WrongRowLength {
        /// Which list.
        what: &'static str,
        /// The offending row (generatrix index i).
        row: usize,
        /// Expected length.
        expected: usize,
        /// Actual length.
        got: usize,
    },
    /// An entry of a per-vertex input (row i, column j) is NaN or infinite.
    #[error("{what} at row {row}, column {column} is not finite")]
    NonFiniteEntry {
        /// Which input.
        what: &'static str,
        /// Row (generatrix index i).
        row: usize,
        /// Column (directrix index j).
        column: usize,
    },
    /// A scalar input lies outside its admissible range.
    #[error("{what}{} is {value}, expected {expected}", location(*.row, *.column))]
    OutOfRange {
        /// Which input.
        what: &'static str,
        /// Row, when the input is per vertex.
        row: Option<usize>,
        /// Column, when the input is per column or per vertex.
        column: Option<usize>,
        /// The offending value.
        value: f64,
        /// The admissible range, in words.
        expected: &'static str,
    },
    /// A single parameter (ε, assistance, scale L, …) is invalid.
    #[error("invalid {what}: {value} (expected {expected})")]
    InvalidParameter {
        /// Which parameter.
        what: &'static str,
        /// The offending value.
        value: f64,
        /// The admissible range, in words.
        expected: &'static str,
    },
    /// The default (bisecting) plane at directrix vertex `column` is undefined because the directrix
    /// turns back on itself there (ê_j + ê_{j+1} = 0).
    #[error(
        "the bisecting plane at directrix vertex {column} is undefined: the directrix reverses direction there"
    )]
    DirectrixReverses {
        /// Directrix vertex index j.
        column: usize,
    },
    /// A construction plane (almost) contains the incoming directrix edge (P·ê_j ≈ 0), so it cannot be
    /// oriented and the strip degenerates.
    #[error(
        "construction plane{} contains the incoming directrix edge {column} (P·e ≈ 0)",
        location(*.row, Some(*.column))
    )]
    PlaneContainsEdge {
        /// Row (generatrix index i); `None` for a plane shared by all rows.
        row: Option<usize>,
        /// Column j of the plane Π_{i,j}.
        column: usize,
    },
    /// A construction-plane normal is (almost) the zero vector.
    #[error("construction-plane normal{} is a zero-length vector", location(*.row, Some(*.column)))]
    ZeroNormal {
        /// Row, when normals are given per vertex.
        row: Option<usize>,
        /// Column j of the plane.
        column: usize,
    },
    /// A construction step is degenerate: the direction V is (almost) parallel to the construction
    /// plane (|V·P| ≤ 1e-12 |V||P|), or V vanishes because the previous vertex is the cone apex.
    #[error(
        "construction step at row {row}, column {column} is degenerate: the direction V is parallel to the construction plane (V·P ≈ 0)"
    )]
    ParallelStep {
        /// Row (generatrix index i).
        row: usize,
        /// Column j of the vertex being constructed.
        column: usize,
    },
    /// The support plane through X_{j−1}, X_j and G_{i,j−1} is undefined because G_{i,j−1} lies on the
    /// line of directrix edge j (needed by the ratio and coplanar constructions).
    #[error(
        "support plane at row {row}, column {column} is undefined: vertex ({row}, {}) lies on the line of directrix edge {column}",
        .column - 1
    )]
    DegenerateSupport {
        /// Row (generatrix index i).
        row: usize,
        /// Column j of the plane being built.
        column: usize,
    },
    /// A computed value overflowed (is not finite).
    #[error("{what} at row {row}, column {column} is not finite (overflow or degenerate input)")]
    NonFiniteOutput {
        /// Which output.
        what: &'static str,
        /// Row.
        row: usize,
        /// Column.
        column: usize,
    },
    /// The apex fix of the assisted correction needs a non-positive apex value: no valid configuration
    /// can be reached at this column (paper, Appendix A).
    #[error(
        "assisted correction impossible at column {column}: the apex fix needs a = {value}, which is not positive; change the construction inputs"
    )]
    ApexFixImpossible {
        /// Column j0 whose apex value a_{j0} would have to change.
        column: usize,
        /// The apex value a' the fix computed.
        value: f64,
    },
    /// The assisted correction did not reach a valid configuration at this column.
    #[error("assisted correction did not converge at column {column}")]
    CorrectionFailed {
        /// Column j0 of the bad configuration.
        column: usize,
    },
    /// The mesh handed to the encoder is not a cone-net: the edges of a strip miss a common point.
    #[error(
        "mesh is not a cone-net: the edges of strip {column} (between columns {column} and {}) miss a common point by {residual:.3e} (relative)",
        .column + 1
    )]
    NotAConeNet {
        /// Strip index j (columns j and j+1).
        column: usize,
        /// Relative concurrency residual.
        residual: f64,
    },
    /// The operation does not support this mesh layout.
    #[error("unsupported mesh: {0}")]
    Unsupported(&'static str),
}

/// Formats an optional (row, column) location as `" at row i, column j"`.
fn location(row: Option<usize>, column: Option<usize>) -> String {
    match (row, column) {
        (Some(i), Some(j)) => format!(" at row {i}, column {j}"),
        (None, Some(j)) => format!(" at column {j}"),
        (Some(i), None) => format!(" at row {i}"),
        (None, None) => String::new(),
    }
}

/// Checks that every component of every point is finite.
pub fn check_finite_points(
    what: &'static str,
    points: &[glam::DVec3],
) -> Result<(), GeometryError> {
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
