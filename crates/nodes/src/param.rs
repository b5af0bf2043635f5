//! Parameters: the values a designer sets (the editor shows them as sliders, toggles and fields).
//!
//! Every parameter node has an input `value` and an output `value`, except the list makers
//! (`param.series`, `param.range`, `param.list`), whose output is `values`.

use cnets_engine::ValueType;
use cnets_engine::prelude::*;

/// A number as a designer reads it: plain digits for everyday magnitudes, scientific notation for
/// huge or tiny ones (`1e308`, not 309 digits).
fn readable(x: f64) -> String {
    if x == 0.0 || (1e-6..1e15).contains(&x.abs()) {
        x.to_string()
    } else {
        format!("{x:e}")
    }
}

node! {
    /// A number set by the designer; the editor shows it as a slider from `min` to `max`. The value
    /// is clamped to that range and snapped to multiples of `step` from `min` (`step` 0: no snapping).
    #[node(id = "param.number", category = "Params", name = "Number slider", flags(Parameter))]
    pub fn number[ctx](
        /// The value.
        #[ui(widget = Slider, range_inputs = ("min", "max"), step_input = "step")]
        value: k::Number = 0.5,
        /// Slider minimum.
        min: k::Number = 0.0,
        /// Slider maximum.
        max: k::Number = 1.0,
        /// Slider step (0 = continuous).
        #[ui(widget = DragValue, hard = 0.0..=f64::MAX)]
        step: k::Number = 0.0,
    ) -> (
        /// The value, clamped and snapped.
        value: k::Number,
    ) {
        if !(value.is_finite() && min.is_finite() && max.is_finite() && step.is_finite()) {
            return Err("value, min, max and step must be finite numbers".into());
        }
        if min > max {
            return Err(format!("min ({min}) is greater than max ({max})").into());
        }
        if step < 0.0 {
            return Err(format!("step must be 0 (continuous) or positive, got {step}").into());
        }
        let mut v = value.clamp(min, max);
        if v != value {
            ctx.warn(format!(
                "value {} is outside [{min}, {max}]; clamped to {v}",
                readable(value)
            ));
        }
        if step > 0.0 {
            v = cnets_engine::numbers::snap(v, min, step).clamp(min, max);
        }
        Ok((v,))
    }
}

node! {
    /// A whole number set by the designer; the editor shows it as a slider from `min` to `max`
    /// (the value is clamped to that range, with a warning).
    #[node(id = "param.integer", category = "Params", name = "Integer slider", flags(Parameter))]
    pub fn integer[ctx](
        /// The value.
        #[ui(widget = Slider, range_inputs = ("min", "max"))]
        value: k::Integer = 1,
        /// Slider minimum.
        min: k::Integer = 0,
        /// Slider maximum.
        max: k::Integer = 10,
    ) -> (
        /// The value, clamped.
        value: k::Integer,
    ) {
        if min > max {
            return Err(format!("min ({min}) is greater than max ({max})").into());
        }
        let v = value.clamp(min, max);
        if v != value {
            ctx.warn(format!("value {value} is outside [{min}, {max}]; clamped to {v}"));
        }
        Ok((v,))
    }
}

node! {
    /// A true/false toggle set by the designer.
    #[node(id = "param.boolean", category = "Params", name = "Boolean toggle", flags(Parameter))]
    pub fn boolean(
        /// The value.
        #[ui(widget = Toggle)]
        value: k::Boolean = false,
    ) -> (
        /// The value.
        value: k::Boolean,
    ) {
        Ok((value,))
    }
}

node! {
    /// A point set by the designer (x, y, z).
    #[node(id = "param.point", category = "Params", name = "Point", flags(Parameter))]
    pub fn point(
        /// The point.
        #[ui(widget = PointHandles)]
        value: k::Point = DVec3::ZERO,
    ) -> (
        /// The point.
        value: k::Point,
    ) {
        if !value.is_finite() {
            return Err(format!("point {value} is not finite").into());
        }
        Ok((value,))
    }
}

