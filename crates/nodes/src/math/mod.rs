//! Math on numbers and lists: arithmetic, remapping, min/max, clamping.
//!
//! Every input here has item access, so the nodes work on numbers and lists alike: a list on any
//! input runs the node once per item (lists of different lengths are matched by index, the shorter
//! one repeating its last item), and a list of lists runs it per item of every row. Inputs must be
//! finite and results must be finite; otherwise the node fails naming what overflowed.

pub mod expression;
pub mod random;

use std::cell::RefCell;
use std::sync::Arc;

use cnets_engine::prelude::*;

fn finite(what: &str, x: f64) -> Result<f64, NodeError> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(NodeError::new(format!(
            "{what} is {x}, expected a finite number"
        )))
    }
}

fn result(what: &str, x: f64) -> Result<(f64,), NodeError> {
    if x.is_finite() {
        Ok((x,))
    } else {
        Err(NodeError::new(format!(
            "{what} is not a finite number (got {x})"
        )))
    }
}

node! {
    /// a + b, on numbers or lists (item by item).
    #[node(id = "math.add", category = "Math")]
    pub fn add(
        /// First term.
        a: k::Number = 0.0,
        /// Second term.
        b: k::Number = 0.0,
    ) -> (
        /// a + b.
        result: k::Number,
    ) {
        let (a, b) = (finite("a", a)?, finite("b", b)?);
        let (r,) = result("the sum", a + b)?;
        Ok((r,))
    }
}

node! {
    /// a − b, on numbers or lists (item by item).
    #[node(id = "math.subtract", category = "Math")]
    pub fn subtract(
        /// Number to subtract from.
        a: k::Number = 0.0,
        /// Number to subtract.
        b: k::Number = 0.0,
    ) -> (
        /// a − b.
        result: k::Number,
    ) {
        let (a, b) = (finite("a", a)?, finite("b", b)?);
        let (r,) = result("the difference", a - b)?;
        Ok((r,))
    }
}

node! {
    /// a · b, on numbers or lists (item by item).
    #[node(id = "math.multiply", category = "Math")]
    pub fn multiply(
        /// First factor.
        a: k::Number = 1.0,
        /// Second factor.
        b: k::Number = 1.0,
    ) -> (
        /// a · b.
        result: k::Number,
    ) {
        let (a, b) = (finite("a", a)?, finite("b", b)?);
        let (r,) = result("the product", a * b)?;
        Ok((r,))
    }
}

node! {
    /// a / b, on numbers or lists (item by item). Dividing by zero is an error.
    #[node(id = "math.divide", category = "Math")]
    pub fn divide(
        /// Dividend.
        a: k::Number = 1.0,
        /// Divisor (≠ 0).
        b: k::Number = 1.0,
    ) -> (
        /// a / b.
        result: k::Number,
    ) {
        let (a, b) = (finite("a", a)?, finite("b", b)?);
        if b == 0.0 {
            return Err(format!("division by zero ({a} / 0)").into());
        }
        let (r,) = result("the quotient", a / b)?;
        Ok((r,))
    }
}

node! {
    /// base raised to exponent, on numbers or lists (item by item). A negative base needs a whole
    /// exponent; 0 to a negative power is an error.
    #[node(id = "math.power", category = "Math")]
    pub fn power(
        /// The base.
        base: k::Number = 2.0,
        /// The exponent.
        exponent: k::Number = 2.0,
    ) -> (
        /// base^exponent.
        result: k::Number,
    ) {
        let (b, e) = (finite("base", base)?, finite("exponent", exponent)?);
        if b < 0.0 && e.fract() != 0.0 {
            return Err(format!("{b} ^ {e}: a negative base needs a whole exponent").into());
        }
        if b == 0.0 && e < 0.0 {
            return Err(format!("0 ^ {e}: zero to a negative power is undefined").into());
        }
        let (r,) = result("the power", b.powf(e))?;
        Ok((r,))
    }
}

