//! Outline graph → apex-locating function (CNets Graph to Apex Function, paper Sec. 4.4.2, notes §7).
//!
//! The widths y_0 … y_{M−1} of the support strips along the directrix give `a_j = y_j / y_{j−1}`
//! (j = 1 … M−1): the ratio of consecutive widths, exact for a straight directrix with uniform edges
//! and ratios ½ (a Monge surface). The normalized form is `ā_j = 1 − (1 − a_j) L / l_j` with the
//! directrix edge lengths l_j and the scale L (directrix length / 5 unless given), the inverse of the
//! kernel's normalization (notes §5), so feeding ā back with `normalized` reproduces a_j.

use super::FabricationError;
use crate::Polyline;
use crate::conenet::SweptDirectrix;
use crate::conenet::normalize::{default_scale, normalize};

/// Checks the widths: at least two, all finite and > 0.
fn check_widths(widths: &[f64]) -> Result<(), FabricationError> {
    if widths.len() < 2 {
        return Err(FabricationError::TooSmall {
            what: "widths",
            needed: 2,
            unit: "values",
            got: widths.len(),
        });
    }
    match widths.iter().position(|y| !(y.is_finite() && *y > 0.0)) {
        Some(index) => Err(FabricationError::BadWidth {
            index,
            value: widths[index],
        }),
        None => Ok(()),
    }
}

/// The plain apex function `a_j = y_j / y_{j−1}` (M widths → M−1 values).
pub fn graph_to_apex(widths: &[f64]) -> Result<Vec<f64>, FabricationError> {
    check_widths(widths)?;
    Ok(widths.windows(2).map(|w| w[1] / w[0]).collect())
}

/// The normalized apex function `ā_j = 1 − (1 − a_j) L / l_j` for the given directrix (whose swept
/// point count must equal the number of widths) and scale L (`None`: directrix length / 5).
pub fn graph_to_normalized_apex(
    widths: &[f64],
    directrix: &Polyline,
    scale: Option<f64>,
) -> Result<Vec<f64>, FabricationError> {
    let a = graph_to_apex(widths)?;
    let dx = SweptDirectrix::new(directrix)?;
    if dx.columns() != widths.len() {
        return Err(FabricationError::WrongLength {
            what: "widths",
            expected: format!("{} (one per directrix point, M, as swept)", dx.columns()),
            got: widths.len(),
        });
    }
    let l = match scale {
        None => default_scale(dx.length()),
        Some(l) => l,
    };
    if !(l.is_finite() && l > 0.0) {
        return Err(FabricationError::BadParameter {
            what: "scale L",
            value: l,
            expected: "a finite number > 0",
        });
    }
    let out = normalize(&a, &dx.lengths[1..], l);
    match out.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(FabricationError::BadEntry {
            what: "normalized apex",
            index,
            value: out[index],
            expected: "a finite number",
        }),
        None => Ok(out),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn ratios_of_consecutive_widths() {
        assert_eq!(graph_to_apex(&[2.0, 1.0, 1.5]).unwrap(), vec![0.5, 1.5]);
        assert!(matches!(
            graph_to_apex(&[1.0, 0.0]),
            Err(FabricationError::BadWidth { index: 1, .. })
        ));
        assert!(graph_to_apex(&[1.0]).is_err());
        assert!(graph_to_apex(&[1.0, f64::NAN]).is_err());
    }

    #[test]
    fn normalized_form_matches_hand_computation() {
        // Straight directrix of 3 unit edges: length 3, L = 0.6.
        let d = Polyline::open((0..4).map(|k| DVec3::new(k as f64, 0.0, 0.0)).collect());
        let abar = graph_to_normalized_apex(&[1.0, 0.5, 0.5, 1.0], &d, None).unwrap();
        // a = [0.5, 1, 2] ⇒ ā = 1 − (1 − a) 0.6 / 1.
        let expected = [1.0 - 0.5 * 0.6, 1.0, 1.0 + 0.6];
        for (x, y) in abar.iter().zip(expected) {
            assert!((x - y).abs() < 1e-15, "{x} vs {y}");
        }
        assert!(graph_to_normalized_apex(&[1.0, 2.0], &d, None).is_err());
        assert!(graph_to_normalized_apex(&[1.0, 2.0, 1.0, 1.0], &d, Some(0.0)).is_err());
    }
}
