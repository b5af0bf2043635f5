//! Reversing and joining polylines.

use glam::DVec3;

use crate::error::check_finite_points;
use crate::{GeometryError, Polyline};

/// The curve run backwards. An open curve's points are reversed; a closed curve **keeps its first
/// point** and visits the others in reverse order (p₀, p_{n−1}, …, p₁), so its seam does not move.
pub fn reverse(curve: &Polyline) -> Polyline {
    let mut points = curve.points.clone();
    if curve.closed && points.len() > 1 {
        points[1..].reverse();
    } else {
        points.reverse();
    }
    Polyline {
        points,
        closed: curve.closed,
    }
}

/// Joins open polylines that meet end to end (within `tolerance`) into longer ones, flipping pieces
/// as needed. Chains are grown greedily from the first unused curve in input order: at its end, then
/// at its start, always taking the first unused curve that touches. A chain whose two ends meet
/// becomes closed (when it has at least three points). Where two ends meet, only the first of the
/// two points is kept. Closed input curves are passed through unchanged. The result keeps input
/// order by each chain's first curve.
pub fn join(curves: &[Polyline], tolerance: f64) -> Result<Vec<Polyline>, GeometryError> {
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        return Err(GeometryError::InvalidParameter {
            what: "tolerance",
            value: tolerance,
            expected: "a finite number ≥ 0",
        });
    }
    for (k, c) in curves.iter().enumerate() {
        if c.points.is_empty() {
            return Err(GeometryError::Degenerate(format!(
                "curve {k} has no points"
            )));
        }
        check_finite_points("curve", &c.points)
            .map_err(|_| GeometryError::Degenerate(format!("curve {k} has a non-finite point")))?;
    }
    let meets = |a: DVec3, b: DVec3| a.distance(b) <= tolerance;
    let mut used = vec![false; curves.len()];
    let mut out = Vec::new();
    for first in 0..curves.len() {
        if used[first] {
            continue;
        }
        used[first] = true;
        if curves[first].closed {
            out.push(curves[first].clone());
            continue;
        }
        let mut chain = curves[first].points.clone();
        loop {
            let (start, end) = (chain[0], chain[chain.len() - 1]);
            if chain.len() > 2 && meets(start, end) {
                break;
            }
            let found = (0..curves.len()).find_map(|k| {
                let c = &curves[k];
                if used[k] || c.closed {
                    return None;
                }
                let (a, b) = (c.points[0], c.points[c.points.len() - 1]);
                if meets(end, a) {
                    Some((k, true, false))
                } else if meets(end, b) {
                    Some((k, true, true))
                } else if meets(start, b) {
                    Some((k, false, false))
                } else if meets(start, a) {
                    Some((k, false, true))
                } else {
                    None
                }
            });
            let Some((k, at_end, flip)) = found else {
                break;
            };
            used[k] = true;
            let mut piece = curves[k].points.clone();
            if flip {
                piece.reverse();
            }
            if at_end {
                chain.extend_from_slice(&piece[1..]);
            } else {
                piece.pop();
                piece.extend_from_slice(&chain);
                chain = piece;
            }
        }
        let closed = chain.len() > 3 && meets(chain[0], chain[chain.len() - 1]);
        if closed {
            chain.pop();
        }
        out.push(Polyline {
            points: chain,
            closed,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seg(a: [f64; 2], b: [f64; 2]) -> Polyline {
        Polyline::open(vec![
            DVec3::new(a[0], a[1], 0.0),
            DVec3::new(b[0], b[1], 0.0),
        ])
    }

    #[test]
    fn reverse_keeps_the_seam_of_closed_curves() {
        let p = Polyline::closed(vec![DVec3::ZERO, DVec3::X, DVec3::Y]);
        assert_eq!(reverse(&p).points, vec![DVec3::ZERO, DVec3::Y, DVec3::X]);
        let o = Polyline::open(vec![DVec3::ZERO, DVec3::X, DVec3::Y]);
        assert_eq!(reverse(&o).points, vec![DVec3::Y, DVec3::X, DVec3::ZERO]);
        assert_eq!(reverse(&reverse(&p)), p);
    }

    #[test]
    fn joins_in_any_orientation_and_closes_loops() {
        // A unit square as four segments, two of them flipped, shuffled.
        let pieces = vec![
            seg([0.0, 0.0], [1.0, 0.0]),
            seg([0.0, 1.0], [1.0, 1.0]), // flipped
            seg([1.0, 0.0], [1.0, 1.0]),
            seg([0.0, 0.0], [0.0, 1.0]), // flipped
        ];
        let joined = join(&pieces, 1e-9).unwrap();
        assert_eq!(joined.len(), 1);
        assert!(joined[0].closed);
        assert_eq!(joined[0].points.len(), 4);
        assert!((joined[0].length() - 4.0).abs() < 1e-12);
    }

    #[test]
    fn separate_pieces_stay_separate_and_tolerance_matters() {
        let pieces = vec![seg([0.0, 0.0], [1.0, 0.0]), seg([1.001, 0.0], [2.0, 0.0])];
        assert_eq!(join(&pieces, 1e-6).unwrap().len(), 2);
        let j = join(&pieces, 0.01).unwrap();
        assert_eq!(j.len(), 1);
        assert_eq!(j[0].points.len(), 3);
        assert!(!j[0].closed);
        // Growing at the start: the second piece ends where the first starts.
        let pieces = vec![seg([1.0, 0.0], [2.0, 0.0]), seg([0.0, 0.0], [1.0, 0.0])];
        let j = join(&pieces, 0.0).unwrap();
        assert_eq!(j[0].points[0], DVec3::ZERO);
        assert_eq!(j[0].points.len(), 3);
    }

    #[test]
    fn bad_inputs() {
        assert!(join(&[seg([0.0, 0.0], [1.0, 0.0])], -1.0).is_err());
        assert!(join(&[Polyline::open(vec![])], 0.0).is_err());
        assert!(join(&[], 0.0).unwrap().is_empty());
        let nan = Polyline::open(vec![DVec3::NAN, DVec3::X]);
        assert!(join(&[nan], 0.0).is_err());
    }
}
