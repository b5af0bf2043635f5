//! Outputs vouched finite (`NodeContext::vouch_finite`): the evaluator skips its own scan of them
//! in release builds; debug builds (every test) scan them anyway and panic when the promise is
//! broken. Outputs not vouched for are always scanned.

use cnets_engine::eval::evaluate_node;
use cnets_engine::prelude::*;

node! {
    /// Divides by `d`; vouches for `vouched` only.
    #[node(id = "t.divide", category = "Test")]
    pub fn divide[ctx](
        /// Divisor.
        d: k::Number = 1.0,
        /// Whether the quotient is vouched finite.
        promise: k::Boolean = false,
    ) -> (
        /// 1 / d.
        quotient: k::Number,
        /// 2 / d, never vouched.
        twice: k::Number,
    ) {
        if promise {
            ctx.vouch_finite("quotient");
        }
        Ok((1.0 / d, 2.0 / d))
    }
}

fn run(d: f64, promise: bool) -> Result<Vec<Value>, String> {
    let ctx = NodeContext::default();
    evaluate_node(
        &divide(),
        &ctx,
        &[Value::Number(d), Value::Boolean(promise)],
    )
    .map(|o| o.values)
    .map_err(|e| e.to_string())
}

#[test]
fn finite_outputs_pass_whether_vouched_or_not() {
    for promise in [false, true] {
        let values = run(4.0, promise).expect("finite");
        assert_eq!(values, vec![Value::Number(0.25), Value::Number(0.5)]);
    }
}

#[test]
fn an_output_not_vouched_for_is_scanned() {
    let message = run(0.0, false).expect_err("1 / 0 is not finite");
    assert!(
        message.contains("output 'quotient' is not a finite number"),
        "{message}"
    );
}

#[cfg(debug_assertions)]
#[test]
#[should_panic(expected = "output 'quotient' was vouched finite but is not")]
fn a_broken_promise_panics_in_debug_builds() {
    let _ = run(0.0, true);
}
