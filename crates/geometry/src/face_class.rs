//! The configuration class of a cone-net face, from the configurations of its two support-strip
//! quads (paper Sec. 4.2.1, Fig. 5b). A mesh keeps its faces' classes (`QuadGrid::classes`,
//! `PolygonMesh::classes`) through cuts, mirrors, joins and welds, so the legend and the fold
//! finder work on a trimmed, mirrored structure.

use glam::DVec3;

/// The configuration class of a cone-net face (i, j) from the configurations c_{i,j} and c_{i+1,j} of
/// its two support-strip quads (paper Sec. 4.2.1, Fig. 5b).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum FaceClass {
    /// ((++), (++)): convex and properly aligned (the desired case).
    Convex,
    /// ((++), (−−)) or ((−−), (++)): not convex.
    NonConvex,
    /// ((−−), (−−)): convex, but may crease sharply.
    MinusMinus,
    /// (+−) or (−+) involved: the apex lies on the directrix edge (a_{j+1} < 0).
    NegativeApex,
    /// No configuration given (column 0 of the older M−2-label tables).
    Unclassified,
}

impl FaceClass {
    /// Every class, in index order.
    pub const ALL: [FaceClass; 5] = [
        Self::Convex,
        Self::NonConvex,
        Self::MinusMinus,
        Self::NegativeApex,
        Self::Unclassified,
    ];

    /// Index 0 … 4 (the order of [`FaceClass::ALL`]).
    pub fn index(self) -> usize {
        self as usize
    }

    /// A short name: `convex`, `non-convex`, `minus-minus`, `negative-apex`, `unclassified`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Convex => "convex",
            Self::NonConvex => "non-convex",
            Self::MinusMinus => "minus-minus",
            Self::NegativeApex => "negative-apex",
            Self::Unclassified => "unclassified",
        }
    }

    /// Its colour (sRGB, 0–1): calm blue for the desired case, red, orange and purple for the others,
    /// and a pale neutral (the plain surface colour) for faces without configurations.
    pub fn colour(self) -> DVec3 {
        match self {
            Self::Convex => DVec3::new(0.56, 0.71, 0.85),
            Self::NonConvex => DVec3::new(0.85, 0.15, 0.15),
            Self::MinusMinus => DVec3::new(0.95, 0.60, 0.10),
            Self::NegativeApex => DVec3::new(0.55, 0.30, 0.75),
            Self::Unclassified => DVec3::new(0.72, 0.78, 0.84),
        }
    }
}

impl FaceClass {
    /// The class of a face from the signs (s1 > 0, s2 > 0) of its two support-strip quads'
    /// configurations c_{i,j} and c_{i+1,j}.
    pub fn of_signs(a: (bool, bool), b: (bool, bool)) -> Self {
        match (a, b) {
            ((true, false), _) | ((false, true), _) | (_, (true, false)) | (_, (false, true)) => {
                Self::NegativeApex
            }
            ((true, true), (true, true)) => Self::Convex,
            ((false, false), (false, false)) => Self::MinusMinus,
            _ => Self::NonConvex,
        }
    }
}
