//! Curves: every curve is a polyline; every sampling count is an input.
//!
//! - [`primitives`]: `curve.polyline`, `curve.line`, `curve.arc`, `curve.circle`, `curve.polygon`,
//!   `curve.helix`;
//! - [`sampling`]: `curve.spline`, `curve.resample`, `curve.subdivide`;
//! - [`edit`]: `curve.transform`, `curve.reverse`, `curve.join`;
//! - [`query`]: `curve.length`, `curve.points`.
//!
//! Angles are in degrees. Counts are numbers of points; a closed polyline stores each point once.

pub mod edit;
pub mod primitives;
pub mod query;
pub mod sampling;

pub use edit::{join, reverse, transform};
pub use primitives::{arc, circle, helix, line, polygon, polyline};
pub use query::{length, points};
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
    ]
}

#[cfg(test)]
pub(crate) mod test_util {
    use cnets_engine::eval::evaluate_node;
    use cnets_engine::prelude::*;

    /// Runs `def` with the named inputs (others default or empty).
    pub fn run(def: &NodeDef, named: &[(&str, Value)]) -> Result<Vec<Value>, String> {
        for (n, _) in named {
            assert!(def.input_index(n).is_some(), "{} has no input {n}", def.id);
        }
        let inputs: Vec<Value> = def
            .inputs
            .iter()
            .map(|p| {
                named
                    .iter()
                    .find(|(n, _)| *n == p.name)
                    .map(|(_, v)| v.clone())
                    .or_else(|| p.default.clone())
                    .unwrap_or(Value::Null)
            })
            .collect();
        evaluate_node(def, &NodeContext::default(), &inputs).map(|o| o.values)
    }

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
