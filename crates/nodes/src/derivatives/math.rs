//! Partial derivatives of the math nodes (item ports: one number in, one out) and of
//! `vector.point` (three numbers in, one point out).

use cnets_engine::optimize::vjp::{VjpArgs, VjpResult};
use cnets_engine::prelude::*;

type Product = fn(&VjpArgs<'_>) -> VjpResult;

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or(0.0)
}

/// Input cotangents `c · ∂result/∂input_k` from the partial derivatives.
fn scale(args: &VjpArgs<'_>, partials: &[f64]) -> VjpResult {
    let c = args.cotangent(0).first().copied().unwrap_or(0.0);
    Ok(args
        .wanted
        .iter()
        .enumerate()
        .map(|(k, &w)| {
            (w && k < partials.len() && args.inputs[k].as_f64().is_some())
                .then(|| vec![c * partials[k]])
        })
        .collect())
}

fn add(a: &VjpArgs<'_>) -> VjpResult {
    scale(a, &[1.0, 1.0])
}

fn subtract(a: &VjpArgs<'_>) -> VjpResult {
    scale(a, &[1.0, -1.0])
}

fn multiply(a: &VjpArgs<'_>) -> VjpResult {
    let (x, y) = (num(&a.inputs[0]), num(&a.inputs[1]));
    scale(a, &[y, x])
}

fn divide(a: &VjpArgs<'_>) -> VjpResult {
    let (x, y) = (num(&a.inputs[0]), num(&a.inputs[1]));
    scale(a, &[1.0 / y, -x / (y * y)])
}

fn power(a: &VjpArgs<'_>) -> VjpResult {
    let (b, e) = (num(&a.inputs[0]), num(&a.inputs[1]));
    let db = if e == 0.0 { 0.0 } else { e * b.powf(e - 1.0) };
    let de = if b > 0.0 { b.powf(e) * b.ln() } else { 0.0 };
    if b <= 0.0 && a.wanted.get(1) == Some(&true) {
        return Err(NodeError::new(
            "the power's derivative in the exponent needs a positive base",
        ));
    }
    scale(a, &[db, de])
}

fn remap(a: &VjpArgs<'_>) -> VjpResult {
    let x: Vec<f64> = a.inputs[..5].iter().map(num).collect();
    let (v, s0, s1, t0, t1) = (x[0], x[1], x[2], x[3], x[4]);
    let clamp = matches!(a.inputs.get(5), Some(Value::Boolean(true)));
    let t = (v - s0) / (s1 - s0);
    let y = t0 + t * (t1 - t0);
    if clamp && (y < t0.min(t1) || y > t0.max(t1)) {
        // Clamped: the result is the bound.
        let at_start = (y - t0).abs() < (y - t1).abs();
        return scale(
            a,
            &[
                0.0,
                0.0,
                0.0,
                f64::from(u8::from(at_start)),
                f64::from(u8::from(!at_start)),
            ],
        );
    }
    let w = s1 - s0;
    scale(
        a,
        &[
            (t1 - t0) / w,
            (t1 - t0) * (v - s1) / (w * w),
            -(t1 - t0) * (v - s0) / (w * w),
            1.0 - t,
            t,
        ],
    )
}

fn min(a: &VjpArgs<'_>) -> VjpResult {
    let first = num(&a.inputs[0]) <= num(&a.inputs[1]);
    scale(
        a,
        &[f64::from(u8::from(first)), f64::from(u8::from(!first))],
    )
}

fn max(a: &VjpArgs<'_>) -> VjpResult {
    let first = num(&a.inputs[0]) >= num(&a.inputs[1]);
    scale(
        a,
        &[f64::from(u8::from(first)), f64::from(u8::from(!first))],
    )
}

fn clamp(a: &VjpArgs<'_>) -> VjpResult {
    let (x, lo, hi) = (num(&a.inputs[0]), num(&a.inputs[1]), num(&a.inputs[2]));
    let which = if x < lo {
        [0.0, 1.0, 0.0]
    } else if x > hi {
        [0.0, 0.0, 1.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    scale(a, &which)
}

/// `vector.point`: the point's cotangent, component by component, to x, y and z.
fn point(a: &VjpArgs<'_>) -> VjpResult {
    let c = a.cotangent(0);
    Ok(a.wanted
        .iter()
        .enumerate()
        .map(|(k, &w)| {
            (w && k < 3 && a.inputs[k].as_f64().is_some())
                .then(|| vec![c.get(k).copied().unwrap_or(0.0)])
        })
        .collect())
}

/// The product of a math node, by id.
pub fn product(id: &str) -> Option<Product> {
    Some(match id {
        "math.add" => add,
        "math.subtract" => subtract,
        "math.multiply" => multiply,
        "math.divide" => divide,
        "math.power" => power,
        "math.remap" => remap,
        "math.min" => min,
        "math.max" => max,
        "math.clamp" => clamp,
        "vector.point" => point,
        _ => return None,
    })
}
