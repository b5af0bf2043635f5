//! Reversing and joining polylines.

use std::collections::VecDeque;

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
///
/// The end points are kept in a spatial hash (cubic cells of side ≥ `tolerance`, see [`EndHash`]),
/// so joining is near-linear in the number of curves rather than quadratic.
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
    let mut ends = EndHash::new(curves, tolerance);
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
        // A deque: pieces are added at both ends in O(piece) each.
        let mut chain: VecDeque<DVec3> = curves[first].points.iter().copied().collect();
        loop {
            let (start, end) = (chain[0], chain[chain.len() - 1]);
            if chain.len() > 2 && meets(start, end) {
                break;
            }
            // The first unused open curve with an end point near `end` or `start`.
            let near = ends
                .first_near(curves, end, &used, meets)
                .into_iter()
                .chain(ends.first_near(curves, start, &used, meets))
                .min();
            let found = near.map(|k| {
                let c = &curves[k];
                let (a, b) = (c.points[0], c.points[c.points.len() - 1]);
                if meets(end, a) {
                    (k, true, false)
                } else if meets(end, b) {
                    (k, true, true)
                } else if meets(start, b) {
                    (k, false, false)
                } else {
                    (k, false, true)
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
                chain.extend(&piece[1..]);
            } else {
                piece.pop();
                for p in piece.into_iter().rev() {
                    chain.push_front(p);
                }
            }
        }
        let closed = chain.len() > 3 && meets(chain[0], chain[chain.len() - 1]);
        if closed {
            chain.pop_back();
        }
        out.push(Polyline {
            points: chain.into(),
            closed,
        });
    }
    Ok(out)
}

/// The end points of the open curves in a hash of cubic cells of side `h ≥ tolerance`: two points
/// within `tolerance` lie in the same or neighbouring cells. `h` is also at least the bounding box's
/// diagonal over the number of end points, so exact joins (tolerance 0) do not crowd one cell.
struct EndHash {
    cells: std::collections::HashMap<[i64; 3], Vec<u32>>,
    origin: DVec3,
    inv_h: f64,
}

impl EndHash {
    fn new(curves: &[Polyline], tolerance: f64) -> Self {
        let ends = || {
            curves
                .iter()
                .filter(|c| !c.closed)
                .flat_map(|c| [c.points[0], c.points[c.points.len() - 1]])
        };
        let (lo, hi) = ends().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p), hi.max(p))
        });
        let count = ends().count().max(1) as f64;
        let diagonal = if lo.is_finite() && hi.is_finite() {
            (hi * 0.5 - lo * 0.5).length() * 2.0
        } else {
            0.0
        };
        let h = tolerance.max(diagonal / count).max(f64::MIN_POSITIVE);
        let mut hash = Self {
            cells: std::collections::HashMap::new(),
            origin: if lo.is_finite() { lo } else { DVec3::ZERO },
            inv_h: 1.0 / h,
        };
        for (k, c) in curves.iter().enumerate() {
            if c.closed || k >= u32::MAX as usize {
                continue;
            }
            for p in [c.points[0], c.points[c.points.len() - 1]] {
                hash.cells.entry(hash.cell(p)).or_default().push(k as u32);
            }
        }
        hash
    }

    fn cell(&self, p: DVec3) -> [i64; 3] {
        let c = ((p - self.origin) * self.inv_h).floor();
        // `as` saturates; points far outside the box (never end points) only probe empty cells.
        [c.x as i64, c.y as i64, c.z as i64]
    }

    /// The smallest unused curve index with an end point within the tolerance of `p` (`meets`).
    /// Used curves are dropped from the cells visited.
    fn first_near(
        &mut self,
        curves: &[Polyline],
        p: DVec3,
        used: &[bool],
        meets: impl Fn(DVec3, DVec3) -> bool,
    ) -> Option<usize> {
        let [x, y, z] = self.cell(p);
        let mut best: Option<usize> = None;
        for dx in -1..=1i64 {
            for dy in -1..=1i64 {
                for dz in -1..=1i64 {
                    let key = [
                        x.saturating_add(dx),
                        y.saturating_add(dy),
                        z.saturating_add(dz),
                    ];
                    let Some(list) = self.cells.get_mut(&key) else {
                        continue;
                    };
                    list.retain(|&k| !used[k as usize]);
                    for &k in list.iter() {
                        let k = k as usize;
                        if best.is_some_and(|b| b <= k) {
                            continue;
                        }
                        let c = &curves[k].points;
                        if meets(p, c[0]) || meets(p, c[c.len() - 1]) {
                            best = Some(k);
                        }
                    }
                }
            }
        }
        best
    }
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

    /// The quadratic reference: the first unused curve touching, in input order.
    fn join_naive(curves: &[Polyline], tolerance: f64) -> Vec<Polyline> {
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
        out
    }

    #[test]
    fn the_hash_joins_like_the_quadratic_search() {
        // Segments on a small integer lattice (many coincident ends, branches, loops), some flipped,
        // some closed, at tolerance 0 and at one that merges neighbours.
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = move |m: u64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % m
        };
        for round in 0..40 {
            let curves: Vec<Polyline> = (0..60)
                .map(|_| {
                    let a = DVec3::new(next(5) as f64, next(5) as f64, 0.0);
                    let b = a + DVec3::new(next(3) as f64 - 1.0, next(3) as f64 - 1.0, 0.0);
                    let b = if b == a { b + DVec3::X } else { b };
                    if next(10) == 0 {
                        Polyline::closed(vec![a, b, a + DVec3::Y * 0.5])
                    } else {
                        Polyline::open(vec![a, b])
                    }
                })
                .collect();
            for tolerance in [0.0, 1e-9, 1.2] {
                assert_eq!(
                    join(&curves, tolerance).unwrap(),
                    join_naive(&curves, tolerance),
                    "round {round}, tolerance {tolerance}"
                );
            }
        }
    }

    #[test]
    fn forty_thousand_segments_join_fast() {
        // A 200 × 200 lattice path, as 40 000 segments in a shuffled order (the old search took
        // 9.9 s).
        let n = 40_000usize;
        let points: Vec<DVec3> = (0..=n)
            .map(|k| {
                let (row, col) = (k / 200, k % 200);
                let x = if row % 2 == 0 { col } else { 199 - col };
                DVec3::new(x as f64, row as f64, 0.0)
            })
            .collect();
        let mut order: Vec<usize> = (0..n).collect();
        let mut state = 12345u64;
        for i in (1..n).rev() {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            order.swap(i, (state >> 33) as usize % (i + 1));
        }
        let curves: Vec<Polyline> = order
            .iter()
            .map(|&k| Polyline::open(vec![points[k], points[k + 1]]))
            .collect();
        let started = std::time::Instant::now();
        let joined = join(&curves, 1e-9).unwrap();
        let took = started.elapsed();
        eprintln!("40 000 segments joined in {took:?}");
        assert_eq!(joined.len(), 1);
        assert_eq!(joined[0].points.len(), n + 1);
        // A figure (≈ 1 s in the test build on the 2-core machine), with a bound that no busy
        // machine reaches and a hang or a cubic search would (issue 30: 30× the measured time).
        assert!(took.as_secs_f64() < 30.0, "{took:?}");
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
