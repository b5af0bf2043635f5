//! Configuration classification (paper Sec. 4.2.1, notes §6):
//! `s1 = (G_{i,j+1} − X_j)·P_{i,j}`, `s2 = (X_{j+1} − G_{i,j})·P_{i,j+1}`, for every support-strip quad
//! j = 0 … M−2. The first quad has no construction plane Π_{i,0}: its s1 is the analogous test against
//! the generatrix, `P_{i,0}` being the normal of the plane through X_0 and G_{i,0} perpendicular to the
//! support plane, `ê_1 − (ê_1·ŵ)ŵ` with `ŵ = unit(G_{i,0} − X_0)` ([`generatrix_normal`]); its s2 is
//! Eq. (2) at j = 0.

use std::fmt;
use std::ops::Range;

use glam::DVec3;

use super::lanes::{F, LANES};
use crate::{FaceClass, QuadGrid};

/// The stand-in for the missing plane Π_{i,0} in the first configuration c_{i,0}: the unit normal of
/// the plane through `x0` = X_0 and `g` = G_{i,0} perpendicular to the support plane of strip i,
/// oriented towards `e` = ê_1 (`ê_1 − (ê_1·ŵ)ŵ`, ŵ = unit(g − x0)). Every plane through the line
/// X_0 G_{i,0} gives the same sign to the points of the (planar) support strip, so the test is the
/// paper's s1 against the generatrix ruling. ê_1 when g lies on the directrix line.
#[inline]
pub fn generatrix_normal(x0: DVec3, e: DVec3, g: DVec3) -> DVec3 {
    let d = g - x0;
    let dd = d.length_squared();
    if !(dd > 0.0 && dd.is_finite()) {
        return e;
    }
    let n = e - d * (e.dot(d) / dd);
    let nn = n.length_squared();
    if nn > 1e-24 && nn.is_finite() {
        n / nn.sqrt()
    } else {
        e
    }
}

/// The configuration c_{i,j} of support-strip quad (i, j) from the signs of s1 and s2.
/// A sign is `+` when the value is strictly positive, `−` otherwise (zero counts as `−`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, bytemuck::Zeroable)]
#[repr(u8)]
pub enum Configuration {
    /// s1 > 0 and s2 > 0: convex, properly oriented (the desired case).
    #[default]
    PlusPlus,
    /// s1 ≤ 0 and s2 ≤ 0.
    MinusMinus,
    /// s1 > 0 and s2 ≤ 0.
    PlusMinus,
    /// s1 ≤ 0 and s2 > 0.
    MinusPlus,
}

impl Configuration {
    /// [`Configuration::from_signs`] of every lane, without branches.
    #[inline(always)]
    pub(crate) fn lane_codes(s1: F, s2: F) -> [Configuration; LANES] {
        // Indexed by (s1 ≤ 0) + 2 (s2 ≤ 0); NaN counts as ≤ 0, as in `from_signs`.
        const BY_SIGNS: [Configuration; 4] = [
            Configuration::PlusPlus,
            Configuration::MinusPlus,
            Configuration::PlusMinus,
            Configuration::MinusMinus,
        ];
        let zero = F::splat(0.0);
        let (minus1, minus2) = (!s1.gt(zero), !s2.gt(zero));
        std::array::from_fn(|l| {
            BY_SIGNS[usize::from(minus1.get(l)) | usize::from(minus2.get(l)) << 1]
        })
    }

    /// The four configurations in discriminant order (`ALL[c as usize] == c`).
    pub const ALL: [Configuration; 4] = [
        Self::PlusPlus,
        Self::MinusMinus,
        Self::PlusMinus,
        Self::MinusPlus,
    ];

    /// Classifies from s1 and s2.
    #[inline]
    pub fn from_signs(s1: f64, s2: f64) -> Self {
        match (s1 > 0.0, s2 > 0.0) {
            (true, true) => Self::PlusPlus,
            (false, false) => Self::MinusMinus,
            (true, false) => Self::PlusMinus,
            (false, true) => Self::MinusPlus,
        }
    }

    /// The label used in node outputs: `"++"`, `"--"`, `"+-"` or `"-+"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::PlusPlus => "++",
            Self::MinusMinus => "--",
            Self::PlusMinus => "+-",
            Self::MinusPlus => "-+",
        }
    }

    /// Whether this is the desired (++) configuration.
    pub fn is_good(self) -> bool {
        self == Self::PlusPlus
    }
}

impl fmt::Display for Configuration {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// How many vertices are in each configuration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ConfigurationCounts {
    /// Number of (++).
    pub plus_plus: usize,
    /// Number of (−−).
    pub minus_minus: usize,
    /// Number of (+−).
    pub plus_minus: usize,
    /// Number of (−+).
    pub minus_plus: usize,
}

impl ConfigurationCounts {
    /// Total number of classified vertices.
    pub fn total(&self) -> usize {
        self.plus_plus + self.minus_minus + self.plus_minus + self.minus_plus
    }

    /// Number of vertices not in (++).
    pub fn bad(&self) -> usize {
        self.total() - self.plus_plus
    }
}

/// The configurations c_{i,j} for i = 0 … N−1 and j = 0 … M−2 (one per support-strip quad).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Configurations {
    rows: usize,
    /// M − 1.
    cols: usize,
    /// Row stride in `data` (≥ cols; the sweep pads each row by one slot).
    stride: usize,
    data: Vec<Configuration>,
}

