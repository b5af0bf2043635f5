//! Correction records and the closed-form apex fix (paper Appendix A, notes §6).

use std::fmt;

use glam::DVec3;

/// What a correction changed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CorrectionKind {
    /// The apex value a_j (all rows of column j move along their rulings).
    Apex,
    /// A plane Π_{i,j} of the ratio construction, reported as the equivalent ratio r_{i,j}.
    Ratio,
    /// The shared plane Π_j of the coplanar construction, reported as its rotation ratio τ_j.
    PlaneRotation,
    /// The first-column fix of footnote 2: the generatrix scaled about X_0 (every G_{i,0} moves
    /// towards X_0), reported as its scale factor (`column` 0, 1 = as given).
    Generatrix,
}

/// One correction made by the assisted construction: `kind` at `column` (and `row` for a per-row
/// plane), from `old` to `new`.
///
/// `column` is the index j of the changed value: a_j for [`CorrectionKind::Apex`], the plane Π_{·,j}
/// otherwise. A bad configuration at vertex column j0 is repaired by changing a_{j0} or Π_{·,j0+1}.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Correction {
    /// What changed.
    pub kind: CorrectionKind,
    /// Column j of the changed value.
    pub column: usize,
    /// Row i for a per-row plane fix; `None` when the change affects every row.
    pub row: Option<usize>,
    /// The value before the fix.
    pub old: f64,
    /// The value after the fix.
    pub new: f64,
}

impl fmt::Display for Correction {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.kind, self.row) {
            (CorrectionKind::Apex, _) => {
                write!(
                    f,
                    "apex fix at column {}: a = {} → {}",
                    self.column, self.old, self.new
                )
            }
            (CorrectionKind::Ratio, Some(i)) => write!(
                f,
                "plane fix at column {}, row {i}: ratio {} → {}",
                self.column, self.old, self.new
            ),
            (CorrectionKind::Ratio, None) => {
                write!(
                    f,
                    "plane fix at column {}: ratio {} → {}",
                    self.column, self.old, self.new
                )
            }
            (CorrectionKind::PlaneRotation, _) => write!(
                f,
                "plane fix at column {} (all rows): rotation ratio {} → {}",
                self.column, self.old, self.new
            ),
            (CorrectionKind::Generatrix, _) => write!(
                f,
                "generatrix fix at column {}: scaled about the first directrix point by {} → {}",
                self.column, self.old, self.new
            ),
        }
    }
}

/// The apex value a_{i,j0} that puts G_{i,j0} exactly on Π_{i,j0+1} (Appendix A):
/// `K1 = (g − X_{j0+1})·P1`, `K2 = −(g − X_{j0})·P0`, `W = K1 P0 + K2 P1`,
/// `a = ((g − X_{j0})·W) / ((g − X_{j0−1})·W)`, with `g = G_{i,j0−1}`, `P0 = P_{i,j0}`,
/// `P1 = P_{i,j0+1}`. `x` holds X_{j0−1}, X_{j0}, X_{j0+1}. May be non-finite for degenerate input.
#[inline]
pub fn apex_fix_value(g: DVec3, x: [DVec3; 3], p0: DVec3, p1: DVec3) -> f64 {
    let k1 = (g - x[2]).dot(p1);
    let k2 = -(g - x[1]).dot(p0);
    let w = p0 * k1 + p1 * k2;
    (g - x[1]).dot(w) / (g - x[0]).dot(w)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::conenet::prepare::step;

    #[test]
    fn apex_fix_value_puts_the_vertex_on_the_next_plane() {
        let x = [
            DVec3::ZERO,
            DVec3::new(1.0, 0.1, 0.0),
            DVec3::new(2.1, 0.3, 0.2),
        ];
        let g = DVec3::new(0.1, 1.0, 0.4);
        let p0 = DVec3::new(1.0, 0.2, 0.1).normalize();
        let p1 = DVec3::new(1.0, -0.3, 0.2).normalize();
        let a = apex_fix_value(g, x, p0, p1);
        let gj = step(g, x[0], x[1], a, p0).unwrap();
        assert!((gj - x[1]).dot(p0).abs() < 1e-13, "on its own plane");
        assert!(
            (x[2] - gj).dot(p1).abs() < 1e-13,
            "on the next plane: a = {a}"
        );
    }

    #[test]
    fn display_names_column_row_and_values() {
        let c = Correction {
            kind: CorrectionKind::Ratio,
            column: 4,
            row: Some(2),
            old: 0.8,
            new: 0.6,
        };
        assert_eq!(
            c.to_string(),
            "plane fix at column 4, row 2: ratio 0.8 → 0.6"
        );
        let a = Correction {
            kind: CorrectionKind::Apex,
            column: 3,
            row: None,
            old: 1.5,
            new: 1.2,
        };
        assert_eq!(a.to_string(), "apex fix at column 3: a = 1.5 → 1.2");
    }
}