node! {
    /// Points set by the designer (Grasshopper's "Set multiple points"): a literal list the editor
    /// shows as handles in the 3D view — drawn with the Draw curve tool, dragged, nudged or typed.
    /// Every point must be finite.
    #[node(id = "param.points", category = "Params", name = "Points", flags(Parameter))]
    pub fn points(
        /// The points.
        #[ui(widget = PointHandles)]
        points: k::List<k::Point> = Value::list(vec![]),
    ) -> (
        /// The points.
        points: k::List<k::Point>,
    ) {
        if let Some(k) = points.iter().position(|p| !p.is_finite()) {
            return Err(format!("point {k} ({}) is not finite", points[k]).into());
        }
        Ok((points,))
    }
}

node! {
    /// A vector set by the designer (x, y, z).
    #[node(id = "param.vector", category = "Params", name = "Vector", flags(Parameter))]
    pub fn vector(
        /// The vector.
        value: k::Vector = DVec3::Z,
    ) -> (
        /// The vector.
        value: k::Vector,
    ) {
        if !value.is_finite() {
            return Err(format!("vector {value} is not finite").into());
        }
        Ok((value,))
    }
}

node! {
    /// A piece of text set by the designer (a file name, a graph type, a method name…).
    #[node(id = "param.text", category = "Params", name = "Text", flags(Parameter))]
    pub fn text(
        /// The text.
        value: k::Text = "",
    ) -> (
        /// The text.
        value: k::Text,
    ) {
        Ok((value,))
    }
}

node! {
    /// One of a list of options, picked by the designer (Grasshopper's Value List): the editor shows
    /// a drop-down of `options`. Outputs the chosen text and its index; an index outside the
    /// options is an error naming the options.
    #[node(id = "param.choice", category = "Params", name = "Value list", flags(Parameter))]
    pub fn choice(
        /// The options offered, in order.
        #[ui(widget = MultilineText)]
        options: k::List<k::Text>,
        /// Index of the chosen option (0 = first).
        #[ui(widget = Choice, options_input = "options")]
        index: k::Integer = 0,
    ) -> (
        /// The chosen option.
        value: k::Text,
        /// Its index.
        index: k::Integer,
    ) {
        if options.is_empty() {
            return Err("there are no options to choose from: set options".into());
        }
        let k = usize::try_from(index)
            .ok()
            .filter(|&k| k < options.len())
            .ok_or_else(|| {
                NodeError::new(format!(
                    "index {index} is out of range: there are {} options ({})",
                    options.len(),
                    options.join(", ")
                ))
            })?;
        Ok((options[k].clone(), index))
    }
}

/// Largest list a list-making parameter produces.
const MAX_COUNT: i64 = 10_000_000;

fn check_list_count(count: i64) -> Result<usize, NodeError> {
    if count < 0 {
        return Err(format!("count must be 0 or more, got {count}").into());
    }
    if count > MAX_COUNT {
        return Err(format!("count {count} is too large (at most {MAX_COUNT})").into());
    }
    Ok(count as usize)
}

node! {
    /// An arithmetic series: `count` numbers start, start + step, start + 2·step, … (count 0 gives
    /// an empty list).
    #[node(id = "param.series", category = "Params", name = "Series", flags(Parameter))]
    pub fn series[ctx](
        /// First number.
        start: k::Number = 0.0,
        /// Difference between consecutive numbers (may be negative or 0).
        step: k::Number = 1.0,
        /// How many numbers (≥ 0).
        count: k::Integer = 10,
    ) -> (
        /// The numbers.
        values: k::List<k::Number>,
    ) {
        if !(start.is_finite() && step.is_finite()) {
            return Err("start and step must be finite numbers".into());
        }
        let n = check_list_count(count)?;
        ctx.reserve_values(n as u128, &format!("a series of {n} numbers"))?;
        let values: Vec<f64> = (0..n).map(|k| start + step * k as f64).collect();
        if values.iter().any(|v| !v.is_finite()) {
            return Err("the series overflows".into());
        }
        Ok((values,))
    }
}