impl Configurations {
    /// Wraps a row-major buffer with `stride ≥ cols` entries per row.
    pub(crate) fn from_padded(
        rows: usize,
        cols: usize,
        stride: usize,
        data: Vec<Configuration>,
    ) -> Self {
        debug_assert!(stride >= cols && data.len() == rows * stride);
        Self {
            rows,
            cols,
            stride,
            data,
        }
    }

    /// Number of rows N.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Number of classified columns, M − 1.
    pub fn cols(&self) -> usize {
        self.cols
    }

    /// c_{i,j} for j = 0 … M−2.
    #[inline]
    pub fn get(&self, i: usize, j: usize) -> Configuration {
        assert!(
            j < self.cols,
            "configuration column {j} out of 0..{}",
            self.cols
        );
        self.data[i * self.stride + j]
    }

    /// Row i as a slice (entry j is c_{i,j}).
    pub fn row(&self, i: usize) -> &[Configuration] {
        &self.data[self.row_range(i)]
    }

    /// Where row i's configurations are in the table [`Configurations::codes`] returns.
    pub fn row_range(&self, i: usize) -> Range<usize> {
        i * self.stride..i * self.stride + self.cols
    }

    /// The class of every face of `mesh` (the net these configurations were found for), in quad
    /// order: face (i, j) from c_{i,j} and c_{i+1,j}; faces beyond the table are
    /// [`FaceClass::Unclassified`]. Empty when the table does not have the mesh's rows.
    pub fn face_classes(&self, mesh: &QuadGrid) -> Vec<FaceClass> {
        if self.rows != mesh.rows {
            return Vec::new();
        }
        let signs = |c: Configuration| match c {
            Configuration::PlusPlus => (true, true),
            Configuration::MinusMinus => (false, false),
            Configuration::PlusMinus => (true, false),
            Configuration::MinusPlus => (false, true),
        };
        let mut out = Vec::with_capacity(mesh.quad_count());
        for i in 0..mesh.quad_rows() {
            let (a, b) = (self.row(i), self.row((i + 1) % mesh.rows));
            out.extend((0..mesh.quad_cols()).map(|j| match (a.get(j), b.get(j)) {
                (Some(&a), Some(&b)) => FaceClass::of_signs(signs(a), signs(b)),
                _ => FaceClass::Unclassified,
            }));
        }
        out
    }

    /// Every configuration as its code (`c as u8`, the index in [`Configuration::ALL`]), in the
    /// layout [`Configurations::row_range`] describes.
    pub fn codes(&self) -> Vec<u8> {
        self.data.iter().map(|&c| c as u8).collect()
    }

    /// N lists of M−1 labels (`"++"`, …; entry j is c_{i,j}), as the nodes output them.
    pub fn to_strings(&self) -> Vec<Vec<&'static str>> {
        (0..self.rows)
            .map(|i| self.row(i).iter().map(|c| c.as_str()).collect())
            .collect()
    }

    /// Counts per class.
    pub fn counts(&self) -> ConfigurationCounts {
        let mut n = [0usize; 4];
        for i in 0..self.rows {
            let row = self.row(i);
            // Usually every vertex is (++): one vectorizable test, the histogram only otherwise.
            if row.iter().any(|c| !c.is_good()) {
                for &c in row {
                    n[c as usize] += 1;
                }
            }
        }
        let total = self.rows * self.cols;
        ConfigurationCounts {
            plus_plus: total - n[1] - n[2] - n[3],
            minus_minus: n[1],
            plus_minus: n[2],
            minus_plus: n[3],
        }
    }

    /// The first vertex (i, j) not in (++), in the order the correction visits them: by column j,
    /// then row i.
    pub fn first_bad(&self) -> Option<(usize, usize)> {
        // Row by row (the storage order), keeping the smallest (j, i).
        (0..self.rows)
            .filter_map(|i| {
                let j = self.row(i).iter().position(|c| !c.is_good())?;
                Some((j, i))
            })
            .min()
            .map(|(j, i)| (i, j))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classification_and_counts() {
        assert_eq!(Configuration::from_signs(1.0, 2.0), Configuration::PlusPlus);
        assert_eq!(Configuration::from_signs(-1.0, -2.0).as_str(), "--");
        assert_eq!(Configuration::from_signs(1.0, 0.0).as_str(), "+-");
        assert_eq!(Configuration::from_signs(-0.0, 1.0).as_str(), "-+");
        use Configuration::*;
        let data = vec![
            PlusPlus, MinusMinus, PlusPlus, PlusPlus, PlusPlus, MinusPlus,
        ];
        let c = Configurations::from_padded(2, 2, 3, data);
        assert_eq!(c.get(0, 1), MinusMinus);
        assert_eq!(c.get(1, 1), PlusPlus);
        assert_eq!(
            c.counts(),
            ConfigurationCounts {
                plus_plus: 3,
                minus_minus: 1,
                plus_minus: 0,
                minus_plus: 0
            }
        );
        assert_eq!(c.first_bad(), Some((0, 1)));
        assert_eq!(c.to_strings(), vec![vec!["++", "--"], vec!["++", "++"]]);
    }
}
