//! Laying flat shapes out side by side: each shape is turned so its minimum-area bounding rectangle
//! is axis-aligned with the long side along x, then the shapes are stacked along +y, bounding box
//! above bounding box with a gap. Boxes that do not overlap contain shapes that do not overlap.

use glam::DVec2;

/// The convex hull of `points` (Andrew's monotone chain), counter-clockwise, without repeated or
/// collinear points. Fewer than three distinct points are returned as they are (sorted, deduplicated).
pub fn convex_hull(points: &[DVec2]) -> Vec<DVec2> {
    let mut p: Vec<DVec2> = points.to_vec();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let cross = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut hull: Vec<DVec2> = Vec::with_capacity(2 * p.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &DVec2>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &q in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}

/// The rotation angle (radians) that makes the minimum-area bounding rectangle of `points`
/// axis-aligned with its long side along x.
pub fn min_area_angle(points: &[DVec2]) -> f64 {
    let hull = convex_hull(points);
    if hull.len() < 2 {
        return 0.0;
    }
    let mut best = (f64::INFINITY, 0.0, 0.0, 0.0);
    for k in 0..hull.len() {
        let d = hull[(k + 1) % hull.len()] - hull[k];
        let len = d.length();
        if !(len > 0.0) {
            continue;
        }
        let u = d / len;
        let v = u.perp();
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for p in &hull {
            let q = DVec2::new(p.dot(u), p.dot(v));
            lo = lo.min(q);
            hi = hi.max(q);
        }
        let size = hi - lo;
        let area = size.x * size.y;
        if area < best.0 * (1.0 - 1e-12) {
            best = (area, u.y.atan2(u.x), size.x, size.y);
        }
    }
    let (_, along, w, h) = best;
    // Rotating by −along puts the hull edge on the x axis; a further quarter turn when the rectangle
    // is taller than wide.
    if h > w {
        -along + std::f64::consts::FRAC_PI_2
    } else {
        -along
    }
}

/// Rotates a point by `angle` radians about the origin.
pub fn rotate(p: DVec2, angle: f64) -> DVec2 {
    DVec2::from_angle(angle).rotate(p)
}

/// Axis-aligned bounds of points; `None` when empty.
pub fn bounds(points: &[DVec2]) -> Option<(DVec2, DVec2)> {
    let first = *points.first()?;
    Some(
        points
            .iter()
            .fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p))),
    )
}

/// The gap between stacked outlines when none is given: a tenth of the tallest outline, each
/// measured turned to its minimum-area rectangle (as [`stack`] lays it).
pub fn default_gap(shapes: &[Vec<DVec2>]) -> f64 {
    let tallest = shapes
        .iter()
        .map(|s| {
            let angle = min_area_angle(s);
            let r: Vec<DVec2> = s.iter().map(|p| rotate(*p, angle)).collect();
            bounds(&r).map_or(0.0, |(lo, hi)| hi.y - lo.y)
        })
        .fold(0.0, f64::max);
    0.1 * tallest
}

/// Lays the shapes out in place: turned by [`min_area_angle`], then stacked along +y from the origin
/// with `gap` between consecutive bounding boxes. Returns the rigid map applied to each shape as
/// (angle, translation after rotation).
pub fn stack(shapes: &mut [Vec<DVec2>], gap: f64) -> Vec<(f64, DVec2)> {
    let mut y = 0.0;
    let mut maps = Vec::with_capacity(shapes.len());
    for shape in shapes.iter_mut() {
        let angle = min_area_angle(shape);
        for p in shape.iter_mut() {
            *p = rotate(*p, angle);
        }
        let (lo, hi) = bounds(shape).unwrap_or((DVec2::ZERO, DVec2::ZERO));
        let shift = DVec2::new(-lo.x, y - lo.y);
        for p in shape.iter_mut() {
            *p += shift;
        }
        y += (hi.y - lo.y) + gap;
        maps.push((angle, shift));
    }
    maps
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_of_square_with_inner_point() {
        let pts = [
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(0.5, 0.5),
            DVec2::new(1.0, 1.0),
            DVec2::new(0.0, 1.0),
            DVec2::new(0.5, 0.0),
        ];
        let h = convex_hull(&pts);
        assert_eq!(h.len(), 4);
        assert!(!h.contains(&DVec2::new(0.5, 0.5)));
    }

    #[test]
    fn tilted_rectangle_is_turned_flat_and_shapes_are_stacked() {
        let a = 0.3f64;
        let (u, v) = (DVec2::from_angle(a), DVec2::from_angle(a).perp());
        let rect = vec![DVec2::ZERO, u * 4.0, u * 4.0 + v, v];
        let mut shapes = vec![rect.clone(), rect];
        stack(&mut shapes, 0.5);
        let (lo0, hi0) = bounds(&shapes[0]).unwrap();
        let (lo1, hi1) = bounds(&shapes[1]).unwrap();
        assert!((hi0 - lo0 - DVec2::new(4.0, 1.0)).length() < 1e-12);
        assert!((lo1.y - hi0.y - 0.5).abs() < 1e-12);
        assert!((hi1.y - lo1.y - 1.0).abs() < 1e-12);
    }
}