node! {
    /// `count` evenly spaced numbers from `start` to `end`, both included (the domain is given by
    /// its two ends; `end` may be smaller than `start`). Count 1 gives `[start]`, count 0 an empty
    /// list.
    #[node(id = "param.range", category = "Params", name = "Range", flags(Parameter))]
    pub fn range[ctx](
        /// Start of the domain (the first number).
        start: k::Number = 0.0,
        /// End of the domain (the last number).
        end: k::Number = 1.0,
        /// How many numbers (≥ 0).
        count: k::Integer = 11,
    ) -> (
        /// The numbers.
        values: k::List<k::Number>,
    ) {
        if !(start.is_finite() && end.is_finite() && (end - start).is_finite()) {
            return Err("start and end must be finite numbers".into());
        }
        let n = check_list_count(count)?;
        ctx.reserve_values(n as u128, &format!("a range of {n} numbers"))?;
        let values: Vec<f64> = (0..n)
            .map(|k| {
                if k + 1 == n && n > 1 {
                    end
                } else if n == 1 {
                    start
                } else {
                    start + (end - start) * k as f64 / (n - 1) as f64
                }
            })
            .collect();
        Ok((values,))
    }
}

/// The item types `param.list` accepts.
const LIST_TYPES: &str = "number, integer, boolean, text, point, vector, any";

/// Converts one leaf of a literal list to `ty` by the engine's implicit conversions
/// ([`cnets_engine::convert::coerce_item`]), naming its position on failure. A point read where
/// numbers are expected is the file reader's three-number row: it becomes three numbers.
fn convert_leaf(v: &Value, ty: &ValueType, at: &str) -> Result<Value, NodeError> {
    if let (ValueType::Number | ValueType::Integer, Value::Point(p) | Value::Vector(p)) = (ty, v) {
        return p
            .to_array()
            .iter()
            .enumerate()
            .map(|(k, x)| convert_leaf(&Value::Number(*x), ty, &format!("{at}[{k}]")))
            .collect::<Result<Vec<_>, _>>()
            .map(Value::list);
    }
    cnets_engine::convert::coerce_item(v, ty).map_err(|e| match e {
        cnets_engine::convert::ConvertError::NotInteger(x) => {
            NodeError::new(format!("item {at} is {x}, expected a whole number"))
        }
        _ => NodeError::new(format!("item {at} is {}, expected {ty}", v.type_name())),
    })
}

fn convert_tree(v: &Value, ty: &ValueType, at: &str) -> Result<Value, NodeError> {
    match v {
        Value::List(items) => items
            .iter()
            .enumerate()
            .map(|(k, item)| {
                let at = if at.is_empty() {
                    k.to_string()
                } else {
                    format!("{at}[{k}]")
                };
                convert_tree(item, ty, &at)
            })
            .collect::<Result<Vec<_>, _>>()
            .map(Value::list),
        Value::Null => Err(NodeError::new(format!(
            "item {} is empty",
            if at.is_empty() { "0" } else { at }
        ))),
        leaf => convert_leaf(leaf, ty, if at.is_empty() { "0" } else { at }),
    }
}

