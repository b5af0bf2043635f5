//! Helpers shared by the node modules' unit tests.

use cnets_engine::eval::evaluate_node;
use cnets_engine::prelude::*;

/// Runs `def` with the named inputs (the others take their defaults, or stay empty) and returns
/// its outputs or its error message.
pub fn run_named(def: &NodeDef, named: &[(&str, Value)]) -> Result<Vec<Value>, String> {
    for (name, _) in named {
        assert!(
            def.input_index(name).is_some(),
            "{} has no input '{name}'",
            def.id
        );
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
    evaluate_node(def, &NodeContext::default(), &inputs)
        .map(|o| o.values)
        .map_err(|e| e.to_string())
}

/// A list of numbers.
pub fn nums(xs: &[f64]) -> Value {
    Value::list(xs.iter().map(|&x| Value::Number(x)).collect())
}

/// A list of integers.
pub fn ints(xs: &[i64]) -> Value {
    Value::list(xs.iter().map(|&x| Value::Integer(x)).collect())
}

/// A list of booleans.
pub fn bools(xs: &[bool]) -> Value {
    Value::list(xs.iter().map(|&x| Value::Boolean(x)).collect())
}

/// A list of points.
pub fn points(ps: &[[f64; 3]]) -> Value {
    Value::list(ps.iter().map(|p| Value::Point(DVec3::from(*p))).collect())
}
