//! Curve operations on polylines: primitives (line, arc, circle, polygon, helix), interpolating
//! splines, arc-length resampling, subdivision, transforms, reversing and joining, the graph
//! mapper functions y = f(x) used to shape lists of numbers, and the flattening of Bézier curves and
//! elliptical arcs (the curved segments of SVG paths).
//!
//! Conventions shared by every function here:
//! - angles are in **degrees**, measured in a plane from its x axis towards its y axis;
//! - a count is a number of points (open curves include both ends; closed curves store each point
//!   once, the closing edge is implicit);
//! - every function validates its input and returns a typed [`GeometryError`] instead of panicking:
//!   non-finite coordinates, too few points, zero-length curves, counts out of range.

pub mod flatten;
pub mod join;
pub mod mapper;
pub mod nurbs;
pub mod offset;
pub mod primitives;
#[cfg(test)]
mod props;
pub mod query;
pub mod resample;
pub mod spline;
pub mod subdivide;
pub mod transform;

pub use join::{join, reverse};
pub use mapper::{Domains, GraphMapper, MapperKind};
pub use nurbs::Nurbs;
pub use offset::offset;
pub use primitives::{arc, arc_span_rise, arc_through, circle, helix, line, polygon};
pub use query::{closest_point, evaluate};
pub use resample::{divide_equal_chords, resample_by_count, resample_by_length};
pub use spline::{Spline, SplineKind};
pub use subdivide::{SubdivisionScheme, subdivide};
pub use transform::Transform;

use glam::DVec3;

use crate::{GeometryError, Polyline};

/// Largest number of points a curve operation will create (guards against runaway counts).
pub const MAX_POINTS: usize = 10_000_000;

/// Checks a requested point count: at least `min`, at most [`MAX_POINTS`].
pub(crate) fn check_count(
    what: &'static str,
    count: usize,
    min: usize,
) -> Result<(), GeometryError> {
    if count < min {
        return Err(GeometryError::Degenerate(format!(
            "{what} must be at least {min}, got {count}"
        )));
    }
    if count > MAX_POINTS {
        return Err(GeometryError::Degenerate(format!(
            "{what} {count} is too large (at most {MAX_POINTS} points)"
        )));
    }
    Ok(())
}

/// Checks that a scalar is finite.
pub(crate) fn check_finite(what: &'static str, value: f64) -> Result<(), GeometryError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(GeometryError::InvalidParameter {
            what,
            value,
            expected: "a finite number",
        })
    }
}

/// Checks that a point or vector is finite.
pub(crate) fn check_finite_vec(what: &'static str, v: DVec3) -> Result<(), GeometryError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(GeometryError::NonFinite { what, index: 0 })
    }
}

/// Checks that every point of a computed curve is finite (huge inputs can overflow).
pub(crate) fn check_output(what: &str, curve: Polyline) -> Result<Polyline, GeometryError> {
    match curve.points.iter().position(|p| !p.is_finite()) {
        None => Ok(curve),
        Some(index) => Err(GeometryError::Degenerate(format!(
            "{what}: point {index} overflows (the inputs are too large)"
        ))),
    }
}

/// Cumulative arc length at each point of `points` (first entry 0).
pub(crate) fn cumulative_lengths(points: &[DVec3]) -> Vec<f64> {
    let mut acc = 0.0;
    let mut out = Vec::with_capacity(points.len());
    out.push(0.0);
    for w in points.windows(2) {
        acc += w[0].distance(w[1]);
        out.push(acc);
    }
    if points.is_empty() {
        out.clear();
    }
    out
}

/// The key of a choice word: lower case, the separators `-`, `_` and spaces dropped
/// (`Catmull-Rom` → `catmullrom`). A word holding any other character — a control, format or
/// combining character, another letter — has no key (`None`): it is refused, not silently read
/// as a valid word.
pub fn choice_key(word: &str) -> Option<String> {
    let mut key = String::with_capacity(word.len());
    for c in word.trim().chars() {
        match c {
            '-' | '_' | ' ' => {}
            c if c.is_ascii_alphanumeric() => key.push(c.to_ascii_lowercase()),
            _ => return None,
        }
    }
    Some(key)
}

#[cfg(test)]
mod choice_tests {
    use super::choice_key;
    use super::spline::SplineKind;
    use super::subdivide::SubdivisionScheme;

    #[test]
    fn choice_words_with_hidden_characters_are_refused() {
        assert_eq!(choice_key(" Catmull-Rom ").as_deref(), Some("catmullrom"));
        assert_eq!(choice_key("four_point").as_deref(), Some("fourpoint"));
        for bad in [
            "natural\u{301}",
            "natural\u{200b}",
            "catmull-rom\u{0}",
            "natüral",
        ] {
            assert_eq!(choice_key(bad), None, "{bad:?}");
            assert!(SplineKind::parse(bad).is_err(), "{bad:?}");
        }
        assert!(SplineKind::parse("Natural").is_ok());
        assert!(SubdivisionScheme::parse("linear\u{7}").is_err());
        assert!(SubdivisionScheme::parse("Four-Point").is_ok());
    }
}