node! {
    /// A literal list typed in by the designer, checked against `item_type` (number, integer,
    /// boolean, text, point, vector, or any): every item is converted to that type (integers ↔
    /// numbers, points ↔ vectors) or the node fails naming the first bad item. Nested lists (tables)
    /// are kept as they are. A single value becomes a one-element list. For number and integer lists
    /// a three-number row that the file reader took for a point is read back as three numbers.
    #[node(id = "param.list", category = "Params", name = "List of numbers", flags(Parameter))]
    pub fn list(
        /// The items (a list, possibly nested).
        #[ui(item_type_input = "item_type")]
        values: k::Tree<k::Any> = Value::list(vec![]),
        /// The item type: number, integer, boolean, text, point, vector or any.
        item_type: k::Choice<crate::choices::ListItemType> = "number",
    ) -> (
        /// The checked list.
        values: k::Tree<k::Any>,
    ) {
        let ty = match ValueType::parse(item_type) {
            Some(ty) => ty,
            _ => {
                return Err(
                    format!("unknown item_type '{item_type}': expected one of {LIST_TYPES}").into(),
                );
            }
        };
        let converted = convert_tree(&values, &ty, "")?;
        let out = match converted {
            Value::List(_) => converted,
            single => Value::list(vec![single]),
        };
        Ok((out,))
    }
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![
        number(),
        integer(),
        boolean(),
        point(),
        points(),
        vector(),
        text(),
        choice(),
        series(),
        range(),
        list(),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_engine::eval::{evaluate_node, run_mapped};

    fn run(def: &NodeDef, inputs: &[f64]) -> Result<Vec<Value>, NodeError> {
        let values: Vec<Value> = inputs.iter().map(|&x| Value::Number(x)).collect();
        run_mapped(def, &NodeContext::default(), &values)
    }

    fn numbers(v: &Value) -> Vec<f64> {
        v.as_list()
            .expect("a list")
            .iter()
            .map(|x| x.as_f64().expect("a number"))
            .collect()
    }

    #[test]
    fn choice_picks_an_option_and_names_them_when_out_of_range() {
        let options = Value::list(vec![Value::text("graph"), Value::text("bezier")]);
        let ctx = NodeContext::default();
        let out = evaluate_node(&choice(), &ctx, &[options.clone(), Value::Integer(1)]).unwrap();
        assert_eq!(out.values, vec![Value::text("bezier"), Value::Integer(1)]);
        let e = evaluate_node(&choice(), &ctx, &[options, Value::Integer(2)])
            .unwrap_err()
            .to_string();
        assert!(e.contains("index 2") && e.contains("graph, bezier"), "{e}");
        let e = evaluate_node(&choice(), &ctx, &[Value::list(vec![]), Value::Integer(0)]);
        assert!(e.unwrap_err().to_string().contains("no options"));
    }

    #[test]
    fn number_clamps_and_snaps() {
        let def = number();
        assert_eq!(
            run(&def, &[0.26, 0.0, 1.0, 0.1]).unwrap(),
            vec![Value::Number(0.3)]
        );
        assert_eq!(
            run(&def, &[5.0, 0.0, 1.0, 0.0]).unwrap(),
            vec![Value::Number(1.0)]
        );
        assert!(
            run(&def, &[0.5, 2.0, 1.0, 0.0])
                .unwrap_err()
                .to_string()
                .contains("greater than max")
        );
        assert!(run(&def, &[f64::NAN, 0.0, 1.0, 0.0]).is_err());
        assert!(run(&def, &[0.5, 0.0, 1.0, -0.1]).is_err());
    }

    #[test]
    fn clamping_warns_with_a_readable_value() {
        let ctx = NodeContext::default();
        let inputs = [1e308, 4.0, 30.0, 0.0].map(Value::Number);
        let out = evaluate_node(&number(), &ctx, &inputs).unwrap();
        assert_eq!(out.values, vec![Value::Number(30.0)]);
        assert_eq!(
            out.warnings,
            vec!["value 1e308 is outside [4, 30]; clamped to 30".to_string()]
        );
        assert_eq!(readable(35.5), "35.5");
        assert_eq!(readable(-2e-9), "-2e-9");
    }

    #[test]
    fn integer_clamps_with_a_warning() {
        let ctx = NodeContext::default();
        let out = evaluate_node(
            &integer(),
            &ctx,
            &[Value::Integer(12), Value::Integer(0), Value::Integer(10)],
        )
        .unwrap();
        assert_eq!(out.values, vec![Value::Integer(10)]);
        assert_eq!(out.warnings.len(), 1);
        let bad = [Value::Integer(1), Value::Integer(3), Value::Integer(2)];
        assert!(evaluate_node(&integer(), &ctx, &bad).is_err());
    }

    #[test]
    fn simple_parameters_pass_their_value_through() {
        let ctx = NodeContext::default();
        let b = evaluate_node(&boolean(), &ctx, &[Value::Boolean(true)]).unwrap();
        assert_eq!(b.values, vec![Value::Boolean(true)]);
        let p = DVec3::new(1.0, 2.0, 3.0);
        let out = evaluate_node(&point(), &ctx, &[Value::Point(p)]).unwrap();
        assert_eq!(out.values, vec![Value::Point(p)]);
        let out = evaluate_node(&vector(), &ctx, &[Value::Point(p)]).unwrap();
        assert_eq!(out.values, vec![Value::Vector(p)]);
        assert!(evaluate_node(&point(), &ctx, &[Value::Point(DVec3::NAN)]).is_err());
        let t = evaluate_node(&text(), &ctx, &[Value::text("bezier")]).unwrap();
        assert_eq!(t.values, vec![Value::text("bezier")]);
    }

    #[test]
    fn series_and_range() {
        let out = run(&series(), &[1.0, -0.5, 4.0]).unwrap();
        assert_eq!(numbers(&out[0]), vec![1.0, 0.5, 0.0, -0.5]);
        assert_eq!(
            numbers(&run(&series(), &[1.0, 1.0, 0.0]).unwrap()[0]).len(),
            0
        );
        assert!(run(&series(), &[0.0, 1.0, -1.0]).is_err());
        let out = run(&range(), &[2.0, 0.0, 5.0]).unwrap();
        assert_eq!(numbers(&out[0]), vec![2.0, 1.5, 1.0, 0.5, 0.0]);
        assert_eq!(
            numbers(&run(&range(), &[2.0, 3.0, 1.0]).unwrap()[0]),
            vec![2.0]
        );
        assert!(numbers(&run(&range(), &[2.0, 3.0, 0.0]).unwrap()[0]).is_empty());
        assert!(run(&range(), &[f64::NAN, 3.0, 2.0]).is_err());
        // A list of counts maps: one range per count.
        let out = run_mapped(
            &range(),
            &NodeContext::default(),
            &[
                Value::Number(0.0),
                Value::Number(1.0),
                Value::list(vec![Value::Integer(2), Value::Integer(3)]),
            ],
        )
        .unwrap();
        assert_eq!(numbers(&out[0].as_list().unwrap()[1]), vec![0.0, 0.5, 1.0]);
    }

    #[test]
    fn list_checks_and_converts_items() {
        let ctx = NodeContext::default();
        let mixed = Value::list(vec![Value::Integer(1), Value::Number(2.5)]);
        let out = evaluate_node(&list(), &ctx, &[mixed.clone(), Value::text("number")]).unwrap();
        assert_eq!(numbers(&out.values[0]), vec![1.0, 2.5]);
        let err = evaluate_node(&list(), &ctx, &[mixed, Value::text("integer")])
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("item 1 is 2.5, expected a whole number"),
            "{err}"
        );
        // Points and vectors convert into each other (the engine's implicit conversions).
        let at = Value::list(vec![Value::Point(DVec3::X)]);
        let out = evaluate_node(&list(), &ctx, &[at, Value::text("vector")]).unwrap();
        assert_eq!(out.values[0].as_list().unwrap()[0], Value::Vector(DVec3::X));
        // A row of three numbers parsed as a point is read back as numbers.
        let table = Value::list(vec![Value::Point(DVec3::new(0.1, 0.2, 0.3))]);
        let out = evaluate_node(&list(), &ctx, &[table, Value::text("number")]).unwrap();
        assert_eq!(
            numbers(&out.values[0].as_list().unwrap()[0]),
            vec![0.1, 0.2, 0.3]
        );
        let words = Value::list(vec![Value::text("a"), Value::Number(1.0)]);
        let err = evaluate_node(&list(), &ctx, &[words, Value::text("text")])
            .unwrap_err()
            .to_string();
        assert!(err.contains("item 1 is number"), "{err}");
        let single =
            evaluate_node(&list(), &ctx, &[Value::Number(3.0), Value::text("any")]).unwrap();
        assert_eq!(numbers(&single.values[0]), vec![3.0]);
        assert!(evaluate_node(&list(), &ctx, &[Value::Number(1.0), Value::text("float")]).is_err());
    }
}
