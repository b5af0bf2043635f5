//! Lines drawn on flat parts — fold lines and marks of unrolled strips — carried along when the
//! parts are moved rigidly onto sheets ([`super::nest`]), and told which part they belong to.
//!
//! A line belongs to the outline that contains the midpoint of its middle segment (even–odd rule),
//! or, when none does (a joint line lies on its piece's edge), to the outline nearest to that
//! point. The rigid
//! motion of a part is recovered from its outline before and after (same points, same order): the
//! rotation that takes the direction from its first point to its farthest point onto the placed
//! one, and the translation of the first point; applied to every point of the line, so the line
//! keeps its place on the part to rounding.

use glam::{DVec2, DVec3};

use super::FabricationError;
use crate::Polyline;

/// Whether `p` is inside the closed polygon `poly` (even–odd rule, x and y).
fn inside(p: DVec2, poly: &[DVec3]) -> bool {
    let n = poly.len();
    let mut odd = false;
    for k in 0..n {
        let (a, b) = (poly[k].truncate(), poly[(k + 1) % n].truncate());
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if p.x < x {
                odd = !odd;
            }
        }
    }
    odd
}

/// The distance from `p` to the closed polygon's edges (x and y).
fn distance(p: DVec2, poly: &[DVec3]) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|k| {
            let (a, b) = (poly[k].truncate(), poly[(k + 1) % n].truncate());
            let d = b - a;
            let t = if d.length_squared() > 0.0 {
                ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            p.distance(a + d * t)
        })
        .fold(f64::INFINITY, f64::min)
}

/// The outline a line belongs to: the one containing the midpoint of its middle segment, else the
/// nearest one. `None`
/// when there is no outline or the line has no points.
pub fn owner_of(line: &[DVec3], outlines: &[Polyline]) -> Option<usize> {
    let m = line.len().checked_sub(1)? / 2;
    let mid = ((line[m] + line[(m + 1).min(line.len() - 1)]) * 0.5).truncate();
    let boxes_hold = |o: &Polyline| {
        let (lo, hi) = o.points.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(p.truncate()), hi.max(p.truncate())),
        );
        mid.cmpge(lo).all() && mid.cmple(hi).all()
    };
    if let Some(k) = outlines
        .iter()
        .position(|o| boxes_hold(o) && inside(mid, &o.points))
    {
        return Some(k);
    }
    outlines
        .iter()
        .enumerate()
        .map(|(k, o)| (k, distance(mid, &o.points)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(k, _)| k)
}

/// The rigid motion (rotation angle, then translation) that took outline `from` to `to`.
pub fn rigid_motion(from: &Polyline, to: &Polyline) -> Option<(f64, DVec2)> {
    if from.points.len() != to.points.len() || from.points.is_empty() {
        return None;
    }
    let (p0, q0) = (from.points[0].truncate(), to.points[0].truncate());
    let far = (0..from.points.len()).max_by(|&a, &b| {
        let da = from.points[a].truncate().distance_squared(p0);
        let db = from.points[b].truncate().distance_squared(p0);
        da.total_cmp(&db)
    })?;
    let (u, v) = (
        from.points[far].truncate() - p0,
        to.points[far].truncate() - q0,
    );
    let angle = if u.length_squared() > 0.0 {
        u.perp_dot(v).atan2(u.dot(v))
    } else {
        0.0
    };
    let rotated = DVec2::from_angle(angle).rotate(p0);
    Some((angle, q0 - rotated))
}

/// Lines on the parts `before`, moved with their part to where it is `after` (same outlines, same
/// order, moved rigidly). Returns the moved lines and the part of each.
pub fn carry(
    lines: &[Polyline],
    before: &[Polyline],
    after: &[Polyline],
) -> Result<(Vec<Polyline>, Vec<usize>), FabricationError> {
    let motions = before
        .iter()
        .zip(after)
        .enumerate()
        .map(|(k, (a, b))| {
            rigid_motion(a, b).ok_or_else(|| FabricationError::DegenerateFace {
                what: "nest",
                face: k,
                reason: format!("outline {k} was not moved rigidly"),
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut owners = Vec::with_capacity(lines.len());
    let mut moved = Vec::with_capacity(lines.len());
    for (k, line) in lines.iter().enumerate() {
        let owner = owner_of(&line.points, before).ok_or(FabricationError::DegenerateFace {
            what: "nest",
            face: k,
            reason: format!("line {k} has no points or there is no outline to carry it"),
        })?;
        let (angle, shift) = motions[owner];
        let turn = DVec2::from_angle(angle);
        moved.push(Polyline {
            points: line
                .points
                .iter()
                .map(|p| {
                    let q = turn.rotate(p.truncate()) + shift;
                    DVec3::new(q.x, q.y, 0.0)
                })
                .collect(),
            closed: line.closed,
        });
        owners.push(owner);
    }
    Ok((moved, owners))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(o: DVec2, s: f64) -> Polyline {
        Polyline::closed(
            [(0., 0.), (1., 0.), (1., 1.), (0., 1.)]
                .iter()
                .map(|&(x, y)| DVec3::new(o.x + s * x, o.y + s * y, 0.0))
                .collect(),
        )
    }

    #[test]
    fn lines_follow_their_part() {
        let before = vec![square(DVec2::ZERO, 1.0), square(DVec2::new(3.0, 0.0), 1.0)];
        // The second part turned a quarter and moved; the first moved only.
        let turn = DVec2::from_angle(std::f64::consts::FRAC_PI_2);
        let moved = |p: &DVec3| {
            let q = turn.rotate(p.truncate()) + DVec2::new(10.0, 5.0);
            DVec3::new(q.x, q.y, 0.0)
        };
        let after = vec![
            Polyline::closed(before[0].points.iter().map(|p| *p + DVec3::Y).collect()),
            Polyline::closed(before[1].points.iter().map(moved).collect()),
        ];
        let lines = vec![
            Polyline::open(vec![DVec3::new(3.5, 0.0, 0.0), DVec3::new(3.5, 1.0, 0.0)]),
            // On the first square's right edge: nearest to it.
            Polyline::open(vec![DVec3::new(1.0, 0.2, 0.0), DVec3::new(1.0, 0.4, 0.0)]),
        ];
        let (out, owners) = carry(&lines, &before, &after).unwrap();
        assert_eq!(owners, [1, 0]);
        for (p, q) in lines[0].points.iter().zip(&out[0].points) {
            assert!(moved(p).distance(*q) < 1e-12);
        }
        assert!(out[1].points[0].distance(DVec3::new(1.0, 1.2, 0.0)) < 1e-15);
    }
}