node! {
    /// Maps a number (or each number of a list) linearly from the domain [from_start, from_end]
    /// to [to_start, to_end]: from_start ↦ to_start, from_end ↦ to_end. Either domain may run
    /// backwards. Values outside the source domain are extrapolated, or clamped to the target
    /// domain when `clamp` is on. An empty source domain (from_start = from_end) is an error.
    #[node(id = "math.remap", category = "Math")]
    pub fn remap(
        /// The number to map.
        value: k::Number,
        /// Start of the source domain.
        from_start: k::Number = 0.0,
        /// End of the source domain (≠ from_start).
        from_end: k::Number = 1.0,
        /// Start of the target domain.
        to_start: k::Number = 0.0,
        /// End of the target domain.
        to_end: k::Number = 1.0,
        /// Clamp results to the target domain.
        clamp: k::Boolean = false,
    ) -> (
        /// The mapped number.
        result: k::Number,
    ) {
        let x = finite("value", value)?;
        let (a, b) = (finite("from_start", from_start)?, finite("from_end", from_end)?);
        let (c, d) = (finite("to_start", to_start)?, finite("to_end", to_end)?);
        if a == b {
            return Err(format!("the source domain is empty (from_start = from_end = {a})").into());
        }
        let t = (x - a) / (b - a);
        let mut y = c + t * (d - c);
        if t == 1.0 {
            y = d;
        }
        if clamp {
            y = y.clamp(c.min(d), c.max(d));
        }
        let (r,) = result("the remapped value", y)?;
        Ok((r,))
    }
}

node! {
    /// The smaller of a and b, on numbers or lists (item by item). For the smallest number of a
    /// whole list use `math.bounds`.
    #[node(id = "math.min", category = "Math")]
    pub fn min(
        /// First number.
        a: k::Number,
        /// Second number.
        b: k::Number,
    ) -> (
        /// min(a, b).
        result: k::Number,
    ) {
        Ok((finite("a", a)?.min(finite("b", b)?),))
    }
}

node! {
    /// The larger of a and b, on numbers or lists (item by item). For the largest number of a
    /// whole list use `math.bounds`.
    #[node(id = "math.max", category = "Math")]
    pub fn max(
        /// First number.
        a: k::Number,
        /// Second number.
        b: k::Number,
    ) -> (
        /// max(a, b).
        result: k::Number,
    ) {
        Ok((finite("a", a)?.max(finite("b", b)?),))
    }
}

node! {
    /// The smallest and largest number of a whole list (an empty list is an error).
    #[node(id = "math.bounds", category = "Math")]
    pub fn bounds(
        /// The numbers.
        values: k::List<k::Number>,
    ) -> (
        /// The smallest number.
        min: k::Number,
        /// The largest number.
        max: k::Number,
    ) {
        if values.is_empty() {
            return Err("the list is empty: it has no smallest or largest number".into());
        }
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for (k, &v) in values.iter().enumerate() {
            finite(&format!("value {k}"), v)?;
            lo = lo.min(v);
            hi = hi.max(v);
        }
        Ok((lo, hi))
    }
}

node! {
    /// Limits a number (or each number of a list) to [min, max].
    #[node(id = "math.clamp", category = "Math")]
    pub fn clamp(
        /// The number.
        value: k::Number,
        /// Lower limit.
        min: k::Number = 0.0,
        /// Upper limit (≥ min).
        max: k::Number = 1.0,
    ) -> (
        /// The clamped number.
        result: k::Number,
    ) {
        let (x, lo, hi) = (finite("value", value)?, finite("min", min)?, finite("max", max)?);
        if lo > hi {
            return Err(format!("min ({lo}) is greater than max ({hi})").into());
        }
        Ok((x.clamp(lo, hi),))
    }
}

thread_local! {
    /// The last expression parsed on this thread: a node mapped over a list parses its text once.
    static LAST_EXPRESSION: RefCell<Option<(String, Arc<expression::Expr>)>> =
        const { RefCell::new(None) };
}

fn parsed(text: &str) -> Result<Arc<expression::Expr>, NodeError> {
    LAST_EXPRESSION.with(|last| {
        let mut last = last.borrow_mut();
        if let Some((cached, expr)) = last.as_ref()
            && cached == text
        {
            return Ok(expr.clone());
        }
        let expr = Arc::new(expression::parse(text).map_err(|e| {
            NodeError::new(format!(
                "expression '{}': {e}",
                cnets_engine::files::excerpt(text, 60)
            ))
        })?);
        *last = Some((text.to_string(), expr.clone()));
        Ok(expr)
    })
}

