//! The normalized apex-locating function (paper Sec. 4.3, notes §5):
//! `a_j = 1 − (1 − ā_j) l_j / L`, with L = directrix length / 5 unless given.

use super::directrix::SweptDirectrix;
use super::inputs::ApexInput;
use crate::GeometryError;

/// The default normalization scale: total (swept) directrix length divided by 5.
pub fn default_scale(total_length: f64) -> f64 {
    total_length / 5.0
}

/// Maps normalized values ā_j to a_j for edge lengths `lengths[k] = l_{k+1}` and scale L.
/// `ā_j = 1` gives exactly `a_j = 1`.
pub fn denormalize(normalized: &[f64], lengths: &[f64], scale: f64) -> Vec<f64> {
    normalized
        .iter()
        .zip(lengths)
        .map(|(&abar, &l)| {
            if abar == 1.0 {
                1.0
            } else {
                1.0 - (1.0 - abar) * l / scale
            }
        })
        .collect()
}

/// The inverse map: `ā_j = 1 − (1 − a_j) L / l_j`.
pub fn normalize(apex: &[f64], lengths: &[f64], scale: f64) -> Vec<f64> {
    apex.iter()
        .zip(lengths)
        .map(|(&a, &l)| {
            if a == 1.0 {
                1.0
            } else {
                1.0 - (1.0 - a) * scale / l
            }
        })
        .collect()
}

/// Resolves the user's apex input to the apex values a_j (j = 1 … M−1, index j − 1) actually used by
/// the construction: broadcast, validated, and denormalized when requested.
pub fn resolve_apex(
    input: &ApexInput,
    directrix: &SweptDirectrix,
) -> Result<Vec<f64>, GeometryError> {
    let mut a = resolve_given(input, directrix)?;
    if let (Some(apex), Some(first)) = (input.seam, a.first_mut()) {
        let (x0, x1) = (directrix.points[0], directrix.points[1]);
        *first = super::seam_apex::seam_apex(x0, x1, apex)?.value;
    }
    Ok(a)
}

/// The apex values as given: broadcast, validated, and denormalized when requested.
fn resolve_given(input: &ApexInput, directrix: &SweptDirectrix) -> Result<Vec<f64>, GeometryError> {
    let columns = directrix.columns() - 1;
    let values = input.values.resolve("apex", columns)?;
    if !input.normalized {
        return Ok(values);
    }
    let scale = match input.scale {
        Some(l) if l.is_finite() && l > 0.0 => l,
        Some(l) => {
            return Err(GeometryError::InvalidParameter {
                what: "scale",
                value: l,
                expected: "a finite number > 0",
            });
        }
        None => default_scale(directrix.length()),
    };
    if !(scale.is_finite() && scale > 0.0) {
        return Err(GeometryError::InvalidParameter {
            what: "scale (directrix length / 5)",
            value: scale,
            expected: "a finite number > 0",
        });
    }
    let a = denormalize(&values, &directrix.lengths[1..], scale);
    match a.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(GeometryError::NonFinite {
            what: "normalized apex",
            index,
        }),
        None => Ok(a),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn denormalize_matches_hand_computation_and_inverts() {
        // l = 2, L = 4, ā = 0.5 ⇒ a = 1 − 0.5 · 2 / 4 = 0.75.
        assert_eq!(
            denormalize(&[0.5, 1.0, 2.0], &[2.0, 3.0, 1.0], 4.0),
            vec![0.75, 1.0, 1.25]
        );
        let a = denormalize(&[0.3, 1.7], &[0.2, 5.0], 1.3);
        let back = normalize(&a, &[0.2, 5.0], 1.3);
        assert!((back[0] - 0.3).abs() < 1e-14 && (back[1] - 1.7).abs() < 1e-14);
    }

    #[test]
    fn positivity_threshold_is_one_minus_l_over_lj() {
        // a_j > 0 ⇔ ā_j > 1 − L / l_j (notes §5): at the threshold a_j = 0.
        let (l, scale) = (3.0, 2.0);
        let threshold = 1.0 - scale / l;
        assert!(denormalize(&[threshold], &[l], scale)[0].abs() < 1e-15);
        assert!(denormalize(&[threshold + 1e-3], &[l], scale)[0] > 0.0);
    }
}
