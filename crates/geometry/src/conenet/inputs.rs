//! Construction inputs: the three input records (C-tube, CNets Construct, CNets Construct Coplanar)
//! and the broadcast forms of their per-column and per-vertex values.
//!
//! Column values are indexed j = 1 … M−1 (one per directrix edge / construction plane), stored at
//! index `j − 1`. Row values are indexed by the generatrix point i = 0 … N−1.

use glam::DVec3;
use rayon::prelude::*;

use crate::{GeometryError, Polyline};

/// One scalar per directrix column j = 1 … M−1: a single number broadcast to every column, or a list
/// of M−1 numbers.
#[derive(Debug, Clone, PartialEq)]
pub enum ColumnValues {
    /// The same value for every column.
    Uniform(f64),
    /// One value per column j = 1 … M−1 (index j − 1).
    List(Vec<f64>),
}

impl From<f64> for ColumnValues {
    fn from(v: f64) -> Self {
        Self::Uniform(v)
    }
}

impl From<Vec<f64>> for ColumnValues {
    fn from(v: Vec<f64>) -> Self {
        Self::List(v)
    }
}

impl From<&[f64]> for ColumnValues {
    fn from(v: &[f64]) -> Self {
        Self::List(v.to_vec())
    }
}

impl ColumnValues {
    /// Expands to exactly `columns` finite values, failing with a typed error on a wrong length or a
    /// non-finite entry.
    pub fn resolve(&self, what: &'static str, columns: usize) -> Result<Vec<f64>, GeometryError> {
        let values = match self {
            Self::Uniform(v) => vec![*v; columns],
            Self::List(list) => {
                if list.len() != columns {
                    return Err(GeometryError::WrongLength {
                        what,
                        expected: format!("{columns} (one per directrix edge, M − 1)"),
                        got: list.len(),
                    });
                }
                list.clone()
            }
        };
        if let Self::Uniform(v) = self
            && !v.is_finite()
        {
            return Err(GeometryError::NonFinite { what, index: 0 });
        }
        crate::error::check_finite_scalars(what, &values)?;
        Ok(values)
    }
}

/// One scalar per vertex (i, j), j = 1 … M−1: a single number, a list of M−1 numbers shared by all
/// rows, or N lists of M−1 numbers (one list per generatrix point).
#[derive(Debug, Clone, PartialEq)]
pub enum GridValues {
    /// The same value everywhere.
    Uniform(f64),
    /// One value per column j = 1 … M−1, shared by all rows.
    PerColumn(Vec<f64>),
    /// `rows[i][j − 1]`: N lists of M−1 values.
    PerVertex(Vec<Vec<f64>>),
}

impl From<f64> for GridValues {
    fn from(v: f64) -> Self {
        Self::Uniform(v)
    }
}

impl From<Vec<f64>> for GridValues {
    fn from(v: Vec<f64>) -> Self {
        Self::PerColumn(v)
    }
}

impl From<Vec<Vec<f64>>> for GridValues {
    fn from(v: Vec<Vec<f64>>) -> Self {
        Self::PerVertex(v)
    }
}

/// A validated [`GridValues`]: the values of one row as a slice (entry `j − 1` is column j). A
/// per-vertex table is borrowed, not copied.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Grid<'a> {
    /// M−1 values shared by the rows.
    Shared(Vec<f64>),
    /// N lists of M−1 values.
    PerRow(&'a [Vec<f64>]),
}

impl Grid<'_> {
    /// The values of row i (entry `j − 1` is column j = 1 … M−1).
    #[inline]
    pub(crate) fn row(&self, i: usize) -> &[f64] {
        match self {
            Self::Shared(values) => values,
            Self::PerRow(rows) => &rows[i],
        }
    }

    /// The value at row i, column j (1 … M−1).
    #[inline]
    pub(crate) fn get(&self, i: usize, j: usize) -> f64 {
        self.row(i)[j - 1]
    }
}

