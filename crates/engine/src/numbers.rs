//! Numbers a designer sets by hand — a slider's step, a dragged value, a grid-snapped coordinate —
//! snapped to their step and stored as the shortest decimal at its precision, so `0.1 + 0.2` is
//! stored as `0.3`, not `0.30000000000000004`. The one rule for the node library (`param.number`)
//! and the editor (sliders, handles, the grid).

/// Decimals a number needs as written in its shortest form (`0.25` → 2, `3` → 0, `1e-7` → 7).
fn decimals(x: f64) -> usize {
    let text = format!("{}", x.abs());
    text.split_once('.').map_or(0, |(_, frac)| frac.len())
}

/// `x` rounded to `decimals` decimals through its decimal text (the nearest short decimal).
fn shortest(x: f64, decimals: usize) -> f64 {
    if !x.is_finite() || decimals > 17 {
        return x;
    }
    let snapped: f64 = format!("{x:.decimals$}").parse().unwrap_or(x);
    // −0 is written as 0.
    if snapped == 0.0 { 0.0 } else { snapped }
}

/// `x` snapped to the nearest `origin + k · step` (`step` ≤ 0 or not finite: `x` unchanged),
/// stored as the shortest decimal at the precision of `origin` and `step`.
pub fn snap(x: f64, origin: f64, step: f64) -> f64 {
    if !(step.is_finite() && step > 0.0 && x.is_finite() && origin.is_finite()) {
        return x;
    }
    let snapped = origin + ((x - origin) / step).round() * step;
    shortest(snapped, decimals(origin).max(decimals(step)))
}

/// `x` rounded to a thousandth of `range`, as a power of ten (range 1 → 0.001, range 30 → 0.01):
/// a dragged value keeps the digits a pixel can set (`range` ≤ 0: unchanged).
pub fn snap_to_range(x: f64, range: f64) -> f64 {
    if !(range.is_finite() && range > 0.0) {
        return x;
    }
    let unit = 10f64.powf((range.log10() - 3.0).floor());
    snap(x, 0.0, unit)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_give_the_short_decimal() {
        assert_eq!(snap(0.26, 0.0, 0.1), 0.3);
        assert_eq!(snap(0.1 + 0.2, 0.0, 0.1), 0.3);
        assert_eq!(snap(0.74, 0.0, 0.25), 0.75);
        assert_eq!(snap(0.16, 0.05, 0.1), 0.15);
        assert_eq!(snap(7.0 * 0.2, 0.0, 0.2), 1.4);
        assert_eq!(snap(-0.01, 0.0, 0.5), 0.0);
        assert_eq!(snap(5.0, 0.0, 0.0), 5.0, "no step: unchanged");
        assert!(snap(f64::NAN, 0.0, 1.0).is_nan());
        assert_eq!(snap(123456.789, 0.0, 1e-7), 123456.789);
    }

    #[test]
    fn a_thousandth_of_the_range() {
        assert_eq!(snap_to_range(1.2340169334411621, 1.0), 1.234);
        assert_eq!(snap_to_range(0.40179139375686646, 1.0), 0.402);
        assert_eq!(snap_to_range(17.436, 30.0), 17.44);
        assert_eq!(snap_to_range(-0.30000000000000004, 2.0), -0.3);
        assert_eq!(snap_to_range(5.0, 0.0), 5.0, "no range: unchanged");
    }
}
