//! Curves: every curve is a polyline; every sampling count is an input.
//!
//! - [`primitives`]: `curve.polyline`, `curve.line`, `curve.arc`, `curve.circle`, `curve.polygon`,
//!   `curve.helix`;
//! - [`sampling`]: `curve.spline`, `curve.resample`, `curve.subdivide`;
//! - [`edit`]: `curve.transform`, `curve.reverse`, `curve.join`, `curve.offset`;
//! - [`query`]: `curve.length`, `curve.points`, `curve.evaluate`, `curve.closest_point`.
//!
//! Angles are in degrees. Counts are numbers of points; a closed polyline stores each point once.

pub mod edit;
pub mod primitives;
pub mod query;
pub mod sampling;

pub use edit::{join, offset, reverse, transform};
pub use primitives::{
    arc, arc_span_rise, arc_three_points, circle, helix, line, polygon, polyline,
};
pub use query::{closest_point, evaluate, length, points};
pub use sampling::{resample, spline, subdivide};

use cnets_engine::NodeDef;

/// A non-negative integer count from a node input, or an error naming it.
pub(crate) fn count_input(name: &str, value: i64) -> Result<usize, cnets_engine::NodeError> {
    usize::try_from(value)
        .map_err(|_| cnets_engine::NodeError::new(format!("{name} must be 0 or more, got {value}")))
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![
        polyline(),
        line(),
        arc(),
        arc_three_points(),
        arc_span_rise(),
        circle(),
        polygon(),
        helix(),
        spline(),
        resample(),
        subdivide(),
        transform(),
        reverse(),
        join(),
        length(),
        points(),
        evaluate(),
        closest_point(),
        offset(),
    ]
}

#[cfg(test)]
pub(crate) mod test_util {
    use cnets_engine::prelude::*;

    /// Runs `def` with the named inputs (others default or empty).
    pub use crate::testing::run_named as run;

    /// The polyline in a value.
    pub fn poly(v: &Value) -> Polyline {
        match v {
            Value::Polyline(p) => (**p).clone(),
            other => panic!("expected a polyline, got {}", other.type_name()),
        }
    }

    /// A list of points as a value.
    pub fn pts(ps: &[DVec3]) -> Value {
        Value::list(ps.iter().map(|&p| Value::Point(p)).collect())
    }

    /// A polyline value.
    pub fn pl(points: &[DVec3], closed: bool) -> Value {
        Value::from(Polyline {
            points: points.to_vec(),
            closed,
        })
    }
}