impl GridValues {
    /// Validates against N rows and M−1 columns and checks every value lies in `[lo, hi]`.
    pub(crate) fn resolve(
        &self,
        what: &'static str,
        rows: usize,
        columns: usize,
        (lo, hi, expected): (f64, f64, &'static str),
    ) -> Result<Grid<'_>, GeometryError> {
        let check = |v: f64, row: Option<usize>, column: usize| -> Result<(), GeometryError> {
            if !v.is_finite() {
                return Err(match row {
                    Some(row) => GeometryError::NonFiniteEntry { what, row, column },
                    None => GeometryError::NonFinite {
                        what,
                        index: column.saturating_sub(1),
                    },
                });
            }
            if !(lo..=hi).contains(&v) {
                return Err(GeometryError::OutOfRange {
                    what,
                    row,
                    column: Some(column),
                    value: v,
                    expected,
                });
            }
            Ok(())
        };
        match self {
            Self::Uniform(v) => {
                check(*v, None, 1)?;
                Ok(Grid::Shared(vec![*v; columns]))
            }
            Self::PerColumn(list) => {
                if list.len() != columns {
                    return Err(GeometryError::WrongLength {
                        what,
                        expected: format!("{columns} (one per directrix edge, M − 1)"),
                        got: list.len(),
                    });
                }
                for (k, v) in list.iter().enumerate() {
                    check(*v, None, k + 1)?;
                }
                Ok(Grid::Shared(list.clone()))
            }
            Self::PerVertex(table) => {
                if table.len() != rows {
                    return Err(GeometryError::WrongLength {
                        what,
                        expected: format!("{rows} lists (one per generatrix point, N)"),
                        got: table.len(),
                    });
                }
                // Rows in parallel (a large table is read once here); the first bad row reports.
                let first_error = table.par_iter().enumerate().find_map_first(|(i, row)| {
                    if row.len() != columns {
                        return Some(GeometryError::WrongRowLength {
                            what,
                            row: i,
                            expected: columns,
                            got: row.len(),
                        });
                    }
                    // Cheap test first, the error (and its column) only for a bad row.
                    if row.iter().all(|v| (lo..=hi).contains(v)) {
                        return None;
                    }
                    row.iter()
                        .enumerate()
                        .find_map(|(k, v)| check(*v, Some(i), k + 1).err())
                });
                match first_error {
                    Some(e) => Err(e),
                    None => Ok(Grid::PerRow(table)),
                }
            }
        }
    }
}

/// Construction-plane normals for the C-tube construction.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum NormalsInput {
    /// Default Monge (bisecting) planes (notes §2).
    #[default]
    Monge,
    /// One normal per column j = 1 … M−1, shared by all rows.
    PerColumn(Vec<DVec3>),
    /// `rows[i][j − 1]`: N lists of M−1 normals.
    PerVertex(Vec<Vec<DVec3>>),
}

impl From<Vec<DVec3>> for NormalsInput {
    fn from(v: Vec<DVec3>) -> Self {
        Self::PerColumn(v)
    }
}

impl From<Vec<Vec<DVec3>>> for NormalsInput {
    fn from(v: Vec<Vec<DVec3>>) -> Self {
        Self::PerVertex(v)
    }
}

/// How the construction plane at an end vertex of an open directrix is chosen, where no outgoing
/// edge exists (a closed directrix has no ends).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EndPlanes {
    /// The plane at X_{M−1} is perpendicular to the last edge (the C-tubes code's choice).
    #[default]
    Perpendicular,
    /// The plane at X_{M−1} is the plane at X_{M−2} reflected in the perpendicular bisector plane of
    /// the last edge: on a circular arc that is the meridian plane. With M = 2 there is no plane at
    /// X_0 to reflect and the perpendicular plane is used (it is its own mirror image).
    Mirror,
}

