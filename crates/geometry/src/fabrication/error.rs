//! Typed errors of the fabrication tools. Each variant names the offending indices; errors of the
//! kernel's own checks (non-finite points, grid sizes, …) are wrapped unchanged.

use thiserror::Error;

use crate::GeometryError;

/// Everything that can go wrong in the supplementary and fabrication tools.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum FabricationError {
    /// A check of the geometry kernel failed (non-finite point, wrong grid size, bad face, …).
    #[error(transparent)]
    Geometry(#[from] GeometryError),
    /// The input mesh (or list) has nothing to work on.
    #[error("{0} is empty")]
    Empty(&'static str),
    /// The caller asked to stop (a newer edit supersedes the work).
    #[error("cancelled")]
    Cancelled,
    /// A grid is too small for the operation.
    #[error("{what} needs at least {needed} {unit}, got {got}")]
    TooSmall {
        /// Which input.
        what: &'static str,
        /// Minimum count.
        needed: usize,
        /// What is counted (rows, columns, points).
        unit: &'static str,
        /// Actual count.
        got: usize,
    },
    /// The directrix does not match the mesh: it must have one point per mesh column.
    #[error(
        "the directrix has {points} points ({swept} as swept), but the mesh has {columns} columns: give the directrix the mesh was built from"
    )]
    DirectrixMismatch {
        /// Stored points of the directrix.
        points: usize,
        /// Points as swept (a closed directrix repeats its first point).
        swept: usize,
        /// Columns of the mesh.
        columns: usize,
    },
    /// A width of the outline graph is not a positive finite number.
    #[error("width y_{index} is {value}: widths must be finite and > 0")]
    BadWidth {
        /// Index j of the width.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// A panel of a strip is longer than the pieces a strip is split into may be.
    #[error(
        "{strip} panel {panel} is {length} long on its own, more than max_length {max_length}: pieces are cut at folds, raise max_length"
    )]
    PanelTooLong {
        /// The strip's short name.
        strip: String,
        /// The panel, in strip order.
        panel: usize,
        /// Its length (the long side of its minimum-area rectangle).
        length: f64,
        /// The asked maximum.
        max_length: f64,
    },
    /// A scalar parameter is out of range.
    #[error("{what} is {value}, expected {expected}")]
    BadParameter {
        /// Which parameter.
        what: &'static str,
        /// The offending value.
        value: f64,
        /// The admissible range, in words.
        expected: &'static str,
    },
    /// An entry of a per-edge list is out of range.
    #[error("{what}[{index}] is {value}, expected {expected}")]
    BadEntry {
        /// Which list.
        what: &'static str,
        /// Index in the list.
        index: usize,
        /// The offending value.
        value: f64,
        /// The admissible range, in words.
        expected: &'static str,
    },
    /// The node axis of vertex (i, j) is undefined: the vertex lies on the directrix point X_j.
    #[error(
        "node axis at row {row}, column {column} is undefined: G_{{{row},{column}}} coincides with X_{column}"
    )]
    DegenerateAxis {
        /// Row i.
        row: usize,
        /// Column j.
        column: usize,
    },
    /// Two lines that should meet in one point are parallel (or one has no direction): the new vertex
    /// (i, j) of a derived layer is undefined.
    #[error("{what}: vertex at row {row}, column {column} is undefined: {reason}")]
    NoIntersection {
        /// Which tool.
        what: &'static str,
        /// Row i of the vertex being built.
        row: usize,
        /// Column j of the vertex being built.
        column: usize,
        /// Why, in words.
        reason: &'static str,
    },
    /// The inputs do not belong together: the mesh is not the construction of this directrix and apex
    /// function (the line from a vertex towards its cone apex misses the next node axis).
    #[error(
        "{what}: at row {row}, column {column} the mesh does not follow the directrix and apex values (the line towards the cone apex misses the node axis by {residual:.3e}, relative); give the directrix, mesh and apex of one construction"
    )]
    Inconsistent {
        /// Which tool.
        what: &'static str,
        /// Row i.
        row: usize,
        /// Column j.
        column: usize,
        /// Distance between the two lines relative to the mesh size.
        residual: f64,
    },
    /// A mesh edge has (almost) zero length where a direction is needed.
    #[error("{what}: the mesh edge from ({row}, {column}) to ({row2}, {column2}) has zero length")]
    ZeroEdge {
        /// Which tool.
        what: &'static str,
        /// Row of the first vertex.
        row: usize,
        /// Column of the first vertex.
        column: usize,
        /// Row of the second vertex.
        row2: usize,
        /// Column of the second vertex.
        column2: usize,
    },
    /// A face of a strip to unroll is not planar within the tolerance.
    #[error(
        "strip {strip}, quad {quad} (mesh quad at row {row}, column {column}) is not planar: planarity {planarity:.3e} > tolerance {tolerance:.3e}; unrolling would distort it (raise `tolerance` to unroll anyway and read max_length_error)"
    )]
    NonPlanarFace {
        /// Strip index.
        strip: usize,
        /// Quad index along the strip.
        quad: usize,
        /// Mesh quad row i.
        row: usize,
        /// Mesh quad column j.
        column: usize,
        /// Its planarity (libigl measure).
        planarity: f64,
        /// The tolerance it exceeds.
        tolerance: f64,
    },
    /// A face of a polygon-mesh strip to unroll is not planar within the tolerance.
    #[error(
        "strip {strip}, mesh face {face} is not planar: planarity {planarity:.3e} > tolerance {tolerance:.3e}; unrolling would distort it (raise `tolerance` to unroll anyway and read max_length_error)"
    )]
    NonPlanarPolygon {
        /// Strip number.
        strip: usize,
        /// Mesh face index.
        face: usize,
        /// Its planarity (`polygon_planarity`).
        planarity: f64,
        /// The tolerance it exceeds.
        tolerance: f64,
    },
    /// A face is degenerate (no area, no normal) where the operation needs one.
    #[error("{what}: face {face} is degenerate ({reason})")]
    DegenerateFace {
        /// Which tool.
        what: &'static str,
        /// Face index (for strips: the quad index along the strip, see the message).
        face: usize,
        /// Why, in words.
        reason: String,
    },
    /// A configuration label is not one of `++`, `--`, `+-`, `-+`.
    #[error("configuration at row {row}, column {column} is '{label}', expected ++, --, +- or -+")]
    BadLabel {
        /// Row i.
        row: usize,
        /// Column j (0 … M−2).
        column: usize,
        /// The offending label.
        label: String,
    },
    /// A list of per-item values has the wrong length.
    #[error("{what} has {got} entries, expected {expected}")]
    WrongLength {
        /// Which list.
        what: &'static str,
        /// Expected length, in words.
        expected: String,
        /// Actual length.
        got: usize,
    },
    /// The nesting engine (jagua-rs) rejected an input, or an outline does not fit on a sheet.
    #[error("nesting: {0}")]
    Nesting(String),
    /// An unknown option name.
    #[error("{what} '{value}' is unknown: expected {expected}")]
    UnknownOption {
        /// Which option.
        what: &'static str,
        /// What was given.
        value: String,
        /// The accepted values.
        expected: &'static str,
    },
}

impl FabricationError {
    /// A [`FabricationError::BadParameter`] unless `value` is finite.
    pub(crate) fn check_finite(
        what: &'static str,
        value: f64,
        expected: &'static str,
    ) -> Result<(), Self> {
        if value.is_finite() {
            Ok(())
        } else {
            Err(Self::BadParameter {
                what,
                value,
                expected,
            })
        }
    }
}