node! {
    /// Evaluates an arithmetic expression in x, y and z (Grasshopper's Expression). Operators
    /// `+ - * / ^` (power, right-associative; `-2^2` is −4), unary minus, parentheses; functions
    /// `sin cos tan asin acos atan atan2(y, x) sqrt abs exp ln log10 floor ceil round min(a, b, …)
    /// max(a, b, …)` (angles in radians; `round` rounds halves away from zero); constants `pi` and
    /// `e`. Division is real (`1/2` is 0.5). A syntax error names its column, an unknown name is
    /// named, and a result that is not a finite number (`sqrt(-1)`, `1/0`) is an error. Lists on x,
    /// y or z evaluate the expression per item.
    #[node(id = "math.expression", category = "Math", name = "Expression")]
    pub fn expression(
        /// The expression, e.g. `sin(pi*x)^2 + y/4`.
        expression: k::Text,
        /// The value of x.
        x: k::Number = 0.0,
        /// The value of y.
        y: k::Number = 0.0,
        /// The value of z.
        z: k::Number = 0.0,
    ) -> (
        /// The expression's value.
        result: k::Number,
    ) {
        let expr = parsed(&expression)?;
        let value = expr.eval(&[x, y, z]);
        if !value.is_finite() {
            return Err(format!(
                "expression '{}' is not a finite number at x = {x}, y = {y}, z = {z} (got {value})",
                cnets_engine::files::excerpt(&expression, 60)
            )
            .into());
        }
        Ok((value,))
    }
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![
        expression(),
        random::random(),
        add(),
        subtract(),
        multiply(),
        divide(),
        power(),
        remap(),
        min(),
        max(),
        bounds(),
        clamp(),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_engine::eval::evaluate_node;

    fn num(x: f64) -> Value {
        Value::Number(x)
    }

    fn nums(xs: &[f64]) -> Value {
        Value::list(xs.iter().map(|&x| num(x)).collect())
    }

    fn run(def: NodeDef, inputs: &[Value]) -> Result<Vec<Value>, String> {
        let mut all = inputs.to_vec();
        for p in &def.inputs[inputs.len()..] {
            all.push(p.default.clone().unwrap_or(Value::Null));
        }
        evaluate_node(&def, &NodeContext::default(), &all)
            .map(|o| o.values)
            .map_err(|e| e.to_string())
    }

    fn one(def: NodeDef, inputs: &[Value]) -> f64 {
        run(def, inputs).unwrap()[0].as_f64().unwrap()
    }

    #[test]
    fn expression_evaluates_the_contract_example_and_maps_over_lists() {
        let text = Value::text("sin(pi*x)^2 + y/4");
        let v = one(expression(), &[text.clone(), num(0.5), num(2.0)]);
        assert!((v - 1.5).abs() < 1e-15, "{v}");
        let out = run(
            expression(),
            &[
                Value::text("x*y + z"),
                nums(&[1.0, 2.0, 3.0]),
                num(10.0),
                num(0.5),
            ],
        )
        .unwrap();
        assert_eq!(out[0], nums(&[10.5, 20.5, 30.5]));
        let e = run(expression(), &[Value::text("sqrt(x)"), num(-1.0)]).unwrap_err();
        assert!(e.contains("not a finite number"), "{e}");
        let e = run(expression(), &[Value::text("x + q")]).unwrap_err();
        assert!(
            e.contains("unknown name 'q'") && e.contains("column 5"),
            "{e}"
        );
        let e = run(expression(), &[Value::text("(x")]).unwrap_err();
        assert!(e.contains("column 3"), "{e}");
    }

    #[test]
    fn arithmetic_on_numbers() {
        assert_eq!(one(add(), &[num(1.5), num(2.0)]), 3.5);
        assert_eq!(one(subtract(), &[num(1.5), num(2.0)]), -0.5);
        assert_eq!(one(multiply(), &[num(1.5), num(2.0)]), 3.0);
        assert_eq!(one(divide(), &[num(3.0), num(2.0)]), 1.5);
        assert_eq!(one(power(), &[num(2.0), num(10.0)]), 1024.0);
        assert_eq!(one(power(), &[num(-2.0), num(3.0)]), -8.0);
        assert_eq!(one(min(), &[num(-2.0), num(3.0)]), -2.0);
        assert_eq!(one(max(), &[num(-2.0), num(3.0)]), 3.0);
        assert_eq!(one(clamp(), &[num(1.7)]), 1.0);
    }

    #[test]
    fn arithmetic_maps_over_lists_with_longest_list_matching() {
        let out = run(add(), &[nums(&[1.0, 2.0, 3.0]), nums(&[10.0, 20.0])]).unwrap();
        assert_eq!(out[0], nums(&[11.0, 22.0, 23.0]));
        let out = run(multiply(), &[nums(&[1.0, 2.0]), num(0.5)]).unwrap();
        assert_eq!(out[0], nums(&[0.5, 1.0]));
        let table = Value::list(vec![nums(&[1.0, 2.0]), nums(&[3.0])]);
        let out = run(subtract(), &[table, num(1.0)]).unwrap();
        assert_eq!(out[0], Value::list(vec![nums(&[0.0, 1.0]), nums(&[2.0])]));
    }

    #[test]
    fn errors_name_the_problem() {
        let e = run(divide(), &[num(1.0), num(0.0)]).unwrap_err();
        assert!(e.contains("division by zero"), "{e}");
        let e = run(divide(), &[num(1.0), nums(&[1.0, 0.0])]).unwrap_err();
        assert!(e.contains("item 1"), "{e}");
        assert!(run(power(), &[num(-2.0), num(0.5)]).is_err());
        assert!(run(power(), &[num(0.0), num(-1.0)]).is_err());
        assert!(
            run(power(), &[num(10.0), num(400.0)])
                .unwrap_err()
                .contains("finite")
        );
        assert!(run(add(), &[num(f64::NAN), num(1.0)]).is_err());
        assert!(run(multiply(), &[num(1e300), num(1e300)]).is_err());
        assert!(run(clamp(), &[num(0.5), num(2.0), num(1.0)]).is_err());
    }

    #[test]
    fn remap_maps_domains_both_ways_and_clamps() {
        let r = |x: f64, a: f64, b: f64, c: f64, d: f64, cl: bool| {
            one(
                remap(),
                &[num(x), num(a), num(b), num(c), num(d), Value::Boolean(cl)],
            )
        };
        assert_eq!(r(5.0, 0.0, 10.0, 1.0, 2.0, false), 1.5);
        assert_eq!(r(10.0, 0.0, 10.0, 2.0, -2.0, false), -2.0);
        assert_eq!(r(0.25, 1.0, 0.0, 0.0, 100.0, false), 75.0);
        assert_eq!(r(20.0, 0.0, 10.0, 0.0, 1.0, false), 2.0);
        assert_eq!(r(20.0, 0.0, 10.0, 0.0, 1.0, true), 1.0);
        assert_eq!(r(-5.0, 0.0, 10.0, 1.0, 0.0, true), 1.0);
        let e = run(remap(), &[num(1.0), num(2.0), num(2.0)]).unwrap_err();
        assert!(e.contains("source domain is empty"), "{e}");
        let out = run(
            remap(),
            &[
                nums(&[0.0, 0.5, 1.0]),
                num(0.0),
                num(1.0),
                num(10.0),
                num(20.0),
            ],
        )
        .unwrap();
        assert_eq!(out[0], nums(&[10.0, 15.0, 20.0]));
    }

    #[test]
    fn bounds_of_a_list() {
        let out = run(bounds(), &[nums(&[3.0, -1.0, 2.0])]).unwrap();
        assert_eq!(out, vec![num(-1.0), num(3.0)]);
        assert!(run(bounds(), &[nums(&[])]).unwrap_err().contains("empty"));
        assert!(run(bounds(), &[nums(&[1.0, f64::NAN])]).is_err());
    }
}