impl EndPlanes {
    /// The choices as the nodes spell them.
    pub const NAMES: [&'static str; 2] = ["perpendicular", "mirror"];

    /// Parses `"perpendicular"` or `"mirror"` (ASCII case-insensitive, surrounding spaces ignored).
    pub fn parse(text: &str) -> Option<Self> {
        let t = text.trim();
        if t.eq_ignore_ascii_case("perpendicular") {
            Some(Self::Perpendicular)
        } else if t.eq_ignore_ascii_case("mirror") {
            Some(Self::Mirror)
        } else {
            None
        }
    }
}

/// The apex-locating function as given by the user: values, whether they are normalized (§5), and
/// the normalization scale L.
#[derive(Debug, Clone, PartialEq)]
pub struct ApexInput {
    /// a_j (or ā_j when normalized) for j = 1 … M−1.
    pub values: ColumnValues,
    /// Whether `values` is the normalized apex function ā (paper Sec. 4.3).
    pub normalized: bool,
    /// The scale L of the normalization; `None` = directrix length / 5.
    pub scale: Option<f64>,
    /// The apex the first strip must share (a net continuing another across a seam): a_1 is set
    /// so, overriding the value given ([`super::seam_apex`]); `None` = as given.
    pub seam: Option<glam::DVec3>,
}

impl Default for ApexInput {
    fn default() -> Self {
        Self {
            values: ColumnValues::Uniform(1.0),
            normalized: false,
            scale: None,
            seam: None,
        }
    }
}

/// Inputs of the base C-tube construction (`ctube.construct`).
#[derive(Debug, Clone, PartialEq)]
pub struct CtubeInputs {
    /// The directrix X (open, or closed: swept once around).
    pub directrix: Polyline,
    /// The generatrix G_{:,0} (closed ⇒ the mesh wraps in the row direction).
    pub generatrix: Polyline,
    /// The apex-locating function.
    pub apex: ApexInput,
    /// Construction-plane normals (default: Monge planes).
    pub normals: NormalsInput,
    /// The default plane at the directrix's last vertex (used by Monge normals only).
    pub end_planes: EndPlanes,
}

impl CtubeInputs {
    /// Inputs with default apex (a ≡ 1) and default Monge planes.
    pub fn new(directrix: Polyline, generatrix: Polyline) -> Self {
        Self {
            directrix,
            generatrix,
            apex: ApexInput::default(),
            normals: NormalsInput::Monge,
            end_planes: EndPlanes::Perpendicular,
        }
    }

    /// Sets the plane normals (builder style).
    pub fn normals(mut self, normals: impl Into<NormalsInput>) -> Self {
        self.normals = normals.into();
        self
    }
}

/// The assisted-correction settings shared by both CNets constructions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Assistance {
    /// α: negative = off, 0 = planes only, 1 = apex only, between = hybrid.
    pub alpha: f64,
    /// ε ∈ (0, 1): safety margin of every fix.
    pub epsilon: f64,
}

impl Default for Assistance {
    fn default() -> Self {
        Self {
            alpha: -1.0,
            epsilon: 0.01,
        }
    }
}

impl Assistance {
    /// Assistance α with the default ε = 0.01.
    pub fn new(alpha: f64) -> Self {
        Self {
            alpha,
            ..Self::default()
        }
    }

    /// Whether the correction is enabled (α ≥ 0).
    pub fn enabled(&self) -> bool {
        self.alpha >= 0.0
    }

    /// Checks α is finite and ≤ 1 and ε ∈ (0, 1).
    pub fn validate(&self) -> Result<(), GeometryError> {
        if !self.alpha.is_finite() || self.alpha > 1.0 {
            return Err(GeometryError::InvalidParameter {
                what: "assistance",
                value: self.alpha,
                expected: "a finite number ≤ 1 (negative disables the correction)",
            });
        }
        if !(self.epsilon > 0.0 && self.epsilon < 1.0) {
            return Err(GeometryError::InvalidParameter {
                what: "epsilon",
                value: self.epsilon,
                expected: "a number in (0, 1)",
            });
        }
        Ok(())
    }
}

/// Inputs of CNets Construct (`cnets.construct`): ratios pick the rulings of the support strips.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstructInputs {
    /// The directrix X.
    pub directrix: Polyline,
    /// The generatrix G_{:,0}.
    pub generatrix: Polyline,
    /// The apex-locating function.
    pub apex: ApexInput,
    /// Ratios r_{i,j} ∈ [0, 1] (default ½ = Monge).
    pub ratios: GridValues,
    /// Assisted correction (default off).
    pub assistance: Assistance,
    /// The bisecting plane and outgoing edge at the directrix's last vertex.
    pub end_planes: EndPlanes,
}

impl ConstructInputs {
    /// Inputs with a ≡ 1, ratios ½, assistance off, ε = 0.01.
    pub fn new(directrix: Polyline, generatrix: Polyline) -> Self {
        Self {
            directrix,
            generatrix,
            apex: ApexInput::default(),
            ratios: GridValues::Uniform(0.5),
            assistance: Assistance::default(),
            end_planes: EndPlanes::Perpendicular,
        }
    }

