//! Parameters: the values a designer sets (the editor shows them as sliders, toggles and fields).

use cnets_engine::prelude::*;

node! {
    /// A number set by the designer; the editor shows it as a slider from `min` to `max`. The value
    /// is clamped to that range and snapped to multiples of `step` from `min` (`step` 0: no snapping).
    #[node(id = "param.number", category = "Params", flags(Parameter))]
    pub fn number[ctx](
        /// The value.
        value: k::Number = 0.5,
        /// Slider minimum.
        min: k::Number = 0.0,
        /// Slider maximum.
        max: k::Number = 1.0,
        /// Slider step (0 = continuous).
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
        let mut v = value.clamp(min, max);
        if v != value {
            ctx.warn(format!("value {value} is outside [{min}, {max}]; clamped to {v}"));
        }
        if step > 0.0 {
            v = (min + ((v - min) / step).round() * step).clamp(min, max);
        }
        Ok((v,))
    }
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![number()]
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_engine::eval::run_mapped;

    fn run(def: &NodeDef, inputs: &[f64]) -> Result<Vec<Value>, NodeError> {
        let values: Vec<Value> = inputs.iter().map(|&x| Value::Number(x)).collect();
        run_mapped(def, &NodeContext::default(), &values)
    }

    #[test]
    fn number_clamps_and_snaps() {
        let def = number();
        assert_eq!(
            run(&def, &[0.26, 0.0, 1.0, 0.1]).unwrap(),
            vec![Value::Number(0.30000000000000004)]
        );
        assert_eq!(
            run(&def, &[5.0, 0.0, 1.0, 0.0]).unwrap(),
            vec![Value::Number(1.0)]
        );
        assert!(
            run(&def, &[0.5, 2.0, 1.0, 0.0])
                .unwrap_err()
                .message
                .contains("greater than max")
        );
        assert!(run(&def, &[f64::NAN, 0.0, 1.0, 0.0]).is_err());
    }
}