    /// Sets the ratios (builder style).
    pub fn ratios(mut self, ratios: impl Into<GridValues>) -> Self {
        self.ratios = ratios.into();
        self
    }
}

/// Inputs of CNets Construct Coplanar (`cnets.construct_coplanar`): one ruling ratio and one
/// plane-rotation ratio per column; every generatrix-aligned polyline is planar.
#[derive(Debug, Clone, PartialEq)]
pub struct CoplanarInputs {
    /// The directrix X.
    pub directrix: Polyline,
    /// The generatrix G_{:,0}.
    pub generatrix: Polyline,
    /// The apex-locating function.
    pub apex: ApexInput,
    /// Ruling ratios ρ_j ∈ [0, 1] of support strip 0 (default ½).
    pub ruling_ratios: ColumnValues,
    /// Plane-rotation ratios τ_j ∈ [0, 1] (default ½).
    pub plane_ratios: ColumnValues,
    /// Assisted correction (default off).
    pub assistance: Assistance,
    /// The bisecting plane and outgoing edge at the directrix's last vertex.
    pub end_planes: EndPlanes,
}

impl CoplanarInputs {
    /// Inputs with a ≡ 1, ρ = τ = ½, assistance off, ε = 0.01.
    pub fn new(directrix: Polyline, generatrix: Polyline) -> Self {
        Self {
            directrix,
            generatrix,
            apex: ApexInput::default(),
            ruling_ratios: ColumnValues::Uniform(0.5),
            plane_ratios: ColumnValues::Uniform(0.5),
            assistance: Assistance::default(),
            end_planes: EndPlanes::Perpendicular,
        }
    }

    /// Sets the ruling ratios ρ (builder style).
    pub fn ruling_ratios(mut self, values: impl Into<ColumnValues>) -> Self {
        self.ruling_ratios = values.into();
        self
    }

    /// Sets the plane-rotation ratios τ (builder style).
    pub fn plane_ratios(mut self, values: impl Into<ColumnValues>) -> Self {
        self.plane_ratios = values.into();
        self
    }
}

/// Builder methods for the apex function, shared by the three input records.
macro_rules! apex_builders {
    ($($t:ty),*) => {$(
        impl $t {
            /// Sets the apex values (builder style).
            pub fn apex(mut self, values: impl Into<ColumnValues>) -> Self {
                self.apex.values = values.into();
                self
            }

            /// Marks the apex values as normalized, with an optional scale L (builder style).
            pub fn normalized(mut self, normalized: bool, scale: Option<f64>) -> Self {
                self.apex.normalized = normalized;
                self.apex.scale = scale;
                self
            }
        }
    )*};
}

/// Builder methods for the assisted correction, shared by both CNets constructions.
macro_rules! assistance_builders {
    ($($t:ty),*) => {$(
        impl $t {
            /// Sets the assistance α (builder style).
            pub fn assistance(mut self, alpha: f64) -> Self {
                self.assistance.alpha = alpha;
                self
            }

            /// Sets ε (builder style).
            pub fn epsilon(mut self, epsilon: f64) -> Self {
                self.assistance.epsilon = epsilon;
                self
            }
        }
    )*};
}

/// The end-plane builder, shared by the three input records.
macro_rules! end_plane_builders {
    ($($t:ty),*) => {$(
        impl $t {
            /// Sets the end-plane choice (builder style).
            pub fn end_planes(mut self, end_planes: EndPlanes) -> Self {
                self.end_planes = end_planes;
                self
            }
        }
    )*};
}

end_plane_builders!(CtubeInputs, ConstructInputs, CoplanarInputs);
apex_builders!(CtubeInputs, ConstructInputs, CoplanarInputs);
assistance_builders!(ConstructInputs, CoplanarInputs);

/// Checks a list of ratios lies in `[0, 1]` (per column).
pub(crate) fn check_unit_interval(what: &'static str, values: &[f64]) -> Result<(), GeometryError> {
    for (k, &v) in values.iter().enumerate() {
        if !(0.0..=1.0).contains(&v) {
            return Err(GeometryError::OutOfRange {
                what,
                row: None,
                column: Some(k + 1),
                value: v,
                expected: "a value in [0, 1]",
            });
        }
    }
    Ok(())
}
